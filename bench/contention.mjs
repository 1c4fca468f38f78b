#!/usr/bin/env node
// How do two builds of `gaitlab bench` share 2 cores with another process? Runs each build's
// full mode on 1 and 2 threads (100 characters, 240 steps x 3 runs), the builds alternately,
// ROUNDS times, first on the machine as it is and then with a competing process that is busy for
// BUSY ms and idle for IDLE ms in turn (a stand-in for the other work of a shared machine or a
// browser's own threads). Prints, per build and condition, the ranges over rounds of the 2-thread
// step times on 1 and 2 threads, the 2-thread speedup and the p99/median of the 2-thread step.
//
//   node bench/contention.mjs OLD_GAITLAB [NEW_GAITLAB=build/native/gaitlab] [LEGS=4] [ROUNDS=3]
//                             [BUSY=3] [IDLE=5] [--quiet-only]
//
// --quiet-only skips the competing process (to compare two builds' cost alone).
//
// OLD_GAITLAB is a binary built from another commit, e.g. (then /tmp/old/build/native/gaitlab)
//   git worktree add /tmp/old HEAD~1 && cd /tmp/old && bash scripts/setup.sh &&
//   cmake -S native -B build/native -G Ninja -DCMAKE_BUILD_TYPE=Release && ninja -C build/native gaitlab
import { spawn, spawnSync } from 'node:child_process';
import os from 'node:os';
import path from 'node:path';
import { fileURLToPath } from 'node:url';

const root = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '..');
const args = process.argv.slice(2);
if (args.length < 1) {
  console.error('usage: node bench/contention.mjs OLD_GAITLAB [NEW_GAITLAB] [LEGS=4] [ROUNDS=3] [BUSY=3] [IDLE=5]');
  process.exit(2);
}
const quietOnly = args.includes('--quiet-only');
const [oldBin, newBin = path.join(root, 'build/native/gaitlab'), legs = '4', rounds = '3', busy = '3', idle = '5'] = args.filter((a) => a !== '--quiet-only');
const builds = { old: path.resolve(oldBin), new: path.resolve(newBin) };

function bench(bin) {
  const r = spawnSync(bin, ['bench', '--legs', legs, '--characters', '100', '--threads', '1,2', '--mode', 'full',
    '--steps', '240', '--runs', '3', '--json'], { encoding: 'utf8' });
  if (r.status !== 0) throw new Error(`${bin}: ${r.stderr}`);
  const points = JSON.parse(r.stdout).points;
  const at = (t) => points.find((p) => p.threads === t);
  const [one, two] = [at(1), at(2)];
  return {
    speedup: one.step_ms.mean / two.step_ms.mean,
    step1: one.step_ms.mean,
    step2: two.step_ms.mean,
    tail2: two.step_ms.p99 / two.step_ms.p50,
    hash: two.state_hash,
  };
}

// The competing process: a busy loop for `busy` ms, then a sleep of `idle` ms, until killed.
function startLoad() {
  const code = `const s = new Int32Array(new SharedArrayBuffer(4));
    for (;;) { const t = performance.now() + ${Number(busy)}; while (performance.now() < t); Atomics.wait(s, 0, 0, ${Number(idle)}); }`;
  return spawn(process.execPath, ['-e', code], { stdio: 'ignore' });
}

const range = (xs, digits) => {
  const s = [...xs].sort((a, b) => a - b);
  return `${s[Math.floor(s.length / 2)].toFixed(digits)} (${s[0].toFixed(digits)}–${s.at(-1).toFixed(digits)})`;
};

console.log(`# ${os.cpus()[0].model}, ${os.cpus().length} logical cores, load ${os.loadavg()[0].toFixed(2)}, ${new Date().toISOString()}`);
console.log(`# ${legs === '4' ? 'quadrupeds' : legs === '2' ? 'bipeds' : legs}, 100 characters, full mode, 240 steps x 3 runs, ${rounds} rounds; median (min–max) over rounds`);
console.log('| condition | build | 1-thread step ms | 2-thread step ms | 2-thread speedup | p99/median, 2 threads | state hash |');
console.log('|---|---|---|---|---|---|---|');
for (const condition of ['machine as it is', ...(quietOnly ? [] : [`competing process (busy ${busy} ms, idle ${idle} ms)`])]) {
  const load = condition.startsWith('competing') ? startLoad() : null;
  const samples = { old: [], new: [] };
  for (let r = 0; r < Number(rounds); ++r) {
    for (const b of ['old', 'new']) {
      samples[b].push(bench(builds[b]));
      process.stderr.write('.');
    }
  }
  load?.kill();
  for (const b of ['old', 'new']) {
    const s = samples[b];
    console.log(`| ${condition} | ${b} | ${range(s.map((x) => x.step1), 2)} | ${range(s.map((x) => x.step2), 2)} | ${range(s.map((x) => x.speedup), 2)} | ${range(s.map((x) => x.tail2), 2)} | ${[...new Set(s.map((x) => x.hash))].join(', ')} |`);
  }
}
console.log(`# load at the end ${os.loadavg()[0].toFixed(2)}`);
