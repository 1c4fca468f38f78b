// The figures' parts (web/src/render/figures.ts): placed on the bodies they hang from, the arms
// swinging with the opposite thigh as the simulation has it, one instance each.
import * as THREE from 'three';
import { describe, expect, it } from 'vitest';
import { Figures, PARTS, roundedUnitBox } from '../../../web/src/render/figures';

/** A column-major matrix of a box of `size` at `position`, pitched by `pitch` about x. */
const box = (position: [number, number, number], size: [number, number, number], pitch = 0) =>
  new THREE.Matrix4().compose(new THREE.Vector3(...position), new THREE.Quaternion().setFromAxisAngle(new THREE.Vector3(1, 0, 0), pitch), new THREE.Vector3(...size)).toArray();

/** A standing biped (native/src/body/morphology.cpp): leg frame, then per leg thigh, shin, foot. */
function biped(leftThighPitch: number, rightThighPitch: number): Float32Array {
  const leg = (x: number, pitch: number) => [...box([x, 0.7, 0], [0.12, 0.42, 0.12], pitch), ...box([x, 0.27, 0], [0.1, 0.42, 0.1]), ...box([x, 0.03, 0.04], [0.1, 0.06, 0.24])];
  return new Float32Array([...box([0, 1.16, 0], [0.34, 0.56, 0.22]), ...leg(0.09, leftThighPitch), ...leg(-0.09, rightThighPitch)]);
}

describe('Figures', () => {
  it('gives a biped a head above its leg frame and arms at its shoulders, in one instanced mesh', () => {
    const figures = new Figures(roundedUnitBox(), new THREE.MeshStandardMaterial(), 64);
    figures.update(biped(0, 0), new Int32Array(7).fill(5), 7);
    expect(figures.mesh.count).toBe(PARTS.biped.length);
    const position = (i: number) => new THREE.Vector3().setFromMatrixPosition(new THREE.Matrix4().fromArray(figures.mesh.instanceMatrix.array, i * 16));
    // The head (part 1) sits on the leg frame's top (1.16 + 0.28) and above the neck.
    expect(position(1).y).toBeGreaterThan(1.44 + 0.1);
    expect(position(1).y).toBeGreaterThan(position(0).y);
    // Upper arms hang beside the leg frame, at either side.
    expect(position(2).x).toBeCloseTo(0.21, 5);
    expect(position(3).x).toBeCloseTo(-0.21, 5);
    expect(position(2).y).toBeLessThan(1.44);
    // Two feet each: contact shading under every foot.
    expect(figures.contacts.count).toBe(2);
  });

  it('swings each arm with the opposite thigh: the left arm forward when the right thigh is', () => {
    const figures = new Figures(roundedUnitBox(), new THREE.MeshStandardMaterial(), 64);
    // A thigh pitched by −0.4 about x swings its knee forward (+z).
    figures.update(biped(0.4, -0.4), new Int32Array(7).fill(0), 7);
    const z = (i: number) => new THREE.Vector3().setFromMatrixPosition(new THREE.Matrix4().fromArray(figures.mesh.instanceMatrix.array, i * 16)).z;
    expect(z(2)).toBeGreaterThan(0.03); // left upper arm: forward, with the right thigh
    expect(z(3)).toBeLessThan(-0.03); // right upper arm: back, with the left thigh
  });

  it('leaves props alone', () => {
    const figures = new Figures(roundedUnitBox(), new THREE.MeshStandardMaterial(), 64);
    figures.update(new Float32Array(box([0, 0.15, 0], [0.3, 0.3, 0.3])), new Int32Array([-1]), 1);
    expect(figures.mesh.count).toBe(0);
  });
});
