// The TypeScript binding of gaitlab's C ABI (native/src/api/c_api.h): the one place the page's
// workers (the sim worker, the optimiser's, the performance page's) call `_gl_` functions.
//
// The module is Emscripten 3.1.6 output: `gaitlab.mjs` default-exports a factory that resolves
// to the Module object. Its memory is fixed-size and shared (pthreads), so HEAPU8.buffer is a
// SharedArrayBuffer that stays valid for the module's lifetime.
//
// The ABI's contract (c_api.h): a refused call returns a negative GL_ERR_* code, NULL or NaN and
// leaves a message in gl_last_error; `check`, `checkPointer` and `checkNumber` turn that into a
// thrown GaitlabError carrying the message. Settings structs are written into module memory at
// the offsets of STRUCTS, which mirror c_api.h's static_asserts (tests/web/sim/gaitlab-wasm.test.ts
// compares them), after the library's own gl_*_defaults filled them.
import type { TerrainGrid, TerrainKind } from './terrain-grid';
import { KIND_NUMBERS } from '../gait/character';

/** The Emscripten Module with every function of the C ABI. Pointers are byte offsets (numbers). */
export interface GaitlabModule {
  HEAPU8: Uint8Array;
  HEAP32: Int32Array;
  HEAPU32: Uint32Array;
  HEAPF64: Float64Array;
  UTF8ToString(ptr: number): string;
  stringToUTF8(text: string, pointer: number, maxBytes: number): void;
  lengthBytesUTF8(text: string): number;
  _malloc(bytes: number): number;
  _free(pointer: number): void;

  _gl_last_error(): number;
  _gl_version(): number;
  _gl_max_threads(): number;
  _gl_pool_threads(): number;
  _gl_default_threads(): number;
  // Simulation.
  _gl_sim_create(threads: number, seed: number): number;
  _gl_sim_destroy(sim: number): void;
  _gl_sim_spawn(sim: number, kind: number, x: number, z: number, heading: number): number;
  _gl_sim_room(sim: number, kind: number): number;
  _gl_sim_add_characters(sim: number, kind: number, count: number): number;
  _gl_sim_add_apart(sim: number, kind: number): number;
  _gl_sim_spawn_creature(sim: number, creatureJson: number, x: number, z: number, heading: number): number;
  _gl_sim_add_apart_creature(sim: number, creatureJson: number): number;
  _gl_cruise_speed(kind: number): number;
  _gl_top_speed(kind: number): number;
  _gl_sim_demo_scene(sim: number, characters: number): number;
  _gl_sim_step(sim: number, steps: number): number;
  _gl_sim_time(sim: number): number;
  _gl_sim_step_index(sim: number): number;
  _gl_sim_body_count(sim: number): number;
  _gl_sim_threads(sim: number): number;
  _gl_sim_state_hash(sim: number): number;
  _gl_sim_render_buffer(sim: number): number;
  // Gait parameters.
  _gl_schema_json(): number;
  _gl_preset_json(kind: number): number;
  _gl_sim_set_params(sim: number, id: number, kind: number, json: number): number;
  _gl_sim_get_params(sim: number, id: number): number;
  _gl_sim_patch_params(sim: number, id: number, kind: number, patch: number): number;
  _gl_gait_normalize(json: number): number;
  // Interaction.
  _gl_sim_set_goal(sim: number, id: number, speed: number, turnRate: number): number;
  _gl_throw_defaults(settings: number): void;
  _gl_sim_throw_box(sim: number, settings: number): number;
  _gl_throw_at_defaults(settings: number): void;
  _gl_sim_throw_at(sim: number, settings: number): number;
  _gl_drag_defaults(settings: number): void;
  _gl_sim_drag(sim: number, settings: number): number;
  _gl_sim_end_drag(sim: number): void;
  _gl_sim_reset_character(sim: number, id: number): number;
  _gl_sim_remove_character(sim: number, id: number): number;
  _gl_sim_set_auto_reset(sim: number, seconds: number): number;
  _gl_sim_set_wander(sim: number, id: number, arenaRadius: number): number;
  _gl_sim_character_count(sim: number): number;
  _gl_sim_character_info(sim: number, out: number, capacity: number): number;
  // Terrain.
  _gl_sim_set_terrain(sim: number, kind: number): number;
  _gl_sim_terrain_grid(sim: number, out: number): void;
  _gl_sim_terrain_heights(sim: number): number;
  _gl_sim_ground_height(sim: number, x: number, z: number): number;
  // Optimisation.
  _gl_opt_defaults(settings: number): void;
  _gl_opt_create(settings: number, startJson: number, objectiveJson: number): number;
  _gl_opt_create_creature(settings: number, startJson: number, objectiveJson: number, creatureJson: number): number;
  _gl_opt_destroy(opt: number): void;
  _gl_opt_settings_json(): number;
  _gl_opt_step(opt: number): number;
  _gl_opt_generation(opt: number): number;
  _gl_opt_evaluations(opt: number): number;
  _gl_opt_best_json(opt: number): number;
  // Benchmark.
  _gl_bench_machine(): number;
  _gl_bench_warm_up(legs: number, threads: number): number;
  _gl_bench_max_characters(legs: number): number;
  _gl_bench_defaults(settings: number): void;
  _gl_bench_point(settings: number): number;
}

