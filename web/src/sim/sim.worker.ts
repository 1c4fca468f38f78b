// The sim worker: owns the WASM module and runs the fixed-step loop in real time (README.md,
// architecture). The simulation never runs on the browser's main thread: a step blocks (the
// thread pool waits on futexes, which the main thread may not do) and takes milliseconds.
//
// This worker is also the Emscripten "main thread" of the module, so the module's pthread pool
// consists of workers nested in this one.
import { FixedStepClock } from './fixed-step-clock';
import { gaitlabVersion, INFO, Kind, loadGaitlab, normalizeGait, Simulation, type GaitlabModule } from './gaitlab-wasm';
import type { TerrainKind } from './terrain-grid';
import { CHARACTER_TYPES, typeOfKind } from '../gait/character';
import {
  errorMessage,
  type CharacterStatus,
  type CharacterType,
  type SceneCommand,
  type SimCommand,
  type SimEvent,
  type SimOptions,
  type TimeScale,
} from './protocol';

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
  postMessage(message: SimEvent, transfer?: Transferable[]): void;
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

/**
 * Slow motion: the clock is fed a virtual time that runs at `timeScale` of the wall clock, so it
 * asks for proportionally fewer steps; each step is still the fixed 1/120 s (the physics and the
 * controller see no difference).
 */
let timeScale: TimeScale = 1;
let virtualTime = 0;
let lastWall = performance.now() / 1000;
const now = () => {
  const wall = performance.now() / 1000;
  virtualTime += (wall - lastWall) * timeScale;
  lastWall = wall;
  return virtualTime;
};

/** Scene commands waiting for the start of the next fixed step. */
let pending: SceneCommand[] = [];
/**
 * Every scene command applied, with the index of the step it preceded: with the seed and the
 * scene options this replays the run. Bounded, so a long session does not grow without end.
 */
const commandLog: { step: number; command: SceneCommand }[] = [];
const COMMAND_LOG_LIMIT = 10_000;
let commandsApplied = 0;

/** Crowd layout: a grid facing +z; added characters take the next free places. */
const SPACING_X = 2.5;
const SPACING_Z = 3;
let gridColumns = 1;
let nextSlot = 0;
/**
 * The goal each type starts with: its cruise speed (gl_cruise_speed, the speed its preset is
 * benchmarked at; a 0.49 m dog walks slower than a 1.8 m human), set once the module is loaded.
 * A goal given to all characters replaces both.
 */
const lastGoals: Record<CharacterType, { speed: number; turn: number }> = {
  biped: { speed: 0, turn: 0 },
  quadruped: { speed: 0, turn: 0 },
};
/**
 * The gait last given to every character of a type (setParams with id 'all'): characters added
 * later, and the characters of a new scene, walk with it too.
 */
const typeGaits: Partial<Record<CharacterType, string>> = {};

/**
 * The optimize panel's learner (scene command 'learner'): its id, the command that made it
 * (replayed to start it over), and the simulated time it started. It stands this far to the
 * left (−x) of the crowd's grid, level with its middle row: apart, so it can be watched alone.
 */
let learner: { id: number; command: Extract<SceneCommand, { type: 'learner' }>; since: number } | null = null;
const LEARNER_GAP = 5;
/** A new learner (so a new id) is reported at once, not at the next 4 Hz report. */
let learnerChanged = false;

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
  // The ground first, so that the characters are spawned standing on it.
  if (terrain !== 'flat' && !sim.setTerrain(terrain)) terrain = 'flat';
  gridColumns = Math.max(1, Math.ceil(Math.sqrt(options.characters)));
  nextSlot = 0;
  pending = [];
  commandLog.length = 0;
  commandsApplied = 0;
  learner = null;
  // A mixed crowd: bipeds and quadrupeds alternate, so each type spreads over the whole grid.
  addCharacters(options.characters, (i) => (i % 2 === 0 ? 'biped' : 'quadruped'));
  sim.setAutoReset(autoResetSeconds);
  // What the new scene keeps from the session (goal, auto-reset, gaits of a whole type) opens
  // its command log, so that the log alone with the seed still replays the run.
  const carried: SceneCommand[] = [
    ...(terrain !== 'flat' ? [{ type: 'setTerrain' as const, terrain }] : []),
    // One goal for all, once one was given to all; until then each type's start goal, which
    // addCharacters gives every character it spawns.
    ...(sameGoal(lastGoals.biped, lastGoals.quadruped) ? [{ type: 'setGoal' as const, id: 'all' as const, ...lastGoals.biped }] : []),
    { type: 'autoReset', seconds: autoResetSeconds },
    ...Object.entries(typeGaits).map(([character, json]) => ({ type: 'setParams' as const, id: 'all' as const, character: character as CharacterType, json: json! })),
  ];
  for (const command of carried) commandLog.push({ step: 0, command });
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
    schema: module._gl_schema_json ? module.UTF8ToString(module._gl_schema_json()) : null,
    optimizerSchema: module._gl_opt_settings_json ? module.UTF8ToString(module._gl_opt_settings_json()) : null,
  });
  postTerrain();
  if (!paused) clock.start(now());
}

