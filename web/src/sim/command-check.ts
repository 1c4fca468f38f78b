// The sim worker's gate: every message from the main thread is checked here before the worker
// acts on it, field by field (types, integers, finiteness, api/limits.h's ranges through
// limits.ts), so that no message, however made, can throw inside the worker's loop, hang it, or
// hand the module a number it would turn into a character that is not finite. The module
// checks the numbers again (the C ABI refuses with a message naming them); this keeps the worker
// itself safe and answers in the same words. Pure: tests/web/sim/command-check.test.ts drives it
// with generated messages.
//
// One rule per message type (RULES, SCENE_RULES): a new command is a new line there.
import { CHARACTER_TYPES } from '../gait/character';
import { MAX_THREADS } from './gaitlab-wasm';
import {
  MAX_AUTO_RESET,
  MAX_COORDINATE,
  MAX_DRAG_LOCAL,
  MAX_GOAL_SPEED,
  MAX_GOAL_TURN,
  MAX_HEADING,
  MAX_JSON_ARRAY,
  MAX_JSON_BYTES,
  MAX_JSON_STRING,
  MAX_THROW_HALF,
  MAX_THROW_SPEED,
  MIN_AIM_SPEED,
  MIN_THROW_HALF,
} from './limits';
import type { SceneCommand, SimCommand } from './protocol';
import { TERRAIN_KINDS } from './terrain-grid';

/** A message that passed, typed; or why it did not (naming the field), and its request if any. */
export type Checked = { ok: true; command: SimCommand } | { ok: false; error: string; request?: number };

class Refused extends Error {}

type Fields = Record<string, unknown>;

function fields(value: unknown, name: string): Fields {
  if (typeof value !== 'object' || value === null || Array.isArray(value)) throw new Refused(`${name}: expected an object`);
  return value as Fields;
}

function show(value: unknown): string {
  if (typeof value === 'number') return Number.isNaN(value) ? 'NaN' : String(value);
  if (typeof value === 'string') return JSON.stringify(value.length > 40 ? `${value.slice(0, 37)}...` : value);
  if (value === null || value === undefined) return String(value);
  return Array.isArray(value) ? 'an array' : typeof value;
}

/** A finite number with |value| <= max (or within [min, max]). */
function number(value: unknown, name: string, min: number, max: number): number {
  if (typeof value !== 'number') throw new Refused(`${name}: expected a number, got ${show(value)}`);
  if (!Number.isFinite(value)) throw new Refused(`${name}: ${show(value)} is not finite`);
  if (value < min || value > max) throw new Refused(`${name}: ${value} is outside [${min}, ${max}]`);
  return value;
}

function integer(value: unknown, name: string, min: number, max: number): number {
  const v = number(value, name, min, max);
  if (!Number.isInteger(v)) throw new Refused(`${name}: ${v} is not a whole number`);
  return v;
}

const INT32_MIN = -(2 ** 31);
const INT32_MAX = 2 ** 31 - 1;
/** A character id: the module's ids are int32 (a larger number would wrap to another id). */
const id = (value: unknown, name = 'id') => integer(value, name, INT32_MIN, INT32_MAX);
const idOrAll = (value: unknown) => (value === 'all' ? 'all' : id(value));

function flag(value: unknown, name: string): boolean {
  if (typeof value !== 'boolean') throw new Refused(`${name}: expected true or false`);
  return value;
}

function oneOf<T extends string | number>(value: unknown, name: string, allowed: readonly T[]): T {
  if (!(allowed as readonly unknown[]).includes(value)) {
    throw new Refused(`${name}: ${show(value)} is not ${allowed.map((a) => JSON.stringify(a)).join(', ')}`);
  }
  return value as T;
}

function vec3(value: unknown, name: string, max: number): [number, number, number] {
  if (!Array.isArray(value) || value.length !== 3) throw new Refused(`${name}: expected 3 numbers`);
  return [number(value[0], `${name}[0]`, -max, max), number(value[1], `${name}[1]`, -max, max), number(value[2], `${name}[2]`, -max, max)];
}

/** JSON text for the module: a string within the byte limit (the module checks the rest). */
function jsonText(value: unknown, name: string): string {
  if (typeof value !== 'string') throw new Refused(`${name}: expected JSON text, got ${show(value)}`);
  // A UTF-16 unit is at most 3 UTF-8 bytes: exact only when it could matter.
  if (value.length > MAX_JSON_BYTES / 3 && new TextEncoder().encode(value).length > MAX_JSON_BYTES) {
    throw new Refused(`${name}: the text is longer than ${MAX_JSON_BYTES} bytes`);
  }
  return value;
}

