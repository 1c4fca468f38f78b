// The sim worker's gate (web/src/sim/command-check.ts) under generated messages: every message,
// however made (wrong types, NaN, infinities, huge and negative numbers, deep objects, unknown
// commands), is either passed on with only checked fields or refused naming the field, never
// thrown on; what passes carries only finite numbers within the limits.
import { describe, expect, it } from 'vitest';
import { checkSimCommand } from '../../../web/src/sim/command-check';
import { MAX_COORDINATE, MAX_GOAL_SPEED } from '../../../web/src/sim/limits';
import { mulberry32 as random } from '../../../web/src/random';

/** Every number inside `value`, found without recursion. */
function numbersIn(value: unknown): number[] {
  const out: number[] = [];
  const stack: unknown[] = [value];
  while (stack.length) {
    const v = stack.pop();
    if (typeof v === 'number') out.push(v);
    else if (v && typeof v === 'object') stack.push(...Object.values(v));
  }
  return out;
}

const SCENE_TYPES = ['setGoal', 'throwBox', 'throwAt', 'drag', 'endDrag', 'resetCharacter', 'resetFallen', 'remove', 'add', 'autoReset',
  'setParams', 'patchParams', 'learner', 'removeLearner', 'setTerrain', 'nope', '__proto__', 'constructor'];
const TYPES = ['init', 'pause', 'resume', 'reset', 'released', 'step', 'timeScale', 'scene', 'getParams', 'getPreset', 'normalize',
  'toString', 'hasOwnProperty', 'x'];

const NUMBERS = [NaN, Infinity, -Infinity, 1e308, -1e308, 2 ** 53, 2 ** 31, -1, 0, -0, 0.5, 1, 3, 1e-320, 7];
const STRINGS = ['all', 'biped', 'quadruped', 'box', 'flat', 'lava', '', '{}', 'x'.repeat(300000)];
/** An array nested 10,000 deep (made once: the checker must not walk it). */
const DEEP: unknown = (() => {
  let deep: unknown = 0;
  for (let i = 0; i < 10000; i++) deep = [deep];
  return deep;
})();

function hostile(next: () => number, depth = 0): unknown {
  const pick = <T,>(items: readonly T[]) => items[Math.floor(next() * items.length)];
  const numbers = NUMBERS;
  switch (Math.floor(next() * (depth > 3 ? 5 : 8))) {
    case 0: return pick(numbers);
    case 1: return next() * 20 - 10;
    case 2: return pick(STRINGS);
    case 3: return pick([null, undefined, true, false]);
    case 4: return [hostile(next, depth + 1), hostile(next, depth + 1), hostile(next, depth + 1)];
    case 5: return DEEP;
    default: {
      const o: Record<string, unknown> = {};
      for (const k of ['id', 'speed', 'turn', 'from', 'velocity', 'half', 'segment', 'local', 'target', 'count', 'kind', 'seconds',
        'character', 'json', 'patch', 'request', 'terrain', 'loopSeconds', 'scale', 'generation', 'options']) {
        if (next() < 0.4) o[k] = hostile(next, depth + 1);
      }
      return o;
    }
  }
}

