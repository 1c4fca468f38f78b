// Messages between the performance page (main thread) and its benchmark worker. The worker owns
// the WASM module (with its pthread pool) and runs one point of the experiment per C API call
// (gl_bench_point), so progress is reported and a cancel is honoured between points.

/** One point of the experiment, as gl_bench_point takes it. */
export interface PointSpec {
  /** 2 bipeds, 4 quadrupeds, 'mixed' (alternating). */
  legs: 2 | 4 | 'mixed';
  characters: number;
  threads: number;
  mode: 'serial' | 'controller' | 'full';
}

/** The experiment's inputs: the same fields as a document's "inputs" (bench/schema.json). */
export interface BenchInputs {
  legs: Array<2 | 4 | 'mixed'>;
  characters: number[];
  threads: number[];
  modes: Array<'serial' | 'controller' | 'full'>;
  steps: number;
  runs: number;
  shards: number;
  spacing_m: number;
  seed: number;
  step_hz: 120;
  frames: boolean;
}

export type BenchCommand =
  | { type: 'run'; wasmUrl: string; inputs: BenchInputs; grid: PointSpec[] }
  /**
   * "How many can this device run?": the real-time capacity at 120 Hz of bipeds, then of
   * quadrupeds, full mode on `threads` threads (capacity.ts), each search at most `secondsPerType`.
   */
  | { type: 'capacity'; wasmUrl: string; threads: number; secondsPerType: number }
  | { type: 'cancel' };

export type BenchEvent =
  | { type: 'machine'; machine: Record<string, unknown> }
  /** What the worker is doing before the first point (the untimed warm-up). */
  | { type: 'status'; message: string }
  /** `point` is the JSON element of "points" for grid[index]. */
  | { type: 'point'; index: number; point: Record<string, unknown>; seconds: number }
  | { type: 'done'; cancelled: boolean }
  /** A crowd the capacity search measured: its mean whole step. */
  | { type: 'capacityProbe'; legs: 2 | 4; characters: number; stepMs: number }
  /**
   * A type's capacity: the largest crowd measured within 8.33 ms a step, and the smallest over;
   * `stopped` when the time limit (or a cancel) ended the search before it closed in.
   */
  | { type: 'capacity'; legs: 2 | 4; within: { characters: number; stepMs: number } | null; over: { characters: number; stepMs: number } | null; seconds: number; stopped: boolean }
  | { type: 'error'; message: string };

/**
 * The grid of points for the inputs, in the order `gaitlab bench` runs them: per leg count, per
 * mode, per thread count, per crowd size; serial once, with 1 thread.
 */
export function buildGrid(inputs: BenchInputs): PointSpec[] {
  const grid: PointSpec[] = [];
  for (const legs of inputs.legs) {
    for (const mode of inputs.modes) {
      for (const threads of inputs.threads) {
        if (mode === 'serial' && threads !== inputs.threads[0]) continue;
        for (const characters of inputs.characters) {
          grid.push({ legs, characters, threads: mode === 'serial' ? 1 : threads, mode });
        }
      }
    }
  }
  return grid;
}

/**
 * Relative cost of a point, for the time-left estimate: the physics dominates and grows with the
 * bodies simulated (a quadruped has 18 segments, a biped 7), over the threads that share it.
 */
export function pointCost(p: PointSpec, inputs: Pick<BenchInputs, 'steps' | 'runs'>): number {
  const bodies = p.legs === 2 ? 7 : p.legs === 4 ? 18 : 12.5;
  const parallel = p.mode === 'full' ? p.threads : 1;
  return (inputs.steps * inputs.runs * (0.2 + p.characters * bodies)) / parallel;
}

/** Parses "1-100:10,150" like the CLI's --characters. Throws on bad input. */
export function parseList(text: string, lo: number, hi: number): number[] {
  const out: number[] = [];
  for (const item of text.split(',').map((s) => s.trim())) {
    const m = /^(\d+)(?:-(\d+)(?::(\d+))?)?$/.exec(item);
    if (!m) throw new Error(`'${item}' is not a number or a range A-B[:STEP]`);
    const a = Number(m[1]);
    const b = m[2] === undefined ? a : Number(m[2]);
    const step = m[3] === undefined ? 1 : Number(m[3]);
    if (a < lo || b > hi || b < a || step < 1) throw new Error(`'${item}' is outside [${lo}, ${hi}]`);
    for (let v = a; v <= b; v += step) out.push(v);
    if (out[out.length - 1] !== b) out.push(b);
  }
  return out;
}
