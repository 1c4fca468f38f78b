// The sim worker: owns the WASM module and runs the fixed-step loop in real time. The simulation
// never runs on the browser's main thread: a step blocks (the thread pool waits on futexes, which
// the main thread may not do) and takes milliseconds.
//
// The file is the worker's message handling (handle) around one object, the WorkerScene: the
// module, the simulation and everything the scene keeps between steps.
//
// This worker is also the Emscripten "main thread" of the module, so the module's pthread pool
// consists of workers nested in this one.
import { checkSimCommand } from './command-check';
import { FixedStepClock } from './fixed-step-clock';
import {
  ALTERNATING,
  cruiseSpeed,
  topSpeed,
  ERR,
  GaitlabError,
  gaitlabVersion,
  INFO,
  Kind,
  loadGaitlab,
  normalizeGait,
  optimizerSettingsJson,
  poolThreads,
  presetJson,
  schemaJson,
  Simulation,
  type GaitlabModule,
} from './gaitlab-wasm';
import type { TerrainKind } from './terrain-grid';
import { CHARACTER_TYPES, typeOfKind } from '../gait/character';
import {
  errorMessage,
  MAX_CHARACTERS,
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

/** The command log is bounded, so a long session does not grow without end. */
const COMMAND_LOG_LIMIT = 10_000;

type Goal = { speed: number; turn: number };

/**
 * The wandering crowd's arena (native/src/sim/wander.h), a circle about the origin sized for the
 * crowd: about 28 m² per character (3 m × √n of radius), and at least 12 m, so that a biped at
 * 1 m/s, which needs 7.7 m to turn round at the 0.3 rad/s wandering allows, has room to wander.
 */
export function arenaRadiusFor(characters: number): number {
  return Math.max(12, 3 * Math.sqrt(characters));
}
const sameGoal = (a: Goal, b: Goal) => a.speed === b.speed && a.turn === b.turn;

/**
 * The running scene: the loaded module and its one simulation, the real-time loop's clock and
 * timers, the queued and applied scene commands, and what a new scene carries over from the last
 * (goals, auto-reset, gaits of a whole type, the ground).
 */
class WorkerScene {
  private sim: Simulation | null = null;
  /** Counts the simulations made; the main thread names render buffers by it. */
  private generation = 0;
  /** A reset waits for the main thread to release the current render buffer. */
  private resetPending = false;
  private paused: boolean;
  private timer: ReturnType<typeof setTimeout> | undefined;
  private statsTimer: ReturnType<typeof setInterval> | undefined;
  private failed = false;

  private readonly clock = new FixedStepClock({ step: STEP, maxStepsPerTick: MAX_STEPS_PER_TICK });
  /**
   * Slow motion: the clock is fed a virtual time that runs at `timeScale` of the wall clock, so
   * it asks for proportionally fewer steps; each step is still the fixed 1/120 s (the physics and
   * the controller see no difference).
   */
  private timeScale: TimeScale = 1;
  private virtualTime = 0;
  private lastWall = performance.now() / 1000;

  /** Scene commands waiting for the start of the next fixed step. */
  private pending: SceneCommand[] = [];
  /**
   * Every scene command applied, with the index of the step it preceded: with the seed and the
   * scene options this replays the run.
   */
  private readonly commandLog: { step: number; command: SceneCommand }[] = [];
  private commandsApplied = 0;

  /**
   * The goal each type starts with: its cruise speed (gl_cruise_speed, the speed its preset is
   * benchmarked at; a 0.49 m dog walks slower than a 1.8 m human). A goal given to all
   * characters replaces both.
   */
  private readonly lastGoals: Record<CharacterType, Goal>;
  /**
   * The gait last given to every character of a type (setParams with id 'all'): characters added
   * later, and the characters of a new scene, walk with it too.
   */
  private readonly typeGaits: Partial<Record<CharacterType, string>> = {};
  private autoResetSeconds = 0;
  /** The ground: kept across new scenes, like the goal and the auto-reset. */
  private terrain: TerrainKind;
  /** Arena wandering of the crowd (on by default: the demo's crowd stays in view); kept across scenes. */
  private wandering = true;
  /** The characters wandering now (a character steered by hand leaves it; the learner is never in it). */
  private readonly wanderers = new Set<number>();
  private arenaRadius = arenaRadiusFor(0);

  /**
   * The optimize panel's learner (scene command 'learner'): its id, the command that made it
   * (replayed to start it over), and the simulated time it started. It stands apart, left of
   * the crowd's grid level with its middle row, so it can be watched alone.
   */
  private learner: { id: number; command: Extract<SceneCommand, { type: 'learner' }>; since: number } | null = null;
  /** A new learner (so a new id) is reported at once, not at the next 4 Hz report. */
  private learnerChanged = false;

  // Step timing accumulated between statistics reports.
  private stepWallMs = 0;
  private stepsTimed = 0;
  private droppedSteps = 0;

  constructor(private readonly module: GaitlabModule, private readonly options: SimOptions) {
    this.paused = options.paused === true;
    this.terrain = options.terrain ?? 'flat';
    this.lastGoals = Object.fromEntries(
      CHARACTER_TYPES.map((type) => [type, { speed: cruiseSpeed(module, Kind[type]), turn: 0 }]),
    ) as Record<CharacterType, { speed: number; turn: number }>;
  }

  /** Builds the first scene and starts the loop and the statistics heartbeat. */
  start(): void {
    this.newScene();
    this.schedule();
    this.statsTimer = setInterval(() => this.reportStats(), STATS_INTERVAL_MS);
  }

  get hasFailed(): boolean {
    return this.failed;
  }

  fail(error: unknown): void {
    // The first report is the informative one (an abort is also rethrown as a RuntimeError).
    if (this.failed) return;
    this.failed = true;
    clearTimeout(this.timer);
    clearInterval(this.statsTimer);
    console.error(error);
    post({ type: 'error', message: errorMessage(error) });
  }

  private now(): number {
    const wall = performance.now() / 1000;
    this.virtualTime += (wall - this.lastWall) * this.timeScale;
    this.lastWall = wall;
    return this.virtualTime;
  }

  /** Builds a fresh demo scene and hands its render buffer to the main thread. */
  private newScene(): void {
    const { module, options } = this;
    // The previous simulation is gone by now (see 'released'): its pthreads are back in the pool.
    // At most what the module's pthread pool serves: it is sized from the same
    // navigator.hardwareConcurrency as the page's default, but `?threads=` may ask for more.
    const sim = (this.sim = new Simulation(module, Math.min(options.threads, poolThreads(module)), options.seed));
    // The ground first, so that the characters are spawned standing on it.
    if (this.terrain !== 'flat') sim.setTerrain(this.terrain);
    this.pending = [];
    this.commandLog.length = 0;
    this.commandsApplied = 0;
    this.learner = null;
    this.wanderers.clear();
    // A mixed crowd: bipeds and quadrupeds alternate, so each type spreads over the whole grid
    // (the first group added sizes the layout's grid).
    this.addCharacters(options.characters, ALTERNATING);
    sim.setAutoReset(this.autoResetSeconds);
    // What the new scene keeps from the session (goal, auto-reset, gaits of a whole type) opens
    // its command log, so that the log alone with the seed still replays the run.
    const { lastGoals, terrain } = this;
    const carried: SceneCommand[] = [
      ...(terrain !== 'flat' ? [{ type: 'setTerrain' as const, terrain }] : []),
      // One goal for all, once one was given to all; until then each type's start goal, which
      // addCharacters gives every character it spawns.
      ...(CHARACTER_TYPES.every((t) => sameGoal(lastGoals.biped, lastGoals[t])) ? [{ type: 'setGoal' as const, id: 'all' as const, ...lastGoals.biped }] : []),
      { type: 'autoReset', seconds: this.autoResetSeconds },
      ...(this.wandering ? [{ type: 'wander' as const, on: true }] : []),
      ...Object.entries(this.typeGaits).map(([character, json]) => ({ type: 'setParams' as const, id: 'all' as const, character: character as CharacterType, json: json! })),
    ];
    for (const command of carried) this.commandLog.push({ step: 0, command });
    // Publish an initial frame (zero steps) so the first thing drawn is the scene as spawned.
    sim.step(0);
    this.generation += 1;
    post({
      type: 'ready',
      generation: this.generation,
      memory: module.HEAPU8.buffer as SharedArrayBuffer,
      header: sim.renderHeader,
      threads: sim.threads,
      version: gaitlabVersion(module),
      schema: schemaJson(module),
      optimizerSchema: optimizerSettingsJson(module),
      speedRanges: Object.fromEntries(
        CHARACTER_TYPES.map((type) => [type, { min: 0, max: topSpeed(module, Kind[type]) }]),
      ) as Record<CharacterType, { min: number; max: number }>,
    });
    this.postTerrain();
    if (!this.paused) this.clock.start(this.now());
  }

  /** Sends the ground's grid and samples to the main thread (a copy, transferred). */
  private postTerrain(): void {
    if (!this.sim) return;
    const grid = this.sim.terrainGrid();
    scope.postMessage({ type: 'terrain', generation: this.generation, grid }, grid.heights ? [grid.heights.buffer] : []);
  }

  /**
   * Adds `count` characters in the next free places of the scene's layout (gl_sim_add_characters,
   * which places them and stops when the render buffer is full), then gives each its type's goal
   * and gait of this session.
   */
  private addCharacters(count: number, kindCode: number): void {
    const { sim } = this;
    if (!sim) return;
    const added = sim.addCharacters(kindCode, count);
    if (added < count) {
      // The scene is full: say so with its real limits (gl_sim_room: the render buffer, and the
      // memory the module can still afford) rather than adding fewer in silence.
      const rooms = CHARACTER_TYPES.map((type) => `${sim.room(Kind[type])} more ${type}s`).join(', ');
      post({ type: 'commandError', message: `added ${added} of ${count} characters: the scene is full (room now: ${rooms})` });
    }
    const info = sim.characterInfo(); // the added characters are the last ones
    for (let o = info.length - added * INFO.fields; o < info.length; o += INFO.fields) {
      const id = info[o + INFO.id];
      const kind = typeOfKind(info[o + INFO.kind]);
      if (!kind) continue;
      sim.setGoal(id, this.lastGoals[kind].speed, this.lastGoals[kind].turn);
      const gait = this.typeGaits[kind];
      if (gait) {
        try {
          sim.setParams(id, Kind[kind], gait);
        } catch {
          delete this.typeGaits[kind]; // refused: back to the preset
        }
      }
    }
    if (this.wandering && added > 0) {
      // The newcomers wander; the arena grows with the crowd (one arena: the last radius given).
      // Characters steered by hand stay so.
      this.arenaRadius = arenaRadiusFor(info.length / INFO.fields - (this.learner ? 1 : 0));
      for (let o = info.length - added * INFO.fields; o < info.length; o += INFO.fields) {
        sim.setWander(info[o + INFO.id], this.arenaRadius);
        this.wanderers.add(info[o + INFO.id]);
      }
    }
  }

  /**
   * Wandering on or off for every wanderer (on: every character but the learner, in an arena
   * sized for the crowd now; the module keeps one arena, the last radius given).
   */
  private setWander(on: boolean): void {
    const sim = this.sim;
    if (!sim) return;
    const info = sim.characterInfo();
    const ids: number[] = [];
    for (let o = 0; o < info.length; o += INFO.fields) if (info[o + INFO.id] !== this.learner?.id) ids.push(info[o + INFO.id]);
    this.arenaRadius = arenaRadiusFor(ids.length);
    if (!on) {
      for (const id of this.wanderers) sim.setWander(id, 0);
      this.wanderers.clear();
      return;
    }
    for (const id of ids) {
      sim.setWander(id, this.arenaRadius);
      this.wanderers.add(id);
    }
  }

  /**
   * Applies one scene command to the simulation (the start of a fixed step). A command the
   * module refuses is reported to the page; one naming a character that is gone (removed or
   * replaced since the page named it) has nothing to act on and is dropped, as the page expects.
   */
  private apply(command: SceneCommand): void {
    try {
      this.applyToSimulation(command);
    } catch (error) {
      if (!(error instanceof GaitlabError)) throw error;
      if (error.code === ERR.noCharacter) return;
      post({ type: 'commandError', message: `the command '${command.type}' was refused: ${error.detail}` });
    }
  }

  private applyToSimulation(command: SceneCommand): void {
    const sim = this.sim;
    if (!sim) return;
    switch (command.type) {
      case 'setGoal': {
        const goal = { speed: command.speed, turn: command.turn };
        if (command.id !== 'all') {
          // Steered by hand: it leaves the wandering crowd.
          sim.setGoal(command.id, goal.speed, goal.turn);
          if (this.wanderers.delete(command.id)) sim.setWander(command.id, 0);
          return;
        }
        const kinds = command.character ? [command.character] : CHARACTER_TYPES;
        for (const kind of kinds) this.lastGoals[kind] = goal;
        if (!command.character) {
          sim.setGoal(-1, goal.speed, goal.turn);
          return;
        }
        const info = sim.characterInfo();
        for (let o = 0; o < info.length; o += INFO.fields) {
          if (info[o + INFO.kind] === Kind[command.character] && info[o + INFO.id] !== this.learner?.id) sim.setGoal(info[o + INFO.id], goal.speed, goal.turn);
        }
        return;
      }
      case 'wander':
        if (command.id === undefined) {
          this.wandering = command.on;
          this.setWander(command.on);
        } else if (command.on && command.id !== this.learner?.id) {
          sim.setWander(command.id, this.arenaRadius);
          this.wanderers.add(command.id);
        } else if (!command.on) {
          sim.setWander(command.id, 0);
          this.wanderers.delete(command.id);
        }
        return;
      case 'throwBox':
        sim.throwBox(command.from, command.velocity, command.half);
        return;
      case 'throwAt':
        sim.throwAt(command.from, command.id, command.segment, command.local, command.speed, command.half);
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
        if (this.learner?.id === command.id) this.learner = null;
        this.wanderers.delete(command.id);
        sim.removeCharacter(command.id);
        return;
      case 'add': {
        // Two limits, whichever is nearer: the page's (MAX_CHARACTERS) and the module's memory
        // (gl_sim_room), so an add is refused whole, with the limit named, before anything fails.
        const pageRoom = MAX_CHARACTERS - sim.characterCount;
        const moduleRoom = sim.room(Kind[command.kind]);
        const asked = Math.max(0, Math.min(64, Math.floor(command.count)));
        if (asked > Math.min(pageRoom, moduleRoom)) {
          post({
            type: 'commandError',
            message: moduleRoom < pageRoom
              ? `the crowd is at its limit: the module's memory holds ${moduleRoom} more ${command.kind}s`
              : `the crowd is at its limit: the page holds at most ${MAX_CHARACTERS} characters (${pageRoom} more)`,
          });
          return;
        }
        this.addCharacters(asked, Kind[command.kind]);  // says so itself if fewer fit after all
        return;
      }
      case 'spawnCreature': {
        // The new character's id, or the refusal: to the request if there is one (the reason
        // alone: the asker knows what it asked), else as a commandError (which says what was
        // refused when the module refused it).
        const answer = (id: number | null, error: string | null, what = '') => {
          if (command.request !== undefined) post({ type: 'spawned', request: command.request, id, error });
          else if (error !== null) post({ type: 'commandError', message: what + error });
        };
        if (sim.characterCount >= MAX_CHARACTERS) {
          answer(null, `the crowd is at its limit: the page holds at most ${MAX_CHARACTERS} characters`);
          return;
        }
        let id: number;
        try {
          id = sim.spawnCreature(command.json, command.x, command.z, command.heading);
        } catch (error) {
          if (!(error instanceof GaitlabError)) throw error;
          answer(null, error.detail, "the command 'spawnCreature' was refused: ");
          return;
        }
        const refused = command.gait === undefined ? null : this.giveGait(sim, id, command.gait, 'the creature was not added');
        if (refused !== null) {
          answer(null, refused);
          return;
        }
        sim.setGoal(id, command.speed, 0);
        answer(id, null);
        return;
      }
      case 'autoReset':
        this.autoResetSeconds = Math.max(0, command.seconds);
        sim.setAutoReset(this.autoResetSeconds);
        return;
      case 'setParams':
        try {
          sim.setParams(command.id === 'all' ? -1 : command.id, Kind[command.character], command.json);
        } catch (error) {
          if (!(error instanceof GaitlabError)) throw error;
          post({ type: 'commandError', message: `the gait was not applied: ${error.detail}` });
          return;
        }
        if (command.id === 'all') this.typeGaits[command.character] = command.json;
        return;
      case 'patchParams': {
        const who = command.id === 'all' ? `every ${command.character}` : `${command.character} #${command.id}`;
        let error: string | null = null;
        try {
          // Speed keys, when given, go in the same patch ("speed" and "keys", gl_sim_patch_params).
          const patch = command.speedKeys ? { ...command.patch, ...command.speedKeys } : command.patch;
          sim.patchParams(command.id === 'all' ? -1 : command.id, Kind[command.character], JSON.stringify(patch));
        } catch (e) {
          if (!(e instanceof GaitlabError)) throw e;
          error = `the edit of ${who} (patchParams) was refused: ${e.detail}`;
        }
        if (!error && command.id === 'all') {
          // Characters added later walk with the type's gait as edited: the first of the type's,
          // as the editors show it.
          const first = this.characterStatus().find((c) => c.type === command.character);
          if (first) this.typeGaits[command.character] = sim.getParams(first.id);
        }
        if (command.request !== undefined) post({ type: 'patched', request: command.request, accepted: error ? null : command.patch, error });
        else if (error) post({ type: 'commandError', message: error });
        return;
      }
      case 'learner':
        this.startLearner(sim, command);
        return;
      case 'removeLearner':
        if (this.learner) sim.removeCharacter(this.learner.id);
        this.learner = null;
        return;
      case 'setTerrain':
        sim.setTerrain(command.terrain);
        this.terrain = command.terrain;
        this.postTerrain();
        return;
      default: {
        const unknown: never = command;
        throw new Error(`unknown scene command ${JSON.stringify(unknown)}`);
      }
    }
  }

  /**
   * Gives character `id` the gait file `json` (of its own kind, which the module checks); a
   * refused gait removes the character. Returns null when it was given, else the refusal as
   * "`what`: FIELD: WHAT".
   */
  private giveGait(sim: Simulation, id: number, json: string, what: string): string | null {
    const info = sim.characterInfo();
    let kind = -1;
    for (let o = 0; o < info.length; o += INFO.fields) if (info[o + INFO.id] === id) kind = info[o + INFO.kind];
    try {
      sim.setParams(id, kind, json);
      return null;
    } catch (error) {
      if (!(error instanceof GaitlabError)) throw error;
      sim.removeCharacter(id);
      return `${what}: ${error.detail}`;
    }
  }

  /** The learner: spawned apart from the crowd with the command's gait and goal. */
  private startLearner(sim: Simulation, command: Extract<SceneCommand, { type: 'learner' }>): void {
    if (this.learner) sim.removeCharacter(this.learner.id);
    this.learner = null;
    let id: number;
    try {
      // The scene layout's place apart, left of the crowd's grid, where it can be watched alone.
      id = command.creature !== undefined ? sim.addApartCreature(command.creature) : sim.addApart(Kind[command.character]);
    } catch (error) {
      if (!(error instanceof GaitlabError)) throw error;
      post({ type: 'commandError', message: `the learner was not added: ${error.code === ERR.full ? 'the scene is full' : error.detail}` });
      return;
    }
    const refused = this.giveGait(sim, id, command.json, 'the learner was not added');
    if (refused !== null) {
      post({ type: 'commandError', message: refused });
      return;
    }
    sim.setGoal(id, command.speed, command.turn);
    this.learner = { id, command, since: sim.time };
    this.learnerChanged = true;
  }

  /** Applies the queued commands, logged with the index of the step they precede. */
  private applyPending(): void {
    if (!this.sim || this.pending.length === 0) return;
    const step = this.sim.stepIndex;
    for (const command of this.pending) {
      this.apply(command);
      if (this.commandLog.length >= COMMAND_LOG_LIMIT) this.commandLog.shift();
      this.commandLog.push({ step, command });
      this.commandsApplied++;
    }
    this.pending = [];
  }

  private characterStatus(): CharacterStatus[] {
    if (!this.sim) return [];
    const info = this.sim.characterInfo();
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
        legs: info[o + INFO.legs],
        wanders: this.wanderers.has(info[o + INFO.id]),
      });
    }
    return out;
  }

  reportStats(): void {
    const sim = this.sim;
    if (!sim || this.failed) return;
    post({
      type: 'stats',
      generation: this.generation,
      simTime: sim.time,
      stepIndex: sim.stepIndex,
      bodies: sim.bodyCount,
      threads: sim.threads,
      paused: this.paused,
      stepMs: this.stepsTimed > 0 ? this.stepWallMs / this.stepsTimed : 0,
      droppedSteps: this.droppedSteps,
      timeScale: this.timeScale,
      characters: this.characterStatus(),
      commandsApplied: this.commandsApplied,
      learner: this.learner?.id ?? null,
      terrain: this.terrain,
      wander: { on: this.wandering, arenaRadius: this.arenaRadius },
    });
    this.stepWallMs = 0;
    this.stepsTimed = 0;
    this.droppedSteps = 0;
  }

  /** One turn of the real-time loop: take the steps that are due, then sleep until the next. */
  private tick(): void {
    this.timer = undefined;
    const sim = this.sim;
    if (this.failed || !sim) return;
    try {
      const { steps, dropped, wait } = this.clock.tick(this.now());
      this.droppedSteps += dropped;
      if (steps > 0) {
        const t0 = performance.now();
        // The learner starts over every loopSeconds: as a logged command, so the log replays it.
        const learner = this.learner;
        if (learner && learner.command.loopSeconds > 0 && sim.time - learner.since >= learner.command.loopSeconds) {
          this.pending.push(learner.command);
        }
        this.applyPending();
        // One call for all due steps: gl_sim_step publishes a frame once, after the last.
        sim.step(steps);
        this.stepWallMs += performance.now() - t0;
        this.stepsTimed += steps;
        if (this.learnerChanged) {
          // The main thread marks and follows the learner by id: tell it the new one now.
          this.learnerChanged = false;
          this.reportStats();
        }
      }
      // Returning to the event loop between ticks is what lets commands in; a timeout of 0 when
      // behind still does.
      if (!this.paused) this.timer = setTimeout(() => this.tick(), wait * 1000);
    } catch (error) {
      this.fail(error);
    }
  }

  private schedule(): void {
    if (this.timer === undefined && !this.paused && !this.failed) this.timer = setTimeout(() => this.tick(), 0);
  }

  pause(): void {
    this.paused = true;
    this.clock.stop();
    clearTimeout(this.timer);
    this.timer = undefined;
    this.reportStats();
  }

  resume(): void {
    if (!this.paused) return;
    this.paused = false;
    this.clock.start(this.now());
    this.schedule();
    this.reportStats();
  }

  /** Asks the main thread to release the render buffer; 'released' then builds the new scene. */
  requestReset(): void {
    if (!this.sim || this.resetPending) return;
    // Freeing the simulation now could let the main thread read released memory; and making
    // the new one first would need more pthreads than the module's fixed pool holds.
    this.resetPending = true;
    post({ type: 'release', generation: this.generation });
  }

  released(generation: number): void {
    if (!this.resetPending || generation !== this.generation || !this.sim) return;
    this.resetPending = false;
    this.sim.destroy();
    this.sim = null;
    this.newScene();
    this.schedule();
  }

  /** `count` fixed steps while paused (while running, steps come from the clock). */
  stepPaused(count: number): void {
    if (!this.sim || !this.paused) return;
    this.applyPending();
    this.sim.step(Math.max(1, Math.min(1200, Math.floor(count))));
    this.reportStats();
  }

  setTimeScale(scale: TimeScale): void {
    // Account for the time so far at the old scale before switching.
    this.now();
    this.timeScale = scale;
    this.reportStats();
  }

  queue(command: SceneCommand): void {
    this.pending.push(command);
    if (this.paused && this.sim) {
      // Nothing steps while paused: apply now and publish, so the change shows at once.
      this.applyPending();
      this.sim.step(0);
      this.reportStats();
    }
  }

  /** A gait file as the module reads it: normalised, or refused naming the field. */
  normalize(json: string): string {
    return normalizeGait(this.module, json);
  }

  /** A character's gait file, or a type's preset. */
  gaitJson(command: Extract<SimCommand, { type: 'getParams' | 'getPreset' }>): string {
    if (!this.sim) throw new Error('no simulation yet');
    return command.type === 'getParams' ? this.sim.getParams(command.id) : presetJson(this.module, Kind[command.character]);
  }
}