/**
 * Most threads a simulation, a search or a benchmark point uses: GL_MAX_THREADS of c_api.h (why
 * there is a limit is said there). Written out here because the page checks its options before
 * the module loads; tests/web/sim/gaitlab-wasm.test.ts checks it against the header, and
 * loadGaitlab against the module's gl_max_threads(). A loaded module serves at most
 * poolThreads(module): its pthread pool is sized from the device's cores when it loads.
 */
export const MAX_THREADS = 16;

/**
 * Physics shards of a crowd (sim::kCrowdShards, native/src/sim/physics_shards.h, which says why
 * 16): the benchmark's and the capacity search's crowds are split over this many Bullet worlds,
 * as the demo's is. tests/web/sim/gaitlab-wasm.test.ts checks it against the header.
 */
export const CROWD_SHARDS = 16;

/** GL_ERR_* of c_api.h: what a refused int-returning call returns. */
export const ERR = { argument: -1, kind: -2, noCharacter: -3, invalidParams: -4, full: -5 } as const;

/** Kinds for gl_sim_spawn (GL_KIND_*): the character types' numbers (gait/character.ts), and the box's. */
export const Kind = { ...KIND_NUMBERS, box: 2 } as const;
/** gl_sim_add_characters' kind for bipeds and quadrupeds in turn (GL_LAYOUT_ALTERNATING). */
export const ALTERNATING = 3;

/** Doubles per character written by gl_sim_character_info (GL_INFO_* in c_api.h). */
export const INFO = {
  id: 0,
  kind: 1,
  x: 2,
  y: 3,
  z: 4,
  heading: 5,
  speed: 6,
  fallen: 7,
  fallenSeconds: 8,
  goalSpeed: 9,
  goalTurn: 10,
  phase: 11,
  legs: 12,
  fields: 13,
} as const;

/** Terrain kinds of gl_sim_set_terrain (GL_TERRAIN_*), and the fields of gl_sim_terrain_grid (GL_GRID_*). */
export const TERRAIN: Record<TerrainKind, number> = { flat: 0, slope: 1, bumps: 2 };
const GRID = { kind: 0, columns: 1, rows: 2, spacing: 3, originX: 4, originZ: 5, plane: 6, fields: 7 } as const;

/** GL_METHOD_*, GL_LEGS_*, GL_MODE_* of c_api.h. */
export const METHOD = { greedy: 0, cmaes: 1 } as const;
export const LEGS = { mixed: 0, 2: 2, 4: 4 } as const;
export const MODE = { serial: 0, controller: 1, full: 2 } as const;

/**
 * Byte offsets of the settings structs' fields and their sizes (c_api.h static_asserts them).
 * A field's type: 'i32', 'u32', 'f64', or 'f64x3' (double[3]).
 */
