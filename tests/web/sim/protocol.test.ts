// Helpers of the main-thread ⇄ sim-worker protocol, and the overlay's rate meter.
import { describe, expect, it } from 'vitest';
import { defaultThreads, errorMessage, MAX_THREADS, simOptionsFromQuery, type SimOptions } from '../../../web/src/sim/protocol';
import { RateMeter } from '../../../web/src/ui/rate-meter';

const defaults: SimOptions = { wasmUrl: '/wasm/gaitlab.mjs', threads: 2, seed: 1, characters: 6 };

describe('defaultThreads', () => {
  it('uses one thread per core, at most the module\'s MAX_THREADS (16) and at least 1', () => {
    expect(MAX_THREADS).toBe(16);
    expect(defaultThreads(1)).toBe(1);
    expect(defaultThreads(2)).toBe(2);
    expect(defaultThreads(4)).toBe(4);
    expect(defaultThreads(5)).toBe(5);
    expect(defaultThreads(8)).toBe(8);
    expect(defaultThreads(16)).toBe(16);
    expect(defaultThreads(64)).toBe(MAX_THREADS);
    expect(defaultThreads(0)).toBe(1);
    expect(defaultThreads(undefined)).toBe(1);
    expect(defaultThreads(Number.NaN)).toBe(1);
  });
});

describe('simOptionsFromQuery', () => {
  it('keeps the defaults without a query', () => {
    expect(simOptionsFromQuery('', defaults)).toEqual(defaults);
  });

  it('takes integers in range from the query', () => {
    expect(simOptionsFromQuery('?threads=1&seed=4294967295&characters=12', defaults)).toEqual({
      ...defaults,
      threads: 1,
      seed: 4294967295,
      characters: 12,
    });
  });

  it('replaces a value out of range by the nearest valid one, and says so', () => {
    const notes: string[] = [];
    expect(simOptionsFromQuery('?threads=0&seed=-3&characters=2.5', defaults, notes)).toEqual({ ...defaults, threads: 1, seed: 0, characters: 3 });
    expect(notes).toEqual([
      '?threads=0 is not a whole number in [1, 16]: using 1',
      '?seed=-3 is not a whole number in [0, 4294967295]: using 0',
      '?characters=2.5 is not a whole number in [0, 256]: using 3',
    ]);
    notes.length = 0;
    expect(simOptionsFromQuery('?threads=abc&seed=4294967296&characters=300', defaults, notes)).toEqual({
      ...defaults,
      seed: 4294967295,
      characters: 256,
    });
    expect(notes).toEqual([
      '?threads=abc is not a number: using 2',
      '?seed=4294967296 is not a whole number in [0, 4294967295]: using 4294967295',
      '?characters=300 is not a whole number in [0, 256]: using 256',
    ]);
    // More threads than the module's pthread pool serves would hang the simulation.
    expect(simOptionsFromQuery(`?threads=${MAX_THREADS + 1}`, defaults).threads).toBe(MAX_THREADS);
    expect(simOptionsFromQuery(`?threads=${MAX_THREADS}`, defaults).threads).toBe(MAX_THREADS);
    notes.length = 0;
    expect(simOptionsFromQuery('?terrain=lava&threads=1e400', defaults, notes)).toEqual(defaults);
    expect(notes).toEqual(['?terrain=lava is not flat, slope or bumps: using flat', '?threads=1e400 is not a number: using 2']);
    notes.length = 0;
    expect(simOptionsFromQuery('?threads=2&seed=9', defaults, notes)).toEqual({ ...defaults, seed: 9 });
    expect(notes).toEqual([]);
  });

  it('starts paused only with paused=1', () => {
    expect(simOptionsFromQuery('?paused=1', defaults).paused).toBe(true);
    expect(simOptionsFromQuery('?paused=yes', defaults).paused).toBeUndefined();
    expect(simOptionsFromQuery('', defaults).paused).toBeUndefined();
  });

  it('never takes the module URL from the query', () => {
    expect(simOptionsFromQuery('?wasmUrl=https://example.com/x.mjs', defaults).wasmUrl).toBe(defaults.wasmUrl);
  });
});

describe('errorMessage', () => {
  it('reads Errors, strings and other thrown values', () => {
    expect(errorMessage(new TypeError('bad'))).toBe('TypeError: bad');
    expect(errorMessage('Aborted(OOM)')).toBe('Aborted(OOM)');
    expect(errorMessage({ code: 3 })).toBe('{"code":3}');
    expect(errorMessage(undefined)).toBe('undefined');
  });
});

describe('RateMeter', () => {
  it('measures a steady rate', () => {
    const meter = new RateMeter(0.5, 0.5);
    for (let frame = 0; frame <= 120; frame++) meter.sample(frame, frame / 60);
    expect(meter.rate).toBeCloseTo(60, 6);
  });

  it('is 0 before a full window', () => {
    const meter = new RateMeter(0.5);
    meter.sample(0, 0);
    meter.sample(1, 0.1);
    expect(meter.rate).toBe(0);
  });

  it('follows a change smoothly', () => {
    const meter = new RateMeter(1, 0.5);
    for (let t = 0; t <= 10; t++) meter.sample(t, t); // real time
    for (let t = 11; t <= 20; t++) meter.sample(10 + (t - 10) * 0.5, t); // half speed from t = 10
    expect(meter.rate).toBeCloseTo(0.5, 2);
  });

  it('starts over when the quantity goes backwards (a new simulation)', () => {
    const meter = new RateMeter(0.5, 1);
    meter.sample(0, 0);
    meter.sample(10, 1);
    expect(meter.rate).toBe(10);
    meter.sample(0, 1.1); // reset
    expect(meter.rate).toBe(0);
    meter.sample(1, 2.1);
    expect(meter.rate).toBe(1);
  });
});
