#!/usr/bin/env node
// Which parallel physics for `full` mode? Compares, natively, side by side in one run:
//   shards     gaitlab's physics shards: independent Bullet worlds stepped by the pool
//              (`gaitlab bench --mode full`, the design kept);
//   bullet-mt  Bullet's btDiscreteDynamicsWorldMt with its tasks on the same pool
//              (native/probes/bullet_mt.cpp, Bullet compiled with BT_THREADSAFE).
// Both on one crowd, serial (1 thread) and 2 threads, alternating, REPEAT times; prints the
// machine, the medians and spreads, the state hashes, and Bullet's allocations per step.
//
//   node bench/probe-bullet-mt.mjs [LEGS=4] [CHARACTERS=50] [STEPS=240] [RUNS=3] [REPEAT=3]
import { spawnSync } from 'node:child_process';
import os from 'node:os';
import path from 'node:path';
import { fileURLToPath } from 'node:url';

const root = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '..');
const [legs = '4', characters = '50', steps = '240', runs = '3', repeat = '3'] = process.argv.slice(2);

const build = spawnSync('ninja', ['-C', 'build/native', 'gaitlab', 'gaitlab_bullet_mt'], { cwd: root, encoding: 'utf8' });
if (build.status !== 0) {
  console.error(build.stdout, build.stderr);
  process.exit(1);
}

function shards(threads) {
  const mode = threads === 1 ? 'serial' : 'full';
  const r = spawnSync(path.join(root, 'build/native/gaitlab'), ['bench', '--legs', legs, '--characters', characters,
    '--threads', String(threads), '--mode', mode, '--steps', steps, '--runs', runs, '--json'], { cwd: root, encoding: 'utf8' });
  if (r.status !== 0) throw new Error(r.stderr);
  const p = JSON.parse(r.stdout).points[0];
  return { step: p.step_ms.mean, physics: p.physics_ms.mean, hash: p.state_hash, allocs: null };
}
function bulletMt(threads) {
  const r = spawnSync(path.join(root, 'build/native/gaitlab_bullet_mt'), [legs, characters, String(threads), steps, runs], { cwd: root, encoding: 'utf8' });
  if (r.status !== 0) throw new Error(r.stderr);
  const p = JSON.parse(r.stdout);
  return { step: p.step_ms.mean, physics: p.physics_ms.mean, hash: p.state_hash, allocs: p.bullet_allocs_per_step };
}

const samples = { 'shards 1T': [], 'shards 2T': [], 'bullet-mt 1T': [], 'bullet-mt 2T': [] };
const hashes = {};
const allocs = {};
for (let i = 0; i < Number(repeat); i++) {
  for (const [name, f, t] of [['shards 1T', shards, 1], ['bullet-mt 1T', bulletMt, 1], ['shards 2T', shards, 2], ['bullet-mt 2T', bulletMt, 2]]) {
    const r = f(t);
    samples[name].push(r);
    hashes[name] = r.hash;
    if (r.allocs !== null) allocs[name] = r.allocs;
  }
}
const median = (xs) => [...xs].sort((a, b) => a - b)[Math.floor(xs.length / 2)];
const spread = (xs) => `${Math.min(...xs).toFixed(2)}–${Math.max(...xs).toFixed(2)}`;
console.log(`machine: ${os.cpus()[0]?.model}, ${os.cpus().length} logical cores, load ${os.loadavg()[0].toFixed(2)}; ` +
  `${legs === '2' ? 'bipeds' : 'quadrupeds'} x ${characters}, ${steps} steps x ${runs} runs, repeated ${repeat} times`);
console.log('| design | threads | whole step ms, median (min–max) | physics ms, median | speedup over its 1T | state hash | Bullet allocations per step |');
console.log('|---|---|---|---|---|---|---|');
for (const name of Object.keys(samples)) {
  const step = samples[name].map((s) => s.step);
  const base = median(samples[name.replace('2T', '1T')].map((s) => s.step));
  console.log(`| ${name.split(' ')[0]} | ${name.split(' ')[1]} | ${median(step).toFixed(2)} (${spread(step)}) | ${median(samples[name].map((s) => s.physics)).toFixed(2)} | ${(base / median(step)).toFixed(2)} | ${hashes[name]} | ${allocs[name]?.toFixed(2) ?? '0 (tests/native/sim/hot_path_test.cpp)'} |`);
}
