// Picking against the instance matrices (web/src/render/picking.ts) and the ballistic throw.
import * as THREE from 'three';
import { describe, expect, it } from 'vitest';
import { MAX_FLIGHT, FASTEST_THROW, pickBody, THROW_SPEED, throwSpeed, throwVelocity } from '../../../web/src/render/picking';

/** A column-major instance matrix: box of `size` at `position`, turned by `yaw` about y. */
function box(position: [number, number, number], size: [number, number, number], yaw = 0): number[] {
  return new THREE.Matrix4()
    .compose(new THREE.Vector3(...position), new THREE.Quaternion().setFromAxisAngle(new THREE.Vector3(0, 1, 0), yaw), new THREE.Vector3(...size))
    .toArray();
}

describe('pickBody', () => {
  const matrices = new Float32Array([...box([0, 1, 0], [0.4, 0.6, 0.2]), ...box([0, 1, -3], [1, 1, 1]), ...box([5, 0.5, 0], [1, 1, 1], Math.PI / 4)]);
  const ray = (from: [number, number, number], to: [number, number, number]) => {
    const o = new THREE.Vector3(...from);
    return new THREE.Ray(o, new THREE.Vector3(...to).sub(o).normalize());
  };

  it('finds the nearest box along the ray, the hit point, and the point in the body frame', () => {
    const hit = pickBody(ray([0, 1.1, 10], [0, 1.1, 0]), matrices, 3);
    expect(hit?.index).toBe(0);
    expect(hit!.distance).toBeCloseTo(10 - 0.1, 5); // front face at z = +0.1
    expect(hit!.point.z).toBeCloseTo(0.1, 5);
    expect(hit!.local.x).toBeCloseTo(0, 5);
    expect(hit!.local.y).toBeCloseTo(0.1, 5);
    expect(hit!.local.z).toBeCloseTo(0.1, 5);
  });

  it('respects the count and misses what is not there', () => {
    expect(pickBody(ray([0, 1, 10], [0, 1, 0]), matrices, 0)).toBeNull();
    expect(pickBody(ray([0, 3, 10], [0, 3, 0]), matrices, 3)).toBeNull();
    // Only the far box is counted when the near one is not: index 1 is behind index 0.
    expect(pickBody(ray([0, 1.45, 10], [0, 1.45, 0]), matrices, 3)?.index).toBe(1);
  });

  it('handles turned boxes', () => {
    // A unit box turned 45° about y reaches out to √½ along x.
    const hit = pickBody(ray([10, 0.5, 0], [5, 0.5, 0]), matrices, 3);
    expect(hit?.index).toBe(2);
    expect(hit!.point.x).toBeCloseTo(5 + Math.SQRT1_2, 5);
  });
});

describe('throwVelocity', () => {
  it('lands a ballistic box on the target', () => {
    const from = new THREE.Vector3(8, 5, 9);
    const target = new THREE.Vector3(-1, 0.3, 2);
    const v = throwVelocity(from, target, 14);
    // Integrate the flight until it passes the target's horizontal distance.
    const p = from.clone();
    const vel = v.clone();
    const dt = 1e-4;
    const horizontal = Math.hypot(target.x - from.x, target.z - from.z);
    while (Math.hypot(p.x - from.x, p.z - from.z) < horizontal) {
      vel.y -= 9.81 * dt;
      p.addScaledVector(vel, dt);
    }
    expect(p.distanceTo(target)).toBeLessThan(0.01);
  });
});

describe('throwSpeed', () => {
  it('throws near targets at the usual speed and far ones harder, so that no flight takes over a second', () => {
    expect(throwSpeed(5)).toBe(THROW_SPEED);
    expect(throwSpeed(THROW_SPEED * MAX_FLIGHT)).toBe(THROW_SPEED);
    expect(throwSpeed(22)).toBeCloseTo(22 / MAX_FLIGHT, 12);
    expect(22 / throwSpeed(22)).toBeLessThanOrEqual(MAX_FLIGHT);
    expect(throwSpeed(500)).toBe(FASTEST_THROW);
  });
});