export const STRUCTS = {
  gl_throw_settings: { size: 56, fields: { from: [0, 'f64x3'], velocity: [24, 'f64x3'], half: [48, 'f64'] } },
  gl_throw_at_settings: {
    size: 72,
    fields: { id: [0, 'i32'], segment: [4, 'i32'], from: [8, 'f64x3'], local: [32, 'f64x3'], speed: [56, 'f64'], half: [64, 'f64'] },
  },
  gl_drag_settings: { size: 56, fields: { id: [0, 'i32'], segment: [4, 'i32'], local: [8, 'f64x3'], target: [32, 'f64x3'] } },
  gl_opt_settings: {
    size: 20,
    fields: { kind: [0, 'i32'], method: [4, 'i32'], candidates: [8, 'i32'], threads: [12, 'i32'], seed: [16, 'u32'] },
  },
  gl_bench_settings: {
    size: 48,
    fields: {
      legs: [0, 'i32'], characters: [4, 'i32'], threads: [8, 'i32'], mode: [12, 'i32'], steps: [16, 'i32'],
      runs: [20, 'i32'], shards: [24, 'i32'], seed: [28, 'u32'], spacing: [32, 'f64'], frames: [40, 'i32'],
    },
  },
} as const;

type FieldType = 'i32' | 'u32' | 'f64' | 'f64x3';
type Layout = { size: number; fields: Record<string, readonly [number, FieldType]> };
type Vec3 = readonly [number, number, number] | readonly number[];
type FieldValue<T extends FieldType> = T extends 'f64x3' ? Vec3 : number;
/** Values for some fields of a struct; the others keep the library's defaults. */
export type StructValues<L extends Layout> = { [K in keyof L['fields']]?: FieldValue<L['fields'][K][1]> };

/** A refused call: `message` is gl_last_error's; `code` the GL_ERR_* it returned (0 for NULL or NaN). */
export class GaitlabError extends Error {
  /** gl_last_error's message alone, without the call's name. */
  readonly detail: string;

  constructor(readonly call: string, detail: string, readonly code = 0) {
    super(`${call}: ${detail}`);
    this.name = 'GaitlabError';
    this.detail = detail;
  }
}

/** gl_last_error: the message of the last refusal on this thread. */
export function lastError(module: GaitlabModule): string {
  return module.UTF8ToString(module._gl_last_error());
}

/** `result` of an int-returning call, or a GaitlabError if it is a refusal (negative). */
export function check(module: GaitlabModule, call: string, result: number): number {
  if (result < 0) throw new GaitlabError(call, lastError(module), result);
  return result;
}

/** `pointer` of a pointer-returning call, or a GaitlabError if it is NULL. */
export function checkPointer(module: GaitlabModule, call: string, pointer: number): number {
  if (!pointer) throw new GaitlabError(call, lastError(module));
  return pointer;
}

/** `value` of a double-returning call, or a GaitlabError if it is NaN. */
export function checkNumber(module: GaitlabModule, call: string, value: number): number {
  if (Number.isNaN(value)) throw new GaitlabError(call, lastError(module));
  return value;
}

/** The string a string-returning call returned, or a GaitlabError for NULL. */
function checkString(module: GaitlabModule, call: string, pointer: number): string {
  return module.UTF8ToString(checkPointer(module, call, pointer));
}

/** Runs `use` with a copy of `text` in module memory (NULL for null), freed afterwards. */
export function withString<T>(module: GaitlabModule, text: string | null, use: (pointer: number) => T): T {
  if (text === null) return use(0);
  const bytes = module.lengthBytesUTF8(text) + 1;
  const pointer = module._malloc(bytes);
  try {
    module.stringToUTF8(text, pointer, bytes);
    return use(pointer);
  } finally {
    module._free(pointer);
  }
}

/**
 * Runs `use` with a settings struct in module memory: filled by `defaults` (the library's
 * gl_*_defaults), then with `values` written over it; freed afterwards.
 */
export function withStruct<L extends Layout, T>(
  module: GaitlabModule,
  layout: L,
  defaults: (pointer: number) => void,
  values: StructValues<L>,
  use: (pointer: number) => T,
): T {
  const pointer = module._malloc(layout.size);
  try {
    defaults(pointer);
    for (const [name, value] of Object.entries(values) as Array<[string, number | Vec3 | undefined]>) {
      if (value === undefined) continue;
      const [offset, type] = layout.fields[name];
      const at = pointer + offset;
      if (type === 'i32') module.HEAP32[at >> 2] = value as number;
      else if (type === 'u32') module.HEAPU32[at >> 2] = (value as number) >>> 0;
      else if (type === 'f64') module.HEAPF64[at >> 3] = value as number;
      else (value as Vec3).forEach((v, i) => { module.HEAPF64[(at >> 3) + i] = v; });
    }
    return use(pointer);
  } finally {
    module._free(pointer);
  }
}

