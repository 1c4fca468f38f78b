// The peer benchmark's measurement (bench/peers/comparison.mjs), shared by the Node runner and the
// performance page's worker: the grid's order, the engines' alternation within rounds, the median
// and range, refusals, and the table. Fake engines stand in for the WebAssembly modules; nothing
// here is timed for its own sake.
import { describe, expect, it } from 'vitest';
import { measurePoint, peerGrid, tableGrid, tableRows, type PeerEngine, type PeerPoint } from '../../../bench/peers/comparison.mjs';

/** An engine whose scenes log their builds and report a fixed root height; `refuseAfter` builds then throws. */
function fakeEngine(name: PeerEngine['name'], log: string[], { refuseAfter = Infinity, runs = (): boolean => true }: { refuseAfter?: number; runs?: () => boolean } = {}): PeerEngine {
  let built = 0;
  return {
    name, label: name, runs,
    make: () => {
      if (built++ >= refuseAfter) throw new Error(`${name} refuses`);
      log.push(name);
      return { step() {}, rootHeight: () => 0.5, destroy() {} };
    },
  } as PeerEngine;
}

describe('the peer benchmark measurement', () => {
  it('measures crowds from the largest down and shows them from the smallest up', () => {
    const grid = { legs: [4, 2] as Array<2 | 4>, characters: [20, 400, 100], threads: [1, 2] };
    expect(peerGrid(grid).map((p) => `${p.legs}:${p.characters}:${p.threads}`).slice(0, 6))
      .toEqual(['4:400:1', '4:400:2', '4:100:1', '4:100:2', '4:20:1', '4:20:2']);
    expect(tableGrid(grid).map((p) => `${p.legs}:${p.characters}:${p.threads}`))
      .toEqual(['4:20:1', '4:20:2', '4:100:1', '4:100:2', '4:400:1', '4:400:2', '2:20:1', '2:20:2', '2:100:1', '2:100:2', '2:400:1', '2:400:2']);
  });

  it('alternates the engines\' order from round to round and reports the median with its range', () => {
    const log: string[] = [];
    const engines = [fakeEngine('gaitlab', log), fakeEngine('jolt-mt', log), fakeEngine('jolt', log, { runs: () => false })];
    const points = measurePoint(engines, { legs: 4, characters: 20, threads: 2 }, { steps: 2, settle: 0, rounds: 3 });
    expect(log).toEqual(['gaitlab', 'jolt-mt', 'jolt-mt', 'gaitlab', 'gaitlab', 'jolt-mt']);
    // Jolt's default build is single-threaded: not listed at all on 2 threads.
    expect(points.map((p) => p.engine)).toEqual(['gaitlab', 'jolt-mt']);
    for (const p of points) {
      expect(p.ms_min!).toBeLessThanOrEqual(p.ms_per_step!);
      expect(p.ms_per_step!).toBeLessThanOrEqual(p.ms_max!);
      expect(p.root_height_m).toBe(0.5);
      expect(p.rounds).toBeUndefined();
    }
  });

  it('keeps the rounds an engine ran before it refused a scene, and reports one that ran none as not run', () => {
    const log: string[] = [];
    const engines = [fakeEngine('gaitlab', log, { refuseAfter: 1 }), fakeEngine('jolt-mt', log, { refuseAfter: 0 })];
    const points = measurePoint(engines, { legs: 4, characters: 400, threads: 1 }, { steps: 1, settle: 0, rounds: 3 });
    const gaitlab = points.find((p) => p.engine === 'gaitlab')!;
    expect(gaitlab.rounds).toBe(1);
    expect(gaitlab.refused).toBe('not run: gaitlab refuses');
    expect(points.find((p) => p.engine === 'jolt-mt')).toEqual({ engine: 'jolt-mt', legs: 4, characters: 400, threads: 1, skipped: 'not run: jolt-mt refuses' });
    const [row] = tableRows(points, [{ legs: 4, characters: 400, threads: 1 }]);
    expect(row.slice(0, 5)).toEqual(['quadrupeds', '400', '1', `${gaitlab.ms_per_step!.toFixed(2)} (1 round)`, '—']);
  });

  it('puts gaitlab over Jolt\'s SIMD build in the table\'s last column', () => {
    const at = (engine: PeerPoint['engine'], ms: number): PeerPoint => ({ engine, legs: 2, characters: 100, threads: 1, ms_per_step: ms, ms_min: ms - 1, ms_max: ms + 1, root_height_m: 1 });
    const [row] = tableRows([at('gaitlab', 6), at('jolt-mt', 8), at('jolt', 30)], [{ legs: 2, characters: 100, threads: 1 }]);
    expect(row).toEqual(['bipeds', '100', '1', '6.00 (5.00–7.00)', '8.00 (7.00–9.00)', '30.00 (29.00–31.00)', '0.75']);
  });
});
