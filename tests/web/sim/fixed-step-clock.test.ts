// Real-time pacing of the sim worker: whole fixed steps, capped catch-up, no catch-up after pauses.
import { describe, expect, it } from 'vitest';
import { FixedStepClock } from '../../../web/src/sim/fixed-step-clock';

const STEP = 1 / 120;

function clock(maxStepsPerTick = 6): FixedStepClock {
  return new FixedStepClock({ step: STEP, maxStepsPerTick });
}

describe('FixedStepClock', () => {
  it('takes no steps until started', () => {
    const c = clock();
    expect(c.running).toBe(false);
    expect(c.tick(10).steps).toBe(0);
  });

  it('follows the wall clock in whole fixed steps, however the ticks fall', () => {
    const c = clock();
    c.start(100);
    let steps = 0;
    let t = 100;
    // Irregular ticks, 1–13 ms apart, for 10 s of wall time.
    const gaps = [0.001, 0.004, 0.013, 0.0083, 0.0021, 0.009];
    for (let i = 0; t < 110; i++) {
      t += gaps[i % gaps.length];
      steps += c.tick(t).steps;
    }
    // Never ahead of the wall clock, and behind by less than one step.
    const owed = (t - 100) / STEP;
    expect(steps).toBeLessThanOrEqual(owed + 1e-6);
    expect(steps).toBeGreaterThan(owed - 1);
  });

  it('says how long to wait for the next step', () => {
    const c = clock();
    c.start(0);
    const first = c.tick(0.005); // 5 ms: not a whole step yet
    expect(first.steps).toBe(0);
    expect(first.wait).toBeCloseTo(STEP - 0.005, 12);
    const second = c.tick(0.02); // 20 ms in all: 2 steps, 3.33 ms left over
    expect(second.steps).toBe(2);
    expect(second.wait).toBeCloseTo(3 * STEP - 0.02, 12);
  });

  it('counts exactly one step per step of wall time (no round-off loss)', () => {
    const c = clock();
    c.start(0);
    let steps = 0;
    for (let i = 1; i <= 1200; i++) steps += c.tick(i * STEP).steps;
    expect(steps).toBe(1200);
  });

  it('caps the catch-up and drops the rest instead of spiralling', () => {
    const c = clock(6);
    c.start(0);
    const late = c.tick(1); // a 1 s stall owes 120 steps
    expect(late.steps).toBe(6);
    expect(late.dropped).toBe(114);
    // The backlog is gone: the next tick owes only what passed since.
    const next = c.tick(1 + 2 * STEP);
    expect(next.steps).toBe(2);
    expect(next.dropped).toBe(0);
  });

  it('does not catch up the time spent stopped', () => {
    const c = clock();
    c.start(0);
    c.tick(0.1);
    c.stop();
    expect(c.tick(5).steps).toBe(0);
    c.start(5);
    expect(c.tick(5 + STEP).steps).toBe(1);
  });

  it('treats a clock going backwards as no time passing', () => {
    const c = clock();
    c.start(10);
    expect(c.tick(9).steps).toBe(0);
    expect(c.tick(9 + STEP).steps).toBe(1);
  });

  it('rejects impossible settings', () => {
    expect(() => new FixedStepClock({ step: 0, maxStepsPerTick: 1 })).toThrow(RangeError);
    expect(() => new FixedStepClock({ step: STEP, maxStepsPerTick: 0 })).toThrow(RangeError);
    expect(() => new FixedStepClock({ step: STEP, maxStepsPerTick: 1.5 })).toThrow(RangeError);
  });
});
