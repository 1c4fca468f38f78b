#!/usr/bin/env node
// The walking benchmark: the shipped presets, measured against every
// walking criterion, with `gaitlab walk` (native) and its WASM twin for the controller's cost.
//
//   node bench/walking.mjs [--character biped|quadruped|both] [--seconds 60] [--wasm] [--params FILE]
//                          [--creature FILE,FILE...]
//                          [--only criteria,sweep,ramp,pushes,boxes,starts,transitions,switches,skills]
//                          [--jobs 2]
//                          [--step 0.1]
//
// Writes bench/results/walking.json and walking.md and prints the table (with --params FILE, a
// gait file to measure instead of the preset: walking-<file name>.{json,md}). With --creature,
// creature files (public/creatures/*.json, body/creature.h) instead of the two characters, each
// under its file's name and with the gait `gaitlab walk --creature` gives it: the walking
// criteria only, at the quadruped's speeds and turns (the biped's for a body of one pair of legs)
// (walking-creatures.{json,md}). With --only, the
// sections run are measured afresh and merged into the results already there (each section says
// when and at which commit it was measured), so one part can be re-measured while iterating.
// --jobs runs that many `gaitlab walk` processes at once.
//
// Sections:
//   - criteria: the walking criteria below;
//   - sweep: goal speeds from 0 to beyond the top of the character's range in --step m/s steps,
//     --seconds each: fell or not, measured speed, heading and position drift, duty factors,
//     flight fraction (share of time with no foot down), and the share of the time it stood on
//     planted feet (goal 0: standing still, native/src/gait/standing.cpp);
//   - ramp: the goal from 0 up to the top speed and back to 0 over 60 s, then 20 s at 0: no fall,
//     speed within ±10 % of the goal wherever the goal exceeds 0.3 m/s (after a lag of up to 1 s;
//     the count at exactly 1 s is shown beside it),
//     standing drift under 0.1 m over the last 20 s; and the same ramp from 20 later starts
//     (0.1–2 s of standing first): how many fall. Where the gait's fastest speed key (the top of
//     the demo's steering range) lies above the top speed, the same ramp again to that key;
//   - pushes: the push ladder in three directions (lateral, forward, backward) at the leg frame,
//     walking at the cruise speed and standing (goal 0): 20 pushes at random phases per impulse;
//     the largest impulse survived every time and in ≥ 90 % of them. Each ladder twice: pushes
//     held for 0.2 s, as the literature pushes (Yin et al. 2007: 350 N for 0.2 s), and the same
//     impulse given in one step, a blow;
//   - boxes: the box-hit trial (`gaitlab walk --box-hits`, native/src/sim/box_hits.h): boxes
//     thrown as the demo throws them at random body parts of the character walking at its cruise
//     speed and standing, 50 hits each; how many knocked it over (the goal: at most 1 in 5);
//   - starts: from rest at 100 gait phases (0, 0.01, ... 0.99; a crowd starts each character at
//     its own), 10 s at each of four goal speeds across the range: how many fall. The walking
//     criteria's 12 starts vary the heading and a push; this varies where in its stride it starts;
//   - transitions: the goal changes between two speeds every 1 to 4 s (at random, so at any phase
//     of the stride), 8 changes per run, 20 runs per pair of speeds, for pairs across each change
//     of gait (the quadruped's walk and trot, and its trot and canter, gait/gait_transition.h;
//     the biped's walk and run, keys of one footfall pattern that blend) and from standing: how
//     many runs fall, and how many changes of footfall pattern the runs made;
//   - skills: the gaits the locomotion criteria name, read from the sweep by each goal's footfall
//     pattern (`footfall` in `gaitlab walk --json`, native/src/gait/footfall.h: a walk when every
//     foot is down more than half the cycle, Alexander 1984; a quadruped's running gaits by the
//     feet that lift off together, Hildebrand 1965, 1977): standing at goal 0; the biped's walk
//     from 0.2 to 1.6 m/s (no flight) and its run at 2.5 m/s or more (a flight phase); the
//     quadruped's walk, its trot to 2.5 m/s, a canter or gallop with a flight phase at 3.5 m/s or
//     more, and its pace (the pace file at the criteria's two speeds); and getting up after a fall;
//   - switches (the quadruped): a gait pinned in mid-stride, as the demo's gait menu pins one
//     (`gaitlab walk --gait-schedule`): from each of the walk, trot and pace files to each other
//     at the demo's quadruped speed (0.4 m/s), 50 switches per pair at times spread over 1 s (more
//     than a stride of each gait, so at every phase): how many fall in the 6 s after. With
//     --params FILE, the file stands in for the trot.
// The walking criteria:
//   - 60 s on flat ground at two goal speeds, one twice the other, without a fall;
//   - mean speed within ±15 % of the goal; heading drift under 10° walking straight;
//   - with a turn command, yaw rate within ±20 % of it;
//   - measured duty factor of every leg within ±0.1 of its configured value;
//   - 30 s on a ±5° slope and on 3 cm bumps without a fall (native/src/physics/terrain.h), at
//     both speeds: the slope starting up it, down it and across it (ridges and valleys every 5 m
//     across +z), the bumps on three bump fields (seeds); every one of those runs must not fall;
//   - pushes: 20 lateral pushes at random phases per impulse, the largest impulse survived in at
//     least 90 % of them.
import { execFile, execFileSync } from 'node:child_process';
import { existsSync, mkdirSync, readFileSync, writeFileSync } from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { GET_UP_SECONDS, skillChecks } from './lib/skills.mjs';

