// The optimize panel's chart of the best objective per generation: its y range and tick labels
// (pure: unit-tested in tests/web). The search's improvements are often a fraction of a per
// cent of the objective, so the axis fits the values and its labels carry the decimals needed.

/** Tick labels with the fewest decimals that still tell every tick apart (0.5635, 0.5640…). */
export function tickLabels(splits: number[]): string[] {
  for (let decimals = 0; decimals <= 10; decimals++) {
    const labels = splits.map((v) => v.toFixed(decimals));
    if (new Set(labels).size === labels.length && splits.every((v, i) => Math.abs(Number(labels[i]) - v) <= Math.abs(v) * 1e-9 + 1e-12)) return labels;
  }
  return splits.map((v) => v.toPrecision(6));
}

/** The chart's y range: the values with a margin (a flat line gets one of its own size). */
export function fitRange(min: number, max: number): [number, number] {
  if (!Number.isFinite(min) || !Number.isFinite(max)) return [0, 1];
  const pad = max > min ? (max - min) * 0.08 : Math.max(Math.abs(max) * 0.05, 1e-3);
  return [min - pad, max + pad];
}

