// The benchmark worker: loads the same WASM module as the demo's sim worker (with its pthread
// pool) and runs the experiment point by point through gl_bench_point, the code `gaitlab bench`
// runs natively (native/src/sim/experiment.cpp). Like the sim worker it is the module's "main
// thread": a point blocks it while the pool's threads work.
import { loadGaitlab, type GaitlabModule } from '../sim/gaitlab-wasm';
import type { BenchCommand, BenchEvent } from './protocol';

/** The benchmark part of the C API (c_api.h, "Benchmark"). */
interface BenchModule extends GaitlabModule {
  _gl_bench_machine(): number;
  _gl_bench_max_characters(legs: number): number;
  _gl_bench_warm_up(legs: number, threads: number): void;
  _gl_bench_point(legs: number, characters: number, threads: number, mode: number, steps: number,
    runs: number, shards: number, spacing: number, seed: number, frames: number): number;
}

interface WorkerScope {
  postMessage(message: BenchEvent): void;
  onmessage: ((event: MessageEvent<BenchCommand>) => void) | null;
}
const scope = self as unknown as WorkerScope;
const post = (event: BenchEvent) => scope.postMessage(event);

const MODES = { serial: 0, controller: 1, full: 2 } as const;
let module: BenchModule | null = null;
let cancelled = false;

const yieldToMessages = () => new Promise<void>((resolve) => setTimeout(resolve, 0));

async function run(command: Extract<BenchCommand, { type: 'run' }>): Promise<void> {
  if (!crossOriginIsolated) throw new Error('the page is not cross-origin isolated: no WASM threads');
  module ??= (await loadGaitlab(command.wasmUrl, {
    printErr: (text) => console.warn(`[gaitlab] ${text}`),
    onAbort: (what) => post({ type: 'error', message: `the WASM module aborted: ${String(what)}` }),
  })) as BenchModule;
  const m = module;
  post({ type: 'machine', machine: JSON.parse(m.UTF8ToString(m._gl_bench_machine())) });
  const { inputs } = command;
  // Refuse a crowd larger than a simulation holds before measuring anything.
  for (const p of command.grid) {
    const most = m._gl_bench_max_characters(p.legs === 'mixed' ? 0 : p.legs);
    if (p.characters > most) {
      throw new Error(`${p.characters} ${p.legs === 'mixed' ? 'mixed characters' : p.legs === 2 ? 'bipeds' : 'quadrupeds'} is more than a simulation holds (${most})`);
    }
  }
  // Untimed, so that the engine has compiled the hot code with its optimising tier before the
  // first point is timed (sim::warmUp).
  post({ type: 'status', message: 'warming up (untimed)' });
  const warmThreads = Math.max(...command.grid.map((p) => p.threads));
  for (const legs of new Set(command.grid.map((p) => p.legs))) m._gl_bench_warm_up(legs === 'mixed' ? 0 : legs, warmThreads);
  for (let i = 0; i < command.grid.length; i++) {
    // Let a 'cancel' message in between points.
    await yieldToMessages();
    if (cancelled) break;
    const p = command.grid[i];
    const t0 = performance.now();
    const json = m.UTF8ToString(m._gl_bench_point(p.legs === 'mixed' ? 0 : p.legs, p.characters,
      p.threads, MODES[p.mode], inputs.steps, inputs.runs, inputs.shards, inputs.spacing_m,
      inputs.seed, inputs.frames ? 1 : 0));
    if (!json) throw new Error(`the module refused point ${JSON.stringify(p)}`);
    post({ type: 'point', index: i, point: JSON.parse(json), seconds: (performance.now() - t0) / 1000 });
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