const root = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '..');
const cli = path.join(root, 'build/native/gaitlab');
const args = process.argv.slice(2);
const opt = (name, fallback) => {
  const i = args.indexOf(`--${name}`);
  return i >= 0 ? args[i + 1] : fallback;
};
const seconds = Number(opt('seconds', '60'));
const jobs = Math.max(1, Number(opt('jobs', '2')));
const sweepStep = Number(opt('step', '0.1'));
const SECTIONS = ['criteria', 'sweep', 'ramp', 'pushes', 'boxes', 'starts', 'transitions', 'switches', 'skills'];
const only = opt('only', SECTIONS.join(',')).split(',');
for (const s of only) {
  if (!SECTIONS.includes(s)) {
    console.error(`walking: --only ${s}: not one of ${SECTIONS.join(', ')}`);
    process.exit(2);
  }
}
// Creature files measured under their own names: `gaitlab walk --creature FILE` for them, and
// `--character NAME` for the two characters.
const creatureFiles = opt('creature', null)?.split(',') ?? [];
const creatures = Object.fromEntries(creatureFiles.map((f) => [path.basename(f, '.json'), path.resolve(f)]));
const who = (character) => (creatures[character] ? ['--creature', creatures[character]] : ['--character', character]);
if (creatureFiles.length && only.some((s) => s !== 'criteria')) {
  console.error('walking: --creature measures the walking criteria only (--only criteria)');
  process.exit(2);
}
const characters = creatureFiles.length ? Object.keys(creatures)
  : opt('character', 'both') === 'both' ? ['biped', 'quadruped'] : [opt('character')];
const withWasm = args.includes('--wasm');
const paramsFile = opt('params', null);
if (!existsSync(cli)) {
  console.error('gaitlab: build/native/gaitlab is missing; run `npm run build` first');
  process.exit(1);
}

// Goal speeds per character, one twice the other, and turn commands: a 0.49 m tall dog walks
// slower than a 1.8 m human (similar Froude numbers, v²/(g·leg length) ≈ 0.05–0.15).
// `top`: the top of the speed range the ramp climbs to (run 2.5 m/s for the biped, trot 2.5 m/s
// for the quadruped; a second ramp climbs to the gait's fastest speed key where that is higher,
// `fastestKey`). `sweepTo`: the sweep's last goal, beyond the fastest gait the criteria name
// (the biped's run at 2.5 m/s, the quadruped's canter or gallop at 3.5 m/s). `cruise`: the speed
// of the walking push trials. `fastTurns`: the turns again at the fastest gaits the criteria name
// (the biped's run, the quadruped's trot at its top and its canter), at the turn rate the demo's
// wandering crowd uses (±0.3 rad/s, native/src/sim/wander.h): turning holds across the new range.
const GOALS = {
  biped: { speeds: [0.5, 1.0], turns: [{ speed: 0.8, turn: 0.3 }, { speed: 0.5, turn: -0.3 }, { speed: 1.0, turn: 0.5 }, { speed: 1.0, turn: -0.5 }],
    fastTurns: [{ speed: 2.5, turn: 0.3 }, { speed: 2.5, turn: -0.3 }], top: 2.5, sweepTo: 2.9, cruise: 0.5 },
  quadruped: { speeds: [0.4, 0.8], turns: [{ speed: 0.6, turn: 0.3 }, { speed: 0.6, turn: -0.3 }],
    fastTurns: [{ speed: 2.5, turn: 0.3 }, { speed: 2.5, turn: -0.3 }, { speed: 3.5, turn: 0.3 }, { speed: 3.5, turn: -0.3 }],
    top: 2.5, sweepTo: 4.5, cruise: 0.4 },
};
// A creature walks the goals of the character its legs make it most like: a single pair (the
// bird) the biped's, more the quadruped's.
for (const [name, file] of Object.entries(creatures)) {
  const like = JSON.parse(readFileSync(file, 'utf8')).legFrames.length === 1 ? GOALS.biped : GOALS.quadruped;
  GOALS[name] = { speeds: like.speeds, turns: like.turns };
}
const PUSHES = [2.5, 5, 7.5, 10, 15, 20, 25, 30, 40, 50, 60, 70, 80];  // N·s at the leg frame
// How long a push lasts, s: held 0.2 s (a push, as the literature measures it), or 0 (one step).
const PUSH_DURATIONS = [0.2, 0];
const PUSH_EVERY = 2.5;                   // s: 20 pushes in 52 s
const PUSH_DIRECTIONS = ['lateral', 'forward', 'backward'];
const RAMP_SECONDS = 60, STAND_SECONDS = 20;
const RAMP_REPEATS = 20, RAMP_REPEAT_STEP = 0.1;  // s of standing before each repeat's ramp
const BOX_HITS = 50, BOX_FALLS_ALLOWED = 0.2;  // at most 1 in 5 hits may knock it over

function walk(character, extra, wasm = false) {
  const argv = ['walk', ...who(character), '--json', ...(paramsFile ? ['--params', paramsFile] : []), ...extra.map(String)];
  const out = wasm
    ? execFileSync(process.execPath, [path.join(root, 'bench/wasm.mjs'), ...argv], { encoding: 'utf8' })
    : execFileSync(cli, argv, { encoding: 'utf8' });
  return JSON.parse(out);
}

// The same as walk(), as a promise, at most `jobs` at once.
let running = 0;
const waiting = [];
function walkAsync(character, extra, params = paramsFile) {
  const argv = ['walk', ...who(character), '--json', ...(params ? ['--params', params] : []), ...extra.map(String)];
  return new Promise((resolve, reject) => {
    const start = () => {
      running++;
      execFile(cli, argv, { encoding: 'utf8', maxBuffer: 1 << 26 }, (error, stdout) => {
        running--;
        if (waiting.length) waiting.shift()();
        if (error) reject(error); else resolve(JSON.parse(stdout));
      });
    };
    if (running < jobs) start(); else waiting.push(start);
  });
}

