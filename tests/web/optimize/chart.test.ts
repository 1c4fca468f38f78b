// The optimize panel's chart helpers (web/src/optimize/chart.ts): a y range fitted to the best
// objective's values, and tick labels with just enough decimals to tell the ticks apart.
import { describe, expect, it } from 'vitest';
import { fitRange, tickLabels } from '../../../web/src/optimize/chart';

describe('the chart of the best objective', () => {
  it('fits the y range to the values with a margin', () => {
    expect(fitRange(0.5, 1.5)).toEqual([0.42, 1.58]);
    // One value (the first generation): a margin of its own size, not a zero-height range.
    const [lo, hi] = fitRange(127, 127);
    expect(lo).toBeCloseTo(120.65);
    expect(hi).toBeCloseTo(133.35);
    expect(fitRange(0, 0)).toEqual([-1e-3, 1e-3]);
    expect(fitRange(Number.NaN, 1)).toEqual([0, 1]);
  });

  it('labels ticks with the decimals they need and no more', () => {
    expect(tickLabels([100, 120, 140])).toEqual(['100', '120', '140']);
    expect(tickLabels([0.5625, 0.563, 0.5635, 0.564])).toEqual(['0.5625', '0.5630', '0.5635', '0.5640']);
    // Floating-point sums from the axis's increments read as the numbers they stand for.
    expect(tickLabels([0.1, 0.1 + 0.2, 0.5])).toEqual(['0.1', '0.3', '0.5']);
    expect(tickLabels([2.5, 5, 7.5])).toEqual(['2.5', '5.0', '7.5']);
  });
});
