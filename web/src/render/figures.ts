// What makes the simulated bodies read as a person and a dog from across the room: a head, neck
// and arms for the biped; a head with snout and ears, a neck and a tail for the quadruped. None of
// them is in the physics (the characters are the thesis's: legs, leg frames and a spine, Larsson
// 2015 §3.1, Figure 3.1), so they are drawn attached to the bodies they would hang from and
// carry no weight. The arms swing with the legs as the simulation has them (each arm follows
// the opposite thigh's pitch, as people swing their arms), so they show the gait's phase and
// never a motion the legs do not make.
//
// All of them are instances of one mesh: one draw call (plus the shadow pass) for the whole
// crowd, whatever its size.
import * as THREE from 'three';
import { MATRIX_FLOATS } from '../sim/render-buffer';
import type { CharacterType } from '../gait/character';

/** One ornament in its parent body's frame (metres; the parent's box scale removed). */
interface Part {
  /** Index of the parent body within the character (morphology order, native/src/body). */
  body: number;
  position: [number, number, number];
  size: [number, number, number];
  colour: number;
  /** Pitch about the parent's x axis (rad), at `position`, before the part's own offset. */
  pitch?: number;
  /** The part hangs from `position` by `hang` metres along −y after the pitch (arms). */
  hang?: number;
  /** Arms: which thigh (body index) the swing follows; the part pitches with −0.8 × its pitch. */
  swingWith?: number;
  /** Forearms: the upper arm's length, hung below the shoulder first. */
  elbow?: number;
}

const SKIN = 0xe8bf98;
const SHIRT = 0xd9734e;
const FUR = 0xc9a25a;
const DARK_FUR = 0x6b4a2c;

// The biped's leg frame is body 0, half extents (0.17, 0.28, 0.11): its top is 0.28 above its
// centre, shoulders at its upper corners. Thighs are bodies 1 (left) and 4 (right).
const TOP = 0.28;
const BIPED: Part[] = [
  { body: 0, position: [0, TOP + 0.05, 0], size: [0.1, 0.1, 0.1], colour: SKIN },
  { body: 0, position: [0, TOP + 0.2, 0.01], size: [0.2, 0.25, 0.22], colour: SKIN },
  // Upper arms (0.3 m) and forearms with hands (0.3 m), the left swinging with the right thigh.
  { body: 0, position: [0.21, TOP - 0.04, 0], size: [0.09, 0.3, 0.09], colour: SHIRT, hang: 0.15, swingWith: 4 },
  { body: 0, position: [-0.21, TOP - 0.04, 0], size: [0.09, 0.3, 0.09], colour: SHIRT, hang: 0.15, swingWith: 1 },
  { body: 0, position: [0.21, TOP - 0.04, 0], size: [0.075, 0.3, 0.075], colour: SKIN, hang: 0.15, elbow: 0.3, swingWith: 4 },
  { body: 0, position: [-0.21, TOP - 0.04, 0], size: [0.075, 0.3, 0.075], colour: SKIN, hang: 0.15, elbow: 0.3, swingWith: 1 },
];

// The quadruped's front leg frame is body 0 (half extents 0.12, 0.09, 0.12; +z is forward), its
// back leg frame body 5 (0.11, 0.08, 0.11).
const QUADRUPED: Part[] = [
  { body: 0, position: [0, 0.1, 0.13], size: [0.1, 0.16, 0.1], colour: FUR, pitch: 0.6 },
  { body: 0, position: [0, 0.2, 0.21], size: [0.15, 0.14, 0.17], colour: FUR },
  { body: 0, position: [0, 0.17, 0.32], size: [0.08, 0.07, 0.12], colour: DARK_FUR },
  { body: 0, position: [0.055, 0.29, 0.18], size: [0.045, 0.09, 0.03], colour: DARK_FUR, pitch: -0.2 },
  { body: 0, position: [-0.055, 0.29, 0.18], size: [0.045, 0.09, 0.03], colour: DARK_FUR, pitch: -0.2 },
  { body: 5, position: [0, 0.05, -0.11], size: [0.04, 0.28, 0.04], colour: FUR, pitch: -2.2, hang: 0.14 },
];

/** The kinds drawn with ornaments: the shipped biped and quadruped (creatures are drawn as they are simulated). */
type Dressed = Extract<CharacterType, 'biped' | 'quadruped'>;
export const PARTS: Record<Dressed, Part[]> = { biped: BIPED, quadruped: QUADRUPED };
/** Feet (body indices, morphology order) and their half heights: where contact shading goes. */
const FEET: Record<Dressed, { bodies: number[]; half: number; blob: number }> = {
  biped: { bodies: [3, 6], half: 0.03, blob: 0.34 },
  quadruped: { bodies: [8, 11, 14, 17], half: 0.02, blob: 0.2 },
};
/** Bodies per character (native/src/body/morphology.cpp): how a character's type is known from the buffer. */
const BODIES: Record<number, Dressed> = { 7: 'biped', 18: 'quadruped' };