/** The scene, once the module has loaded ('init'). */
let scene: WorkerScene | null = null;
/** The options of 'init' while the module loads: a pause or a time scale given meanwhile goes into them. */
let loading: (SimOptions & { timeScale?: TimeScale }) | null = null;
/** A failure before the scene exists (loading the module). */
let failedEarly = false;

function fail(error: unknown): void {
  if (scene) {
    scene.fail(error);
    return;
  }
  if (failedEarly) return;
  failedEarly = true;
  console.error(error);
  post({ type: 'error', message: errorMessage(error) });
}

async function init(options: SimOptions): Promise<void> {
  if (!crossOriginIsolated) {
    throw new Error('the page is not cross-origin isolated, so WASM threads (SharedArrayBuffer) are unavailable');
  }
  loading = { ...options };
  const module = await loadGaitlab(options.wasmUrl, {
    print: (text) => console.log(`[gaitlab] ${text}`),
    printErr: (text) => console.warn(`[gaitlab] ${text}`),
    onAbort: (what) => fail(new Error(`the WASM module aborted: ${errorMessage(what)}`)),
  });
  const { timeScale, ...chosen } = loading;
  loading = null;
  scene = new WorkerScene(module, chosen);
  if (timeScale !== undefined) scene.setTimeScale(timeScale);
  scene.start();
}

