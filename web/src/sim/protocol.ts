// Messages between the main thread and the sim worker.
//
// Only control traffic goes through postMessage: commands one way, lifecycle and statistics the
// other. Render transforms never do: the worker sends the WASM memory (a SharedArrayBuffer) and
// the render-header pointer once per scene, and the main thread reads every frame straight out of
// that memory (see render-buffer.ts).
import { MAX_THREADS } from './gaitlab-wasm';
import { isTerrainKind, type TerrainGrid, type TerrainKind } from './terrain-grid';
import type { CharacterType } from '../gait/character';
import type { ParamPatch, SpeedKeys } from '../share/gait-file';

export type { CharacterType } from '../gait/character';

/** How the worker should set up the simulation. */
export interface SimOptions {
  /** URL of the ES6 WASM glue (gaitlab.mjs); its .wasm and pthread worker sit next to it. */
  wasmUrl: string;
  /** Size of the simulation's thread pool (1 = serial). */
  threads: number;
  /** Seed of every random choice of the scene. */
  seed: number;
  /** Characters in the demo scene: a mixed crowd, bipeds and quadrupeds alternating. */
  characters: number;
  /** Start paused at step 0 (`?paused=1`): for stepping through a run, and for tests. */
  paused?: boolean;
  /** The ground the scene starts on (`?terrain=slope`); flat when absent. */
  terrain?: TerrainKind;
}

export type Vec3 = [number, number, number];

/**
 * Commands that change the running scene. The worker queues them and applies them at the start
 * of the next fixed step, logging each with that step's index, so
 * a run can be replayed from (seed, scene, command log). While paused they apply at once, which
 * is the same thing: no step happens in between.
 */
export type SceneCommand =
  /**
   * Steering goal of one character, or of all (of type `character` only, when given): forward
   * speed (m/s) and turn rate (rad/s, + = left). A character given a goal of its own stops
   * wandering (it is steered by hand); while the crowd wanders, a goal for all sets their speed
   * and wandering keeps choosing their turn rate.
   */
  | { type: 'setGoal'; id: number | 'all'; speed: number; turn: number; character?: CharacterType }
  /**
   * Arena wandering (native/src/sim/wander.h): on, every character but the learner wanders in
   * an arena sized for the crowd (characters added later too); off, each keeps its last goal.
   * With `id`, only that character (back to wandering, or out of it).
   */
  | { type: 'wander'; on: boolean; id?: number }
  /** A box of half size `half` (m) from `from` with `velocity` (m/s). */
  | { type: 'throwBox'; from: Vec3; velocity: Vec3; half: number }
  /**
   * A box of half size `half` thrown from `from` at character `id` (a shift-click on it): the
   * simulation aims it, from the character's state when the command is applied, at where point
   * `local` (segment frame, m) of its segment `segment` will be when the box, covering the
   * distance at `speed` m/s, arrives (gl_sim_throw_at).
   */
  | { type: 'throwAt'; from: Vec3; id: number; segment: number; local: Vec3; speed: number; half: number }
  /** Holds point `local` (segment frame) of segment `segment` of character `id` on a spring to `target`. */
  | { type: 'drag'; id: number; segment: number; local: Vec3; target: Vec3 }
  | { type: 'endDrag' }
  /** Respawns character `id` standing where it is, with its gait and goal. */
  | { type: 'resetCharacter'; id: number }
  /** Respawns every character that is down. */
  | { type: 'resetFallen' }
  | { type: 'remove'; id: number }
  /** `count` new characters on the next free places of the crowd's grid. */
  | { type: 'add'; kind: CharacterType; count: number }
  /**
   * A character whose body is a creature file's text (public/creatures/*.json) standing at
   * (x, z), facing `heading`, walking at `speed` m/s (gl_sim_spawn_creature), with the gait file
   * `gait` of its kind if given (else the gait its body walks when spawned). A refused file or
   * gait is said naming the field; a refused gait removes the creature again. With `request`,
   * answered by a `spawned` event (the new character's id, or the refusal); without, a refusal is
   * a `commandError`.
   */
  | { type: 'spawnCreature'; json: string; x: number; z: number; heading: number; speed: number; gait?: string; request?: number }
  /** Characters down for this long are reset automatically; 0 = never. */
  | { type: 'autoReset'; seconds: number }
  /**
   * New gait parameters (a gait file's JSON, gait-file.ts) for character `id`, or for every
   * character of `character`'s type with id 'all'.
   */
  | { type: 'setParams'; id: number | 'all'; character: CharacterType; json: string }
  /**
   * An edit: some parameters' new values for character `id`, or for every character of
   * `character`'s type with id 'all' (gl_sim_patch_params: each value checked against the
   * schema, all or nothing). With `request`, answered by a `patched` event.
   */
  | { type: 'patchParams'; id: number | 'all'; character: CharacterType; patch: ParamPatch; speedKeys?: SpeedKeys; request?: number }
  /**
   * The optimize panel's learner ("learning to walk", thesis Figure 3.6): a character of its
   * own, apart from the crowd, that walks a search's best gait so far. Each of these replaces
   * the previous learner by a fresh one at the learner's place, facing +z, with gait `json` and
   * goal (`speed`, `turn`); every `loopSeconds` of simulated time (0: never) it starts over
   * there, so it keeps showing the episode the objective scores. With `creature` (a creature
   * file's text, of `character`'s kind) it has that body rather than the kind's shipped one.
   */
  | { type: 'learner'; character: CharacterType; json: string; speed: number; turn: number; loopSeconds: number; creature?: string }
  /** Removes the learner, if there is one. */
  | { type: 'removeLearner' }
  /** The ground: flat, slope or bumps. Every character is re-placed standing on the new ground. */
  | { type: 'setTerrain'; terrain: TerrainKind };