function terrainSupported() {
  try {
    execFileSync(cli, ['walk', '--terrain', 'slope', '--seconds', '0.1', '--json'], { stdio: 'pipe' });
    return true;
  } catch {
    return false;
  }
}

// The terrain runs: 30 s each. On the slope the start decides what comes first (the origin is
// half way up a 5° run facing +z); on the bumps the seed draws the bump field.
const TERRAIN_SECONDS = 30;
const TERRAIN_RUNS = [
  { terrain: 'slope', label: 'up first', args: ['--heading', 0] },
  { terrain: 'slope', label: 'down first', args: ['--heading', Math.PI] },
  { terrain: 'slope', label: 'across', args: ['--heading', Math.PI / 2] },
  { terrain: 'bumps', label: 'seed 1', args: ['--seed', 1] },
  { terrain: 'bumps', label: 'seed 2', args: ['--seed', 2] },
  { terrain: 'bumps', label: 'seed 3', args: ['--seed', 3] },
];

// Robustness: the same 30 s walks from 12 slightly different starts (heading ±0.02 and 0.05 rad,
// a forward or backward push of 2 N·s at t = 0), on each ground. A gait that walks from one start
// only may be balanced on a knife's edge; this counts how often it falls.
const STARTS = [0, 0.02, -0.02, 0.05].flatMap((heading) => [0, 2, -2].map((push) => ({ heading, push })));

let commit = 'unknown';
try {
  commit = execFileSync('git', ['rev-parse', '--short', 'HEAD'], { cwd: root, encoding: 'utf8' }).trim();
  const dirty = execFileSync('git', ['status', '--porcelain', '--untracked-files=no', 'native', 'public/presets', 'public/creatures'], { cwd: root, encoding: 'utf8' }).trim();
  if (dirty) commit += ' + uncommitted changes';
} catch { /* not a checkout */ }
// Each section records the machine it was measured on: a later run of some sections merges into
// the file (below), and the file's sections may then come from different machines.
const machine = `${os.cpus()[0]?.model ?? 'unknown'}, ${os.cpus().length} cores`;
const stamp = { measured: new Date().toISOString(), commit, seconds, machine };

const dir = path.join(root, 'bench/results');
const base = creatureFiles.length ? 'walking-creatures' : paramsFile ? `walking-${path.basename(paramsFile, '.json')}` : 'walking';
// Merge into what is there: the sections not run keep their figures.
let report = { characters: {} };
if (existsSync(path.join(dir, `${base}.json`))) {
  try { report = JSON.parse(readFileSync(path.join(dir, `${base}.json`), 'utf8')); } catch { /* start afresh */ }
}
report.seconds = seconds;
report.characters ??= {};
const hasTerrain = only.includes('criteria') ? terrainSupported() : true;

async function measureCriteria(character) {
  const { speeds: SPEEDS, turns: slowTurns, fastTurns = [] } = GOALS[character];
  const TURNS = [...slowTurns, ...fastTurns];
  process.stderr.write(`${character}: criteria (straight walks, turns, slope and bumps, starts)\n`);
  const straightP = Promise.all(SPEEDS.map((speed) => walkAsync(character, ['--speed', speed, '--seconds', seconds])));
  const turnsP = Promise.all(TURNS.map((t) => walkAsync(character, ['--speed', t.speed, '--turn', t.turn, '--seconds', seconds])));
  const terrainP = hasTerrain
    ? Promise.all(SPEEDS.flatMap((speed) => TERRAIN_RUNS.map(async (run) => ({
      name: run.terrain, start: run.label, speed,
      ...await walkAsync(character, ['--speed', speed, '--terrain', run.terrain, '--seconds', TERRAIN_SECONDS, ...run.args]),
    }))))
    : null;
  const robustnessP = hasTerrain
    ? Promise.all(['flat', 'slope', 'bumps'].flatMap((ground) => SPEEDS.map(async (speed) => {
      const runs = await Promise.all(STARTS.map((s) => walkAsync(character, ['--speed', speed, '--terrain', ground, '--seconds', TERRAIN_SECONDS,
        '--heading', s.heading, '--start-push-forward', s.push])));
      const times = runs.filter((r) => r.fell).map((r) => r.fall_time_s);
      return { ground, speed, starts: runs.length, fell: times.length, fall_times_s: times };
    })))
    : null;
  const [straight, turns, terrain, robustness] = await Promise.all([straightP, turnsP, terrainP, robustnessP]);
  const wasm = withWasm ? walk(character, ['--speed', SPEEDS[0], '--seconds', 10], true) : null;

  const checks = [];
  const check = (what, ok, value) => checks.push({ what, ok, value });
  straight.forEach((r, i) => {
    const g = SPEEDS[i];
    check(`${g} m/s for ${seconds} s without a fall`, !r.fell, r.fell ? `fell at ${r.fall_time_s.toFixed(1)} s` : 'no fall');
    check(`${g} m/s: mean speed within ±15 %`, !r.fell && Math.abs(r.mean_speed_m_s - g) <= 0.15 * g, `${r.mean_speed_m_s.toFixed(3)} m/s`);
    check(`${g} m/s: heading drift under 10°`, !r.fell && r.heading_drift_deg < 10, `${r.heading_drift_deg.toFixed(1)}°`);
    const worst = Math.max(...r.duty_factor_measured.map((d, l) => Math.abs(d - r.duty_factor_config[l])));
    check(`${g} m/s: duty factors within ±0.1`, !r.fell && worst <= 0.1,
      r.duty_factor_measured.map((d, l) => `${d.toFixed(2)}/${r.duty_factor_config[l].toFixed(2)}`).join(' '));
  });
  turns.forEach((r, i) => {
    const t = TURNS[i];
    check(`turn ${t.turn} rad/s at ${t.speed} m/s: no fall, yaw rate within ±20 %`,
      !r.fell && Math.abs(r.yaw_rate_rad_s - t.turn) <= 0.2 * Math.abs(t.turn),
      r.fell ? `fell at ${r.fall_time_s.toFixed(1)} s` : `${r.yaw_rate_rad_s.toFixed(3)} rad/s`);
  });
  if (terrain) {
    for (const name of ['slope', 'bumps']) {
      for (const speed of SPEEDS) {
        const runs = terrain.filter((r) => r.name === name && r.speed === speed);
        check(`${TERRAIN_SECONDS} s on ${name === 'slope' ? 'the ±5° slope' : 'the 3 cm bumps'} at ${speed} m/s without a fall (${runs.length} starts)`,
          runs.every((r) => !r.fell),
          runs.map((r) => `${r.start}: ${r.fell ? `fell at ${r.fall_time_s.toFixed(1)} s` : 'no fall'}`).join('; '));
      }
    }
  } else {
    check('30 s on a ±5° slope and on 3 cm bumps', false, 'not built: --terrain offers flat ground only');
  }
  return {
    ...stamp, straight, turns, terrain, robustness, checks,
    controller_us_per_step: { native: straight[0].controller_us_per_step, wasm_node: wasm?.controller_us_per_step ?? null },
    all_met: checks.every((c) => c.ok),
  };
}

