#!/usr/bin/env node
// Physics settings that change the dynamics, measured against what they cost and whether the biped
// still walks (docs/parallel.md, "Where the physics time goes"). None of them is a default: they
// are read from environment variables by an experimental build made with
// bench/physics-settings.patch, which only this script uses:
//
//   cp -r native tests /tmp/x/ && mkdir -p /tmp/x/public && cp -r public/presets /tmp/x/public/
//   (cd /tmp/x && patch -p1 < $OLDPWD/bench/physics-settings.patch &&
//    cmake -S native -B build -G Ninja -DCMAKE_BUILD_TYPE=Release -DBULLET_ROOT=$OLDPWD/third_party/bullet3 &&
//    ninja -C build gaitlab gaitlab_step_times)
//   node bench/physics-settings.mjs /tmp/x/build [ROUNDS] [STEPS] [setting name filter...]
//
// Per setting: the CPU time of a fixed step per character (100 bipeds, 100 quadrupeds, serial,
// `gaitlab_step_times`, the median over the steps after the first, then the median over ROUNDS
// rounds in alternating order, with min-max), and the biped's 60 s walks at 0.5 and 1.0 m/s
// (`gaitlab walk`): the project's walking criterion is no fall and a mean speed within 15 % of the
// goal. The quadruped's fall time in a 10 s walk at 0.8 m/s is listed beside it.
// Prints a Markdown table.
import { spawnSync } from 'node:child_process';
import os from 'node:os';
import path from 'node:path';

const [buildDir, roundsArg, stepsArg, ...only] = process.argv.slice(2);
if (!buildDir) {
  console.error('usage: node bench/physics-settings.mjs BUILD_DIR [ROUNDS] [STEPS] [filter...]');
  process.exit(2);
}
const rounds = Number(roundsArg ?? 3);
const steps = String(stepsArg ?? 240);

// name, environment of the experimental build (bench/physics-settings.patch)
let settings = [
  ['default (10 iterations, 2 substeps)', {}],
  ['iterations 20', { GL_ITER: '20' }],
  ['iterations 8', { GL_ITER: '8' }],
  ['iterations 5', { GL_ITER: '5' }],
  ['1 substep', { GL_SUBSTEPS: '1' }],
  ['split impulse off', { GL_SPLIT: '0' }],
  ['residual threshold 1e-6', { GL_RESID: '1e-6' }],
  ['residual threshold 1e-4', { GL_RESID: '1e-4' }],
  ['contact processing threshold 0', { GL_CPT: '0' }],
  // The same dynamics bit for bit, at Bullet's own cost (physics/solver.h, physics/joint_rows.h).
  ["Bullet's own sweep", { GL_FASTSOLVER: '0' }],
  ["Bullet's own joint row setup", { GL_FASTROWS: '0' }],
];
if (only.length) settings = settings.filter(([name], i) => i === 0 || only.some((o) => name.includes(o)));

const run = (exe, args, env) => {
  const r = spawnSync(path.join(buildDir, exe), args, { env: { ...process.env, ...env }, encoding: 'utf8', maxBuffer: 1 << 26 });
  if (r.status !== 0) throw new Error(`${exe} ${args.join(' ')}: ${r.stderr}`);
  return JSON.parse(r.stdout);
};
const median = (x) => { const s = [...x].sort((a, b) => a - b); return s[Math.floor((s.length - 1) / 2)]; };

const walks = new Map();
for (const [name, env] of settings) {
  const w = {};
  for (const speed of ['0.5', '1.0']) w[speed] = run('gaitlab', ['walk', '--character', 'biped', '--speed', speed, '--seconds', '60', '--json'], env);
  w.quadruped = run('gaitlab', ['walk', '--character', 'quadruped', '--speed', '0.8', '--seconds', '10', '--json'], env);
  walks.set(name, w);
}
const cost = new Map(settings.map(([name]) => [name, { 2: [], 4: [] }]));
for (let r = 0; r < rounds; ++r) {
  for (const [name, env] of r % 2 === 0 ? settings : [...settings].reverse()) {
    for (const legs of ['2', '4']) {
      const d = run('gaitlab_step_times', [legs, '100', steps, 'serial', '1', '1'], env);
      cost.get(name)[legs].push((d.cpu_ms_without_first_step.p50 * 1e3) / 100);
    }
  }
  console.error(`round ${r + 1}/${rounds}, load average ${os.loadavg()[0].toFixed(1)}`);
}

const base = cost.get(settings[0][0]);
console.log(`${os.cpus()[0]?.model ?? '?'}, ${os.cpus().length} logical cores; ${rounds} rounds of ${steps} steps; load average now ${os.loadavg()[0].toFixed(1)}\n`);
console.log('| setting | biped µs/character/step | × default | quadruped µs/character/step | × default | biped 0.5 m/s, 60 s | biped 1.0 m/s, 60 s | biped walks | quadruped falls at |');
console.log('|---|---|---|---|---|---|---|---|---|');
for (const [name] of settings) {
  const c = cost.get(name);
  const cells = [name];
  for (const legs of ['2', '4']) {
    cells.push(`${median(c[legs]).toFixed(1)} (${Math.min(...c[legs]).toFixed(1)}–${Math.max(...c[legs]).toFixed(1)})`);
    cells.push(`${(median(base[legs]) / median(c[legs])).toFixed(2)}`);
  }
  let ok = true;
  for (const speed of ['0.5', '1.0']) {
    const d = walks.get(name)[speed];
    const err = (d.mean_speed_m_s - Number(speed)) / Number(speed);
    ok = ok && !d.fell && Math.abs(err) <= 0.15;
    cells.push(`${d.fell ? `fell at ${d.fall_time_s.toFixed(1)} s` : 'no fall'}, ${d.mean_speed_m_s.toFixed(3)} m/s (${err >= 0 ? '+' : ''}${(err * 100).toFixed(0)} %)`);
  }
  cells.push(ok ? 'yes' : '**no**');
  const q = walks.get(name).quadruped;
  cells.push(q.fell ? `${q.fall_time_s.toFixed(2)} s` : 'no fall in 10 s');
  console.log(`| ${cells.join(' | ')} |`);
}