/** One character as the worker last saw it (gl_sim_character_info). */
export interface CharacterStatus {
  id: number;
  type: CharacterType;
  /** Root leg frame's centre, metres. */
  position: Vec3;
  /** Radians about +y; 0 faces +z. */
  heading: number;
  /** Horizontal speed of the root leg frame, m/s. */
  speed: number;
  fallen: boolean;
  fallenSeconds: number;
  goal: { speed: number; turn: number };
  /** Gait phase in [0, 1). */
  phase: number;
  /** Its number of legs: 2, 4, 6 or 8 (its `type` is the kind its leg frames make). */
  legs: number;
  /** Wandering chooses its turn rate (else it keeps the goal it was given). */
  wanders?: boolean;
}

/**
 * Most characters the demo page holds: 256 of either type stay near real time on a 4-core
 * machine. The module has its own, larger limit from its memory (gl_sim_room: about 1200 bipeds
 * or 480 quadrupeds in a new scene, README "Limits"); the worker refuses an add beyond either,
 * naming the nearer.
 */
export const MAX_CHARACTERS = 256;

/** Slow motion: simulated seconds per wall-clock second the worker's clock aims for. */
export const TIME_SCALES = [1, 0.5, 0.25] as const;
export type TimeScale = (typeof TIME_SCALES)[number];

/** Main thread → sim worker. */
export type SimCommand =
  | { type: 'init'; options: SimOptions }
  | { type: 'pause' }
  | { type: 'resume' }
  /**
   * Rebuild the demo scene from the same seed: a new simulation, so a new render buffer. The
   * worker first asks the main thread to let go of the old one (event `release`).
   */
  | { type: 'reset' }
  /** Answer to `release`: the main thread no longer reads `generation`'s render buffer. */
  | { type: 'released'; generation: number }
  /** `count` fixed steps (default 1), when paused. */
  | { type: 'step'; count?: number }
  | { type: 'timeScale'; scale: TimeScale }
  | { type: 'scene'; command: SceneCommand }
  /** Asks for character `id`'s gait parameters; answered by a `params` event with the same request. */
  | { type: 'getParams'; request: number; id: number }
  /** Asks for a type's preset gait; answered by a `params` event. */
  | { type: 'getPreset'; request: number; character: CharacterType }
  /**
   * Asks the module to validate and normalise a gait file's JSON from outside (a link, a file):
   * answered by a `params` event with the normalised JSON, or the module's "FIELD: WHAT".
   */
  | { type: 'normalize'; request: number; json: string };

/** Statistics the worker reports a few times a second. */
export interface SimStats {
  generation: number;
  simTime: number;
  stepIndex: number;
  bodies: number;
  threads: number;
  paused: boolean;
  /** Mean wall-clock milliseconds per fixed step (one gl_sim_step call covers several). */
  stepMs: number;
  /** Fixed steps dropped since the last report because the machine could not keep up. */
  droppedSteps: number;
  timeScale: TimeScale;
  characters: CharacterStatus[];
  /** Scene commands applied so far (the command log's length). */
  commandsApplied: number;
  /** The optimize panel's learner's id, or null if there is none. */
  learner: number | null;
  /** The ground the simulation has now. */
  terrain: TerrainKind;
  /** Arena wandering: on or off for the crowd, and the arena's radius (m, about the origin). */
  wander?: { on: boolean; arenaRadius: number };
}

