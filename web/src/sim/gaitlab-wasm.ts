// Typed access to the gaitlab WASM module (native/src/api/c_api.h) from JavaScript.
//
// The module is Emscripten 3.1.6 output: `gaitlab.mjs` default-exports a factory that resolves
// to the Module object. Its memory is fixed-size and shared (pthreads), so HEAPU8.buffer is a
// SharedArrayBuffer that stays valid for the module's lifetime.
import { FLAT_GROUND, type TerrainGrid, type TerrainKind } from './terrain-grid';
import { CHARACTER_TYPES, type CharacterType } from '../gait/character';

/** The parts of the Emscripten Module that gaitlab uses. Pointers are byte offsets (numbers). */
export interface GaitlabModule {
  HEAPU8: Uint8Array;
  UTF8ToString(ptr: number): string;
  _gl_version(): number;
  _gl_sim_create(threads: number, seed: number): number;
  _gl_sim_destroy(sim: number): void;
  _gl_sim_spawn(sim: number, kind: number, x: number, z: number, heading: number): number;
  _gl_sim_demo_scene(sim: number, characters: number): void;
  _gl_cruise_speed(kind: number): number;
  _gl_sim_step(sim: number, steps: number): void;
  _gl_sim_time(sim: number): number;
  _gl_sim_step_index(sim: number): number;
  _gl_sim_body_count(sim: number): number;
  _gl_sim_threads(sim: number): number;
  _gl_sim_state_hash(sim: number): number;
  _gl_sim_render_buffer(sim: number): number;
  // Interaction (c_api.h, "Interaction: the demo page's commands").
  _gl_sim_set_goal(sim: number, id: number, speed: number, turnRate: number): number;
  _gl_sim_throw_box(sim: number, x: number, y: number, z: number, vx: number, vy: number, vz: number, half: number): number;
  _gl_sim_drag(sim: number, id: number, segment: number, lx: number, ly: number, lz: number, tx: number, ty: number, tz: number): number;
  _gl_sim_end_drag(sim: number): void;
  _gl_sim_reset_character(sim: number, id: number): number;
  _gl_sim_remove_character(sim: number, id: number): number;
  _gl_sim_set_auto_reset(sim: number, seconds: number): void;
  _gl_sim_character_count(sim: number): number;
  _gl_sim_character_info(sim: number, out: number, capacity: number): number;
  // Terrain (c_api.h, "Terrain"); absent from builds before it.
  _gl_sim_set_terrain?(sim: number, kind: number): number;
  _gl_sim_terrain_grid?(sim: number, out: number): void;
  _gl_sim_terrain_heights?(sim: number): number;
  _malloc(bytes: number): number;
  _free(pointer: number): void;
  HEAPF64: Float64Array;
  // The parameter schema and gait files (c_api.h, "Gait parameters"); absent from builds before them.
  _gl_schema_json?(): number;
  _gl_preset_json?(kind: number): number;
  _gl_sim_set_params?(sim: number, id: number, kind: number, json: number): number;
  _gl_sim_get_params?(sim: number, id: number): number;
  _gl_sim_patch_params?(sim: number, id: number, kind: number, patch: number): number;
  _gl_gait_normalize?(json: number): number;
  _gl_last_error?(): number;
  // The optimiser's settings table (the optimize panel; absent from builds before it).
  _gl_opt_settings_json?(): number;
  stringToUTF8(text: string, pointer: number, maxBytes: number): void;
  lengthBytesUTF8(text: string): number;
}

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
  fields: 12,
} as const;

/** Terrain kinds of gl_sim_set_terrain (GL_TERRAIN_*), and the fields of gl_sim_terrain_grid (GL_GRID_*). */
export const TERRAIN: Record<TerrainKind, number> = { flat: 0, slope: 1, bumps: 2 };
const GRID = { kind: 0, columns: 1, rows: 2, spacing: 3, originX: 4, originZ: 5, plane: 6, fields: 7 } as const;

