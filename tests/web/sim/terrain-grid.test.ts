// The page's view of the ground (web/src/sim/terrain-grid.ts): heights between samples follow
// the triangles Bullet's heightfield makes of each cell, and the plane lies beyond the grid.
import { describe, expect, it } from 'vitest';
import { FLAT_GROUND, groundHeight, intersectGround, isTerrainKind, type TerrainGrid } from '../../../web/src/sim/terrain-grid';
import { simOptionsFromQuery, type SimOptions } from '../../../web/src/sim/protocol';

// 3 × 3 samples, 0.5 m apart, from (-0.5, -0.5).
const grid: TerrainGrid = {
  kind: 'bumps', columns: 3, rows: 3, spacing: 0.5, originX: -0.5, originZ: -0.5, plane: -0.05,
  heights: new Float32Array([
    0.0, 0.1, 0.0,
    0.2, 0.0, 0.3,
    0.0, 0.4, 0.0,
  ]),
};

describe('groundHeight', () => {
  it('is the samples at the samples', () => {
    expect(groundHeight(grid, -0.5, -0.5)).toBeCloseTo(0, 6);
    expect(groundHeight(grid, 0, -0.5)).toBeCloseTo(0.1, 6);
    expect(groundHeight(grid, -0.5, 0)).toBeCloseTo(0.2, 6);
    expect(groundHeight(grid, 0.5, 0)).toBeCloseTo(0.3, 6);
    expect(groundHeight(grid, 0, 0.5)).toBeCloseTo(0.4, 6);
  });

  it('splits each cell along the diagonal from (c+1, r) to (c, r+1)', () => {
    // Cell (0, 0): corners 0 (c, r), 0.1 (c+1, r), 0.2 (c, r+1), 0 (c+1, r+1). On the diagonal
    // the height is the mean of its two ends, whichever the other corners are.
    expect(groundHeight(grid, -0.25, -0.25)).toBeCloseTo((0.1 + 0.2) / 2, 6);
    // First triangle (fx + fz < 1) does not see the (c+1, r+1) corner...
    expect(groundHeight(grid, -0.4, -0.4)).toBeCloseTo(0 + 0.2 * 0.1 + 0.2 * 0.2, 6);
    // ...the second (fx + fz > 1) does not see (c, r).
    expect(groundHeight(grid, -0.1, -0.1)).toBeCloseTo(0 + 0.2 * (0.2 - 0) + 0.2 * (0.1 - 0), 6);
  });

  it('is the plane outside the grid, and when flat', () => {
    expect(groundHeight(grid, 0.51, 0)).toBe(-0.05);
    expect(groundHeight(grid, 0, -0.6)).toBe(-0.05);
    expect(groundHeight(FLAT_GROUND, 12, -3)).toBe(0);
  });
});

describe('intersectGround', () => {
  it('finds where a ray meets the relief, within a millimetre', () => {
    const d = { x: 0.3, y: -1, z: 0.2 };
    const n = Math.hypot(d.x, d.y, d.z);
    const p = intersectGround(grid, { x: -0.3, y: 2, z: -0.4 }, { x: d.x / n, y: d.y / n, z: d.z / n });
    expect(p).not.toBeNull();
    expect(Math.abs(p!.y - groundHeight(grid, p!.x, p!.z))).toBeLessThan(1e-3);
    expect(p!.x).toBeGreaterThan(-0.5);
    expect(p!.x).toBeLessThan(0.5);
  });
  it('meets the plane beyond the grid, and nothing when looking up', () => {
    const p = intersectGround(grid, { x: 3, y: 1, z: 0 }, { x: 0, y: -1, z: 0 });
    expect(Math.abs(p!.y + 0.05)).toBeLessThan(1e-3);
    expect(intersectGround(grid, { x: 0, y: 1, z: 0 }, { x: 0, y: 1, z: 0 })).toBeNull();
  });
});

describe('terrain kinds', () => {
  const defaults: SimOptions = { wasmUrl: '/wasm/gaitlab.mjs', threads: 2, seed: 1, characters: 6 };
  it('knows flat, slope and bumps', () => {
    expect(['flat', 'slope', 'bumps'].every(isTerrainKind)).toBe(true);
    expect(isTerrainKind('ice')).toBe(false);
    expect(isTerrainKind(undefined)).toBe(false);
  });
  it('takes the starting ground from the query', () => {
    expect(simOptionsFromQuery('?terrain=slope', defaults).terrain).toBe('slope');
    expect(simOptionsFromQuery('?terrain=bumps&seed=3', defaults)).toEqual({ ...defaults, seed: 3, terrain: 'bumps' });
    expect(simOptionsFromQuery('?terrain=flat', defaults)).toEqual(defaults);
    expect(simOptionsFromQuery('?terrain=lava', defaults)).toEqual(defaults);
  });
});
