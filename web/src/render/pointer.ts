// What the pointer does to the scene: click a character to select it, click the ground to
// throw a box there (shift-click throws at whatever is under the pointer, characters included:
// at a character, the simulation aims the box at where it will be when the box arrives), press
// on a body and drag to pull it on a spring. Orbiting the camera keeps the remaining
// gestures (dragging the ground, wheel, right button). On a touch screen a finger never holds a
// body: one finger orbits and two pinch wherever they land (a pinch whose finger landed on a
// character used to pull it instead of zooming), and a tap still selects or throws.
import * as THREE from 'three';
import type { CrowdMesh } from './crowd-mesh';
import { pickBody, throwSpeed, throwVelocity } from './picking';
import type { Stage } from './stage';
import type { SceneCommand, Vec3 } from '../sim/protocol';
import { groundHeight, intersectGround } from '../sim/terrain-grid';

export interface PointerActions {
  send(command: SceneCommand): void;
  select(id: number | null): void;
}

/** Pointer travel (CSS pixels) below which a press and release is a click, not a drag. */
const CLICK_SLOP = 5;
/** Half size of thrown boxes, metres. */
export const BOX_HALF = 0.12;

const toVec3 = (v: THREE.Vector3): Vec3 => [v.x, v.y, v.z];

export class PointerInteraction {
  private readonly raycaster = new THREE.Raycaster();
  private readonly ground = new THREE.Plane(new THREE.Vector3(0, 1, 0), 0);
  private press: {
    x: number;
    y: number;
    pointer: number;
    hit: { id: number; segment: number; local: THREE.Vector3; point: THREE.Vector3 } | null;
    /** The press holds the body hit (a mouse or pen on a character): a drag pulls it. */
    holds: boolean;
    touch: boolean;
    /** Another finger was down when this one pressed: a gesture (a pinch), never a tap. */
    gesture: boolean;
    dragging: boolean;
    plane: THREE.Plane;
  } | null = null;

  constructor(
    private readonly stage: Stage,
    private readonly crowd: CrowdMesh,
    private readonly actions: PointerActions,
  ) {
    const canvas = stage.renderer.domElement;
    // Capture phase: decide before OrbitControls whether this press is ours (a body) or its.
    canvas.addEventListener('pointerdown', (e) => this.down(e), { capture: true });
    canvas.addEventListener('pointermove', (e) => this.move(e));
    canvas.addEventListener('pointerup', (e) => this.up(e));
    canvas.addEventListener('pointercancel', () => this.cancel());
  }

  private ray(event: PointerEvent): THREE.Ray {
    const rect = this.stage.renderer.domElement.getBoundingClientRect();
    const ndc = new THREE.Vector2(((event.clientX - rect.left) / rect.width) * 2 - 1, -((event.clientY - rect.top) / rect.height) * 2 + 1);
    this.raycaster.setFromCamera(ndc, this.stage.camera);
    return this.raycaster.ray;
  }

  /** The owner of the body at a point of the page (CSS pixels; −1 a prop), or null: for tests. */
  ownerAt(clientX: number, clientY: number): number | null {
    return this.pickCharacter(this.ray({ clientX, clientY } as PointerEvent))?.owner ?? null;
  }

  /** The character body under the pointer: its owner, segment index and the point hit. */
  private pickCharacter(ray: THREE.Ray) {
    const { array, count } = this.crowd.matrices();
    const hit = pickBody(ray, array, count);
    if (!hit) return null;
    const owner = this.crowd.owners[hit.index];
    // A character's bodies are contiguous and in morphology order: the segment is the offset
    // from its first body.
    let first = hit.index;
    while (first > 0 && this.crowd.owners[first - 1] === owner) first--;
    return { owner, segment: hit.index - first, local: hit.local, point: hit.point, distance: hit.distance };
  }

  private down(event: PointerEvent): void {
    if (event.button !== 0) return;
    const ray = this.ray(event);
    const hit = this.pickCharacter(ray);
    const onCharacter = hit && hit.owner >= 0 && !event.shiftKey;
    // (Touches only: a finger's release always reaches the canvas, which holds it implicitly, so
    // a press still recorded is a finger still down.)
    const touch = event.pointerType === 'touch';
    const gesture = touch && this.press !== null && this.press.touch && this.press.pointer !== event.pointerId;
    const holds = Boolean(onCharacter) && !touch;
    if (holds) {
      // Ours: keep OrbitControls from rotating the view while a body is held.
      event.stopImmediatePropagation();
      this.stage.controls.enabled = false;
      this.stage.renderer.domElement.setPointerCapture(event.pointerId);
    }
    // Drag in the plane through the point held, facing the camera.
    const normal = this.stage.camera.getWorldDirection(new THREE.Vector3()).negate();
    this.press = {
      x: event.clientX,
      y: event.clientY,
      pointer: event.pointerId,
      hit: onCharacter ? { id: hit.owner, segment: hit.segment, local: hit.local, point: hit.point } : null,
      holds,
      touch,
      gesture,
      dragging: false,
      plane: new THREE.Plane().setFromNormalAndCoplanarPoint(normal, hit?.point ?? new THREE.Vector3()),
    };
  }