// The speed sweep: one run per goal speed.
async function measureSweep(character) {
  const { sweepTo } = GOALS[character];
  const goals = [];
  for (let k = 0; k * sweepStep <= sweepTo + 1e-9; k++) goals.push(Math.round(k * sweepStep * 100) / 100);
  process.stderr.write(`${character}: sweep over ${goals.length} goal speeds, ${seconds} s each\n`);
  const runs = await Promise.all(goals.map((goal) => walkAsync(character, ['--speed', goal, '--seconds', seconds])));
  const rows = runs.map((r, i) => ({
    goal: goals[i], fell: r.fell, fall_time_s: r.fall_time_s, mean_speed_m_s: r.mean_speed_m_s,
    heading_drift_deg: r.heading_drift_deg, position_drift_m: r.position_drift_m,
    duty_factor_measured: r.duty_factor_measured, duty_factor_config: r.duty_factor_config,
    flight_fraction: r.flight_fraction, standing_fraction: r.standing_fraction, footfall: r.footfall,
    gait: paramsFile ? path.basename(paramsFile, '.json') : 'preset',
  }));
  // Top speed walked: the highest goal up to which every goal walked the whole run without a fall.
  let topWalked = null;
  for (const r of rows) {
    if (r.fell) break;
    topWalked = r.goal;
  }
  // Tracked: no fall and the mean speed within ±10 % of the goal (goals above 0.3 m/s).
  const tracked = rows.filter((r) => r.goal > 0.3 && !r.fell && Math.abs(r.mean_speed_m_s - r.goal) <= 0.1 * r.goal).map((r) => r.goal);
  return { ...stamp, step: sweepStep, rows, top_without_fall_m_s: topWalked, tracked_within_10pct: tracked };
}

// The fastest speed key of the gait a character walks here (the --params file, else its preset):
// the top of its steering range in the demo (gl_top_speed), where the ramp to the top of the range
// goes. Null for a gait without keys.
function fastestKey(character) {
  const file = paramsFile ?? path.join(root, 'public/presets', `${character}.json`);
  if (!existsSync(file)) return null;
  const keys = JSON.parse(readFileSync(file, 'utf8')).keys ?? [];
  return keys.length ? Math.max(...keys.map((k) => k.speed)) : null;
}

// The ramp: 0 → top → 0 over 60 s, then standing.
async function measureRamp(character, top = GOALS[character].top) {
  // The ramp after `d` s of standing.
  const rampAfter = (d) => `${d > 0 ? `0:0,${d}:0` : '0:0'},${d + RAMP_SECONDS / 2}:${top},${d + RAMP_SECONDS}:0`;
  const schedule = rampAfter(0);
  process.stderr.write(`${character}: ramp 0 → ${top} → 0 m/s over ${RAMP_SECONDS} s, then ${STAND_SECONDS} s standing\n`);
  const r = await walkAsync(character, ['--speed-schedule', schedule, '--seconds', RAMP_SECONDS + STAND_SECONDS,
    '--drift-window', STAND_SECONDS]);
  // The same ramp from 20 later starts (0.1 to 2 s of standing first, so at other phases of the
  // stride): one ramp is one sample of a chaotic system, and near the top of a range it may fall
  // or not by chance.
  const offsets = Array.from({ length: RAMP_REPEATS }, (_, k) => Math.round((k + 1) * 100 * RAMP_REPEAT_STEP) / 100);
  const repeats = await Promise.all(offsets.map((d) => walkAsync(character, ['--speed-schedule', rampAfter(d), '--seconds', d + RAMP_SECONDS])));
  const repeatFalls = repeats.map((x, k) => (x.fell ? x.fall_time_s - offsets[k] : null)).filter((t) => t !== null);
  const within = r.tracking.samples ? r.tracking.within_10pct / r.tracking.samples : 0;
  // The later starts' speed tracking, by the same reading: how many track within ±10 % at every
  // sample, and the fewest samples any of them kept (a start from another phase shows whether the
  // first ramp's tracking is a property of the gait or of that one start).
  const tracked = repeats.filter((x) => !x.fell && x.tracking.samples && x.tracking.within_10pct === x.tracking.samples).length;
  const fewest = repeats.reduce((m, x) => (x.tracking.samples ? Math.min(m, x.tracking.within_10pct) : m), Infinity);
  const checks = [
    { what: 'ramp: no fall', ok: !r.fell, value: r.fell ? `fell at ${r.fall_time_s.toFixed(1)} s` : 'no fall' },
    { what: 'ramp: speed within ±10 % of the goal where the goal > 0.3 m/s (lag up to 1 s)', ok: !r.fell && within === 1,
      value: `${r.tracking.within_10pct}/${r.tracking.samples} samples; worst ${(100 * r.tracking.worst_relative_error).toFixed(0)} %` +
        ` (at a lag of exactly 1 s: ${r.tracking.within_10pct_lag_1s}/${r.tracking.samples})` },
    { what: `ramp: standing drift under 0.1 m over the last ${STAND_SECONDS} s`, ok: !r.fell && r.position_drift_m < 0.1,
      value: `${r.position_drift_m.toFixed(3)} m` },
    { what: `ramp from ${RAMP_REPEATS} later starts (after ${offsets[0]}–${offsets.at(-1)} s standing): no fall`,
      ok: repeatFalls.length === 0,
      value: repeatFalls.length ? `${repeatFalls.length} of ${RAMP_REPEATS} fell, ${repeatFalls.map((t) => t.toFixed(1)).join(', ')} s into the ramp` : 'none fell' },
    { what: `ramp from ${RAMP_REPEATS} later starts: speed within ±10 % of the goal at every sample (lag up to 1 s)`,
      ok: tracked === RAMP_REPEATS,
      value: `${tracked} of ${RAMP_REPEATS}; the fewest samples within: ${fewest}/${r.tracking.samples}` },
  ];
  return { ...stamp, schedule, fell: r.fell, fall_time_s: r.fall_time_s, tracking: r.tracking,
    standing_drift_m: r.position_drift_m, repeats: RAMP_REPEATS, repeat_falls: repeatFalls.length,
    repeat_fall_times_s: repeatFalls, repeats_tracked: tracked, repeats_fewest_within: fewest, checks };
}