describe('checkSimCommand', () => {
  it('passes valid commands through, with only their own fields', () => {
    const goal = checkSimCommand({ type: 'scene', command: { type: 'setGoal', id: 'all', speed: 1, turn: 0.2, extra: 1 } });
    expect(goal).toEqual({ ok: true, command: { type: 'scene', command: { type: 'setGoal', id: 'all', speed: 1, turn: 0.2 } } });
    const thrown = { type: 'throwBox', from: [0, 1, 2], velocity: [0, 0, 12], half: 0.12 };
    expect(checkSimCommand({ type: 'scene', command: thrown })).toEqual({ ok: true, command: { type: 'scene', command: thrown } });
    const aimed = { type: 'throwAt', from: [0, 3, -8], id: 4, segment: 0, local: [0, 0.1, 0], speed: 14, half: 0.12 };
    expect(checkSimCommand({ type: 'scene', command: aimed })).toEqual({ ok: true, command: { type: 'scene', command: aimed } });
    expect(checkSimCommand({ type: 'normalize', request: 3, json: '{}' }).ok).toBe(true);
    expect(checkSimCommand({ type: 'step' })).toEqual({ ok: true, command: { type: 'step' } });
    const patch = { type: 'patchParams', id: 4, character: 'biped', patch: { 'gains.kp': 3, 'legFrame.pitch': [0, 1, 2, 3] }, request: 9 };
    expect(checkSimCommand({ type: 'scene', command: patch })).toEqual({ ok: true, command: { type: 'scene', command: patch } });
    const spawn = { type: 'spawnCreature', json: '{}', x: 1, z: -2, heading: 0, speed: 0.4, request: 12 };
    expect(checkSimCommand({ type: 'scene', command: spawn })).toEqual({ ok: true, command: { type: 'scene', command: spawn } });
  });

  it('refuses each bad number naming it', () => {
    const scene = (command: object) => checkSimCommand({ type: 'scene', command });
    expect(scene({ type: 'setGoal', id: 'all', speed: NaN, turn: 0 })).toEqual({ ok: false, error: 'scene: setGoal: speed: NaN is not finite' });
    expect(scene({ type: 'setGoal', id: 1, speed: 1, turn: Infinity })).toMatchObject({ ok: false, error: expect.stringMatching(/turn: Infinity is not finite/) });
    expect(scene({ type: 'setGoal', id: 1, speed: MAX_GOAL_SPEED + 1, turn: 0 })).toMatchObject({ ok: false, error: expect.stringMatching(/speed: 6 is outside \[-5, 5\]/) });
    expect(scene({ type: 'setGoal', id: 2 ** 40, speed: 1, turn: 0 })).toMatchObject({ ok: false, error: expect.stringMatching(/id: /) });
    expect(scene({ type: 'drag', id: 1, segment: 0, local: [0, 0, 0], target: [0, MAX_COORDINATE * 2, 0] })).toMatchObject({ ok: false, error: expect.stringMatching(/target\[1\]/) });
    expect(scene({ type: 'throwBox', from: [0, 1, 0], velocity: [80, 80, 0], half: 0.1 })).toMatchObject({ ok: false, error: expect.stringMatching(/velocity: faster/) });
    const aimed = { type: 'throwAt', from: [0, 3, -8], id: 4, segment: 0, local: [0, 0, 0], speed: 14, half: 0.12 };
    expect(scene({ ...aimed, from: [0, NaN, 0] })).toMatchObject({ ok: false, error: expect.stringMatching(/from\[1\]: NaN is not finite/) });
    expect(scene({ ...aimed, id: 'all' })).toMatchObject({ ok: false, error: expect.stringMatching(/id: expected a number/) });
    expect(scene({ ...aimed, segment: -1 })).toMatchObject({ ok: false, error: expect.stringMatching(/segment: -1 is outside/) });
    expect(scene({ ...aimed, local: [0, Infinity, 0] })).toMatchObject({ ok: false, error: expect.stringMatching(/local\[1\]: Infinity/) });
    expect(scene({ ...aimed, speed: 0.5 })).toMatchObject({ ok: false, error: expect.stringMatching(/speed: 0.5 is outside \[1, 100\]/) });
    expect(scene({ ...aimed, half: 2 })).toMatchObject({ ok: false, error: expect.stringMatching(/half: 2 is outside/) });
    expect(scene({ type: 'add', kind: 'biped', count: 2.5 })).toMatchObject({ ok: false, error: expect.stringMatching(/count: 2.5 is not a whole number/) });
    expect(scene({ type: 'patchParams', id: 'all', character: 'biped', patch: { a: [1, NaN] } })).toMatchObject({ ok: false, error: expect.stringMatching(/a\[1\]: NaN/) });
    expect(checkSimCommand({ type: 'getParams', request: 5, id: 'x' })).toMatchObject({ ok: false, request: 5 });
    expect(scene({ type: 'spawnCreature', json: '{}', x: 0, z: 0, heading: 0, speed: 0.4, request: -1 })).toMatchObject({ ok: false, error: expect.stringMatching(/request: -1 is outside/) });
    expect(checkSimCommand({ type: 'normalize', request: 1, json: 'x'.repeat(300 * 1024) })).toMatchObject({ ok: false, request: 1, error: expect.stringMatching(/longer than 262144 bytes/) });
    expect(checkSimCommand(null)).toMatchObject({ ok: false });
    expect(checkSimCommand({ type: 'toString' })).toMatchObject({ ok: false, error: expect.stringMatching(/not a command/) });
    expect(checkSimCommand({ type: 'scene', command: { type: '__proto__' } })).toMatchObject({ ok: false });
  });

  it('never throws on generated messages, and passes only finite numbers', () => {
    const next = random(17);
    let passed = 0;
    for (let i = 0; i < 2000; i++) {
      const message = hostile(next) as Record<string, unknown>;
      const shaped = message && typeof message === 'object' && !Array.isArray(message) ? message : { value: message };
      shaped.type = TYPES[Math.floor(next() * TYPES.length)];
      if (shaped.type === 'scene') shaped.command = { ...(hostile(next) as object), type: SCENE_TYPES[Math.floor(next() * SCENE_TYPES.length)] };
      const checked = checkSimCommand(shaped);
      if (checked.ok) {
        passed++;
        for (const n of numbersIn(checked.command)) expect(Number.isFinite(n)).toBe(true);
      } else {
        expect(checked.error.length).toBeGreaterThan(0);
      }
    }
    expect(passed).toBeGreaterThan(50);
  });
});