/** A rounded unit box: segments and ornaments alike read as rounded limbs, not crates. */
export function roundedUnitBox(): THREE.BufferGeometry {
  // A sphere pushed out towards its bounding cube: smooth normals everywhere (three's
  // RoundedBoxGeometry has flat faces that show as crates once scaled to a limb).
  const geometry = new THREE.SphereGeometry(0.5, 16, 12);
  const position = geometry.attributes.position as THREE.BufferAttribute;
  const v = new THREE.Vector3();
  for (let i = 0; i < position.count; i++) {
    v.fromBufferAttribute(position, i).multiplyScalar(2); // a unit direction
    // A superellipsoid |x|^p + |y|^p + |z|^p = 0.5^p with p = 3: flat-ish sides, round edges; a
    // limb's thin box becomes a capsule, the head's near-cube a rounded head.
    const p = 3;
    const norm = Math.pow(Math.pow(Math.abs(v.x), p) + Math.pow(Math.abs(v.y), p) + Math.pow(Math.abs(v.z), p), 1 / p);
    v.multiplyScalar(0.5 / norm);
    position.setXYZ(i, v.x, v.y, v.z);
  }
  geometry.computeVertexNormals();
  return geometry;
}

export class Figures {
  readonly mesh: THREE.InstancedMesh;
  private readonly parent = new THREE.Matrix4();
  private readonly rotation = new THREE.Quaternion();
  private readonly scale = new THREE.Vector3();
  private readonly origin = new THREE.Vector3();
  private readonly local = new THREE.Matrix4();
  private readonly step = new THREE.Matrix4();
  private readonly colour = new THREE.Color();
  private readonly thighAxis = new THREE.Vector3();
  private readonly inverse = new THREE.Quaternion();

  /**
   * Contact shading: a soft dark disc on the ground under each foot, darkest when the foot is
   * down and fading as it lifts (ambient light the foot blocks; the sun's shadow is separate).
   * One more instanced mesh, multiplied into what is drawn below it.
   */
  readonly contacts: THREE.InstancedMesh;

  constructor(geometry: THREE.BufferGeometry, material: THREE.Material, capacity: number) {
    this.contacts = new THREE.InstancedMesh(
      new THREE.PlaneGeometry(1, 1).rotateX(-Math.PI / 2),
      new THREE.MeshBasicMaterial({
        // (No texture outside a browser: the unit tests place the parts without drawing them.)
        map: typeof document === 'undefined' ? null : blobTexture(),
        blending: THREE.MultiplyBlending,
        premultipliedAlpha: true,
        transparent: true,
        depthWrite: false,
        polygonOffset: true,
        polygonOffsetFactor: -2,
      }),
      Math.max(1, capacity),
    );
    this.contacts.instanceMatrix.setUsage(THREE.DynamicDrawUsage);
    this.contacts.instanceColor = new THREE.InstancedBufferAttribute(new Float32Array(Math.max(1, capacity) * 3).fill(1), 3);
    this.contacts.frustumCulled = false;
    this.contacts.renderOrder = 1;
    this.contacts.count = 0;
    this.mesh = new THREE.InstancedMesh(geometry, material, Math.max(1, capacity));
    this.mesh.instanceMatrix.setUsage(THREE.DynamicDrawUsage);
    this.mesh.instanceColor = new THREE.InstancedBufferAttribute(new Float32Array(Math.max(1, capacity) * 3).fill(1), 3);
    this.mesh.castShadow = true;
    this.mesh.receiveShadow = true;
    this.mesh.frustumCulled = false;
    this.mesh.count = 0;
  }