const sameGoal = (a: { speed: number; turn: number }, b: { speed: number; turn: number }) =>
  a.speed === b.speed && a.turn === b.turn;

let autoResetSeconds = 0;
/** The ground: kept across new scenes, like the goal and the auto-reset. */
let terrain: TerrainKind = 'flat';

/** Sends the ground's grid and samples to the main thread (a copy, transferred). */
function postTerrain(): void {
  if (!sim) return;
  const grid = sim.terrainGrid();
  scope.postMessage({ type: 'terrain', generation, grid }, grid.heights ? [grid.heights.buffer] : []);
}

/** Places `count` characters on the next free grid places, centred on the origin. */
function addCharacters(count: number, type: (i: number) => CharacterType): void {
  if (!sim || !options) return;
  const rows = Math.max(1, Math.ceil(options.characters / gridColumns));
  for (let i = 0; i < count; i++) {
    const slot = nextSlot++;
    const x = ((slot % gridColumns) - (gridColumns - 1) / 2) * SPACING_X;
    // Rows beyond the initial crowd continue behind it (−z), away from where the crowd walks.
    const z = ((rows - 1) / 2 - Math.floor(slot / gridColumns)) * SPACING_Z;
    const kind = type(i);
    const id = sim.spawn(Kind[kind], x, z, 0);
    if (id < 0) break; // the render buffer is full
    sim.setGoal(id, lastGoals[kind].speed, lastGoals[kind].turn);
    const gait = typeGaits[kind];
    if (gait && sim.setParams(id, Kind[kind], gait)) delete typeGaits[kind]; // refused: back to the preset
  }
}

/** Applies one scene command to the simulation (the start of a fixed step). */
function apply(command: SceneCommand): void {
  if (!sim) return;
  switch (command.type) {
    case 'setGoal':
      if (command.id === 'all') {
        for (const kind of CHARACTER_TYPES) lastGoals[kind] = { speed: command.speed, turn: command.turn };
      }
      sim.setGoal(command.id === 'all' ? -1 : command.id, command.speed, command.turn);
      return;
    case 'throwBox':
      sim.throwBox(command.from, command.velocity, command.half);
      return;
    case 'drag':
      sim.drag(command.id, command.segment, command.local, command.target);
      return;
    case 'endDrag':
      sim.endDrag();
      return;
    case 'resetCharacter':
      sim.resetCharacter(command.id);
      return;
    case 'resetFallen': {
      const info = sim.characterInfo();
      for (let o = 0; o < info.length; o += INFO.fields) {
        if (info[o + INFO.fallen]) sim.resetCharacter(info[o + INFO.id]);
      }
      return;
    }
    case 'remove':
      sim.removeCharacter(command.id);
      if (learner?.id === command.id) learner = null;
      return;
    case 'add':
      addCharacters(Math.max(0, Math.min(64, Math.floor(command.count))), () => command.kind);
      return;
    case 'autoReset':
      autoResetSeconds = Math.max(0, command.seconds);
      sim.setAutoReset(autoResetSeconds);
      return;
    case 'setParams': {
      const problem = sim.setParams(command.id === 'all' ? -1 : command.id, Kind[command.character], command.json);
      if (problem) post({ type: 'commandError', message: `the gait was not applied: ${problem}` });
      else if (command.id === 'all') typeGaits[command.character] = command.json;
      return;
    }
    case 'patchParams': {
      const who = command.id === 'all' ? `every ${command.character}` : `${command.character} #${command.id}`;
      const problem = sim.patchParams(command.id === 'all' ? -1 : command.id, Kind[command.character], JSON.stringify(command.patch));
      const error = problem ? `the edit of ${who} (patchParams) was refused: ${problem}` : null;
      if (!problem && command.id === 'all') {
        // Characters added later walk with the type's gait as edited: the first of the type's, as
        // the editors show it.
        const first = characterStatus().find((c) => c.type === command.character);
        if (first) typeGaits[command.character] = sim.getParams(first.id);
      }
      if (command.request !== undefined) post({ type: 'patched', request: command.request, accepted: error ? null : command.patch, error });
      else if (error) post({ type: 'commandError', message: error });
      return;
    }
    case 'learner': {
      if (learner) sim.removeCharacter(learner.id);
      learner = null;
      const x = -((gridColumns - 1) / 2) * SPACING_X - LEARNER_GAP;
      const id = sim.spawn(Kind[command.character], x, 0, 0);
      if (id < 0) {
        post({ type: 'commandError', message: 'the learner was not added: the scene is full' });
        return;
      }
      const problem = sim.setParams(id, Kind[command.character], command.json);
      if (problem) {
        sim.removeCharacter(id);
        post({ type: 'commandError', message: `the learner was not added: ${problem}` });
        return;
      }
      sim.setGoal(id, command.speed, command.turn);
      learner = { id, command, since: sim.time };
      learnerChanged = true;
      return;
    }
    case 'removeLearner':
      if (learner) sim.removeCharacter(learner.id);
      learner = null;
      return;
    case 'setTerrain':
      if (!sim.setTerrain(command.terrain)) {
        post({ type: 'commandError', message: `this build of the simulation has no '${command.terrain}' terrain` });
        return;
      }
      terrain = command.terrain;
      postTerrain();
      return;
    default: {
      const unknown: never = command;
      throw new Error(`unknown scene command ${JSON.stringify(unknown)}`);
    }
  }
}