/** Options the 3.1.6 factory understands that gaitlab passes. */
export interface GaitlabModuleOptions {
  print?: (text: string) => void;
  printErr?: (text: string) => void;
  /** Called when the module aborts, on any of its threads (a pthread's abort is relayed). */
  onAbort?: (what: unknown) => void;
  /**
   * The threads its pthread pool serves (2 to MAX_THREADS), instead of the device's cores
   * (navigator.hardwareConcurrency): native/src/api/pthread_pool.pre.js.in.
   */
  poolThreads?: number;
}

export type GaitlabFactory = (options?: GaitlabModuleOptions) => Promise<GaitlabModule>;

/**
 * Loads the ES6 build from `url` (absolute, or relative to the calling module's origin), and
 * checks that the page's MAX_THREADS is the module's: the page and the module are built together.
 */
export async function loadGaitlab(url: string, options: GaitlabModuleOptions = {}): Promise<GaitlabModule> {
  // Not bundled: the module is a build product served next to its .wasm and pthread worker,
  // which it finds relative to its own URL.
  let glue: { default: GaitlabFactory };
  try {
    glue = (await import(/* @vite-ignore */ url)) as { default: GaitlabFactory };
  } catch (error) {
    const reason = error instanceof Error ? error.message : String(error);
    throw new Error(`cannot load the WASM module ${url} (${reason}). Is it built? (npm run build)`);
  }
  const module = await glue.default(options);
  if (module._gl_max_threads() !== MAX_THREADS) {
    throw new Error(`the WASM module allows ${module._gl_max_threads()} threads, the page ${MAX_THREADS}: rebuild both (npm run build)`);
  }
  return module;
}

/**
 * Most threads one simulation, search or benchmark point can use in this module (gl_pool_threads):
 * 1 + the workers of its pthread pool, sized from the device when the module loaded.
 */
export function poolThreads(module: GaitlabModule): number {
  return module._gl_pool_threads();
}

/** The library version string. */
export function gaitlabVersion(module: GaitlabModule): string {
  return module.UTF8ToString(module._gl_version());
}

/** The parameter schema (gl_schema_json) and the optimiser's settings table (gl_opt_settings_json). */
export function schemaJson(module: GaitlabModule): string {
  return module.UTF8ToString(module._gl_schema_json());
}
export function optimizerSettingsJson(module: GaitlabModule): string {
  return module.UTF8ToString(module._gl_opt_settings_json());
}

/** The preset gait file's JSON of a character kind. */
export function presetJson(module: GaitlabModule, kind: number): string {
  return checkString(module, 'gl_preset_json', module._gl_preset_json(kind));
}

/**
 * A gait file's JSON validated and normalised by the module (gl_gait_normalize): the current
 * schema version, every parameter, canonical values. Throws a GaitlabError with "FIELD: WHAT".
 */
export function normalizeGait(module: GaitlabModule, json: string): string {
  return withString(module, json, (pointer) => checkString(module, 'gl_gait_normalize', module._gl_gait_normalize(pointer)));
}

/** The fastest speed a character kind's preset gait is tuned for, m/s: its fastest speed key (gl_top_speed). */
export function topSpeed(module: GaitlabModule, kind: number): number {
  return checkNumber(module, 'gl_top_speed', module._gl_top_speed(kind));
}

/** The speed a character kind's preset is tuned for, m/s (gl_cruise_speed). */
export function cruiseSpeed(module: GaitlabModule, kind: number): number {
  return checkNumber(module, 'gl_cruise_speed', module._gl_cruise_speed(kind));
}

/** One simulation inside a loaded module; destroy() it when done. */
export class Simulation {
  readonly module: GaitlabModule;
  private handle: number;
  private scratch = 0;
  private scratchBytes = 0;

  constructor(module: GaitlabModule, threads: number, seed: number) {
    this.module = module;
    // NULL when the module cannot afford another simulation (its heap, or its fixed pthread pool).
    this.handle = checkPointer(module, 'gl_sim_create', module._gl_sim_create(threads, seed >>> 0));
  }

