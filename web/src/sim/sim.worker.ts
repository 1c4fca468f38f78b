// The sim worker: owns the WASM module and runs the fixed-step loop in real time (DESIGN.md, data
// flow step 2). The simulation never runs on the browser's main thread: a step blocks (the
// thread pool waits on futexes, which the main thread may not do) and takes milliseconds.
//
// This worker is also the Emscripten "main thread" of the module, so the module's pthread pool
// consists of workers nested in this one.
import { FixedStepClock } from './fixed-step-clock';
import { gaitlabVersion, loadGaitlab, Simulation, type GaitlabModule } from './gaitlab-wasm';
import { errorMessage, type SimCommand, type SimEvent, type SimOptions } from './protocol';

/** The fixed step of the simulation (C API: gl_sim_step takes steps of 1/120 s). */
const STEP = 1 / 120;
/**
 * Catch-up cap: at most 6 steps (50 ms of simulated time) per tick. A machine that needs more
 * than 8.3 ms per step runs slower than real time rather than falling ever further behind.
 */
const MAX_STEPS_PER_TICK = 6;
/**
 * How often statistics go to the main thread. They are sent even while paused: they double as a
 * heartbeat, by which the main thread notices a worker stuck inside the module.
 */
const STATS_INTERVAL_MS = 250;

// The DOM lib's `self` is a Window; this is the part of DedicatedWorkerGlobalScope used here.
interface WorkerScope {
  postMessage(message: SimEvent): void;
  onmessage: ((event: MessageEvent<SimCommand>) => void) | null;
}
const scope = self as unknown as WorkerScope;
const post = (event: SimEvent) => scope.postMessage(event);

let module: GaitlabModule | null = null;
let options: SimOptions | null = null;
let sim: Simulation | null = null;
/** Counts the simulations made; the main thread names render buffers by it. */
let generation = 0;
/** A reset waits for the main thread to release the current render buffer. */
let resetPending = false;
let paused = false;
let timer: ReturnType<typeof setTimeout> | undefined;
let statsTimer: ReturnType<typeof setInterval> | undefined;
let failed = false;

const clock = new FixedStepClock({ step: STEP, maxStepsPerTick: MAX_STEPS_PER_TICK });
const now = () => performance.now() / 1000;

// Step timing accumulated between statistics reports.
let stepWallMs = 0;
let stepsTimed = 0;
let droppedSteps = 0;

function fail(error: unknown): void {
  // The first report is the informative one (an abort is also rethrown as a RuntimeError).
  if (failed) return;
  failed = true;
  clearTimeout(timer);
  clearInterval(statsTimer);
  console.error(error);
  post({ type: 'error', message: errorMessage(error) });
}

/** Builds a fresh demo scene and hands its render buffer to the main thread. */
function newScene(): void {
  if (!module || !options) return;
  // The previous simulation is gone by now (see 'released'): its pthreads are back in the pool.
  sim = new Simulation(module, options.threads, options.seed);
  sim.demoScene(options.characters);
  // Publish an initial frame (zero steps) so the first thing drawn is the scene as spawned.
  sim.step(0);
  generation += 1;
  post({
    type: 'ready',
    generation,
    memory: module.HEAPU8.buffer as SharedArrayBuffer,
    header: sim.renderHeader,
    threads: sim.threads,
    version: gaitlabVersion(module),
  });
  if (!paused) clock.start(now());
}

function reportStats(): void {
  if (!sim || failed) return;
  post({
    type: 'stats',
    generation,
    simTime: sim.time,
    stepIndex: sim.stepIndex,
    bodies: sim.bodyCount,
    threads: sim.threads,
    paused,
    stepMs: stepsTimed > 0 ? stepWallMs / stepsTimed : 0,
    droppedSteps,
  });
  stepWallMs = 0;
  stepsTimed = 0;
  droppedSteps = 0;
}

/** One turn of the real-time loop: take the steps that are due, then sleep until the next. */
function tick(): void {
  timer = undefined;
  if (failed || !sim) return;
  try {
    const { steps, dropped, wait } = clock.tick(now());
    droppedSteps += dropped;
    if (steps > 0) {
      const t0 = performance.now();
      // One call for all due steps: gl_sim_step publishes a frame once, after the last.
      sim.step(steps);
      stepWallMs += performance.now() - t0;
      stepsTimed += steps;
    }
    // Returning to the event loop between ticks is what lets commands in; a timeout of 0 when
    // behind still does.
    if (!paused) timer = setTimeout(tick, wait * 1000);
  } catch (error) {
    fail(error);
  }
}

function schedule(): void {
  if (timer === undefined && !paused && !failed) timer = setTimeout(tick, 0);
}

async function init(initial: SimOptions): Promise<void> {
  if (!crossOriginIsolated) {
    throw new Error('the page is not cross-origin isolated, so WASM threads (SharedArrayBuffer) are unavailable');
  }
  options = initial;
  module = await loadGaitlab(initial.wasmUrl, {
    print: (text) => console.log(`[gaitlab] ${text}`),
    printErr: (text) => console.warn(`[gaitlab] ${text}`),
    onAbort: (what) => fail(new Error(`the WASM module aborted: ${errorMessage(what)}`)),
  });
  newScene();
  schedule();
  statsTimer = setInterval(reportStats, STATS_INTERVAL_MS);
}

function handle(command: SimCommand): void {
  switch (command.type) {
    case 'init':
      init(command.options).catch(fail);
      return;
    case 'pause':
      paused = true;
      clock.stop();
      clearTimeout(timer);
      timer = undefined;
      reportStats();
      return;
    case 'resume':
      if (!paused) return;
      paused = false;
      clock.start(now());
      schedule();
      reportStats();
      return;
    case 'reset':
      if (!sim || resetPending) return;
      // Freeing the simulation now could let the main thread read released memory; and making
      // the new one first would need more pthreads than the module's fixed pool holds.
      resetPending = true;
      post({ type: 'release', generation });
      return;
    case 'released':
      if (!resetPending || command.generation !== generation || !sim) return;
      resetPending = false;
      sim.destroy();
      sim = null;
      newScene();
      schedule();
      return;
    default: {
      const unknown: never = command;
      throw new Error(`unknown command ${JSON.stringify(unknown)}`);
    }
  }
}

scope.onmessage = (event) => {
  if (failed) return;
  try {
    handle(event.data);
  } catch (error) {
    fail(error);
  }
};

// Errors outside the handlers above (e.g. thrown by the module's own callbacks).
self.addEventListener('error', (event) => fail(event.error ?? event.message));
self.addEventListener('unhandledrejection', (event) => fail((event as PromiseRejectionEvent).reason));