/** A parameter edit: names to a finite number or a flat array of finite numbers (knots). */
function patch(value: unknown): Record<string, number | number[]> {
  const p = fields(value, 'patch');
  const names = Object.keys(p);
  if (names.length > MAX_JSON_ARRAY) throw new Refused(`patch: more than ${MAX_JSON_ARRAY} parameters`);
  const out: Record<string, number | number[]> = {};
  for (const name of names) {
    if (name.length > MAX_JSON_STRING) throw new Refused('patch: a parameter name is too long');
    const v = p[name];
    if (Array.isArray(v)) {
      if (v.length > 64) throw new Refused(`${name}: expected at most 64 knots`);
      out[name] = v.map((k, i) => number(k, `${name}[${i}]`, -Number.MAX_VALUE, Number.MAX_VALUE));
    } else {
      out[name] = number(v, name, -Number.MAX_VALUE, Number.MAX_VALUE);
    }
  }
  return out;
}

/** A gait's speed keys (gait-file.ts SpeedKeys): shapes and numbers; the module checks the rest. */
function speedKeys(value: unknown): { speed: number; keys: { speed: number; params: Record<string, number | number[]> }[] } {
  const s = fields(value, 'speedKeys');
  if (!Array.isArray(s.keys)) throw new Refused('speedKeys.keys: expected an array');
  if (s.keys.length > MAX_JSON_ARRAY) throw new Refused(`speedKeys.keys: more than ${MAX_JSON_ARRAY} keys`);
  return {
    speed: number(s.speed, 'speedKeys.speed', 0, MAX_GOAL_SPEED),
    keys: s.keys.map((k: unknown, i: number) => {
      const key = fields(k, `speedKeys.keys[${i}]`);
      return { speed: number(key.speed, `speedKeys.keys[${i}].speed`, 0, MAX_GOAL_SPEED), params: patch(key.params) };
    }),
  };
}

const character = (value: unknown) => oneOf(value, 'character', CHARACTER_TYPES);
const request = (value: unknown) => integer(value, 'request', 0, Number.MAX_SAFE_INTEGER);

const SCENE_RULES: Record<SceneCommand['type'], (c: Fields) => SceneCommand> = {
  setGoal: (c) => ({
    type: 'setGoal',
    id: idOrAll(c.id),
    speed: number(c.speed, 'speed', -MAX_GOAL_SPEED, MAX_GOAL_SPEED),
    turn: number(c.turn, 'turn', -MAX_GOAL_TURN, MAX_GOAL_TURN),
    ...(c.character === undefined ? {} : { character: character(c.character) }),
  }),
  wander: (c) => ({
    type: 'wander',
    on: flag(c.on, 'on'),
    ...(c.id === undefined ? {} : { id: id(c.id) }),
  }),
  throwBox: (c) => {
    const velocity = vec3(c.velocity, 'velocity', MAX_THROW_SPEED);
    if (Math.hypot(...velocity) > MAX_THROW_SPEED) throw new Refused(`velocity: faster than ${MAX_THROW_SPEED} m/s`);
    return { type: 'throwBox', from: vec3(c.from, 'from', MAX_COORDINATE), velocity, half: number(c.half, 'half', MIN_THROW_HALF, MAX_THROW_HALF) };
  },
  throwAt: (c) => ({
    type: 'throwAt',
    from: vec3(c.from, 'from', MAX_COORDINATE),
    id: id(c.id),
    segment: integer(c.segment, 'segment', 0, 1024),
    local: vec3(c.local, 'local', MAX_DRAG_LOCAL),
    speed: number(c.speed, 'speed', MIN_AIM_SPEED, MAX_THROW_SPEED),
    half: number(c.half, 'half', MIN_THROW_HALF, MAX_THROW_HALF),
  }),
  drag: (c) => ({
    type: 'drag',
    id: id(c.id),
    segment: integer(c.segment, 'segment', 0, 1024),
    local: vec3(c.local, 'local', MAX_DRAG_LOCAL),
    target: vec3(c.target, 'target', MAX_COORDINATE),
  }),
  endDrag: () => ({ type: 'endDrag' }),
  resetCharacter: (c) => ({ type: 'resetCharacter', id: id(c.id) }),
  resetFallen: () => ({ type: 'resetFallen' }),
  remove: (c) => ({ type: 'remove', id: id(c.id) }),
  add: (c) => ({ type: 'add', kind: oneOf(c.kind, 'kind', CHARACTER_TYPES), count: integer(c.count, 'count', 0, 64) }),
  spawnCreature: (c) => ({
    type: 'spawnCreature',
    json: jsonText(c.json, 'json'),
    x: number(c.x, 'x', -MAX_COORDINATE, MAX_COORDINATE),
    z: number(c.z, 'z', -MAX_COORDINATE, MAX_COORDINATE),
    heading: number(c.heading, 'heading', -MAX_HEADING, MAX_HEADING),
    speed: number(c.speed, 'speed', -MAX_GOAL_SPEED, MAX_GOAL_SPEED),
    ...(c.gait !== undefined ? { gait: jsonText(c.gait, 'gait') } : {}),
    ...(c.request !== undefined ? { request: request(c.request) } : {}),
  }),
  autoReset: (c) => ({ type: 'autoReset', seconds: number(c.seconds, 'seconds', 0, MAX_AUTO_RESET) }),
  setParams: (c) => ({ type: 'setParams', id: idOrAll(c.id), character: character(c.character), json: jsonText(c.json, 'json') }),
  patchParams: (c) => ({
    type: 'patchParams',
    id: idOrAll(c.id),
    character: character(c.character),
    patch: patch(c.patch),
    ...(c.speedKeys !== undefined ? { speedKeys: speedKeys(c.speedKeys) } : {}),
    ...(c.request !== undefined ? { request: request(c.request) } : {}),
  }),
  learner: (c) => ({
    type: 'learner',
    character: character(c.character),
    json: jsonText(c.json, 'json'),
    speed: number(c.speed, 'speed', -MAX_GOAL_SPEED, MAX_GOAL_SPEED),
    turn: number(c.turn, 'turn', -MAX_GOAL_TURN, MAX_GOAL_TURN),
    loopSeconds: number(c.loopSeconds, 'loopSeconds', 0, MAX_AUTO_RESET),
    ...(c.creature !== undefined ? { creature: jsonText(c.creature, 'creature') } : {}),
  }),
  removeLearner: () => ({ type: 'removeLearner' }),
  setTerrain: (c) => ({ type: 'setTerrain', terrain: oneOf(c.terrain, 'terrain', TERRAIN_KINDS) }),
};

