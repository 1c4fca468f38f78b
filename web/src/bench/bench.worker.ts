// The benchmark worker: loads the same WASM module as the demo's sim worker (with its pthread
// pool) and runs the experiment point by point through gl_bench_point, the code `gaitlab bench`
// runs natively (native/src/sim/experiment.cpp). Like the sim worker it is the module's "main
// thread": a point blocks it while the pool's threads work.
import { bench, CROWD_SHARDS, LEGS, loadGaitlab, MODE, type GaitlabModule } from '../sim/gaitlab-wasm';
import { searchCapacity } from './capacity';
import type { BenchCommand, BenchEvent } from './protocol';

interface WorkerScope {
  postMessage(message: BenchEvent): void;
  onmessage: ((event: MessageEvent<BenchCommand>) => void) | null;
}
const scope = self as unknown as WorkerScope;
const post = (event: BenchEvent) => scope.postMessage(event);

let module: GaitlabModule | null = null;
let cancelled = false;

const yieldToMessages = () => new Promise<void>((resolve) => setTimeout(resolve, 0));

/**
 * The module, loaded once for every run and capacity search, its aborts posted to the page. Its
 * pthread pool serves every core, or the first command's thread counts if they ask for more (the
 * page measures counts above the hardware's too, and flags them); a later point on more threads
 * than that is refused by gl_bench_point.
 */
const loadModule = (wasmUrl: string, threads: number) =>
  loadGaitlab(wasmUrl, {
    printErr: (text) => console.warn(`[gaitlab] ${text}`),
    onAbort: (what) => post({ type: 'error', message: `the WASM module aborted: ${String(what)}` }),
    poolThreads: Math.max(navigator.hardwareConcurrency || 1, threads),
  });

async function run(command: Extract<BenchCommand, { type: 'run' }>): Promise<void> {
  if (!crossOriginIsolated) throw new Error('the page is not cross-origin isolated: no WASM threads');
  module ??= await loadModule(command.wasmUrl, Math.max(1, ...command.grid.map((p) => p.threads)));
  const m = module;
  post({ type: 'machine', machine: bench.machine(m) });
  const { inputs } = command;
  // Refuse a crowd larger than a simulation holds before measuring anything.
  for (const p of command.grid) {
    const most = bench.maxCharacters(m, LEGS[p.legs]);
    if (p.characters > most) {
      throw new Error(`${p.characters} ${p.legs === 'mixed' ? 'mixed characters' : p.legs === 2 ? 'bipeds' : 'quadrupeds'} is more than a simulation holds (${most})`);
    }
  }
  // Untimed, so that the engine has compiled the hot code with its optimising tier before the
  // first point is timed (sim::warmUp).
  post({ type: 'status', message: 'warming up (untimed)' });
  const warmThreads = Math.max(...command.grid.map((p) => p.threads));
  for (const legs of new Set(command.grid.map((p) => p.legs))) bench.warmUp(m, LEGS[legs], warmThreads);
  // The warm-up runs the full mode on every thread; the first point (serial, one thread, the
  // smallest crowd) still ran slower than when repeated (its ratio read "1 : 0"): run it once
  // untimed, as it will be timed, so that its own code paths are warm too.
  if (command.grid.length > 0) {
    const p = command.grid[0];
    bench.point(m, {
      legs: LEGS[p.legs], characters: p.characters, threads: p.threads, mode: MODE[p.mode], steps: Math.min(inputs.steps, 120),
      runs: 1, shards: inputs.shards, spacing: inputs.spacing_m, seed: inputs.seed, frames: 0,
    });
  }
  for (let i = 0; i < command.grid.length; i++) {
    // Let a 'cancel' message in between points.
    await yieldToMessages();
    if (cancelled) break;
    const p = command.grid[i];
    const t0 = performance.now();
    const point = bench.point(m, {
      legs: LEGS[p.legs], characters: p.characters, threads: p.threads, mode: MODE[p.mode], steps: inputs.steps,
      runs: inputs.runs, shards: inputs.shards, spacing: inputs.spacing_m, seed: inputs.seed, frames: inputs.frames ? 1 : 0,
    });
    post({ type: 'point', index: i, point, seconds: (performance.now() - t0) / 1000 });
  }
  post({ type: 'done', cancelled });
}

/**
 * The capacity search (capacity.ts) for bipeds, then quadrupeds: full mode on `threads` threads,
 * 240 steps a crowd (2 s simulated), one run; each type's search stops once `secondsPerType` are
 * spent (with the best answer so far). The quadrupeds' crowd is bounded by the module's memory
 * (gl_bench_max_characters, asked again before each probe), and both by the probes' caps.
 */
async function capacityRun(command: Extract<BenchCommand, { type: 'capacity' }>): Promise<void> {
  if (!crossOriginIsolated) throw new Error('the page is not cross-origin isolated: no WASM threads');
  module ??= await loadModule(command.wasmUrl, command.threads);
  const m = module;
  post({ type: 'machine', machine: bench.machine(m) });
  for (const legs of [2, 4] as const) {
    post({ type: 'status', message: `warming up ${legs === 2 ? 'bipeds' : 'quadrupeds'} (untimed)` });
    bench.warmUp(m, LEGS[legs], command.threads);
    const t0 = performance.now();
    const most = Math.min(bench.maxCharacters(m, LEGS[legs]), legs === 2 ? 1200 : 400);
    const result = await searchCapacity(async (characters) => {
      await yieldToMessages();
      if (cancelled || (performance.now() - t0) / 1000 > command.secondsPerType) return Infinity;
      // The module's room shrinks as probes come and go (freed solver pools below the heap's
      // break are not counted as room: README "Limits"), so it is asked again before each probe;
      // a crowd it cannot hold ends the search as one skipped ("at least").
      if (characters > bench.maxCharacters(m, LEGS[legs])) {
        post({ type: 'status', message: `the module's memory holds no more than ${bench.maxCharacters(m, LEGS[legs])} ${legs === 2 ? 'bipeds' : 'quadrupeds'} now` });
        return Infinity;
      }
      const point = bench.point(m, { legs: LEGS[legs], characters, threads: command.threads, mode: MODE.full, steps: 240, runs: 1, shards: CROWD_SHARDS, spacing: 4, seed: 1, frames: 0 });
      const stepMs = (point.step_ms as { mean: number }).mean;
      post({ type: 'capacityProbe', legs, characters, stepMs });
      return stepMs;
    }, { most, start: legs === 2 ? 64 : 16 });
    // A probe skipped for time or a cancel counts as "over" in the search: not as a measurement.
    const over = result.over && Number.isFinite(result.over.stepMs) ? result.over : null;
    const stopped = result.over !== null && !Number.isFinite(result.over.stepMs);
    post({ type: 'capacity', legs, within: result.within, over, seconds: (performance.now() - t0) / 1000, stopped });
    if (cancelled) break;
  }
  post({ type: 'done', cancelled });
}

scope.onmessage = (event) => {
  const command = event.data;
  if (command.type === 'cancel') {
    cancelled = true;
  } else if (command.type === 'capacity') {
    cancelled = false;
    capacityRun(command).catch((error: unknown) =>
      post({ type: 'error', message: error instanceof Error ? error.message : String(error) }));
  } else if (command.type === 'run') {
    cancelled = false;
    run(command).catch((error: unknown) =>
      post({ type: 'error', message: error instanceof Error ? error.message : String(error) }));
  }
};