/** Sim worker → main thread. */
export type SimEvent =
  | {
      /** A (new) simulation exists; render from this memory and header from now on. */
      type: 'ready';
      generation: number;
      memory: SharedArrayBuffer;
      /** Byte offset of the RenderHeader in `memory`. */
      header: number;
      threads: number;
      version: string;
      /** The parameter schema (gl_schema_json), or null if this build has none. */
      schema: string | null;
      /** The optimiser's objective settings (gl_opt_settings_json), or null if this build has none. */
      optimizerSchema: string | null;
      /**
       * The goal speeds each type's preset walks, m/s: from 0 (it stops and stands) to
       * its fastest speed key (gl_top_speed). The steering sliders span them.
       */
      speedRanges: Record<CharacterType, { min: number; max: number }>;
    }
  /** Answer to getParams / getPreset / normalize: the gait file's JSON, or why there is none. */
  | { type: 'params'; request: number; json: string | null; error: string | null }
  /**
   * Answer to a patchParams with a request: the patch the simulation accepted, or null and the
   * refusal (the command and the parameter named).
   */
  | { type: 'patched'; request: number; accepted: ParamPatch | null; error: string | null }
  /** The answer to a `spawnCreature` with a request: the new character's id, or why there is none. */
  | { type: 'spawned'; request: number; id: number | null; error: string | null }
  /**
   * The ground of scene `generation` changed (or the scene is new): its grid and samples, to draw
   * it exactly as the physics has it. Sent after `ready` and after every setTerrain.
   */
  | { type: 'terrain'; generation: number; grid: TerrainGrid }
  /** A scene command the simulation refused (e.g. parameters out of bounds). */
  | { type: 'commandError'; message: string }
  /**
   * Stop reading `generation`'s render buffer and answer `released`: the worker is about to free
   * it. Only one simulation exists at a time, so the module's fixed pthread pool is never
   * exceeded (a pthread beyond the pool would not start while the worker blocks in a step).
   */
  | { type: 'release'; generation: number }
  | ({ type: 'stats' } & SimStats)
  | { type: 'error'; message: string };

/**
 * Most threads a simulation may use in the browser: the module's limit (GL_MAX_THREADS,
 * native/src/api/c_api.h, which says why), as the binding states it for option parsing before
 * the module loads.
 */
export { MAX_THREADS } from './gaitlab-wasm';

/** The thread count the demo uses: one per core, at most MAX_THREADS (and at least 1). */
export function defaultThreads(hardwareConcurrency: number | undefined): number {
  const cores = Number.isFinite(hardwareConcurrency) ? Math.floor(hardwareConcurrency as number) : 1;
  return Math.max(1, Math.min(cores, MAX_THREADS));
}

/** Most characters the page's `?characters=` may ask for at the start. */
export const MAX_START_CHARACTERS = 256;

/**
 * Simulation options from the page's query string, e.g. `?threads=1&seed=7&characters=12` (and
 * `terrain=slope|bumps`). A number out of range is replaced by the nearest valid value
 * (`?threads=0` runs 1 thread, `?characters=300` starts 256), anything else that is not valid by
 * the default; each replacement is said in `notes` (the page shows them), never done silently.
 */
export function simOptionsFromQuery(search: string, defaults: SimOptions, notes: string[] = []): SimOptions {
  const query = new URLSearchParams(search);
  const int = (name: string, min: number, max: number, fallback: number): number => {
    const raw = query.get(name);
    if (raw === null) return fallback;
    const text = raw.trim();
    const value = text === '' || !/^[-+]?(\d+\.?\d*|\.\d+)(e[-+]?\d+)?$/i.test(text) ? NaN : Number(text);
    if (!Number.isFinite(value)) {
      notes.push(`?${name}=${raw} is not a number: using ${fallback}`);
      return fallback;
    }
    const nearest = Math.min(max, Math.max(min, Math.round(value)));
    if (nearest !== value) notes.push(`?${name}=${raw} is not a whole number in [${min}, ${max}]: using ${nearest}`);
    return nearest;
  };
  const terrain = query.get('terrain');
  if (terrain !== null && !isTerrainKind(terrain)) notes.push(`?terrain=${terrain} is not flat, slope or bumps: using ${defaults.terrain ?? 'flat'}`);
  const paused = query.get('paused');
  if (paused !== null && paused !== '1' && paused !== '0') notes.push(`?paused=${paused} is not 1 or 0: not paused`);
  return {
    wasmUrl: defaults.wasmUrl,
    threads: int('threads', 1, MAX_THREADS, defaults.threads),
    seed: int('seed', 0, 0xffffffff, defaults.seed),
    characters: int('characters', 0, MAX_START_CHARACTERS, defaults.characters),
    ...(paused === '1' ? { paused: true } : {}),
    ...(isTerrainKind(terrain) && terrain !== 'flat' ? { terrain } : {}),
  };
}

/** A readable message from anything thrown (Emscripten aborts throw strings or numbers too). */
export function errorMessage(error: unknown): string {
  if (error instanceof Error) return `${error.name}: ${error.message}`;
  if (typeof error === 'string') return error;
  try {
    return JSON.stringify(error) ?? String(error);
  } catch {
    return String(error);
  }
}