/** Applies the queued commands, logged with the index of the step they precede. */
function applyPending(): void {
  if (!sim || pending.length === 0) return;
  const step = sim.stepIndex;
  for (const command of pending) {
    apply(command);
    if (commandLog.length >= COMMAND_LOG_LIMIT) commandLog.shift();
    commandLog.push({ step, command });
    commandsApplied++;
  }
  pending = [];
}

function characterStatus(): CharacterStatus[] {
  if (!sim) return [];
  const info = sim.characterInfo();
  const out: CharacterStatus[] = [];
  for (let o = 0; o < info.length; o += INFO.fields) {
    out.push({
      id: info[o + INFO.id],
      type: typeOfKind(info[o + INFO.kind]) ?? 'biped',
      position: [info[o + INFO.x], info[o + INFO.y], info[o + INFO.z]],
      heading: info[o + INFO.heading],
      speed: info[o + INFO.speed],
      fallen: info[o + INFO.fallen] !== 0,
      fallenSeconds: info[o + INFO.fallenSeconds],
      goal: { speed: info[o + INFO.goalSpeed], turn: info[o + INFO.goalTurn] },
      phase: info[o + INFO.phase],
    });
  }
  return out;
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
    timeScale,
    characters: characterStatus(),
    commandsApplied,
    learner: learner?.id ?? null,
    terrain,
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
      // The learner starts over every loopSeconds: as a logged command, so the log replays it.
      if (learner && learner.command.loopSeconds > 0 && sim.time - learner.since >= learner.command.loopSeconds) {
        pending.push(learner.command);
      }
      applyPending();
      // One call for all due steps: gl_sim_step publishes a frame once, after the last.
      sim.step(steps);
      stepWallMs += performance.now() - t0;
      stepsTimed += steps;
      if (learnerChanged) {
        // The main thread marks and follows the learner by id: tell it the new one now.
        learnerChanged = false;
        reportStats();
      }
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
  paused = initial.paused === true;
  terrain = initial.terrain ?? 'flat';
  module = await loadGaitlab(initial.wasmUrl, {
    print: (text) => console.log(`[gaitlab] ${text}`),
    printErr: (text) => console.warn(`[gaitlab] ${text}`),
    onAbort: (what) => fail(new Error(`the WASM module aborted: ${errorMessage(what)}`)),
  });
  for (const kind of CHARACTER_TYPES) lastGoals[kind] = { speed: module._gl_cruise_speed(Kind[kind]), turn: 0 };
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
    case 'step':
      // One fixed step while paused (while running, steps come from the clock).
      if (!sim || !paused) return;
      applyPending();
      sim.step(Math.max(1, Math.min(1200, Math.floor(command.count ?? 1))));
      reportStats();
      return;
    case 'timeScale':
      // Account for the time so far at the old scale before switching.
      now();
      timeScale = command.scale;
      reportStats();
      return;
    case 'scene':
      pending.push(command.command);
      if (paused && sim) {
        // Nothing steps while paused: apply now and publish, so the change shows at once.
        applyPending();
        sim.step(0);
        reportStats();
      }
      return;
    case 'getParams':
    case 'getPreset':
    case 'normalize': {
      let json: string | null = null;
      let error: string | null = null;
      try {
        if (command.type === 'normalize') {
          if (!module) throw new Error('the module is not loaded yet');
          json = normalizeGait(module, command.json);
        } else {
          if (!sim) throw new Error('no simulation yet');
          json = command.type === 'getParams' ? sim.getParams(command.id) : sim.presetJson(Kind[command.character]);
        }
      } catch (e) {
        error = errorMessage(e);
      }
      post({ type: 'params', request: command.request, json, error });
      return;
    }
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