function handle(command: SimCommand): void {
  if (command.type === 'init') {
    init(command.options).catch(fail);
    return;
  }
  if (command.type === 'getParams' || command.type === 'getPreset' || command.type === 'normalize') {
    let json: string | null = null;
    let error: string | null = null;
    try {
      if (command.type === 'normalize') {
        // Gait files and links are judged by the module alone (gl_gait_normalize).
        if (!scene) throw new Error('the module is not loaded yet');
        json = scene.normalize(command.json);
      } else {
        if (!scene) throw new Error('no simulation yet');
        json = scene.gaitJson(command);
      }
    } catch (e) {
      error = e instanceof GaitlabError ? e.detail : errorMessage(e);
    }
    post({ type: 'params', request: command.request, json, error });
    return;
  }
  if (!scene) {
    // Still loading: only the loop's settings can be taken now.
    if (loading && (command.type === 'pause' || command.type === 'resume')) loading.paused = command.type === 'pause';
    if (loading && command.type === 'timeScale') loading.timeScale = command.scale;
    return;
  }
  switch (command.type) {
    case 'pause':
      scene.pause();
      return;
    case 'resume':
      scene.resume();
      return;
    case 'reset':
      scene.requestReset();
      return;
    case 'step':
      scene.stepPaused(command.count ?? 1);
      return;
    case 'timeScale':
      scene.setTimeScale(command.scale);
      return;
    case 'scene':
      scene.queue(command.command);
      return;
    case 'released':
      scene.released(command.generation);
      return;
    default: {
      const unknown: never = command;
      throw new Error(`unknown command ${JSON.stringify(unknown)}`);
    }
  }
}

