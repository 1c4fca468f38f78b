// The optimize panel's pure logic (web/src/optimize/options.ts): the form is checked against
// the module's settings table and the search's bounds, every problem named with its field and
// nothing let through; the time left is estimated from the recent generations.
import { describe, expect, it } from 'vitest';
import {
  checkOptimizeForm,
  defaultForm,
  estimateSecondsLeft,
  formatDuration,
  parseNumber,
  type OptimizerSchema,
} from '../../../web/src/optimize/options';

/** A settings table in the shape of gl_opt_settings_json (native/src/optimize/objective.h). */
const schema: OptimizerSchema = {
  settings: [
    { name: 'wd', min: 0, max: 1000, default: 1, unit: '1', description: 'w_d', integer: false },
    { name: 'seconds', min: 0.5, max: 120, default: 800 / 120, unit: 's', description: 'episode length', integer: false },
    { name: 'starts', min: 1, max: 32, default: 1, unit: '1', description: 'start states', integer: true },
    { name: 'turnRate', min: -3, max: 3, default: 0, unit: 'rad/s', description: 'goal turn rate', integer: false },
  ],
  speeds: { min: -5, max: 5, default: [1], unit: 'm/s', description: 'goal speeds' },
};

const form = (changes: Record<string, string | number> = {}) => ({ ...defaultForm(schema, 1), ...changes });

function problems(changes: Record<string, string | number>, selected: 'biped' | 'quadruped' | null = null) {
  const checked = checkOptimizeForm(form(changes), schema, selected);
  if (checked.ok) throw new Error(`accepted ${JSON.stringify(changes)}`);
  return checked.problems;
}

describe('the optimize form', () => {
  it('accepts its defaults and gives every setting to the search', () => {
    const checked = checkOptimizeForm(form(), schema, null);
    expect(checked.ok).toBe(true);
    if (!checked.ok) return;
    expect(checked.options).toEqual({
      character: 'biped',
      method: 'greedy',
      start: 'preset',
      generations: 20,
      candidates: 10,
      seed: 1,
      threads: 1,
      settings: { wd: 1, seconds: 6.66667, starts: 1, turnRate: 0 },
      speeds: [1],
    });
  });

  it('reads what people type: spaces, signs, decimals, exponents, a list of speeds', () => {
    const checked = checkOptimizeForm(
      form({ generations: ' 3 ', candidates: '3', seconds: '1.5', turnRate: '-0.3', wd: '1e1', speeds: '0.5, 1,-0.25', seed: 4294967295 }),
      schema,
      null,
    );
    expect(checked.ok && checked.options).toMatchObject({
      generations: 3,
      candidates: 3,
      seed: 4294967295,
      settings: { seconds: 1.5, turnRate: -0.3, wd: 10 },
      speeds: [0.5, 1, -0.25],
    });
  });

  it('refuses zero generations, fewer than two candidates and non-numbers, naming each field', () => {
    const found = problems({ generations: '0', candidates: '1', seed: 'abc', seconds: '' });
    expect(found.map((p) => p.field)).toEqual(['generations', 'candidates', 'seed', 'seconds']);
    expect(found[0].message).toBe('generations: 0 is below the minimum, 1');
    expect(found[1].message).toBe('candidates: 1 is below the minimum, 2');
    expect(found[2].message).toBe("seed: 'abc' is not a number");
    expect(found[3].message).toBe('seconds: is empty');
  });

  it('refuses what Number() would let through: hex, half exponents, Infinity, NaN', () => {
    for (const text of ['0x10', '1e', 'Infinity', 'NaN', '1,5', '--1', '.']) {
      expect(parseNumber(text), text).toHaveProperty('problem');
    }
    expect(parseNumber(Number.NaN)).toHaveProperty('problem');
    expect(parseNumber('1e400')).toEqual({ problem: "'1e400' is too large" });
    expect(parseNumber(' -.5 ')).toEqual({ value: -0.5 });
  });

  it('refuses fractions where whole numbers are needed, and values out of the module\'s bounds', () => {
    expect(problems({ generations: '2.5' })[0].message).toBe('generations: 2.5 is not a whole number');
    expect(problems({ starts: '1.5' })[0].message).toBe('starts: 1.5 is not a whole number');
    expect(problems({ seconds: '0.1' })[0].message).toBe('seconds: 0.1 is below the minimum, 0.5');
    expect(problems({ turnRate: '4' })[0].message).toBe('turnRate: 4 is above the maximum, 3');
    expect(problems({ threads: '99' })[0].field).toBe('threads');
    expect(problems({ seed: '-1' })[0].field).toBe('seed');
  });

  it('checks every goal speed and needs at least one', () => {
    expect(problems({ speeds: '' })[0].message).toMatch(/at least one goal speed/);
    expect(problems({ speeds: '1, fast' })[0].message).toBe("speeds: 'fast' is not a number");
    expect(problems({ speeds: '1,,2' })[0].message).toBe('speeds: is empty');
    expect(problems({ speeds: '9' })[0].message).toBe('speeds: 9 is above the maximum, 5');
  });

  it('refuses an unknown character or method', () => {
    expect(problems({ character: 'centipede', method: 'annealing' }).map((p) => p.field)).toEqual(['character', 'method']);
  });

  it('starts from the selected character only when there is one of the chosen type', () => {
    expect(problems({ start: 'selected' })[0].message).toMatch(/no character is selected/);
    expect(problems({ start: 'selected', character: 'biped' }, 'quadruped')[0].message).toBe(
      'start: the selected character is a quadruped, not a biped',
    );
    const checked = checkOptimizeForm(form({ start: 'selected', character: 'quadruped' }), schema, 'quadruped');
    expect(checked.ok && checked.options.start).toBe('selected');
  });
});

describe('time left', () => {
  it('is unknown before the first generation', () => {
    expect(estimateSecondsLeft([], 10)).toBeNull();
  });

  it('is the mean of the recent generations times the generations left', () => {
    expect(estimateSecondsLeft([2, 2], 10)).toBe(16);
    // Only the last five count: the search's cost moves as candidates start to walk.
    expect(estimateSecondsLeft([100, 1, 1, 1, 1, 1], 10)).toBe(4);
    expect(estimateSecondsLeft([1, 3], 10, 1)).toBe(24);
  });

  it('is zero when every generation is done (or more were run)', () => {
    expect(estimateSecondsLeft([1, 1, 1], 3)).toBe(0);
    expect(estimateSecondsLeft([1, 1, 1, 1], 3)).toBe(0);
  });

  it('reads as people say durations', () => {
    expect(formatDuration(0.42)).toBe('0.4 s');
    expect(formatDuration(12.4)).toBe('12 s');
    expect(formatDuration(185)).toBe('3 min 5 s');
    expect(formatDuration(120)).toBe('2 min');
    expect(formatDuration(3720)).toBe('1 h 2 min');
    expect(formatDuration(Number.NaN)).toBe('–');
  });
});
