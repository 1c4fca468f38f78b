// The gait file: one character's gait parameters as JSON, the format the CLI reads with
// `--params` and the page exports and imports (and carries, compressed, in share links):
//
//   {"format": "gaitlab-gait", "version": 2, "character": "biped" | "quadruped",
//    "params": {"<dotted name>": number | [4 numbers]}, "meta": {...}}
//
// The page only describes the format here. Which fields exist, their bounds, and how a file of
// an older schema version is brought up to date are the module's alone (native/src/gait/
// schema.cpp and params_io.cpp): everything read from outside — a file, a link — is sent to the
// module (gl_gait_normalize, through the sim worker) and comes back normalised or refused with
// the field named ("FIELD: WHAT").
import type { CharacterType } from '../gait/character';

export type { CharacterType } from '../gait/character';

/** A leg frame or a leg of a character, as the schema names it (thesis §3.3: parameters per leg frame, per leg). */
export interface SchemaPart {
  index: number;
  name: string;
}

/** One parameter of the schema (gl_schema_json). */
export interface SchemaEntry {
  name: string;
  group: string;
  min: number;
  max: number;
  default: number | number[];
  unit: string;
  description: string;
  /** 1: a scalar; 4: a piecewise-linear graph over the gait phase with 4 knots. */
  knots: number;
  /** The parameter's own name within its leg or leg frame ("dutyFactor"), or its whole name. */
  field: string;
  /** The leg frame a per-leg-frame parameter belongs to. */
  legFrame?: SchemaPart;
  /** The leg a per-leg parameter belongs to. */
  leg?: SchemaPart;
}

/** A leg of a character's morphology: its leg frame, and on which side of the body it is. */
export interface SchemaLeg extends SchemaPart {
  legFrame: number;
  side: 'left' | 'right';
}

/** A character's body as the schema describes it (native/src/body/morphology.cpp's order). */
export interface SchemaMorphology {
  /** The module's kind number (gl_sim_spawn). */
  kind: number;
  legFrames: SchemaPart[];
  legs: SchemaLeg[];
}

export interface ParamSchema {
  version: number;
  characters: Record<CharacterType, SchemaEntry[]>;
  morphologies: Record<CharacterType, SchemaMorphology>;
}

export type ParamValue = number | number[];

/** Some parameters and their new values: an edit of a gait. */
export type ParamPatch = Record<string, ParamValue>;

/**
 * A complete parameter set tuned at one speed. A gait of schema 4 may have several: its "params"
 * tuned at its "speed", and more "keys"; the module blends them by the desired speed
 * (native/src/gait/speed_keys.h).
 */
export interface SpeedKey {
  speed: number;
  params: Record<string, ParamValue>;
}

/** A gait's speed keys besides its parameters: the speed "params" is tuned at, and the other keys. */
export interface SpeedKeys {
  speed: number;
  keys: SpeedKey[];
}

export interface GaitFile {
  format: 'gaitlab-gait';
  version: number;
  character: CharacterType;
  /** m/s, the speed `params` is tuned at (absent: 0). */
  speed?: number;
  params: Record<string, ParamValue>;
  /** More parameter sets tuned at other speeds (absent: none). */
  keys?: SpeedKey[];
  meta?: Record<string, unknown>;
}

/** The speed keys of `gait`, with the defaults of a gait without them. */
export function speedKeysOf(gait: GaitFile): SpeedKeys {
  return { speed: gait.speed ?? 0, keys: gait.keys ?? [] };
}

export const GAIT_FORMAT = 'gaitlab-gait';

/** What was wrong with a gait from outside, in words a user can act on. */
export type GaitProblem =
  | 'truncated'
  | 'corrupt'
  | 'too-long'
  | 'unknown-version'
  /** The module refused the gait inside: the message names the field ("FIELD: WHAT"). */
  | 'refused';

export class GaitError extends Error {
  readonly problem: GaitProblem;
  constructor(problem: GaitProblem, message: string) {
    super(message);
    this.name = 'GaitError';
    this.problem = problem;
  }
}

/**
 * Sends a gait file's text to the module and resolves with it normalised (the current schema
 * version, every parameter, canonical values), or rejects with the module's refusal.
 */
export type GaitNormalizer = (json: string) => Promise<GaitFile>;

/** The schema's defaults for a character, as a complete gait. */
export function presetGait(schema: ParamSchema, character: CharacterType): GaitFile {
  const params: Record<string, ParamValue> = {};
  for (const e of schema.characters[character]) params[e.name] = Array.isArray(e.default) ? [...e.default] : e.default;
  return { format: GAIT_FORMAT, version: schema.version, character, params };
}

const sameValue = (x: ParamValue | undefined, y: ParamValue | undefined): boolean => {
  if (Array.isArray(x) || Array.isArray(y)) {
    return Array.isArray(x) && Array.isArray(y) && x.length === y.length && x.every((v, i) => Object.is(v, y[i]));
  }
  return Object.is(x, y);
};

/** Two gaits have the same parameters, exactly (bit for bit: what the sharing tests ask). */
export function sameParams(a: GaitFile, b: GaitFile): boolean {
  if (a.character !== b.character) return false;
  if (JSON.stringify(speedKeysOf(a)) !== JSON.stringify(speedKeysOf(b))) return false;
  const keys = Object.keys(a.params);
  if (keys.length !== Object.keys(b.params).length) return false;
  return keys.every((k) => sameValue(a.params[k], b.params[k]));
}

/**
 * `gait` with `patch` applied, and its speed keys replaced by `speedKeys` when given (a new object;
 * `gait` is left as it was).
 */
export function patched(gait: GaitFile, patch: ParamPatch, speedKeys?: SpeedKeys): GaitFile {
  const params = { ...gait.params };
  for (const [name, value] of Object.entries(patch)) params[name] = Array.isArray(value) ? [...value] : value;
  const result: GaitFile = { ...gait, params };
  if (speedKeys) {
    delete result.speed;
    delete result.keys;
    if (speedKeys.speed !== 0 || speedKeys.keys.length > 0) {
      result.speed = speedKeys.speed;
      result.keys = structuredClone(speedKeys.keys);
    }
  }
  return result;
}