// The push ladder: three directions, walking at the cruise speed and standing. The ladder
// stops climbing after a rung where none of the 20 pushes was survived.
async function measurePushes(character) {
  const { cruise } = GOALS[character];
  const ladders = await Promise.all(PUSH_DURATIONS.flatMap((duration) => PUSH_DIRECTIONS.flatMap((direction) =>
    [cruise, 0].map(async (speed) => {
      const rungs = [];
      for (const impulse of PUSHES) {
        process.stderr.write(`${character}: ${direction} pushes of ${impulse} N·s over ${duration} s at ${speed} m/s\n`);
        const r = await walkAsync(character, ['--speed', speed, '--push-impulse', impulse, '--push-every', PUSH_EVERY,
          '--push-direction', direction, '--push-duration', duration, '--seconds', 2 + 20 * PUSH_EVERY, '--seed', 7]);
        // Pushes not applied because it fell earlier count as not survived.
        rungs.push({ impulse, applied: r.pushes_applied, survived: r.pushes_survived, share: r.pushes_survived / 20, fell: r.fell });
        if (r.pushes_survived === 0) break;
      }
      let all = 0;
      for (const p of rungs) {
        if (p.survived < 20) break;
        all = p.impulse;
      }
      const most = rungs.filter((p) => p.share >= 0.9).reduce((m, p) => Math.max(m, p.impulse), 0);
      return { direction, speed, duration_s: duration, rungs, largest_every_time_n_s: all, largest_90pct_n_s: most };
    }))));
  return { ...stamp, ladders };
}

// The box-hit trial, walking at the cruise speed and standing: 50 hits each, each its own episode;
// each fall watched GET_UP_SECONDS more for the character getting up by itself.
async function measureBoxes(character) {
  const { cruise } = GOALS[character];
  const trials = await Promise.all([cruise, 0].map(async (speed) => {
    process.stderr.write(`${character}: ${BOX_HITS} box hits at ${speed} m/s\n`);
    const r = await walkAsync(character, ['--speed', speed, '--box-hits', BOX_HITS, '--seed', 7, '--get-up', GET_UP_SECONDS]);
    const bySegment = {};
    for (const h of r.hits) {
      const s = (bySegment[h.segment] ??= { hits: 0, falls: 0 });
      s.hits++;
      s.falls += h.fell ? 1 : 0;
    }
    const upTimes = r.hits.filter((h) => h.fell && h.got_up_after_s != null).map((h) => h.got_up_after_s).sort((a, b) => a - b);
    return { speed, throws: r.box_throws, hits: r.box_hits, falls: r.box_hit_falls, by_segment: bySegment,
      met: r.box_hit_falls <= BOX_FALLS_ALLOWED * r.box_hits,
      get_ups: r.box_hit_get_ups, get_up_median_s: upTimes.length ? upTimes[Math.floor((upTimes.length - 1) / 2)] : null,
      get_up_max_s: upTimes.length ? upTimes.at(-1) : null };
  }));
  return { ...stamp, box_half_m: 0.12, get_up_watch_s: GET_UP_SECONDS, trials };
}

// Starts from rest at 100 gait phases, 10 s each, at four goal speeds from the cruise speed to the
// top of what the character walks (the sweep's).
const START_PHASES = 100, START_SECONDS = 10;
async function measureStarts(character) {
  const speeds = character === 'biped' ? [0.5, 1.0, 1.6, 2.5] : [0.4, 0.8, 1.0, 1.3];
  const rows = await Promise.all(speeds.map(async (speed) => {
    process.stderr.write(`${character}: starts from ${START_PHASES} phases at ${speed} m/s\n`);
    const runs = await Promise.all(Array.from({ length: START_PHASES }, (_, k) =>
      walkAsync(character, ['--speed', speed, '--seconds', START_SECONDS, '--start-phase', k / START_PHASES])
        .then((r) => ({ phase: k / START_PHASES, fell: r.fell, fall_time_s: r.fall_time_s }))));
    const fell = runs.filter((x) => x.fell);
    return { speed, starts: runs.length, falls: fell.length, fell_at_phases: fell.map((x) => x.phase) };
  }));
  return { ...stamp, seconds: START_SECONDS, rows };
}