/** Options the 3.1.6 factory understands that gaitlab passes. */
export interface GaitlabModuleOptions {
  print?: (text: string) => void;
  printErr?: (text: string) => void;
  /** Called when the module aborts, on any of its threads (a pthread's abort is relayed). */
  onAbort?: (what: unknown) => void;
}

export type GaitlabFactory = (options?: GaitlabModuleOptions) => Promise<GaitlabModule>;

/** Kinds for gl_sim_spawn: the character types in their order (gait/character.ts), then the box. */
export const Kind = {
  ...(Object.fromEntries(CHARACTER_TYPES.map((t, i) => [t, i])) as Record<CharacterType, number>),
  box: CHARACTER_TYPES.length,
} as const;

/** Calls `call` with `text` as a C string in module memory (freed afterwards). */
function withCString<T>(module: GaitlabModule, text: string, call: (pointer: number) => T): T {
  const bytes = module.lengthBytesUTF8(text) + 1;
  const pointer = module._malloc(bytes);
  try {
    module.stringToUTF8(text, pointer, bytes);
    return call(pointer);
  } finally {
    module._free(pointer);
  }
}

/**
 * A gait file's JSON validated and normalised by the module (gl_gait_normalize): the current
 * schema version, every parameter, canonical values. Throws the module's "FIELD: WHAT".
 */
export function normalizeGait(module: GaitlabModule, json: string): string {
  if (!module._gl_gait_normalize) throw new Error('this build of the module cannot read gait files (no gl_gait_normalize)');
  const out = withCString(module, json, (pointer) => module._gl_gait_normalize!(pointer));
  if (!out) throw new Error(module._gl_last_error ? module.UTF8ToString(module._gl_last_error()) : 'refused');
  return module.UTF8ToString(out);
}

/** Loads the ES6 build from `url` (absolute, or relative to the calling module's origin). */
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
  return glue.default(options);
}

/** The library version string. */
export function gaitlabVersion(module: GaitlabModule): string {
  return module.UTF8ToString(module._gl_version());
}

/** One simulation inside a loaded module; destroy() it when done. */
export class Simulation {
  readonly module: GaitlabModule;
  private handle: number;

  constructor(module: GaitlabModule, threads: number, seed: number) {
    this.module = module;
    this.handle = module._gl_sim_create(threads, seed >>> 0);
    if (!this.handle) throw new Error(`gl_sim_create(${threads}, ${seed}) failed`);
  }

  private get sim(): number {
    if (!this.handle) throw new Error('the simulation was destroyed');
    return this.handle;
  }

  demoScene(characters: number): void {
    this.module._gl_sim_demo_scene(this.sim, characters);
  }

  spawn(kind: number, x: number, z: number, heading: number): number {
    return this.module._gl_sim_spawn(this.sim, kind, x, z, heading);
  }