const TIME_SCALES = [1, 0.5, 0.25] as const;

const RULES: Record<SimCommand['type'], (c: Fields) => SimCommand> = {
  init: (c) => {
    const o = fields(c.options, 'options');
    if (typeof o.wasmUrl !== 'string' || o.wasmUrl.length > 4096) throw new Refused('options.wasmUrl: expected a URL');
    return {
      type: 'init',
      options: {
        wasmUrl: o.wasmUrl,
        threads: integer(o.threads, 'options.threads', 1, MAX_THREADS),
        seed: integer(o.seed, 'options.seed', 0, 0xffffffff),
        characters: integer(o.characters, 'options.characters', 0, 256),
        ...(o.paused !== undefined ? { paused: o.paused === true } : {}),
        ...(o.terrain !== undefined ? { terrain: oneOf(o.terrain, 'options.terrain', TERRAIN_KINDS) } : {}),
      },
    };
  },
  pause: () => ({ type: 'pause' }),
  resume: () => ({ type: 'resume' }),
  reset: () => ({ type: 'reset' }),
  released: (c) => ({ type: 'released', generation: integer(c.generation, 'generation', 0, Number.MAX_SAFE_INTEGER) }),
  step: (c) => ({ type: 'step', ...(c.count !== undefined ? { count: integer(c.count, 'count', 1, 1200) } : {}) }),
  timeScale: (c) => ({ type: 'timeScale', scale: oneOf(c.scale, 'scale', TIME_SCALES) }),
  scene: (c) => {
    const command = fields(c.command, 'command');
    const rule = typeof command.type === 'string' && Object.hasOwn(SCENE_RULES, command.type) ? SCENE_RULES[command.type as SceneCommand['type']] : null;
    if (!rule) throw new Refused(`command.type: ${show(command.type)} is not a scene command`);
    try {
      return { type: 'scene', command: rule(command) };
    } catch (error) {
      if (error instanceof Refused) throw new Refused(`${command.type as string}: ${error.message}`);
      throw error;
    }
  },
  getParams: (c) => ({ type: 'getParams', request: request(c.request), id: id(c.id) }),
  getPreset: (c) => ({ type: 'getPreset', request: request(c.request), character: character(c.character) }),
  normalize: (c) => ({ type: 'normalize', request: request(c.request), json: jsonText(c.json, 'json') }),
};

/**
 * Checks one message from the main thread. The command returned is a fresh object holding only
 * the fields its type has, each checked; anything else is refused with the field named (and the
 * message's request, when it has a valid one, so that its answer can carry the refusal).
 */
export function checkSimCommand(message: unknown): Checked {
  let c: Fields;
  try {
    c = fields(message, 'message');
  } catch (error) {
    return { ok: false, error: (error as Error).message };
  }
  const rule = typeof c.type === 'string' && Object.hasOwn(RULES, c.type) ? RULES[c.type as SimCommand['type']] : null;
  if (!rule) return { ok: false, error: `type: ${show(c.type)} is not a command of the sim worker` };
  try {
    return { ok: true, command: rule(c) };
  } catch (error) {
    if (!(error instanceof Refused)) throw error;
    const r = c.request;
    const valid = typeof r === 'number' && Number.isInteger(r) && r >= 0;
    return { ok: false, error: `${c.type as string}: ${error.message}`, ...(valid ? { request: r } : {}) };
  }
}