// Gait changes in mid-stride: the goal alternates between the two speeds of a pair, each held
// for 1 to 4 s (drawn by a seeded generator, so every run is reproducible), 9 holds per run.
const TRANSITION_PAIRS = {
  biped: [[0, 1.0], [0.5, 2.5], [1.0, 2.5]],
  quadruped: [[0, 0.2], [0.2, 0.6], [0, 0.6], [0.1, 1.0], [2.2, 3.5]],
};
const TRANSITION_RUNS = 20, TRANSITION_HOLDS = 9;
function transitionSchedule(lo, hi, seed) {
  let a = seed >>> 0;  // mulberry32
  const random = () => {
    a = (a + 0x6d2b79f5) >>> 0;
    let t = Math.imul(a ^ (a >>> 15), 1 | a);
    t = (t + Math.imul(t ^ (t >>> 7), 61 | t)) ^ t;
    return ((t ^ (t >>> 14)) >>> 0) / 4294967296;
  };
  const points = [];
  let t = 0;
  for (let k = 0; k < TRANSITION_HOLDS; k++) {
    const goal = k % 2 === 0 ? lo : hi;
    const hold = 1 + 3 * random();
    points.push(`${t.toFixed(3)}:${goal}`, `${(t + hold - 0.001).toFixed(3)}:${goal}`);
    t += hold;
  }
  return { schedule: points.join(','), seconds: Math.round(t * 1000) / 1000 };
}
async function measureTransitions(character) {
  const rows = await Promise.all(TRANSITION_PAIRS[character].map(async ([lo, hi]) => {
    process.stderr.write(`${character}: ${TRANSITION_RUNS} runs changing the goal between ${lo} and ${hi} m/s\n`);
    const runs = await Promise.all(Array.from({ length: TRANSITION_RUNS }, (_, k) => {
      const { schedule, seconds: s } = transitionSchedule(lo, hi, k + 1);
      return walkAsync(character, ['--speed-schedule', schedule, '--seconds', s])
        .then((r) => ({ seed: k + 1, fell: r.fell, fall_time_s: r.fall_time_s, gait_changes: r.gait_changes }));
    }));
    const fell = runs.filter((x) => x.fell);
    return { speeds: [lo, hi], runs: runs.length, goal_changes_per_run: TRANSITION_HOLDS - 1, falls: fell.length,
      fall_times_s: fell.map((x) => x.fall_time_s), gait_changes: runs.reduce((n, x) => n + x.gait_changes, 0) };
  }));
  return { ...stamp, rows };
}

// A gait pinned in mid-stride: the quadruped's gait files, each to each other, at the demo's
// quadruped speed; the switch times spread evenly over SWITCH_SPREAD seconds after SWITCH_AT.
const SWITCH_GAITS = { walk: 'quadruped-walk.json', trot: 'quadruped-trot.json', pace: 'quadruped-pace.json' };
const SWITCH_SPEED = 0.4, SWITCH_RUNS = 50, SWITCH_AT = 3, SWITCH_SPREAD = 1, SWITCH_AFTER = 6;
async function measureSwitches(character) {
  if (character !== 'quadruped') return null;  // the biped has one gait file
  const file = (name) => (name === 'trot' && paramsFile ? paramsFile : path.join(root, 'public/presets', SWITCH_GAITS[name]));
  const names = Object.keys(SWITCH_GAITS);
  const pairs = names.flatMap((from) => names.filter((to) => to !== from).map((to) => [from, to]));
  const rows = await Promise.all(pairs.map(async ([from, to]) => {
    process.stderr.write(`${character}: ${SWITCH_RUNS} switches from the ${from} to the ${to}\n`);
    const runs = await Promise.all(Array.from({ length: SWITCH_RUNS }, (_, k) => {
      const at = SWITCH_AT + (SWITCH_SPREAD * k) / SWITCH_RUNS;
      return walkAsync(character, ['--speed', SWITCH_SPEED, '--seconds', at + SWITCH_AFTER, '--gait-schedule', `${at}:${file(to)}`], file(from))
        .then((r) => ({ at, fell: r.fell, fall_time_s: r.fall_time_s }));
    }));
    const before = runs.filter((x) => x.fell && x.fall_time_s <= x.at);
    const after = runs.filter((x) => x.fell && x.fall_time_s > x.at);
    return { from, to, runs: runs.length, fell_before: before.length, falls: after.length,
      fell_after_s: after.map((x) => x.fall_time_s - x.at) };
  }));
  return { ...stamp, speed: SWITCH_SPEED, seconds_after: SWITCH_AFTER, rows };
}

// The gaits the locomotion criteria name (bench/lib/skills.mjs reads them from the sweep); the
// pace is a file of its own (the demo's gait menu pins it), walked here at the criteria's two
// speeds.
async function measureSkills(character) {
  if (character !== 'quadruped') return { ...stamp };
  const pace = path.join(root, 'public/presets', SWITCH_GAITS.pace);
  process.stderr.write(`${character}: the pace at ${GOALS[character].speeds.join(' and ')} m/s\n`);
  const runs = await Promise.all(GOALS[character].speeds.map((speed) => walkAsync(character, ['--speed', speed, '--seconds', seconds], pace)));
  return { ...stamp, pace: runs.map((x, i) => ({ goal: GOALS[character].speeds[i], fell: x.fell, fall_time_s: x.fall_time_s,
    mean_speed_m_s: x.mean_speed_m_s, footfall: x.footfall, flight_fraction: x.flight_fraction })) };
}

