// The ground as the simulation has it (native/src/physics/terrain.h, c_api.h "Terrain"): a square
// grid of height samples joined by triangles, and a flat plane beyond the grid. The renderer
// builds its ground mesh from these samples and the page's test hook reads ground heights from
// them, so the page never re-implements the terrain's formulas.

export const TERRAIN_KINDS = ['flat', 'slope', 'bumps'] as const;
export type TerrainKind = (typeof TERRAIN_KINDS)[number];

export interface TerrainGrid {
  kind: TerrainKind;
  /** Samples along +x and +z (0 when flat). */
  columns: number;
  rows: number;
  /** Metres between samples. */
  spacing: number;
  /** Position of sample (0, 0), metres. */
  originX: number;
  originZ: number;
  /** Height of the flat ground beyond the grid (everywhere when flat). */
  plane: number;
  /** columns × rows heights, row-major (sample (c, r) at r·columns + c); null when flat. */
  heights: Float32Array | null;
}

export function isTerrainKind(value: unknown): value is TerrainKind {
  return typeof value === 'string' && (TERRAIN_KINDS as readonly string[]).includes(value);
}

export const FLAT_GROUND: TerrainGrid = {
  kind: 'flat', columns: 0, rows: 0, spacing: 1, originX: 0, originZ: 0, plane: 0, heights: null,
};

/**
 * Height of the ground at (x, z): inside the grid the cell's triangle — each cell (c, r) is split
 * along the diagonal from (c+1, r) to (c, r+1), as Bullet's btHeightfieldTerrainShape splits it —
 * and the plane outside.
 */
export function groundHeight(grid: TerrainGrid, x: number, z: number): number {
  const h = grid.heights;
  if (!h || grid.columns < 2 || grid.rows < 2) return grid.plane;
  const u = (x - grid.originX) / grid.spacing;
  const v = (z - grid.originZ) / grid.spacing;
  if (!(u >= 0 && v >= 0 && u <= grid.columns - 1 && v <= grid.rows - 1)) return grid.plane;
  const c = Math.min(Math.floor(u), grid.columns - 2);
  const r = Math.min(Math.floor(v), grid.rows - 2);
  const fx = u - c;
  const fz = v - r;
  const at = (cc: number, rr: number) => h[rr * grid.columns + cc];
  if (fx + fz <= 1) return at(c, r) + fx * (at(c + 1, r) - at(c, r)) + fz * (at(c, r + 1) - at(c, r));
  return at(c + 1, r + 1) + (1 - fx) * (at(c, r + 1) - at(c + 1, r + 1)) + (1 - fz) * (at(c + 1, r) - at(c + 1, r + 1));
}

/**
 * Where a ray (origin, unit direction) first meets the ground within `maxDistance` metres, or
 * null: marched in steps of half a sample, then bisected to a millimetre. For clicks on the
 * ground, so that a box thrown at a point on a slope lands there.
 */
export function intersectGround(
  grid: TerrainGrid,
  origin: { x: number; y: number; z: number },
  direction: { x: number; y: number; z: number },
  maxDistance = 300,
): { x: number; y: number; z: number } | null {
  const at = (t: number) => ({ x: origin.x + direction.x * t, y: origin.y + direction.y * t, z: origin.z + direction.z * t });
  const above = (t: number) => {
    const p = at(t);
    return p.y - groundHeight(grid, p.x, p.z);
  };
  if (above(0) <= 0) return null;
  const step = Math.max(0.01, (grid.heights ? grid.spacing : 1) / 2);
  let near = 0;
  for (let far = step; far <= maxDistance; near = far, far += step) {
    if (above(far) > 0) continue;
    for (let i = 0; i < 40 && far - near > 1e-3; i++) {
      const mid = (near + far) / 2;
      if (above(mid) > 0) near = mid;
      else far = mid;
    }
    return at(far);
  }
  return null;
}
