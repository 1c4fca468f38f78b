// The benchmark worker: loads the same WASM module as the demo's sim worker (with its pthread
// pool) and runs the experiment point by point through gl_bench_point, the code `gaitlab bench`
// runs natively (native/src/sim/experiment.cpp). Like the sim worker it is the module's "main
// thread": a point blocks it while the pool's threads work.
import { bench, LEGS, loadGaitlab, MODE, type GaitlabModule } from '../sim/gaitlab-wasm';
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

async function run(command: Extract<BenchCommand, { type: 'run' }>): Promise<void> {
  if (!crossOriginIsolated) throw new Error('the page is not cross-origin isolated: no WASM threads');
  module ??= await loadGaitlab(command.wasmUrl, {
    printErr: (text) => console.warn(`[gaitlab] ${text}`),
    onAbort: (what) => post({ type: 'error', message: `the WASM module aborted: ${String(what)}` }),
  });
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

scope.onmessage = (event) => {
  const command = event.data;
  if (command.type === 'cancel') {
    cancelled = true;
  } else if (command.type === 'run') {
    cancelled = false;
    run(command).catch((error: unknown) =>
      post({ type: 'error', message: error instanceof Error ? error.message : String(error) }));
  }
};