  private get sim(): number {
    if (!this.handle) throw new Error('the simulation was destroyed');
    return this.handle;
  }

  private check(call: string, result: number): number {
    return check(this.module, call, result);
  }

  demoScene(characters: number): void {
    this.check('gl_sim_demo_scene', this.module._gl_sim_demo_scene(this.sim, characters));
  }

  /** Spawns a thing of `kind` (Kind) standing at (x, z); returns its id. */
  spawn(kind: number, x: number, z: number, heading: number): number {
    return this.check('gl_sim_spawn', this.module._gl_sim_spawn(this.sim, kind, x, z, heading));
  }

  /**
   * How many more things of `kind` (Kind) the simulation can take now (gl_sim_room): the render
   * buffer's room, the most boxes a scene holds, and what the module's fixed heap can afford.
   */
  room(kind: number): number {
    return this.check('gl_sim_room', this.module._gl_sim_room(this.sim, kind));
  }

  /**
   * `count` characters in the next free places of the scene's layout (the first call sizes its
   * grid), walking at their cruise speed. Returns how many were added (the last characters of
   * characterInfo()); throws for a kind that is neither Kind.biped, Kind.quadruped nor ALTERNATING.
   */
  addCharacters(kind: number, count: number): number {
    return this.check('gl_sim_add_characters', this.module._gl_sim_add_characters(this.sim, kind, count));
  }

  /** One character at the layout's place apart, left of the grid; returns its id. */
  addApart(kind: number): number {
    return this.check('gl_sim_add_apart', this.module._gl_sim_add_apart(this.sim, kind));
  }

  /** Advances `steps` fixed steps of 1/120 s and publishes render transforms. */
  step(steps: number): void {
    this.check('gl_sim_step', this.module._gl_sim_step(this.sim, steps));
  }

  get time(): number {
    return this.module._gl_sim_time(this.sim);
  }

  get stepIndex(): number {
    // uint32 in C; wasm returns it as a signed i32.
    return this.module._gl_sim_step_index(this.sim) >>> 0;
  }

  get bodyCount(): number {
    return this.module._gl_sim_body_count(this.sim);
  }

  /** Characters in the scene (gl_sim_character_count). */
  get characterCount(): number {
    return this.module._gl_sim_character_count(this.sim);
  }

  get threads(): number {
    return this.module._gl_sim_threads(this.sim);
  }

  stateHash(): string {
    return this.module.UTF8ToString(this.module._gl_sim_state_hash(this.sim));
  }

  // ---- Interaction ----

  /** The goal of character `id`, or of every character with id −1. */
  setGoal(id: number, speed: number, turnRate: number): void {
    this.check('gl_sim_set_goal', this.module._gl_sim_set_goal(this.sim, id, speed, turnRate));
  }

  /** Throws a box; returns its id. */
  throwBox(from: Vec3, velocity: Vec3, half: number): number {
    const m = this.module;
    return withStruct(m, STRUCTS.gl_throw_settings, (p) => m._gl_throw_defaults(p), { from, velocity, half },
      (p) => this.check('gl_sim_throw_box', m._gl_sim_throw_box(this.sim, p)));
  }

  /**
   * Throws a box from `from` at character `id`, aimed by the simulation at where point `local`
   * of its segment `segment` will be when the box, covering the distance at `speed` m/s,
   * arrives (gl_sim_throw_at); returns its id.
   */
  throwAt(from: Vec3, id: number, segment: number, local: Vec3, speed: number, half: number): number {
    const m = this.module;
    return withStruct(m, STRUCTS.gl_throw_at_settings, (p) => m._gl_throw_at_defaults(p), { id, segment, from, local, speed, half },
      (p) => this.check('gl_sim_throw_at', m._gl_sim_throw_at(this.sim, p)));
  }

  drag(id: number, segment: number, local: Vec3, target: Vec3): void {
    const m = this.module;
    withStruct(m, STRUCTS.gl_drag_settings, (p) => m._gl_drag_defaults(p), { id, segment, local, target },
      (p) => this.check('gl_sim_drag', m._gl_sim_drag(this.sim, p)));
  }

  endDrag(): void {
    this.module._gl_sim_end_drag(this.sim);
  }

  resetCharacter(id: number): void {
    this.check('gl_sim_reset_character', this.module._gl_sim_reset_character(this.sim, id));
  }

