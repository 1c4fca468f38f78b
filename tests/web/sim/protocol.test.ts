// Helpers of the main-thread ⇄ sim-worker protocol, and the overlay's rate meter.
import { describe, expect, it } from 'vitest';
import { defaultThreads, errorMessage, MAX_THREADS, simOptionsFromQuery, type SimOptions } from '../../../web/src/sim/protocol';
import { RateMeter } from '../../../web/src/ui/rate-meter';

const defaults: SimOptions = { wasmUrl: '/wasm/gaitlab.mjs', threads: 2, seed: 1, characters: 6 };

describe('defaultThreads', () => {
  it('uses one thread per core, at most the module\'s MAX_THREADS (5) and at least 1', () => {
    expect(MAX_THREADS).toBe(5);
    expect(defaultThreads(1)).toBe(1);
    expect(defaultThreads(2)).toBe(2);
    expect(defaultThreads(4)).toBe(4);
    expect(defaultThreads(5)).toBe(5);
    expect(defaultThreads(16)).toBe(MAX_THREADS);
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

  it('ignores values that are not integers in range', () => {
    const options = simOptionsFromQuery('?threads=0&seed=-3&characters=2.5', defaults);
    expect(options).toEqual(defaults);
    expect(simOptionsFromQuery('?threads=abc&seed=4294967296&characters=9999', defaults)).toEqual(defaults);
    // More threads than the module's pthread pool serves would hang the simulation.
    expect(simOptionsFromQuery(`?threads=${MAX_THREADS + 1}`, defaults).threads).toBe(defaults.threads);
    expect(simOptionsFromQuery(`?threads=${MAX_THREADS}`, defaults).threads).toBe(MAX_THREADS);
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
