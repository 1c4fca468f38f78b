// The walking benchmark's skill checks (bench/lib/skills.mjs) on made-up sweeps: a walk must be a
// walk at every goal of its range, a run needs its flight phase, a canter its speed.
import { describe, expect, it } from 'vitest';
import { skillChecks, type SweepRow } from '../../../bench/lib/skills.mjs';

const options = { seconds: 60, paceFile: 'quadruped-pace.json', paceSpeeds: [0.4, 0.8] };

// A sweep from 0 to `to` m/s in 0.1 steps, each row made by `row(goal)`.
function sweep(to: number, row: (goal: number) => Partial<SweepRow>): { step: number; rows: SweepRow[] } {
  const rows: SweepRow[] = [];
  for (let k = 0; k * 0.1 <= to + 1e-9; k++) {
    const goal = k / 10;
    rows.push({
      goal, fell: false, fall_time_s: null, mean_speed_m_s: goal, footfall: 'walk',
      duty_factor_measured: [0.6, 0.6], flight_fraction: 0, standing_fraction: goal === 0 ? 0.98 : 0, ...row(goal),
    });
  }
  return { step: 0.1, rows };
}

const byWhat = (checks: { what: string; ok: boolean; value: string }[], start: string) => {
  const found = checks.find((c) => c.what.startsWith(start));
  if (!found) throw new Error(`no check "${start}…"`);
  return found;
};

describe('skillChecks: the biped', () => {
  it('passes a walk with double support to 1.6 m/s and a run with flight from 2.5', () => {
    const biped = sweep(2.9, (g) => (g >= 2.2 ? { footfall: 'run', duty_factor_measured: [0.4, 0.4], flight_fraction: 0.06 } : {}));
    const checks = skillChecks('biped', biped, null, options);
    expect(byWhat(checks, 'stands').ok).toBe(true);
    expect(byWhat(checks, 'walks from 0.2 to 1.6').ok).toBe(true);
    expect(byWhat(checks, 'runs at 2.5').ok).toBe(true);
    expect(byWhat(checks, 'runs at 2.5').value).toContain('2.5–2.9 m/s');
  });

  it('fails the walk on a jog (duty factors under a half, flight) and names the goals', () => {
    const jog = sweep(2.9, () => ({ footfall: 'run', duty_factor_measured: [0.37, 0.33], flight_fraction: 0.07 }));
    const walk = byWhat(skillChecks('biped', jog, null, options), 'walks from 0.2 to 1.6');
    expect(walk.ok).toBe(false);
    expect(walk.value).toContain('not a walk at 0.2, 0.3');
    expect(walk.value).toContain('1.6 m/s (footfall run)');
  });

  it('fails the walk where one goal of the range has flight, falls or misses its speed', () => {
    for (const bad of [{ flight_fraction: 0.03 }, { fell: true, fall_time_s: 12 }, { mean_speed_m_s: 1.3 }, { duty_factor_measured: [0.6, 0.49] }]) {
      const s = sweep(2.9, (g) => (g === 1.0 ? bad : g >= 2.2 ? { footfall: 'run', flight_fraction: 0.06 } : {}));
      const walk = byWhat(skillChecks('biped', s, null, options), 'walks from 0.2 to 1.6');
      expect(walk.ok, JSON.stringify(bad)).toBe(false);
      expect(walk.value).toContain('not a walk at 1.0 m/s');
    }
  });

  it('fails the run without a flight phase, and a fall at goal 0 fails standing', () => {
    const grounded = sweep(2.9, (g) => (g === 0 ? { fell: true, fall_time_s: 3 } : g >= 2.2 ? { footfall: 'run', flight_fraction: 0.01 } : {}));
    const checks = skillChecks('biped', grounded, null, options);
    expect(byWhat(checks, 'runs at 2.5').ok).toBe(false);
    expect(byWhat(checks, 'stands').ok).toBe(false);
    expect(byWhat(checks, 'stands').value).toBe('fell at 3.0 s');
  });

  it('reads getting up from the box-hit trial: unmeasured, too few, and enough falls got up from', () => {
    const walked = sweep(2.9, () => ({}));
    expect(byWhat(skillChecks('biped', walked, null, options), 'gets up').ok).toBe(false);
    expect(byWhat(skillChecks('biped', walked, null, options), 'gets up').value).toMatch(/not measured/);
    const boxes = (ups: number[]) => ({ trials: [{ speed: 0.5, falls: 10, get_ups: ups[0], get_up_median_s: 4 }, { speed: 0, falls: 10, get_ups: ups[1], get_up_median_s: null }] });
    const none = byWhat(skillChecks('biped', walked, null, options, boxes([0, 0])), 'gets up');
    expect(none.ok).toBe(false);
    expect(none.value).toBe('got up from 0 of 20 falls (0.5 m/s: 0 of 10, median 4.0 s; 0 m/s: 0 of 10)');
    expect(byWhat(skillChecks('biped', walked, null, options, boxes([9, 8])), 'gets up').ok).toBe(false);  // 17 of 20
    const most = byWhat(skillChecks('biped', walked, null, options, boxes([10, 8])), 'gets up');  // 18 of 20: 90 %
    expect(most.ok).toBe(true);
    expect(most.value).toMatch(/0\.5 m\/s: 10 of 10, median 4\.0 s; 0 m\/s: 8 of 10/);
    // The trial without its watch (an older result) says nothing about getting up.
    expect(byWhat(skillChecks('biped', walked, null, options, { trials: [{ speed: 0.5, falls: 10 }] }), 'gets up').ok).toBe(false);
  });
});