  removeCharacter(id: number): void {
    this.check('gl_sim_remove_character', this.module._gl_sim_remove_character(this.sim, id));
  }

  /**
   * Character `id` (or every character now in the scene with -1) wanders inside an arena of
   * `arenaRadius` metres about the origin; 0 stops it (native/src/sim/wander.h).
   */
  setWander(id: number, arenaRadius: number): void {
    this.check('gl_sim_set_wander', this.module._gl_sim_set_wander(this.sim, id, arenaRadius));
  }

  setAutoReset(seconds: number): void {
    this.check('gl_sim_set_auto_reset', this.module._gl_sim_set_auto_reset(this.sim, seconds));
  }

  /**
   * Every character's record (INFO fields), as one Float64Array of count × INFO.fields. A
   * scratch block in module memory is kept and grown as needed.
   */
  characterInfo(): Float64Array {
    const count = this.module._gl_sim_character_count(this.sim);
    const bytes = Math.max(1, count) * INFO.fields * 8;
    if (bytes > this.scratchBytes) {
      if (this.scratch) this.module._free(this.scratch);
      this.scratch = this.module._malloc(bytes);
      this.scratchBytes = bytes;
    }
    const n = this.check('gl_sim_character_info', this.module._gl_sim_character_info(this.sim, this.scratch, count));
    const start = this.scratch >> 3;
    // A copy: the heap view must not leave the worker (and the block is reused).
    return this.module.HEAPF64.slice(start, start + Math.min(n, count) * INFO.fields);
  }

  // ---- Gait parameters ----

  /** Character `id`'s parameters as a gait file's JSON. */
  getParams(id: number): string {
    return checkString(this.module, 'gl_sim_get_params', this.module._gl_sim_get_params(this.sim, id));
  }

  /** Sets parameters (gait file JSON) of `id`, or of every character of `kind` with id −1. */
  /**
   * Spawns a character whose body is a creature file's text (public/creatures/*.json) standing
   * at (x, z), facing `heading`; it starts without a goal. Returns its id; a refused file throws a
   * GaitlabError naming the field ("creature: FIELD: WHAT").
   */
  spawnCreature(json: string, x: number, z: number, heading: number): number {
    return withString(this.module, json, (pointer) =>
      this.check('gl_sim_spawn_creature', this.module._gl_sim_spawn_creature(this.sim, pointer, x, z, heading)));
  }

  /** A creature (spawnCreature) at the scene layout's place apart (gl_sim_add_apart_creature). */
  addApartCreature(json: string): number {
    return withString(this.module, json, (pointer) =>
      this.check('gl_sim_add_apart_creature', this.module._gl_sim_add_apart_creature(this.sim, pointer)));
  }

  setParams(id: number, kind: number, json: string): void {
    withString(this.module, json, (pointer) =>
      this.check('gl_sim_set_params', this.module._gl_sim_set_params(this.sim, id, kind, pointer)));
  }

  /**
   * Changes some parameters ({name: value} JSON) of `id`, or of every character of `kind` with
   * id −1, all or nothing; a refused value throws a GaitlabError with "NAME: WHAT".
   */
  patchParams(id: number, kind: number, patch: string): void {
    withString(this.module, patch, (pointer) =>
      this.check('gl_sim_patch_params', this.module._gl_sim_patch_params(this.sim, id, kind, pointer)));
  }

  // ---- Terrain ----

  /** Sets the ground; characters are re-placed on it. */
  setTerrain(kind: TerrainKind): void {
    this.check('gl_sim_set_terrain', this.module._gl_sim_set_terrain(this.sim, TERRAIN[kind]));
  }

  /** The ground's grid and a copy of its samples (the module's array must not leave the worker). */
  terrainGrid(): TerrainGrid {
    const out = this.module._malloc(GRID.fields * 8);
    try {
      this.module._gl_sim_terrain_grid(this.sim, out);
      const f = this.module.HEAPF64.slice(out >> 3, (out >> 3) + GRID.fields);
      const kinds = Object.keys(TERRAIN) as TerrainKind[];
      const columns = f[GRID.columns];
      const rows = f[GRID.rows];
      // NULL when flat: no samples (not a refusal).
      const pointer = this.module._gl_sim_terrain_heights(this.sim);
      const heights = pointer && columns > 0 && rows > 0
        ? new Float32Array(this.module.HEAPU8.buffer, pointer, columns * rows).slice()
        : null;
      return {
        kind: kinds.find((k) => TERRAIN[k] === f[GRID.kind]) ?? 'flat',
        columns, rows, spacing: f[GRID.spacing], originX: f[GRID.originX], originZ: f[GRID.originZ], plane: f[GRID.plane], heights,
      };
    } finally {
      this.module._free(out);
    }
  }

