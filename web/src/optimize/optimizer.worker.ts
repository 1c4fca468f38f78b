// The optimizer worker: the optimize panel's search (thesis §3.3; native/src/optimize) through
// the C API's generation-at-a-time functions (gl_opt_create, gl_opt_step, gl_opt_best_json).
//
// Why a worker of its own, with its own instance of the module, rather than the sim worker:
// gl_opt_step runs a whole generation — K episodes of several simulated seconds each — and
// cannot be cut into pieces. Measured in headless Chromium on the 2-core development machine
// (node bench/optimize-panel.mjs, bench/results/optimize-panel.json), a generation of the
// default search (10 biped candidates from the preset, 6.7 s episodes; the machine's load
// average 11–14) took 0.7 s to 2.8 s: 1.8 s on average at 1 thread, 1.2 s at 2; so one
// episode takes about 0.1 s or more (less when a candidate falls early), against the 8.3 ms
// the sim worker has per fixed step. Run in the sim worker, a generation would stop the crowd
// for 80 to 340 steps, and even one evaluation at a time (which the C API does not offer) for
// a dozen; a time budget between crowd steps cannot help when the smallest piece of work is
// that large. Here the crowd keeps its real-time loop and the two share the cores through the
// operating system.
// The cost is a second module instance (its 256 MB of shared memory and its pthread pool, as
// the performance page's worker has), for as long as a search runs: the panel terminates this
// worker when the search ends or is stopped. Terminating is also what makes Stop immediate
// (a generation in progress cannot be interrupted from inside); the best so far is what the
// last finished generation reported.
import { Kind, loadGaitlab, type GaitlabModule } from '../sim/gaitlab-wasm';
import { errorMessage } from '../sim/protocol';
import type { OptimizerCommand, OptimizerEvent } from './protocol';

/** The optimisation part of the C API (c_api.h, "Optimisation, one generation at a time"). */
interface OptimizerModule extends GaitlabModule {
  _gl_opt_create(kind: number, method: number, candidates: number, seed: number, threads: number, startJson: number, settingsJson: number): number;
  _gl_opt_step(opt: number): number;
  _gl_opt_generation(opt: number): number;
  _gl_opt_evaluations(opt: number): number;
  _gl_opt_best_json(opt: number): number;
  _gl_opt_destroy(opt: number): void;
}

interface WorkerScope {
  postMessage(message: OptimizerEvent): void;
  onmessage: ((event: MessageEvent<OptimizerCommand>) => void) | null;
}
const scope = self as unknown as WorkerScope;
const post = (event: OptimizerEvent) => scope.postMessage(event);

/** A copy of `text` in module memory (free it). */
function cString(m: GaitlabModule, text: string): number {
  const bytes = m.lengthBytesUTF8(text) + 1;
  const pointer = m._malloc(bytes);
  m.stringToUTF8(text, pointer, bytes);
  return pointer;
}

async function run(command: OptimizerCommand): Promise<void> {
  if (!crossOriginIsolated) throw new Error('the page is not cross-origin isolated: no WASM threads');
  const t0 = performance.now();
  const m = (await loadGaitlab(command.wasmUrl, {
    printErr: (text) => console.warn(`[gaitlab optimizer] ${text}`),
    onAbort: (what) => post({ type: 'error', message: `the WASM module aborted: ${errorMessage(what)}` }),
  })) as OptimizerModule;
  if (!m._gl_opt_create) throw new Error('this build of the module has no optimiser (gl_opt_create)');
  const o = command.options;
  const settings = cString(m, JSON.stringify({ ...o.settings, speeds: o.speeds }));
  const start = command.startJson === null ? 0 : cString(m, command.startJson);
  const opt = m._gl_opt_create(Kind[o.character], o.method === 'cmaes' ? 1 : 0, o.candidates, o.seed >>> 0, o.threads, start, settings);
  m._free(settings);
  if (start) m._free(start);
  if (!opt) throw new Error(`the search was refused: ${m._gl_last_error ? m.UTF8ToString(m._gl_last_error()) : 'unknown error'}`);
  post({ type: 'started', loadSeconds: (performance.now() - t0) / 1000 });

  let best = Infinity;
  for (let g = 0; g < o.generations; g++) {
    const g0 = performance.now();
    const objective = m._gl_opt_step(opt);
    const seconds = (performance.now() - g0) / 1000;
    const improved = objective < best;
    best = Math.min(best, objective);
    post({
      type: 'generation',
      generation: m._gl_opt_generation(opt),
      evaluations: m._gl_opt_evaluations(opt),
      best: objective,
      seconds,
      improved,
      gait: improved ? m.UTF8ToString(m._gl_opt_best_json(opt)) : null,
    });
  }
  m._gl_opt_destroy(opt);
  post({ type: 'done' });
}

scope.onmessage = (event) => {
  if (event.data.type === 'start') run(event.data).catch((error: unknown) => post({ type: 'error', message: errorMessage(error) }));
};
self.addEventListener('error', (event) => post({ type: 'error', message: errorMessage(event.error ?? event.message) }));
