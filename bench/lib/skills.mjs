// The walking benchmark's skills (bench/walking.mjs): the gaits the locomotion criteria name,
// read from the speed sweep's rows, each goal walked for --seconds (60 by default) from a start
// at rest, its footfall pattern named by `gaitlab walk` (native/src/gait/footfall.h: a walk when
// every foot is down more than half the cycle, Alexander 1984; a quadruped's running gaits by the
// feet that lift off together, Hildebrand 1965, 1977). The criteria: standing at goal 0; the
// biped's walk from 0.2 to 1.6 m/s with no flight and its run at 2.5 m/s or more with a flight
// phase; the quadruped's walk, its trot to 2.5 m/s, a canter or gallop with a flight phase at
// 3.5 m/s or more, and its pace; and getting up after a fall (native/src/gait/get_up.cpp), read
// from the box-hit trial's falls, each watched GET_UP_SECONDS for the character getting up.

export const WALK_RANGE = [0.2, 1.6];   // m/s, the biped's walk
export const RUN_FROM = 2.5;            // m/s, the biped's run
export const TROT_TO = 2.5;             // m/s, the quadruped's trot
export const GALLOP_FROM = 3.5;         // m/s, the quadruped's canter or gallop
export const FLIGHT = 0.02;             // a flight phase: no foot down at least 2 % of the time
export const STAND_SHARE = 0.9;         // standing: on planted feet at least 90 % of the time at goal 0
export const GET_UP_SECONDS = 10;       // s after a fall the box-hit trial watches for a get-up
export const GET_UP_SHARE = 0.9;        // getting up: from at least 90 % of the box-hit trial's falls

/**
 * The skill checks of one character: `sweep` is the walking benchmark's sweep section (rows of
 * goal, fell, fall_time_s, mean_speed_m_s, footfall, duty_factor_measured, flight_fraction,
 * standing_fraction; step), `skills` its skills section (the quadruped's pace runs), `options`
 * the run's seconds, the pace file's name and the speeds it was walked at, `boxes` its box-hit
 * section (trials of falls and get_ups, get_up_watch_s; null when not measured). Returns rows of
 * { what, ok, value }, as every section of the benchmark does.
 */
