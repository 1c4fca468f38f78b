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
import { Kind, loadGaitlab, METHOD, Search } from '../sim/gaitlab-wasm';
import { errorMessage } from '../sim/protocol';
import type { OptimizerCommand, OptimizerEvent } from './protocol';

interface WorkerScope {
  postMessage(message: OptimizerEvent): void;
  onmessage: ((event: MessageEvent<OptimizerCommand>) => void) | null;
}
const scope = self as unknown as WorkerScope;
const post = (event: OptimizerEvent) => scope.postMessage(event);

async function run(command: OptimizerCommand): Promise<void> {
  if (!crossOriginIsolated) throw new Error('the page is not cross-origin isolated: no WASM threads');
  const t0 = performance.now();
  const m = await loadGaitlab(command.wasmUrl, {
    printErr: (text) => console.warn(`[gaitlab optimizer] ${text}`),
    onAbort: (what) => post({ type: 'error', message: `the WASM module aborted: ${errorMessage(what)}` }),
  });
  const o = command.options;
  let search: Search;
  try {
    search = new Search(m, { kind: Kind[o.character], method: METHOD[o.method], candidates: o.candidates, seed: o.seed, threads: o.threads },
      command.startJson, { ...o.settings, speeds: o.speeds }, command.creature);
  } catch (error) {
    throw new Error(`the search was refused: ${error instanceof Error ? error.message : String(error)}`);
  }
  post({ type: 'started', loadSeconds: (performance.now() - t0) / 1000 });

  let best = Infinity;
  for (let g = 0; g < o.generations; g++) {
    const g0 = performance.now();
    const objective = search.step();
    const seconds = (performance.now() - g0) / 1000;
    const improved = objective < best;
    best = Math.min(best, objective);
    post({
      type: 'generation',
      generation: search.generation,
      evaluations: search.evaluations,
      best: objective,
      seconds,
      improved,
      gait: improved ? search.bestJson() : null,
    });
  }
  search.destroy();
  post({ type: 'done' });
}

scope.onmessage = (event) => {
  if (event.data.type === 'start') run(event.data).catch((error: unknown) => post({ type: 'error', message: errorMessage(error) }));
};
self.addEventListener('error', (event) => post({ type: 'error', message: errorMessage(event.error ?? event.message) }));