scope.onmessage = (event) => {
  if (scene?.hasFailed || failedEarly) return;
  try {
    // Every message is checked before anything acts on it (command-check.ts): a refused one is
    // answered with the field named, and the loop goes on.
    const checked = checkSimCommand(event.data);
    if (checked.ok) handle(checked.command);
    else refuseMessage(event.data, checked.error, checked.request);
  } catch (error) {
    fail(error);
  }
};

/** Answers a refused message: a request gets its answer (with the refusal), anything else a commandError. */
function refuseMessage(message: unknown, error: string, request: number | undefined): void {
  const type = typeof message === 'object' && message !== null ? (message as { type?: unknown }).type : undefined;
  if (type === 'init') {
    fail(new Error(`the worker's options were refused: ${error}`));
    return;
  }
  if (request !== undefined && (type === 'getParams' || type === 'getPreset' || type === 'normalize')) {
    post({ type: 'params', request, json: null, error });
    return;
  }
  const scene = type === 'scene' ? (message as { command?: { type?: unknown; request?: unknown } }).command : undefined;
  const sceneRequest = scene?.request;
  if (typeof sceneRequest === 'number' && Number.isInteger(sceneRequest) && sceneRequest >= 0) {
    if (scene?.type === 'patchParams') {
      post({ type: 'patched', request: sceneRequest, accepted: null, error });
      return;
    }
    if (scene?.type === 'spawnCreature') {
      post({ type: 'spawned', request: sceneRequest, id: null, error: `a message was refused: ${error}` });
      return;
    }
  }
  post({ type: 'commandError', message: `a message was refused: ${error}` });
}

// Errors outside the handlers above (e.g. thrown by the module's own callbacks).
self.addEventListener('error', (event) => fail(event.error ?? event.message));
self.addEventListener('unhandledrejection', (event) => fail((event as PromiseRejectionEvent).reason));
