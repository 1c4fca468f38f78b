// The capacity search (web/src/bench/capacity.ts) against crowds whose step time is known.
import { describe, expect, it } from 'vitest';
import { searchCapacity } from '../../../web/src/bench/capacity';

describe('searchCapacity', () => {
  it('finds the largest crowd within 8.33 ms to 3 %, doubling then bisecting, in few probes', async () => {
    // 0.2 ms plus 15 µs a character: 8.33 ms is reached at 542 characters.
    const result = await searchCapacity((n) => 0.2 + 0.015 * n, { most: 1200 });
    expect(result.within!.characters).toBeLessThanOrEqual(542);
    expect(result.within!.characters).toBeGreaterThanOrEqual(542 * 0.97);
    expect(result.over!.characters).toBeGreaterThan(542);
    expect(result.over!.characters - result.within!.characters).toBeLessThanOrEqual(Math.ceil(result.within!.characters * 0.03));
    expect(result.probes.length).toBeLessThanOrEqual(12);
    expect(result.probes.slice(0, 6).map((p) => p.characters)).toEqual([16, 32, 64, 128, 256, 512]);
  });

  it('stops at the most the page builds when everything fits, and says nothing was over', async () => {
    const result = await searchCapacity(() => 1, { most: 300 });
    expect(result.within!.characters).toBe(300);
    expect(result.over).toBeNull();
  });

  it('reports no crowd within when even the first is over', async () => {
    const result = await searchCapacity(() => 20, { most: 300, start: 16 });
    expect(result.within?.characters ?? 0).toBeLessThan(16);
    expect(result.over).not.toBeNull();
  });
});
