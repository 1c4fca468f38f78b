#!/usr/bin/env node
// The walking benchmark: the shipped presets, measured against every
// walking criterion, with `gaitlab walk` (native) and its WASM twin for the controller's cost.
//
//   node bench/walking.mjs [--character biped|quadruped|both] [--seconds 60] [--wasm] [--params FILE]
//
// Writes bench/results/walking.json and walking.md and prints the table (with --params FILE, a
// gait file to measure instead of the preset: walking-<file name>.{json,md}). The walking criteria:
//   - 60 s on flat ground at two goal speeds, one twice the other, without a fall;
//   - mean speed within ±15 % of the goal; heading drift under 10° walking straight;
//   - with a turn command, yaw rate within ±20 % of it;
//   - measured duty factor of every leg within ±0.1 of its configured value;
//   - 30 s on a ±5° slope and on 3 cm bumps without a fall (native/src/physics/terrain.h), at
//     both speeds: the slope starting up it, down it and across it (ridges and valleys every 5 m
//     across +z), the bumps on three bump fields (seeds); every one of those runs must not fall;
//   - pushes: 20 lateral pushes at random phases per impulse, the largest impulse survived in at
//     least 90 % of them.
import { execFileSync } from 'node:child_process';
import { existsSync, mkdirSync, writeFileSync } from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { fileURLToPath } from 'node:url';

const root = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '..');
const cli = path.join(root, 'build/native/gaitlab');
const args = process.argv.slice(2);
const opt = (name, fallback) => {
  const i = args.indexOf(`--${name}`);
  return i >= 0 ? args[i + 1] : fallback;
};
const seconds = Number(opt('seconds', '60'));
const characters = opt('character', 'both') === 'both' ? ['biped', 'quadruped'] : [opt('character')];
const withWasm = args.includes('--wasm');
const paramsFile = opt('params', null);
if (!existsSync(cli)) {
  console.error('gaitlab: build/native/gaitlab is missing; run `npm run build` first');
  process.exit(1);
}

// Goal speeds per character, one twice the other, and turn commands: a 0.49 m tall dog walks
// slower than a 1.8 m human (similar Froude numbers, v²/(g·leg length) ≈ 0.05–0.15).
const GOALS = {
  biped: { speeds: [0.5, 1.0], turns: [{ speed: 0.8, turn: 0.3 }, { speed: 0.5, turn: -0.3 }] },
  quadruped: { speeds: [0.4, 0.8], turns: [{ speed: 0.6, turn: 0.3 }, { speed: 0.6, turn: -0.3 }] },
};
const PUSHES = [2.5, 5, 7.5, 10, 15, 20, 25, 30, 40, 60, 80];  // N·s, lateral at the leg frame
const PUSH_EVERY = 2.5;                   // s: 20 pushes in 52 s