export function skillChecks(character, sweep, skills, { seconds, paceFile, paceSpeeds }, boxes = null) {
  const within = (x, share) => !x.fell && Math.abs(x.mean_speed_m_s - x.goal) <= share * x.goal;
  // Goals as runs of consecutive sweep steps: "0.4–1.2, 1.4–2.6 m/s".
  const range = (goals) => {
    if (!goals.length) return 'none';
    const runs = [[goals[0], goals[0]]];
    for (const g of goals.slice(1)) {
      if (g - runs.at(-1)[1] <= sweep.step + 1e-9) runs.at(-1)[1] = g; else runs.push([g, g]);
    }
    return `${runs.map(([a, b]) => (a === b ? a.toFixed(1) : `${a.toFixed(1)}–${b.toFixed(1)}`)).join(', ')} m/s`;
  };
  const pct = (f) => `${(100 * f).toFixed(0)} %`;
  const rows = sweep.rows;
  const checks = [];
  const stand = rows.find((x) => x.goal === 0);
  checks.push({ what: `stands at goal 0 (on planted feet ≥ ${100 * STAND_SHARE} % of the time, no fall)`,
    ok: !!stand && !stand.fell && stand.standing_fraction >= STAND_SHARE,
    value: stand ? (stand.fell ? `fell at ${stand.fall_time_s.toFixed(1)} s` : `${pct(stand.standing_fraction)} on planted feet`) : 'not in the sweep' });
  if (character === 'biped') {
    const walkRows = rows.filter((x) => x.goal >= WALK_RANGE[0] - 1e-9 && x.goal <= WALK_RANGE[1] + 1e-9);
    const walks = (x) => within(x, 0.1) && x.footfall === 'walk' && x.flight_fraction < FLIGHT && Math.min(...x.duty_factor_measured) > 0.5;
    const bad = walkRows.filter((x) => !walks(x));
    const duty = walkRows.flatMap((x) => x.duty_factor_measured), flight = walkRows.map((x) => x.flight_fraction);
    checks.push({ what: `walks from ${WALK_RANGE[0]} to ${WALK_RANGE[1]} m/s: every foot down more than half the cycle, no flight (< ${pct(FLIGHT)}), speed within ±10 %`,
      ok: walkRows.length > 0 && bad.length === 0,
      value: `${bad.length ? `not a walk at ${bad.map((x) => x.goal.toFixed(1)).join(', ')} m/s (footfall ${[...new Set(bad.map((x) => x.footfall))].join(', ')})` : 'a walk at every goal'}; ` +
        `duty factors ${Math.min(...duty).toFixed(2)}–${Math.max(...duty).toFixed(2)}, flight ${pct(Math.min(...flight))}–${pct(Math.max(...flight))}` });
    const runs = rows.filter((x) => x.goal >= RUN_FROM - 1e-9 && within(x, 0.1) && x.footfall === 'run' && x.flight_fraction >= FLIGHT);
    checks.push({ what: `runs at ${RUN_FROM} m/s or more: a run's footfall with a flight phase (≥ ${pct(FLIGHT)}), speed within ±10 %`,
      ok: runs.length > 0,
      value: runs.length ? `runs at ${range(runs.map((x) => x.goal))} (flight ${runs.map((x) => pct(x.flight_fraction)).join(', ')})` : `no goal from ${RUN_FROM} m/s is run within ±10 % with a flight phase` });
  } else {
    const walks = rows.filter((x) => x.goal > 0 && within(x, 0.15) && x.footfall === 'walk');
    checks.push({ what: 'walks: a walk\'s footfall (every foot down more than half the cycle), speed within ±15 %',
      ok: walks.length > 0, value: walks.length ? `walks at ${range(walks.map((x) => x.goal))}` : 'no goal is walked' });
    const at = rows.find((x) => Math.abs(x.goal - TROT_TO) < 1e-9);
    const trots = rows.filter((x) => x.goal > 0.3 && within(x, 0.1) && x.footfall === 'trot');
    checks.push({ what: `trots up to ${TROT_TO} m/s or more: a trot's footfall, speed within ±10 %`,
      ok: !!at && within(at, 0.1) && at.footfall === 'trot',
      value: `trots within ±10 % at ${range(trots.map((x) => x.goal))}` + (at ? `; at ${TROT_TO}: ${at.fell ? 'fell' : `${at.mean_speed_m_s.toFixed(2)} m/s, ${at.footfall}`}` : '') });
    const fast = rows.filter((x) => x.goal >= GALLOP_FROM - 1e-9);
    const gallops = fast.filter((x) => within(x, 0.1) && ['canter', 'gallop'].includes(x.footfall) && x.flight_fraction >= FLIGHT);
    const seen = fast.filter((x) => !x.fell);
    checks.push({ what: `canters or gallops at ${GALLOP_FROM} m/s or more: that footfall with a flight phase (≥ ${pct(FLIGHT)}), speed within ±10 %`,
      ok: gallops.length > 0,
      value: gallops.length ? `at ${range(gallops.map((x) => x.goal))}`
        : `none: goals ${GALLOP_FROM}–${fast.at(-1)?.goal.toFixed(1)} m/s ` +
          (seen.length ? `walked ${seen.map((x) => `${x.mean_speed_m_s.toFixed(2)} (${x.footfall})`).join(', ')}` : 'all fell') });
    const pace = skills?.pace ?? [];
    checks.push({ what: `paces (${paceFile} at ${paceSpeeds.join(' and ')} m/s for ${seconds} s): a pace's footfall, no fall, speed within ±15 %`,
      ok: pace.length > 0 && pace.every((x) => within(x, 0.15) && x.footfall === 'pace'),
      value: pace.map((x) => `${x.goal}: ${x.fell ? `fell at ${x.fall_time_s.toFixed(1)} s` : `${x.mean_speed_m_s.toFixed(2)} m/s, ${x.footfall}`}`).join('; ') || 'not measured' });
  }
  checks.push(getUpCheck(boxes));
  return checks;
}


// Getting up: from the falls of the box-hit trial (walking and standing), each watched for
// GET_UP_SECONDS.
function getUpCheck(boxes) {
  const what = `gets up by itself after a fall: from ≥ ${100 * GET_UP_SHARE} % of the box-hit trial's falls within ${GET_UP_SECONDS} s`;
  const trials = (boxes?.trials ?? []).filter((t) => typeof t.get_ups === 'number');
  if (!trials.length) return { what, ok: false, value: 'not measured (the box-hit trial without its get-up watch)' };
  const falls = trials.reduce((n, t) => n + t.falls, 0), ups = trials.reduce((n, t) => n + t.get_ups, 0);
  const each = trials.map((t) => `${t.speed} m/s: ${t.get_ups} of ${t.falls}` + (t.get_up_median_s != null ? `, median ${t.get_up_median_s.toFixed(1)} s` : '')).join('; ');
  return { what, ok: falls > 0 && ups >= GET_UP_SHARE * falls, value: `got up from ${ups} of ${falls} falls (${each})` };
}