  /** Places every character's parts from the bodies drawn now (`owners` per body, −1 = prop). */
  update(matrices: Float32Array, owners: Int32Array, bodyCount: number): void {
    const out = this.mesh.instanceMatrix.array as Float32Array;
    const capacity = this.mesh.instanceMatrix.count;
    let n = 0;
    let blobs = 0;
    const blobOut = this.contacts.instanceMatrix.array as Float32Array;
    for (let first = 0; first < bodyCount; ) {
      const owner = owners[first];
      let end = first + 1;
      while (end < bodyCount && owners[end] === owner) end++;
      const type = owner >= 0 ? BODIES[end - first] : undefined;
      if (type) {
        for (const part of PARTS[type]) {
          if (n >= capacity) break;
          this.place(part, matrices, first, type);
          this.local.toArray(out, n * MATRIX_FLOATS);
          this.mesh.setColorAt(n, this.colour.setHex(part.colour, THREE.SRGBColorSpace));
          n++;
        }
        const feet = FEET[type];
        let lowest = Infinity;
        for (const b of feet.bodies) lowest = Math.min(lowest, matrices[(first + b) * MATRIX_FLOATS + 13]);
        for (const b of feet.bodies) {
          if (blobs >= capacity) break;
          const o = (first + b) * MATRIX_FLOATS;
          const lift = matrices[o + 13] - lowest;
          this.local.makeScale(feet.blob, 1, feet.blob).setPosition(matrices[o + 12], lowest - feet.half + 0.004, matrices[o + 14]);
          this.local.toArray(blobOut, blobs * MATRIX_FLOATS);
          // Darkest (0.5) with the foot down; gone once it is 15 cm up.
          const shade = 0.5 + 0.5 * Math.min(1, lift / 0.15);
          this.contacts.setColorAt(blobs, this.colour.setRGB(shade, shade, shade));
          blobs++;
        }
      }
      first = end;
    }
    this.contacts.count = blobs;
    this.contacts.instanceMatrix.clearUpdateRanges();
    this.contacts.instanceMatrix.addUpdateRange(0, blobs * MATRIX_FLOATS);
    this.contacts.instanceMatrix.needsUpdate = true;
    if (this.contacts.instanceColor) this.contacts.instanceColor.needsUpdate = true;
    this.mesh.count = n;
    this.mesh.instanceMatrix.clearUpdateRanges();
    this.mesh.instanceMatrix.addUpdateRange(0, n * MATRIX_FLOATS);
    this.mesh.instanceMatrix.needsUpdate = true;
    if (this.mesh.instanceColor) this.mesh.instanceColor.needsUpdate = true;
  }

  /** Leaves the part's world matrix (size included) in this.local. */
  private place(part: Part, matrices: Float32Array, first: number, type: CharacterType): void {
    // The parent body's pose without its box scale.
    this.parent.fromArray(matrices, (first + part.body) * MATRIX_FLOATS);
    this.parent.decompose(this.origin, this.rotation, this.scale);
    this.parent.compose(this.origin, this.rotation, this.scale.set(1, 1, 1));
    let pitch = part.pitch ?? 0;
    if (part.swingWith !== undefined && type === 'biped') {
      // The thigh's direction from hip to knee (its −y) in the leg frame's frame: its pitch forward.
      this.step.fromArray(matrices, (first + part.swingWith) * MATRIX_FLOATS);
      this.thighAxis.setFromMatrixColumn(this.step, 1).normalize().negate();
      this.thighAxis.applyQuaternion(this.inverse.copy(this.rotation).invert());
      const thighPitch = Math.atan2(this.thighAxis.z, -this.thighAxis.y);
      // rotX(θ) takes (0, −1, 0) to (0, −cos θ, −sin θ): forward (+z) is θ < 0.
      pitch = -0.8 * thighPitch;
    }
    const m = this.local.copy(this.parent).multiply(this.step.makeTranslation(...part.position));
    if (pitch) m.multiply(this.step.makeRotationX(pitch));
    if (part.elbow) {
      m.multiply(this.step.makeTranslation(0, -part.elbow, 0));
      // The elbow bends a little forward, more when the arm swings forward.
      m.multiply(this.step.makeRotationX(-0.25 + Math.min(0, pitch) * 0.5));
    }
    if (part.hang) m.multiply(this.step.makeTranslation(0, -part.hang, 0));
    m.multiply(this.step.makeScale(...part.size));
  }

  dispose(): void {
    this.mesh.dispose();
    this.contacts.dispose();
  }
}

/** A soft disc: black in the middle fading to white (no change, multiplied) at its edge. */
function blobTexture(): THREE.Texture {
  const size = 64;
  const canvas = document.createElement('canvas');
  canvas.width = canvas.height = size;
  const ctx = canvas.getContext('2d');
  if (!ctx) throw new Error('no 2D canvas context for contact shading');
  const gradient = ctx.createRadialGradient(size / 2, size / 2, 0, size / 2, size / 2, size / 2);
  gradient.addColorStop(0, 'rgb(0, 0, 0)');
  gradient.addColorStop(0.5, 'rgb(150, 150, 150)');
  gradient.addColorStop(1, 'rgb(255, 255, 255)');
  ctx.fillStyle = gradient;
  ctx.fillRect(0, 0, size, size);
  return new THREE.CanvasTexture(canvas);
}