for (const character of characters) {
  const r = (report.characters[character] ??= {});
  // Beside the ramp to `top`, the ramp to the gait's fastest speed key where that is higher.
  const rampTop = only.includes('ramp') ? fastestKey(character) : null;
  const [measured, rampToFastestKey] = await Promise.all([Promise.all([
    only.includes('criteria') ? measureCriteria(character) : null,
    only.includes('sweep') ? measureSweep(character) : null,
    only.includes('ramp') ? measureRamp(character) : null,
    only.includes('pushes') ? measurePushes(character) : null,
    only.includes('boxes') ? measureBoxes(character) : null,
    only.includes('starts') ? measureStarts(character) : null,
    only.includes('transitions') ? measureTransitions(character) : null,
    only.includes('switches') ? measureSwitches(character) : null,
    only.includes('skills') ? measureSkills(character) : null,
  ]), rampTop > GOALS[character].top ? measureRamp(character, rampTop) : null]);
  if (only.includes('ramp')) {
    if (rampToFastestKey) r.ramp_to_fastest_key = rampToFastestKey;
    else delete r.ramp_to_fastest_key;
  }
  SECTIONS.forEach((name, i) => { if (measured[i]) r[name] = measured[i]; });
  // The skills read the sweep and the box hits' get-ups: checked again whenever one was measured.
  if (r.skills && r.sweep && ['skills', 'sweep', 'boxes'].some((name) => only.includes(name))) {
    r.skills.checks = skillChecks(character, r.sweep, r.skills, { seconds, paceFile: SWITCH_GAITS.pace, paceSpeeds: GOALS.quadruped.speeds }, r.boxes);
  }
  // Results of the previous layout (criteria at the top level) are not carried on.
  for (const old of ['straight', 'turns', 'terrain', 'robustness', 'largest_push_survived_90pct_n_s', 'checks', 'controller_us_per_step', 'all_met']) delete r[old];
  if (Array.isArray(r.pushes)) delete r.pushes;
}

if (paramsFile) report.params = paramsFile;
const f2 = (x) => (x == null ? '–' : x.toFixed(2));
// When and where a section was measured: its date and commit, and, when the file's sections come
// from more than one machine, its machine (sections measured before they recorded it say so).
const machineOf = (x) => x.machine ?? 'machine not recorded';
const machines = [...new Set(Object.values(report.characters).flatMap((r) => Object.values(r))
  .filter((x) => x?.measured).map(machineOf))];