describe('skillChecks: the quadruped', () => {
  const pace = { pace: [
    { goal: 0.4, fell: false, fall_time_s: null, mean_speed_m_s: 0.4, footfall: 'pace' },
    { goal: 0.8, fell: false, fall_time_s: null, mean_speed_m_s: 0.79, footfall: 'pace' },
  ] };
  // Walks to 0.2, trots to `trotTo` (falling above it), then `fast(goal)` from there.
  const quadruped = (trotTo: number, fast: (g: number) => Partial<SweepRow>) => sweep(4.5, (g) => (
    g <= 0.2 ? {} : g <= trotTo ? { footfall: 'trot', duty_factor_measured: [0.4, 0.4, 0.4, 0.4] } : fast(g)));

  it('the shipped gait: walk, trot to 2.6, pace; no canter, since it falls from 3.1', () => {
    const checks = skillChecks('quadruped', quadruped(3.0, () => ({ footfall: 'trot', fell: true, fall_time_s: 10 })), pace, options);
    expect(byWhat(checks, 'walks').ok).toBe(true);
    expect(byWhat(checks, 'walks').value).toBe('walks at 0.1–0.2 m/s');
    expect(byWhat(checks, 'trots up to 2.5').ok).toBe(true);
    expect(byWhat(checks, 'paces').ok).toBe(true);
    const canter = byWhat(checks, 'canters or gallops');
    expect(canter.ok).toBe(false);
    expect(canter.value).toContain('all fell');
  });

  it('a canter with flight within ±10 % from 3.5 passes; 20 % short, or a flying trot, does not', () => {
    const canter = (g: number) => ({ footfall: 'canter', flight_fraction: 0.12, mean_speed_m_s: 0.95 * g });
    expect(byWhat(skillChecks('quadruped', quadruped(2.8, canter), pace, options), 'canters or gallops').ok).toBe(true);
    const slow = (g: number) => ({ ...canter(g), mean_speed_m_s: 0.8 * g });
    const short = byWhat(skillChecks('quadruped', quadruped(2.8, slow), pace, options), 'canters or gallops');
    expect(short.ok).toBe(false);
    expect(short.value).toContain('2.80 (canter)');
    const flyingTrot = () => ({ footfall: 'trot', flight_fraction: 0.12 });
    expect(byWhat(skillChecks('quadruped', quadruped(2.8, flyingTrot), pace, options), 'canters or gallops').ok).toBe(false);
  });

  it('a pace file that trots, or falls, is not a pace', () => {
    const trotting = { pace: [{ ...pace.pace[0], footfall: 'trot' }, pace.pace[1]] };
    expect(byWhat(skillChecks('quadruped', quadruped(3.0, () => ({ fell: true })), trotting, options), 'paces').ok).toBe(false);
    const fell = { pace: [pace.pace[0], { ...pace.pace[1], fell: true, fall_time_s: 20 }] };
    const check = byWhat(skillChecks('quadruped', quadruped(3.0, () => ({ fell: true })), fell, options), 'paces');
    expect(check.ok).toBe(false);
    expect(check.value).toContain('0.8: fell at 20.0 s');
  });
});