function walk(character, extra, wasm = false) {
  const argv = ['walk', '--character', character, '--json', ...(paramsFile ? ['--params', paramsFile] : []), ...extra.map(String)];
  const out = wasm
    ? execFileSync(process.execPath, [path.join(root, 'bench/wasm.mjs'), ...argv], { encoding: 'utf8' })
    : execFileSync(cli, argv, { encoding: 'utf8' });
  return JSON.parse(out);
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

const report = { machine: `${os.cpus()[0]?.model ?? 'unknown'}, ${os.cpus().length} cores`, seconds, characters: {} };
const hasTerrain = terrainSupported();
for (const character of characters) {
  const { speeds: SPEEDS, turns: TURNS } = GOALS[character];
  process.stderr.write(`${character}: straight walks\n`);
  const straight = SPEEDS.map((speed) => walk(character, ['--speed', speed, '--seconds', seconds]));
  process.stderr.write(`${character}: turns\n`);
  const turns = TURNS.map((t) => walk(character, ['--speed', t.speed, '--turn', t.turn, '--seconds', seconds]));
  process.stderr.write(`${character}: slope and bumps\n`);
  const terrain = hasTerrain
    ? SPEEDS.flatMap((speed) => TERRAIN_RUNS.map((run) => ({
      name: run.terrain, start: run.label, speed,
      ...walk(character, ['--speed', speed, '--terrain', run.terrain, '--seconds', TERRAIN_SECONDS, ...run.args]),
    })))
    : null;
  process.stderr.write(`${character}: robustness over ${STARTS.length} starts\n`);
  const robustness = hasTerrain
    ? ['flat', 'slope', 'bumps'].flatMap((ground) => SPEEDS.map((speed) => {
      const runs = STARTS.map((s) => walk(character, ['--speed', speed, '--terrain', ground, '--seconds', TERRAIN_SECONDS,
        '--heading', s.heading, '--start-push-forward', s.push]));
      const times = runs.filter((r) => r.fell).map((r) => r.fall_time_s);
      return { ground, speed, starts: runs.length, fell: times.length, fall_times_s: times };
    }))
    : null;
  const pushes = [];
  for (const impulse of PUSHES) {
    process.stderr.write(`${character}: pushes of ${impulse} N·s\n`);
    const r = walk(character, ['--speed', SPEEDS[0], '--push-impulse', impulse, '--push-every', PUSH_EVERY,
      '--seconds', 2 + 20 * PUSH_EVERY, '--seed', 7]);
    // Pushes not applied because it fell earlier count as not survived.
    pushes.push({ impulse, applied: r.pushes_applied, survived: r.pushes_survived, share: r.pushes_survived / 20, fell: r.fell });
  }
  const bestPush = pushes.filter((p) => p.share >= 0.9).reduce((m, p) => Math.max(m, p.impulse), 0);
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

  report.characters[character] = {
    straight, turns, terrain, robustness, pushes, largest_push_survived_90pct_n_s: bestPush, checks,
    controller_us_per_step: { native: straight[0].controller_us_per_step, wasm_node: wasm?.controller_us_per_step ?? null },
    all_met: checks.every((c) => c.ok),
  };
}

if (paramsFile) report.params = paramsFile;
const lines = [`# Walking benchmark (${seconds} s runs, ${report.machine}${paramsFile ? `, gait ${paramsFile}` : ''})`, ''];
for (const [character, r] of Object.entries(report.characters)) {
  const SPEEDS = GOALS[character].speeds;
  lines.push(`## ${character}: ${r.all_met ? 'every criterion met' : 'criteria not all met'}`, '', '| criterion | met | measured |', '|---|---|---|');
  for (const c of r.checks) lines.push(`| ${c.what} | ${c.ok ? 'yes' : '**no**'} | ${c.value} |`);
  lines.push('', `Pushes (lateral, 20 at random phases, walking at ${SPEEDS[0]} m/s): ` +
    r.pushes.map((p) => `${p.impulse} N·s ${p.survived}/20`).join(', ') +
    `; largest survived in ≥90 %: ${r.largest_push_survived_90pct_n_s || 'none of those tried'} N·s.`);
  if (r.robustness) {
    lines.push('', `Falls within ${TERRAIN_SECONDS} s from ${STARTS.length} starts (heading 0, ±0.02, 0.05 rad × push 0, ±2 N·s forward at t = 0):`, '',
      '| ground | ' + SPEEDS.map((v) => `${v} m/s`).join(' | ') + ' |', '|---|' + SPEEDS.map(() => '---|').join(''));
    for (const ground of ['flat', 'slope', 'bumps']) {
      const cells = SPEEDS.map((v) => {
        const x = r.robustness.find((q) => q.ground === ground && q.speed === v);
        return x.fell ? `${x.fell}/${x.starts} fell (${Math.min(...x.fall_times_s).toFixed(1)}–${Math.max(...x.fall_times_s).toFixed(1)} s)` : `0/${x.starts} fell`;
      });
      lines.push(`| ${ground} | ${cells.join(' | ')} |`);
    }
  }
  lines.push('', `Controller: ${r.controller_us_per_step.native.toFixed(2)} µs per step native` +
    (r.controller_us_per_step.wasm_node ? `, ${r.controller_us_per_step.wasm_node.toFixed(2)} µs WASM in Node` : '') + '.', '');
}
const md = lines.join('\n');
const dir = path.join(root, 'bench/results');
mkdirSync(dir, { recursive: true });
const base = paramsFile ? `walking-${path.basename(paramsFile, '.json')}` : 'walking';
writeFileSync(path.join(dir, `${base}.json`), JSON.stringify(report, null, 2) + '\n');
writeFileSync(path.join(dir, `${base}.md`), md + '\n');
console.log(md);