delete report.machine;
const when = (x) => `${x.measured.slice(0, 10)}, ${x.commit}${machines.length > 1 ? `, ${machineOf(x)}` : ''}`;
const lines = [`# Walking benchmark (${machines.length === 1 ? machines[0] : 'sections measured on different machines, as each says'}${paramsFile ? `, gait ${paramsFile}` : ''}${creatureFiles.length ? ', creature files' : ''})`, ''];
for (const [character, r] of Object.entries(report.characters)) {
  const { speeds: SPEEDS } = GOALS[character];
  lines.push(`## ${character}`, '');
  const c = r.criteria;
  if (c) {
    lines.push(`### The walking criteria: ${c.all_met ? 'every criterion met' : 'criteria not all met'} (${c.seconds} s runs; ${when(c)})`, '',
      '| criterion | met | measured |', '|---|---|---|');
    for (const k of c.checks) lines.push(`| ${k.what} | ${k.ok ? 'yes' : '**no**'} | ${k.value} |`);
    if (c.robustness) {
      lines.push('', `Falls within ${TERRAIN_SECONDS} s from ${STARTS.length} starts (heading 0, ±0.02, 0.05 rad × push 0, ±2 N·s forward at t = 0):`, '',
        '| ground | ' + SPEEDS.map((v) => `${v} m/s`).join(' | ') + ' |', '|---|' + SPEEDS.map(() => '---|').join(''));
      for (const ground of ['flat', 'slope', 'bumps']) {
        const cells = SPEEDS.map((v) => {
          const x = c.robustness.find((q) => q.ground === ground && q.speed === v);
          return x.fell ? `${x.fell}/${x.starts} fell (${Math.min(...x.fall_times_s).toFixed(1)}–${Math.max(...x.fall_times_s).toFixed(1)} s)` : `0/${x.starts} fell`;
        });
        lines.push(`| ${ground} | ${cells.join(' | ')} |`);
      }
    }
    lines.push('', `Controller: ${c.controller_us_per_step.native.toFixed(2)} µs per step native` +
      (c.controller_us_per_step.wasm_node ? `, ${c.controller_us_per_step.wasm_node.toFixed(2)} µs WASM in Node` : '') + '.', '');
  }
  const sw = r.sweep;
  if (sw) {
    lines.push(`### Speed sweep (${sw.seconds} s per goal; ${when(sw)})`, '',
      `Top goal walked without a fall (every goal up to it): ${sw.top_without_fall_m_s ?? 'none'} m/s; ` +
      `goals above 0.3 m/s tracked within ±10 %: ${sw.tracked_within_10pct.length ? sw.tracked_within_10pct.join(', ') : 'none'}.`, '',
      '| goal m/s | fell | speed m/s | footfall | heading drift ° | position drift m (2nd half) | duty measured/configured | flight | stood still |',
      '|---|---|---|---|---|---|---|---|---|');
    for (const x of sw.rows) {
      lines.push(`| ${x.goal.toFixed(1)} | ${x.fell ? `at ${x.fall_time_s.toFixed(1)} s` : 'no'} | ${x.fell ? '–' : f2(x.mean_speed_m_s)} | ${x.footfall ?? '–'} | ` +
        `${x.heading_drift_deg.toFixed(1)} | ${f2(x.position_drift_m)} | ` +
        `${x.duty_factor_measured.map((d, l) => `${d.toFixed(2)}/${x.duty_factor_config[l].toFixed(2)}`).join(' ')} | ${(100 * x.flight_fraction).toFixed(0)} % | ` +
        `${(100 * (x.standing_fraction ?? 0)).toFixed(0)} % |`);
    }
    lines.push('');
  }
  const sk = r.skills;
  if (sk?.checks) {
    lines.push(`### Locomotion skills: ${sk.checks.every((k) => k.ok) ? 'every skill shown' : 'skills not all shown'} (from the sweep of ${sw?.measured.slice(0, 10) ?? '–'}; ${when(sk)})`, '',
      '| skill | met | measured |', '|---|---|---|');
    for (const k of sk.checks) lines.push(`| ${k.what} | ${k.ok ? 'yes' : '**no**'} | ${k.value} |`);
    lines.push('');
  }
  for (const [title, rp] of [['Ramp', r.ramp], ['Ramp to the fastest speed key, the top of the steering range', r.ramp_to_fastest_key]]) {
    if (!rp) continue;
    lines.push(`### ${title} (goal ${rp.schedule}, then ${STAND_SECONDS} s at 0; ${when(rp)})`, '',
      '| criterion | met | measured |', '|---|---|---|');
    for (const k of rp.checks) lines.push(`| ${k.what} | ${k.ok ? 'yes' : '**no**'} | ${k.value} |`);
    lines.push('');
  }
  const pu = r.pushes;
  if (pu) {
    lines.push(`### Push ladder (20 pushes at random phases per impulse, at the leg frame; ${when(pu)})`, '',
      '| push | direction | goal m/s | survived every time | survived ≥ 90 % | rungs (N·s: survived/20) |', '|---|---|---|---|---|---|');
    for (const l of pu.ladders) {
      const kind = l.duration_s ? `held ${l.duration_s} s` : 'one step';
      lines.push(`| ${kind} | ${l.direction} | ${l.speed} | ${l.largest_every_time_n_s || 'none'} N·s | ${l.largest_90pct_n_s || 'none'} N·s | ` +
        `${l.rungs.map((p) => `${p.impulse}: ${p.survived}`).join(', ')} |`);
    }
    lines.push('');
  }
  const bx = r.boxes;
  if (bx) {
    lines.push(`### Box hits (boxes thrown as the demo throws them, ${2 * bx.box_half_m} m, 8.3 kg, 14–18 m/s, at random body parts; ${when(bx)})`, '',
      `| goal m/s | hits (throws) | knocked over | at most 1 in 5? | got up by itself within ${bx.get_up_watch_s ?? '–'} s (median, slowest) | falls / hits by body part (render order) |`, '|---|---|---|---|---|---|');
    for (const t of bx.trials) {
      const up = typeof t.get_ups !== 'number' ? 'not watched'
        : `${t.get_ups} of ${t.falls}` + (t.get_up_median_s != null ? ` (${t.get_up_median_s.toFixed(1)} s, ${t.get_up_max_s.toFixed(1)} s)` : '');
      lines.push(`| ${t.speed} | ${t.hits} (${t.throws}) | ${t.falls} (${Math.round((100 * t.falls) / t.hits)} %) | ${t.met ? 'yes' : '**no**'} | ${up} | ` +
        `${Object.entries(t.by_segment).map(([k, s]) => `${k}: ${s.falls}/${s.hits}`).join(', ')} |`);
    }
    lines.push('');
  }
  const st = r.starts;
  if (st) {
    lines.push(`### Starts from rest at ${START_PHASES} gait phases (${st.seconds} s each; ${when(st)})`, '',
      '| goal m/s | fell | at phases |', '|---|---|---|');
    for (const row of st.rows) lines.push(`| ${row.speed} | ${row.falls} of ${row.starts} | ${row.fell_at_phases.join(', ') || '–'} |`);
    lines.push('');
  }
  const tr = r.transitions;
  if (tr) {
    lines.push(`### Gait changes in mid-stride (the goal changes between two speeds every 1–4 s, ${TRANSITION_HOLDS - 1} times per run; ${when(tr)})`, '',
      '| goal speeds m/s | runs that fell | changes of footfall pattern made | fell at s |', '|---|---|---|---|');
    for (const row of tr.rows) {
      lines.push(`| ${row.speeds.join(' ↔ ')} | ${row.falls} of ${row.runs} | ${row.gait_changes} | ` +
        `${row.fall_times_s.map((t) => t.toFixed(1)).join(', ') || '–'} |`);
    }
    lines.push('');
  }
  const sx = r.switches;
  if (sx) {
    lines.push(`### A gait pinned in mid-stride (${SWITCH_RUNS} switches per pair at ${sx.speed} m/s, at times spread over ${SWITCH_SPREAD} s; ${when(sx)})`, '',
      `| from | to | fell within ${sx.seconds_after} s of the switch | fell at s after it |`, '|---|---|---|---|');
    for (const row of sx.rows) {
      lines.push(`| ${row.from} | ${row.to} | ${row.falls} of ${row.runs - row.fell_before}${row.fell_before ? ` (${row.fell_before} fell before it)` : ''} | ` +
        `${row.fell_after_s.map((t) => t.toFixed(1)).join(', ') || '–'} |`);
    }
    lines.push('');
  }
}
const md = lines.join('\n');
mkdirSync(dir, { recursive: true });
writeFileSync(path.join(dir, `${base}.json`), JSON.stringify(report, null, 2) + '\n');
writeFileSync(path.join(dir, `${base}.md`), md + '\n');
console.log(md);
