// The ground's relief, drawn from the samples the physics collides with (sim/terrain-grid.ts):
// every vertex is a sample, every cell the two triangles Bullet's heightfield makes of it. Nothing
// here knows what a slope or a bump is.
//
// A bumps grid has 1921² samples (every 12.5 cm over ±120 m): too many to draw at once. So the
// relief is two meshes:
//   - near: every sample within WINDOW metres of the point the camera looks at, rebuilt when that
//     point moves on; this is where the characters one watches stand, drawn exactly;
//   - far: the whole grid at a stride of several samples (still samples, so no cracks against the
//     plane beyond), with the near window cut out of it in its fragment shader.
// A grid small enough to draw whole (a slope: 481² samples) is one mesh.
import * as THREE from 'three';
import type { TerrainGrid } from '../sim/terrain-grid';

/** Half-size (metres) of the full-resolution window around the camera's target. */
const WINDOW = 24;
/** The window is rebuilt when the target is this far from its centre. */
const RECENTRE = 8;
/** Most samples along a side drawn in one mesh. */
const MAX_SIDE = 481;

export class TerrainMesh {
  readonly group = new THREE.Group();
  private near: THREE.Mesh | null = null;
  private far: THREE.Mesh | null = null;
  private readonly nearMaterial: THREE.MeshStandardMaterial;
  private readonly farMaterial: THREE.MeshStandardMaterial;
  /** The cut-out of the far mesh: (min x, min z, max x, max z) of the near window. */
  private readonly hole = { value: new THREE.Vector4(1, 1, -1, -1) };
  private centre: { c: number; r: number } | null = null;

  constructor(
    private readonly grid: TerrainGrid,
    material: THREE.MeshStandardMaterial,
  ) {
    this.group.name = 'terrain';
    // Drawn over the plane where they meet at the grid's border (the relief blends into it).
    const base = material.clone();
    base.polygonOffset = true;
    base.polygonOffsetFactor = -1;
    base.polygonOffsetUnits = -1;
    this.nearMaterial = base;
    this.farMaterial = base.clone();
    const hole = this.hole;
    this.farMaterial.onBeforeCompile = (shader) => {
      shader.uniforms.terrainHole = hole;
      shader.vertexShader = shader.vertexShader
        .replace('#include <common>', '#include <common>\nvarying vec2 vTerrainXZ;')
        .replace('#include <worldpos_vertex>', '#include <worldpos_vertex>\nvTerrainXZ = (modelMatrix * vec4(transformed, 1.0)).xz;');
      shader.fragmentShader = shader.fragmentShader
        .replace('#include <common>', '#include <common>\nvarying vec2 vTerrainXZ;\nuniform vec4 terrainHole;')
        .replace(
          'void main() {',
          'void main() {\n  if (all(greaterThan(vTerrainXZ, terrainHole.xy)) && all(lessThan(vTerrainXZ, terrainHole.zw))) discard;',
        );
    };
    this.farMaterial.customProgramCacheKey = () => 'terrain-far';

    const g = this.grid;
    const stride = Math.max(1, Math.ceil((Math.max(g.columns, g.rows) - 1) / (MAX_SIDE - 1)));
    this.far = this.build(0, g.columns - 1, 0, g.rows - 1, stride, stride === 1 ? this.nearMaterial : this.farMaterial);
    this.group.add(this.far);
    if (stride === 1) this.far.name = 'terrain-all';
    else this.far.name = 'terrain-far';
  }

  /** Whether the far mesh is decimated and a near window follows the camera. */
  get windowed(): boolean {
    return this.far?.material === this.farMaterial;
  }