  /** Byte address of the RenderHeader in module memory (render-buffer.ts reads it). */
  get renderHeader(): number {
    return this.module._gl_sim_render_buffer(this.sim);
  }

  get memory(): ArrayBufferLike {
    return this.module.HEAPU8.buffer;
  }

  destroy(): void {
    if (this.scratch) this.module._free(this.scratch);
    this.scratch = this.scratchBytes = 0;
    if (this.handle) this.module._gl_sim_destroy(this.handle);
    this.handle = 0;
  }
}

/** The search's own settings (gl_opt_settings); the objective's go as a JSON object. */
export type SearchSettings = StructValues<typeof STRUCTS.gl_opt_settings>;

/** A parameter search, one generation at a time (gl_opt_*); destroy() it when done. */
export class Search {
  readonly module: GaitlabModule;
  private handle: number;

  /**
   * `start`: a gait file's JSON, or null for the preset; `objective`: objective settings, or null;
   * `creature`: a creature file's text whose body every episode walks (gl_opt_create_creature), or
   * null for the kind's shipped body.
   */
  constructor(module: GaitlabModule, settings: SearchSettings, start: string | null, objective: Record<string, unknown> | null, creature: string | null = null) {
    this.module = module;
    this.handle = withStruct(module, STRUCTS.gl_opt_settings, (p) => module._gl_opt_defaults(p), settings, (s) =>
      withString(module, start, (startPointer) =>
        withString(module, objective === null ? null : JSON.stringify(objective), (objectivePointer) =>
          withString(module, creature, (creaturePointer) =>
            checkPointer(module, 'gl_opt_create_creature', module._gl_opt_create_creature(s, startPointer, objectivePointer, creaturePointer))))));
  }

  private get opt(): number {
    if (!this.handle) throw new Error('the search was destroyed');
    return this.handle;
  }

  /** Runs one generation; returns the best objective so far. */
  step(): number {
    return this.module._gl_opt_step(this.opt);
  }

  get generation(): number {
    return this.module._gl_opt_generation(this.opt);
  }

  get evaluations(): number {
    return this.module._gl_opt_evaluations(this.opt);
  }

  /** The best parameters so far, as a gait file's JSON. */
  bestJson(): string {
    return this.module.UTF8ToString(this.module._gl_opt_best_json(this.opt));
  }

  destroy(): void {
    if (this.handle) this.module._gl_opt_destroy(this.handle);
    this.handle = 0;
  }
}

/** One point of the benchmark (gl_bench_settings). */
export type BenchSettings = StructValues<typeof STRUCTS.gl_bench_settings>;

/** The performance page's calls (gl_bench_*): the measurement `gaitlab bench` runs natively. */
export const bench = {
  /** The machine object of a result document. */
  machine(module: GaitlabModule): Record<string, unknown> {
    return JSON.parse(module.UTF8ToString(module._gl_bench_machine())) as Record<string, unknown>;
  },
  /** The largest crowd of `legs` (GL_LEGS_*) one simulation holds. */
  maxCharacters(module: GaitlabModule, legs: number): number {
    return check(module, 'gl_bench_max_characters', module._gl_bench_max_characters(legs));
  },
  warmUp(module: GaitlabModule, legs: number, threads: number): void {
    check(module, 'gl_bench_warm_up', module._gl_bench_warm_up(legs, threads));
  },
  /** Runs one point; returns its element of the document's "points". */
  point(module: GaitlabModule, settings: BenchSettings): Record<string, unknown> {
    return withStruct(module, STRUCTS.gl_bench_settings, (p) => module._gl_bench_defaults(p), settings, (p) =>
      JSON.parse(checkString(module, 'gl_bench_point', module._gl_bench_point(p))) as Record<string, unknown>);
  },
};
