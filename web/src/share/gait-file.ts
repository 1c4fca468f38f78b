// The gait file: one character's gait parameters as JSON, the format the CLI reads with
// `--params` and the page exports and imports (and carries, compressed, in share links):
//
//   {"format": "gaitlab-gait", "version": 2, "character": "biped" | "quadruped",
//    "params": {"<dotted name>": number | [4 numbers]}, "meta": {...}}
//
// `version` is the parameter schema's version (gl_schema_json). Everything read from outside —
// a file, a link — goes through parseGait(), which checks it against the schema and says exactly
// what is wrong rather than letting a bad value reach the simulation.

export type CharacterType = 'biped' | 'quadruped';
export const CHARACTER_TYPES: readonly CharacterType[] = ['biped', 'quadruped'];

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
}

export interface ParamSchema {
  version: number;
  characters: Record<CharacterType, SchemaEntry[]>;
}

export type ParamValue = number | number[];

export interface GaitFile {
  format: 'gaitlab-gait';
  version: number;
  character: CharacterType;
  params: Record<string, ParamValue>;
  meta?: Record<string, unknown>;
}

export const GAIT_FORMAT = 'gaitlab-gait';

/** What was wrong with a gait from outside, in words a user can act on. */
export type GaitProblem =
  | 'truncated'
  | 'corrupt'
  | 'too-long'
  | 'unknown-version'
  | 'out-of-bounds'
  | 'not-finite'
  | 'invalid';

export class GaitError extends Error {
  readonly problem: GaitProblem;
  constructor(problem: GaitProblem, message: string) {
    super(message);
    this.name = 'GaitError';
    this.problem = problem;
  }
}

/**
 * Upgrades a gait made against an older schema version by one version: renames, re-scales,
 * defaults for new parameters. Keyed by the version it upgrades *from*; when a schema change
 * renames, removes or re-scales a parameter, its migration goes here, and links and files made
 * before keep working. The native loader does the same (migrateParams in
 * native/src/gait/params_io.cpp).
 */
export type Migration = (gait: GaitFile) => GaitFile;
export const MIGRATIONS: Readonly<Record<number, Migration>> = {
  // 1 → 2: the quadruped's whole-body stance replaced the per-leg-frame support gain; the swing
  // PDs may follow their targets' velocity (gains.swingTargetRate; 0 keeps the old behaviour).
  1: (gait) => {
    const params = Object.fromEntries(Object.entries(gait.params).filter(([name]) => !name.endsWith('.supportGain')));
    return { ...gait, params: { 'gains.swingTargetRate': 0, ...params } };
  },
};

const isRecord = (value: unknown): value is Record<string, unknown> =>
  typeof value === 'object' && value !== null && !Array.isArray(value);

/** A readable number for messages: enough digits to see the value, not float noise. */
const show = (x: number) => (Number.isFinite(x) ? String(Number(x.toPrecision(6))) : String(x));

/**
 * Checks `data` (parsed JSON) against the schema and returns it as a GaitFile of the schema's
 * version (migrated if it was older), or throws a GaitError naming the first problem.
 *
 * Every parameter of the schema must be there, and no other: a gait that leaves one out, or
 * names one the schema does not know, is refused (as the native reader, gait/params_io.h, does),
 * because filling in or dropping a value would run something other than what the author made.
 */
export function parseGait(
  data: unknown,
  schema: ParamSchema,
  migrations: Readonly<Record<number, Migration>> = MIGRATIONS,
): GaitFile {
  if (!isRecord(data)) throw new GaitError('invalid', 'a gait must be a JSON object');
  if (data.format !== GAIT_FORMAT) {
    throw new GaitError('invalid', `not a gait file: "format" is ${JSON.stringify(data.format)}, expected "${GAIT_FORMAT}"`);
  }
  const version = data.version;
  if (typeof version !== 'number' || !Number.isInteger(version) || version < 1) {
    throw new GaitError('invalid', `"version" must be a positive integer, not ${JSON.stringify(version)}`);
  }
  if (version > schema.version) {
    throw new GaitError(
      'unknown-version',
      `the gait is from parameter schema version ${version}, newer than this page's version ${schema.version}`,
    );
  }
  const character = data.character;
  if (typeof character !== 'string' || !(CHARACTER_TYPES as readonly string[]).includes(character)) {
    throw new GaitError('invalid', `"character" must be "biped" or "quadruped", not ${JSON.stringify(character)}`);
  }
  if (!isRecord(data.params)) throw new GaitError('invalid', '"params" must be an object of parameter values');
  if (data.meta !== undefined && !isRecord(data.meta)) throw new GaitError('invalid', '"meta" must be an object');

  let gait: GaitFile = {
    format: GAIT_FORMAT,
    version,
    character: character as CharacterType,
    params: { ...(data.params as Record<string, ParamValue>) },
    ...(data.meta ? { meta: data.meta as Record<string, unknown> } : {}),
  };
  for (let v = version; v < schema.version; v++) {
    const migrate = migrations[v];
    if (!migrate) {
      throw new GaitError('unknown-version', `the gait is from parameter schema version ${v}, which this page cannot upgrade`);
    }
    gait = { ...migrate(gait), version: v + 1 };
  }

  const entries = new Map(schema.characters[gait.character].map((e) => [e.name, e]));
  for (const [name, value] of Object.entries(gait.params)) {
    const entry = entries.get(name);
    if (!entry) throw new GaitError('invalid', `unknown parameter "${name}" for a ${gait.character}`);
    const values = entry.knots === 1 ? [value] : value;
    if (entry.knots !== 1 && (!Array.isArray(values) || values.length !== entry.knots)) {
      throw new GaitError('invalid', `${name} must be a list of ${entry.knots} numbers (a graph over the gait phase)`);
    }
    for (const x of values as unknown[]) {
      if (typeof x !== 'number') throw new GaitError('invalid', `${name} must be a number, not ${JSON.stringify(x)}`);
      // JSON has no NaN or Infinity, but 1e999 parses to Infinity.
      if (!Number.isFinite(x)) throw new GaitError('not-finite', `${name} is not a finite number (${show(x)})`);
      if (x < entry.min || x > entry.max) {
        throw new GaitError(
          'out-of-bounds',
          `${name} = ${show(x)} is out of bounds (${show(entry.min)} to ${show(entry.max)}${entry.unit ? ` ${entry.unit}` : ''})`,
        );
      }
    }
  }
  for (const name of entries.keys()) {
    if (!(name in gait.params)) throw new GaitError('invalid', `parameter "${name}" is missing`);
  }
  return gait;
}

/** The schema's defaults for a character, as a complete gait. */
export function presetGait(schema: ParamSchema, character: CharacterType): GaitFile {
  const params: Record<string, ParamValue> = {};
  for (const e of schema.characters[character]) params[e.name] = Array.isArray(e.default) ? [...e.default] : e.default;
  return { format: GAIT_FORMAT, version: schema.version, character, params };
}

/** Two gaits have the same parameters, exactly (bit for bit: what the sharing tests ask). */
export function sameParams(a: GaitFile, b: GaitFile): boolean {
  if (a.character !== b.character) return false;
  const keys = Object.keys(a.params);
  if (keys.length !== Object.keys(b.params).length) return false;
  return keys.every((k) => {
    const x = a.params[k];
    const y = b.params[k];
    if (Array.isArray(x) || Array.isArray(y)) {
      return Array.isArray(x) && Array.isArray(y) && x.length === y.length && x.every((v, i) => Object.is(v, y[i]));
    }
    return Object.is(x, y);
  });
}
