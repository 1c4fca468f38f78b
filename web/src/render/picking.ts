// Picking bodies under the pointer, in JavaScript against the frame on screen: the instance
// matrices already hold every body's box (position, orientation and size), so a ray–box test per
// body needs no round trip to the sim worker and always agrees with what the user sees.
import * as THREE from 'three';
import { MATRIX_FLOATS } from '../sim/render-buffer';

export interface BodyHit {
  /** Index of the body in the render buffer. */
  index: number;
  /** Distance along the ray (the ray's direction is normalised: metres). */
  distance: number;
  /** Hit point, world. */
  point: THREE.Vector3;
  /** Hit point in the body's own frame (metres, centre of mass at the origin). */
  local: THREE.Vector3;
}

const inverse = new THREE.Matrix4();
const matrix = new THREE.Matrix4();
const origin = new THREE.Vector3();
const direction = new THREE.Vector3();

/**
 * The nearest body a ray hits, or null. `matrices` holds `count` column-major matrices mapping
 * the unit cube [−½, ½]³ onto each body (rotation × size, then translation).
 */
export function pickBody(ray: THREE.Ray, matrices: Float32Array, count: number): BodyHit | null {
  let best: BodyHit | null = null;
  for (let i = 0; i < count; i++) {
    matrix.fromArray(matrices, i * MATRIX_FLOATS);
    // Cheap rejection first: the distance from the ray to the box centre against its half diagonal.
    const e = matrix.elements;
    const halfDiagonal =
      0.5 * Math.sqrt(e[0] ** 2 + e[1] ** 2 + e[2] ** 2 + e[4] ** 2 + e[5] ** 2 + e[6] ** 2 + e[8] ** 2 + e[9] ** 2 + e[10] ** 2);
    origin.set(e[12], e[13], e[14]);
    if (ray.distanceSqToPoint(origin) > halfDiagonal * halfDiagonal) continue;
    inverse.copy(matrix).invert();
    // In the unit cube's space the ray is origin' + t·direction' with the same t as in the world
    // (the map is affine and direction' is not renormalised).
    origin.copy(ray.origin).applyMatrix4(inverse);
    // (Matrix4.transformDirection would normalise it, so apply the linear part by hand.)
    direction.set(
      inverse.elements[0] * ray.direction.x + inverse.elements[4] * ray.direction.y + inverse.elements[8] * ray.direction.z,
      inverse.elements[1] * ray.direction.x + inverse.elements[5] * ray.direction.y + inverse.elements[9] * ray.direction.z,
      inverse.elements[2] * ray.direction.x + inverse.elements[6] * ray.direction.y + inverse.elements[10] * ray.direction.z,
    );
    const t = slab(origin, direction);
    if (t === null || (best && t >= best.distance)) continue;
    const unit = origin.clone().addScaledVector(direction, t);
    // Unit-cube coordinates times the box's size are body-frame metres.
    const sx = Math.hypot(e[0], e[1], e[2]);
    const sy = Math.hypot(e[4], e[5], e[6]);
    const sz = Math.hypot(e[8], e[9], e[10]);
    best = {
      index: i,
      distance: t,
      point: ray.at(t, new THREE.Vector3()),
      local: new THREE.Vector3(unit.x * sx, unit.y * sy, unit.z * sz),
    };
  }
  return best;
}

/** Entry distance of the ray o + t·d (t ≥ 0) into the cube [−½, ½]³, or null if it misses. */
function slab(o: THREE.Vector3, d: THREE.Vector3): number | null {
  let near = 0;
  let far = Infinity;
  for (const axis of ['x', 'y', 'z'] as const) {
    const od = o[axis];
    const dd = d[axis];
    if (Math.abs(dd) < 1e-12) {
      if (od < -0.5 || od > 0.5) return null;
      continue;
    }
    let t0 = (-0.5 - od) / dd;
    let t1 = (0.5 - od) / dd;
    if (t0 > t1) [t0, t1] = [t1, t0];
    near = Math.max(near, t0);
    far = Math.min(far, t1);
    if (near > far) return null;
  }
  return near;
}

/** How fast the page throws a box, m/s (the straight distance over the flight time), at least. */
export const THROW_SPEED = 14;
/** The longest flight a throw takes, s, and the fastest throw that keeps to it, m/s. */
export const MAX_FLIGHT = 1;
export const FASTEST_THROW = 30;

/**
 * The speed of a throw over `distance` metres: THROW_SPEED, or faster for a target beyond
 * THROW_SPEED·MAX_FLIGHT metres so that the flight stays within MAX_FLIGHT (up to
 * FASTEST_THROW). The camera frames a wandering crowd from 20–40 m: at 14 m/s a box would fly
 * for two or three seconds on an arc rising metres above the line of sight, and a walker's
 * course would change on the way.
 */
export function throwSpeed(distance: number): number {
  return Math.min(FASTEST_THROW, Math.max(THROW_SPEED, distance / MAX_FLIGHT));
}

/**
 * Initial velocity that carries a box thrown from `from` to `target` in a ballistic arc, flying
 * at about `speed` m/s: aim straight, and add the height gravity takes away during the flight.
 * (A throw at a character is aimed by the simulation instead: gl_sim_throw_at.)
 */
export function throwVelocity(from: THREE.Vector3, target: THREE.Vector3, speed = THROW_SPEED, gravity = 9.81): THREE.Vector3 {
  const d = target.clone().sub(from);
  const t = Math.max(0.05, d.length() / speed);
  return d.divideScalar(t).add(new THREE.Vector3(0, 0.5 * gravity * t, 0));
}