  /** Advances `steps` fixed steps of 1/120 s and publishes render transforms. */
  step(steps: number): void {
    this.module._gl_sim_step(this.sim, steps);
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

  get threads(): number {
    return this.module._gl_sim_threads(this.sim);
  }

  stateHash(): string {
    return this.module.UTF8ToString(this.module._gl_sim_state_hash(this.sim));
  }

  // ---- Interaction ----

  /** Returns 0, or -1 if no character has this id (-1 = all characters). */
  setGoal(id: number, speed: number, turnRate: number): number {
    return this.module._gl_sim_set_goal(this.sim, id, speed, turnRate);
  }

  throwBox(from: readonly number[], velocity: readonly number[], half: number): number {
    return this.module._gl_sim_throw_box(this.sim, from[0], from[1], from[2], velocity[0], velocity[1], velocity[2], half);
  }

  drag(id: number, segment: number, local: readonly number[], target: readonly number[]): number {
    return this.module._gl_sim_drag(this.sim, id, segment, local[0], local[1], local[2], target[0], target[1], target[2]);
  }

  endDrag(): void {
    this.module._gl_sim_end_drag(this.sim);
  }

  resetCharacter(id: number): number {
    return this.module._gl_sim_reset_character(this.sim, id);
  }

  removeCharacter(id: number): number {
    return this.module._gl_sim_remove_character(this.sim, id);
  }

  setAutoReset(seconds: number): void {
    this.module._gl_sim_set_auto_reset(this.sim, seconds);
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
    const n = this.module._gl_sim_character_info(this.sim, this.scratch, count);
    const start = this.scratch >> 3;
    // A copy: the heap view must not leave the worker (and the block is reused).
    return this.module.HEAPF64.slice(start, start + Math.min(n, count) * INFO.fields);
  }

  // ---- Gait parameters (c_api.h, "Gait parameters"; absent from builds before them) ----

  private requireSchema(): void {
    if (!this.module._gl_sim_get_params) throw new Error('this build of the module has no parameter schema');
  }

  private lastError(): string {
    return this.module._gl_last_error ? this.module.UTF8ToString(this.module._gl_last_error()) : 'unknown error';
  }

  /** Character `id`'s parameters as a gait file's JSON. */
  getParams(id: number): string {
    this.requireSchema();
    const pointer = this.module._gl_sim_get_params!(this.sim, id);
    if (!pointer) throw new Error(this.lastError());
    return this.module.UTF8ToString(pointer);
  }

  /** The preset gait file's JSON of a kind. */
  presetJson(kind: number): string {
    this.requireSchema();
    const pointer = this.module._gl_preset_json!(kind);
    if (!pointer) throw new Error(this.lastError());
    return this.module.UTF8ToString(pointer);
  }

  /** Sets parameters (gait file JSON) of `id` or of every character of `kind` (id −1); returns null or the problem. */
  setParams(id: number, kind: number, json: string): string | null {
    if (!this.module._gl_sim_set_params) return 'this build of the module has no parameter schema';
    const code = withCString(this.module, json, (pointer) => this.module._gl_sim_set_params!(this.sim, id, kind, pointer));
    return code === 0 ? null : this.lastError();
  }

  /** Changes some parameters ({name: value} JSON) of `id` or of every character of `kind` (id −1), all or nothing; returns null or the problem ("NAME: WHAT"). */
  patchParams(id: number, kind: number, patch: string): string | null {
    if (!this.module._gl_sim_patch_params) return 'this build of the module cannot patch parameters';
    const code = withCString(this.module, patch, (pointer) => this.module._gl_sim_patch_params!(this.sim, id, kind, pointer));
    return code === 0 ? null : this.lastError();
  }

  // ---- Terrain ----

  /** Whether this build of the module has terrain (gl_sim_set_terrain). */
  get hasTerrain(): boolean {
    return typeof this.module._gl_sim_set_terrain === 'function';
  }

  /** Sets the ground; characters are re-placed on it. Returns false for a build without terrain. */
  setTerrain(kind: TerrainKind): boolean {
    if (!this.module._gl_sim_set_terrain) return kind === 'flat';
    return this.module._gl_sim_set_terrain(this.sim, TERRAIN[kind]) === 0;
  }

  /** The ground's grid and a copy of its samples (the module's array must not leave the worker). */
  terrainGrid(): TerrainGrid {
    if (!this.module._gl_sim_terrain_grid || !this.module._gl_sim_terrain_heights) return { ...FLAT_GROUND };
    const out = this.module._malloc(GRID.fields * 8);
    try {
      this.module._gl_sim_terrain_grid(this.sim, out);
      const f = this.module.HEAPF64.slice(out >> 3, (out >> 3) + GRID.fields);
      const kinds = Object.keys(TERRAIN) as TerrainKind[];
      const columns = f[GRID.columns];
      const rows = f[GRID.rows];
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

  private scratch = 0;
  private scratchBytes = 0;

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
