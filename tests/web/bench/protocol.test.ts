// The performance page's grid: the same points, in the same order, as `gaitlab bench`
// (native/src/api/cli_bench.cpp), and the same list syntax as its --characters.
import { describe, expect, it } from 'vitest';
import { buildGrid, parseList, pointCost, type BenchInputs } from '../../../web/src/bench/protocol';

const inputs: BenchInputs = {
  legs: [2, 4], characters: [1, 5], threads: [1, 2], modes: ['serial', 'controller', 'full'],
  steps: 10, runs: 2, shards: 12, spacing_m: 4, seed: 1, step_hz: 120, frames: false,
};

describe('buildGrid', () => {
  it('runs serial once, with one thread, and every other mode per thread count', () => {
    const grid = buildGrid(inputs);
    expect(grid).toHaveLength(2 * (1 + 2 + 2) * 2);
    expect(grid.filter((p) => p.mode === 'serial').every((p) => p.threads === 1)).toBe(true);
    expect(grid.slice(0, 6)).toEqual([
      { legs: 2, characters: 1, threads: 1, mode: 'serial' },
      { legs: 2, characters: 5, threads: 1, mode: 'serial' },
      { legs: 2, characters: 1, threads: 1, mode: 'controller' },
      { legs: 2, characters: 5, threads: 1, mode: 'controller' },
      { legs: 2, characters: 1, threads: 2, mode: 'controller' },
      { legs: 2, characters: 5, threads: 2, mode: 'controller' },
    ]);
  });
});

describe('parseList', () => {
  it('reads numbers and ranges with a step, always ending a range with its last value', () => {
    expect(parseList('1-100:25', 1, 2000)).toEqual([1, 26, 51, 76, 100]);
    expect(parseList('1,3-5', 1, 10)).toEqual([1, 3, 4, 5]);
  });
  it('refuses what the CLI refuses', () => {
    expect(() => parseList('0-5', 1, 100)).toThrow(/outside/);
    expect(() => parseList('x', 1, 100)).toThrow(/not a number/);
    expect(() => parseList('5-2', 1, 100)).toThrow(/outside/);
  });
});

describe('pointCost', () => {
  it('grows with the crowd and shrinks with threads only when the physics is parallel', () => {
    const p = { legs: 4 as const, characters: 10, threads: 2, mode: 'controller' as const };
    expect(pointCost({ ...p, characters: 20 }, inputs)).toBeGreaterThan(pointCost(p, inputs));
    expect(pointCost({ ...p, mode: 'full' }, inputs)).toBeLessThan(pointCost(p, inputs));
  });
});
