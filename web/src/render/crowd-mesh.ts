// Every simulated body — character segments and props — drawn as ONE InstancedMesh of a rounded
// unit box, and the parts that make a figure recognisable (heads, arms, ears, tails: figures.ts)
// as one more: two draw calls (plus the shadow pass) however many bodies there are.
//
// Each animation frame copies the newest complete frame of matrices from the shared render
// buffer straight into instanceMatrix (docs/design.md, data flow step 3). The matrices arrive with
// each box's size baked in, in three.js's column-major layout, so no per-body work is done here.
import * as THREE from 'three';
import { MATRIX_FLOATS, type FrameMeta, type RenderBufferReader } from '../sim/render-buffer';
import { Figures, roundedUnitBox } from './figures';

export class CrowdMesh {
  /** Parent of the instanced mesh; the mesh itself is replaced when the capacity changes. */
  readonly group = new THREE.Group();
  private readonly geometry = roundedUnitBox();
  private figures: Figures | null = null;
  private readonly material = new THREE.MeshStandardMaterial({ color: 0xffffff, roughness: 0.65, metalness: 0 });
  private mesh: THREE.InstancedMesh | null = null;
  private reader: RenderBufferReader | null = null;
  private lastSeq = -1;
  /** infoVersion and body count the instance colours were last read for. */
  private colouredVersion = -1;
  private colouredCount = 0;
  private readonly colour = new THREE.Color();
  /** The frame on screen. */
  frame: FrameMeta | null = null;
  /**
   * Owner (character id, −1 for props) of each body on screen, read from BodyInfo with the
   * colours; a character's bodies are contiguous and in morphology order, its root first.
   */
  owners = new Int32Array(0);

  /** Draws from `reader`'s render buffer from now on (a new scene). */
  attach(reader: RenderBufferReader): void {
    this.reader = reader;
    this.lastSeq = -1;
    this.colouredVersion = -1;
    this.colouredCount = 0;
    this.frame = null;
    if (!this.mesh || this.mesh.instanceMatrix.count !== Math.max(1, reader.capacity)) {
      if (this.mesh) {
        this.group.remove(this.mesh);
        this.mesh.dispose();
      }
      // The capacity comes from the header: the buffers never hold more bodies than that.
      const capacity = Math.max(1, reader.capacity);
      const mesh = new THREE.InstancedMesh(this.geometry, this.material, capacity);
      mesh.instanceMatrix.setUsage(THREE.DynamicDrawUsage);
      // Created up front (white) so the shader is built with per-instance colour from the start.
      mesh.instanceColor = new THREE.InstancedBufferAttribute(new Float32Array(capacity * 3).fill(1), 3);
      mesh.castShadow = true;
      mesh.receiveShadow = true;
      // The bounding sphere is computed once from the matrices; bodies move, so never cull.
      mesh.frustumCulled = false;
      this.mesh = mesh;
      this.group.add(mesh);
      if (this.figures) {
        this.group.remove(this.figures.mesh, this.figures.contacts);
        this.figures.dispose();
      }
      // At most as many parts as bodies: a biped has 6 parts for 7 bodies, a dog 6 for 18.
      this.figures = new Figures(this.geometry, this.material, capacity);
      this.group.add(this.figures.mesh, this.figures.contacts);
    }
    this.mesh.count = 0;
  }

  /**
   * Stops reading the render buffer (it is about to be freed). The last frame stays on screen
   * until the next attach().
   */
  detach(): void {
    this.reader = null;
  }

  /**
   * Brings the instances up to the newest published frame. Returns false when no new frame was
   * published since the last call (or it could not be read consistently this time).
   */
  update(): boolean {
    const { reader, mesh } = this;
    if (!reader || !mesh) return false;
    if (reader.seq() === this.lastSeq) return false;
    const matrices = mesh.instanceMatrix;
    const frame = reader.readFrame(matrices.array as Float32Array);
    if (!frame) return false;
    this.lastSeq = frame.seq;
    this.frame = frame;
    mesh.count = frame.bodyCount;
    // Upload only the part in use.
    matrices.clearUpdateRanges();
    matrices.addUpdateRange(0, frame.bodyCount * MATRIX_FLOATS);
    matrices.needsUpdate = true;
    this.updateColours(reader, mesh, frame.bodyCount);
    this.figures?.update(matrices.array as Float32Array, this.owners, frame.bodyCount);
    return true;
  }

  /**
   * Re-reads BodyInfo colours when bodies were added or removed. Entries below a published
   * frame's body count are complete (they are written before the frame that uses them).
   */
  private updateColours(reader: RenderBufferReader, mesh: THREE.InstancedMesh, bodyCount: number): void {
    const version = reader.infoVersion();
    if (version === this.colouredVersion && bodyCount <= this.colouredCount) return;
    if (this.owners.length < bodyCount) this.owners = new Int32Array(mesh.instanceMatrix.count);
    for (let i = 0; i < bodyCount; i++) {
      const info = reader.bodyInfo(i);
      // 0xRRGGBBAA, sRGB; alpha is not used (every body is opaque).
      mesh.setColorAt(i, this.colour.setHex(info.rgba >>> 8, THREE.SRGBColorSpace));
      this.owners[i] = info.owner;
    }
    if (mesh.instanceColor) mesh.instanceColor.needsUpdate = true;
    this.colouredVersion = version;
    this.colouredCount = bodyCount;
  }

  /** The instance matrices on screen (count × 16 floats, column-major, box scale baked in). */
  matrices(): { array: Float32Array; count: number } {
    return { array: (this.mesh?.instanceMatrix.array as Float32Array) ?? new Float32Array(0), count: this.mesh?.count ?? 0 };
  }

  /** Index of character `id`'s first body (its root leg frame) on screen, or −1. */
  firstBodyOf(id: number): number {
    const count = Math.min(this.mesh?.count ?? 0, this.owners.length);
    for (let i = 0; i < count; i++) if (this.owners[i] === id) return i;
    return -1;
  }

  /** Centre of body `index` on screen. */
  bodyPosition(index: number, target: THREE.Vector3): THREE.Vector3 {
    const m = this.mesh!.instanceMatrix.array;
    return target.set(m[index * MATRIX_FLOATS + 12], m[index * MATRIX_FLOATS + 13], m[index * MATRIX_FLOATS + 14]);
  }

  /** Centre and radius of the bodies on screen (for framing the camera), or null if none. */
  bounds(): THREE.Sphere | null {
    const mesh = this.mesh;
    if (!mesh || mesh.count === 0) return null;
    const box = new THREE.Box3();
    const m = mesh.instanceMatrix.array;
    const point = new THREE.Vector3();
    for (let i = 0; i < mesh.count; i++) {
      const o = i * MATRIX_FLOATS;
      box.expandByPoint(point.set(m[o + 12], m[o + 13], m[o + 14]));
    }
    return box.getBoundingSphere(new THREE.Sphere());
  }

  dispose(): void {
    this.mesh?.dispose();
    this.geometry.dispose();
    this.material.dispose();
  }
}