  private move(event: PointerEvent): void {
    const press = this.press;
    if (!press || event.pointerId !== press.pointer || !press.hit || !press.holds) return;
    if (!press.dragging && Math.hypot(event.clientX - press.x, event.clientY - press.y) < CLICK_SLOP) return;
    press.dragging = true;
    const target = this.ray(event).intersectPlane(press.plane, new THREE.Vector3());
    if (!target) return;
    // Never pull into the ground.
    const floor = this.stage.terrain ? groundHeight(this.stage.terrain, target.x, target.z) : 0;
    target.y = Math.max(target.y, floor + 0.02);
    this.actions.send({ type: 'drag', id: press.hit.id, segment: press.hit.segment, local: toVec3(press.hit.local), target: toVec3(target) });
  }

  private up(event: PointerEvent): void {
    const press = this.press;
    if (!press || event.pointerId !== press.pointer) return;
    this.press = null;
    this.stage.controls.enabled = true;
    if (press.dragging) {
      this.actions.send({ type: 'endDrag' });
      return;
    }
    // An orbit or a pinch.
    if (press.gesture || Math.hypot(event.clientX - press.x, event.clientY - press.y) >= CLICK_SLOP) return;
    if (press.hit) {
      this.actions.select(press.hit.id);
      return;
    }
    // A click on the ground (or a shift-click anywhere): throw a box at that point, or at the
    // character under the pointer.
    const ray = this.ray(event);
    const hit = event.shiftKey ? this.pickCharacter(ray) : null;
    if (hit && hit.owner >= 0) {
      this.throwAtCharacter(hit.owner, hit.segment, hit.local, hit.point);
      return;
    }
    const target = hit ? hit.point : this.groundPoint(ray);
    if (target) this.throwAt(target);
  }

  /** Where a ray meets the ground as the simulation has it (slopes and bumps included). */
  private groundPoint(ray: THREE.Ray): THREE.Vector3 | null {
    const grid = this.stage.terrain;
    if (!grid?.heights) return ray.intersectPlane(this.ground.set(this.ground.normal, -(grid?.plane ?? 0)), new THREE.Vector3());
    const p = intersectGround(grid, ray.origin, ray.direction);
    return p ? new THREE.Vector3(p.x, p.y, p.z) : null;
  }

  private cancel(): void {
    if (this.press?.dragging) this.actions.send({ type: 'endDrag' });
    this.press = null;
    this.stage.controls.enabled = true;
  }

  /** Where a throw towards `target` starts: just in front of the camera. */
  private throwFrom(target: THREE.Vector3): THREE.Vector3 {
    const camera = this.stage.camera.position;
    return camera.clone().add(target.clone().sub(camera).normalize().multiplyScalar(1.0));
  }

  /** Throws a box from just in front of the camera so that it lands on `target` (a point that stays put). */
  throwAt(target: THREE.Vector3): void {
    const from = this.throwFrom(target);
    const velocity = throwVelocity(from, target, throwSpeed(from.distanceTo(target)));
    this.actions.send({ type: 'throwBox', from: toVec3(from), velocity: toVec3(velocity), half: BOX_HALF });
  }

  /**
   * Throws a box at point `local` of segment `segment` of character `id`, seen at `point`. The
   * frame on screen is a frame time and a worker round trip older than the simulation the box
   * flies in, so the page names what was clicked and the simulation aims, from the character's
   * state when the throw happens, at where that point will be when the box arrives
   * (gl_sim_throw_at).
   */
  throwAtCharacter(id: number, segment: number, local: THREE.Vector3, point: THREE.Vector3): void {
    const from = this.throwFrom(point);
    const speed = throwSpeed(from.distanceTo(point));
    this.actions.send({ type: 'throwAt', from: toVec3(from), id, segment, local: toVec3(local), speed, half: BOX_HALF });
  }
}

/**
 * The selected character's marker: a flat ring at its feet, one extra draw call whatever the
 * crowd's size.
 */
export class SelectionRing {
  readonly mesh: THREE.Mesh;
  /** Orange for the selection; the optimize panel's learner has a ring of its own colour. */
  constructor(color = 0xff7a1a, radius = 0.5) {
    this.mesh = new THREE.Mesh(
      new THREE.RingGeometry(radius - 0.05, radius + 0.05, 48).rotateX(-Math.PI / 2),
      new THREE.MeshBasicMaterial({ color, transparent: true, opacity: 0.85, depthWrite: false }),
    );
    this.mesh.visible = false;
    this.mesh.renderOrder = 1;
  }

  place(position: THREE.Vector3 | null): void {
    this.mesh.visible = position !== null;
    if (position) this.mesh.position.set(position.x, 0.01, position.z);
  }
}
