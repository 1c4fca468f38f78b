// "How many can this device run?": the real-time capacity at 120 Hz (the most characters whose
// mean whole step fits the 1/120 s budget, full mode, all threads: the README's capacity table)
// found by a search over crowd sizes instead of the experiment's fixed grid, so that it answers in
// under two minutes. Doubling from a small crowd until a step is over budget, then bisecting
// between the last crowd within it and the first over it, to about 3 %.
import { STEP_BUDGET_MS } from '../../../bench/lib/analysis.mjs';

export interface CapacityProbe {
  characters: number;
  /** Mean whole step, ms. */
  stepMs: number;
}

export interface CapacityResult {
  /** The largest crowd measured within the budget (0 if not even the first), and its step. */
  within: CapacityProbe | null;
  /** The smallest crowd measured over it (null if the largest crowd tried fits). */
  over: CapacityProbe | null;
  probes: CapacityProbe[];
}

/**
 * Searches for the capacity, measuring crowds with `measure` (one benchmark point each), from
 * `start` characters up to `most` (the largest crowd the page may build), within a bound on the
 * number of probes. `measure` may be asynchronous (the worker yields to messages between points).
 */
export async function searchCapacity(
  measure: (characters: number) => Promise<number> | number,
  { start = 16, most, budgetMs = STEP_BUDGET_MS, precision = 0.03, maxProbes = 12 }: { start?: number; most: number; budgetMs?: number; precision?: number; maxProbes?: number },
): Promise<CapacityResult> {
  const probes: CapacityProbe[] = [];
  let within: CapacityProbe | null = null;
  let over: CapacityProbe | null = null;
  const probe = async (characters: number) => {
    const p = { characters, stepMs: await measure(characters) };
    probes.push(p);
    if (p.stepMs <= budgetMs) within = p;
    else over = p;
    return p;
  };
  // Doubling.
  for (let n = Math.min(start, most); probes.length < maxProbes; n = Math.min(most, n * 2)) {
    const p = await probe(n);
    if (p.stepMs > budgetMs || n >= most) break;
  }
  // Bisection between the largest crowd within and the smallest over.
  while (probes.length < maxProbes && over !== null) {
    const lo: number = (within as CapacityProbe | null)?.characters ?? 0;
    const hi: number = (over as CapacityProbe).characters;
    if (hi - lo <= Math.max(1, Math.ceil(lo * precision))) break;
    await probe(Math.floor((lo + hi) / 2));
  }
  return { within, over, probes };
}