  /** Keeps the full-resolution window around `target` (the camera's point of interest). */
  follow(target: THREE.Vector3): void {
    if (!this.windowed) return;
    const g = this.grid;
    const c = Math.round((target.x - g.originX) / g.spacing);
    const r = Math.round((target.z - g.originZ) / g.spacing);
    const limit = RECENTRE / g.spacing;
    if (this.centre && Math.abs(c - this.centre.c) < limit && Math.abs(r - this.centre.r) < limit) return;
    this.centre = { c, r };
    const half = Math.round(WINDOW / g.spacing);
    const c0 = Math.max(0, c - half);
    const c1 = Math.min(g.columns - 1, c + half);
    const r0 = Math.max(0, r - half);
    const r1 = Math.min(g.rows - 1, r + half);
    if (this.near) {
      this.group.remove(this.near);
      this.near.geometry.dispose();
      this.near = null;
    }
    if (c1 <= c0 || r1 <= r0) {
      this.hole.value.set(1, 1, -1, -1);
      return;
    }
    this.near = this.build(c0, c1, r0, r1, 1, this.nearMaterial);
    this.near.name = 'terrain-near';
    this.group.add(this.near);
    // The far mesh gives way a little inside the window's edge: the two overlap there rather than
    // leave a gap (where both draw, the near one is exact and the far one within millimetres).
    const inset = g.spacing * 0.5;
    this.hole.value.set(
      g.originX + c0 * g.spacing + inset,
      g.originZ + r0 * g.spacing + inset,
      g.originX + c1 * g.spacing - inset,
      g.originZ + r1 * g.spacing - inset,
    );
  }

  dispose(): void {
    for (const mesh of [this.near, this.far]) mesh?.geometry.dispose();
    this.nearMaterial.dispose();
    this.farMaterial.dispose();
  }

  /**
   * Samples c0..c1 × r0..r1 every `stride` samples (the last row and column always included) as
   * one mesh: positions are the samples, normals by central differences over neighbouring samples,
   * uv the world's x and z in metres (the ground texture's grid repeats every metre).
   */
  private build(c0: number, c1: number, r0: number, r1: number, stride: number, material: THREE.Material): THREE.Mesh {
    const g = this.grid;
    const h = g.heights!;
    const steps = (a: number, b: number) => {
      const out: number[] = [];
      for (let i = a; i < b; i += stride) out.push(i);
      out.push(b);
      return out;
    };
    const cols = steps(c0, c1);
    const rows = steps(r0, r1);
    const n = cols.length * rows.length;
    const position = new Float32Array(n * 3);
    const normal = new Float32Array(n * 3);
    const uv = new Float32Array(n * 2);
    const at = (c: number, r: number) => h[r * g.columns + c];
    let v = 0;
    for (const r of rows) {
      for (const c of cols) {
        const x = g.originX + c * g.spacing;
        const z = g.originZ + r * g.spacing;
        position.set([x, at(c, r), z], v * 3);
        const cl = Math.max(0, c - 1), cr = Math.min(g.columns - 1, c + 1);
        const rl = Math.max(0, r - 1), rr = Math.min(g.rows - 1, r + 1);
        const dx = (at(cr, r) - at(cl, r)) / ((cr - cl) * g.spacing);
        const dz = (at(c, rr) - at(c, rl)) / ((rr - rl) * g.spacing);
        const len = Math.hypot(dx, 1, dz);
        normal.set([-dx / len, 1 / len, -dz / len], v * 3);
        uv.set([x, z], v * 2);
        v++;
      }
    }
    // Each cell as Bullet splits it: (c, r) (c, r+1) (c+1, r) and (c+1, r) (c, r+1) (c+1, r+1),
    // counter-clockwise seen from above.
    const w = cols.length;
    const cells = (cols.length - 1) * (rows.length - 1);
    const index = n > 65535 ? new Uint32Array(cells * 6) : new Uint16Array(cells * 6);
    let k = 0;
    for (let j = 0; j + 1 < rows.length; j++) {
      for (let i = 0; i + 1 < w; i++) {
        const a = j * w + i, b = (j + 1) * w + i, d = j * w + i + 1, e = (j + 1) * w + i + 1;
        index[k++] = a; index[k++] = b; index[k++] = d;
        index[k++] = d; index[k++] = b; index[k++] = e;
      }
    }
    const geometry = new THREE.BufferGeometry();
    geometry.setAttribute('position', new THREE.BufferAttribute(position, 3));
    geometry.setAttribute('normal', new THREE.BufferAttribute(normal, 3));
    geometry.setAttribute('uv', new THREE.BufferAttribute(uv, 2));
    geometry.setIndex(new THREE.BufferAttribute(index, 1));
    geometry.computeBoundingSphere();
    const mesh = new THREE.Mesh(geometry, material);
    mesh.receiveShadow = true;
    return mesh;
  }
}
