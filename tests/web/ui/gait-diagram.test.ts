// The gait diagram's arithmetic (web/src/ui/gait-diagram.ts): stance intervals from step trigger
// and duty factor (thesis §3.1.1: the trigger is the phase of lift-off), and what dragging each
// part of a stance bar does to them.
import { describe, expect, it } from 'vitest';
import { dragTiming, stanceOf } from '../../../web/src/ui/gait-diagram';

const leg = (stepTrigger: number, dutyFactor: number) => ({ leg: 'x', stepTrigger, dutyFactor });
const bounds: [number, number] = [0.2, 0.9];

describe('stanceOf', () => {
  it('ends stance at the step trigger and starts it a duty factor earlier, wrapping', () => {
    expect(stanceOf(leg(0.5, 0.6))).toEqual({ start: expect.closeTo(0.9, 12), end: 0.5 });
    expect(stanceOf(leg(0, 0.6))).toEqual({ start: expect.closeTo(0.4, 12), end: 0 });
    expect(stanceOf(leg(0.8, 0.3))).toEqual({ start: expect.closeTo(0.5, 12), end: 0.8 });
  });
});

describe('dragTiming', () => {
  it('moving the lift-off end keeps the touch-down', () => {
    const l = leg(0.8, 0.3); // stance 0.5 → 0.8
    const moved = dragTiming(l, 'end', 0.9, 0, bounds);
    expect(moved.stepTrigger).toBeCloseTo(0.9, 12);
    expect(moved.dutyFactor).toBeCloseTo(0.4, 12);
    expect(stanceOf(moved).start).toBeCloseTo(0.5, 12);
  });

  it('moving the touch-down end keeps the lift-off', () => {
    const moved = dragTiming(leg(0.8, 0.3), 'start', 0.2, 0, bounds);
    expect(moved.stepTrigger).toBe(0.8);
    expect(moved.dutyFactor).toBeCloseTo(0.6, 12);
  });

  it('moving the middle shifts the whole stance', () => {
    const moved = dragTiming(leg(0.8, 0.3), 'move', 0.7, 0.6, bounds);
    expect(moved.dutyFactor).toBe(0.3);
    expect(moved.stepTrigger).toBeCloseTo(0.9, 12);
    expect(dragTiming(leg(0.9, 0.3), 'move', 0.5, 0.2, bounds).stepTrigger).toBeCloseTo(0.2, 12); // wraps
  });

  it('keeps duty factors within the schema bounds', () => {
    expect(dragTiming(leg(0.8, 0.3), 'end', 0.51, 0, bounds).dutyFactor).toBe(0.2);
    expect(dragTiming(leg(0.8, 0.3), 'start', 0.85, 0, bounds).dutyFactor).toBe(0.9);
    // Dragging the lift-off onto the touch-down is a whole cycle, clamped: never a zero stance.
    expect(dragTiming(leg(0.8, 0.3), 'end', 0.5, 0, bounds).dutyFactor).toBe(0.9);
  });
});
