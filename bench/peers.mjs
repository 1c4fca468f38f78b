#!/usr/bin/env node
// The peer benchmark: gaitlab's physics beside Jolt Physics on the same reference scene
// (native/src/peers/reference_scene.h; bench/peers/jolt-scene.mjs builds it in Jolt), in one
// Node process (or, with --browser, in headless Chromium: the performance page's section), both as
// WebAssembly, engines alternating within every round so that the machine's load falls on both
// alike.
//
//   node bench/peers.mjs [--browser] [--characters 20,100,400] [--threads 1,2] [--legs 4,2]
//                        [--steps 120] [--rounds 3] [--quick] [--out DIR]
//                        [--jolt mNumVelocitySteps=5,mUseLargeIslandSplitter=false]
//   --jolt overrides fields of Jolt's PhysicsSettings (an experiment; Node only)
//   (also `npm run bench -- --peers [--browser]`)
//
// Engines: gaitlab (Bullet 3.24 as gaitlab builds it: DiscreteWorld, its solver, one world per
// thread), Jolt's multithreaded build (SIMD; 1 thread = no worker threads) and Jolt's default
// single-threaded build (no SIMD; 1 thread only). Each point: a fresh scene, 30 steps to settle
// the first contacts, then `steps` fixed steps of 1/120 s timed; the figure is the median over
// the rounds of the mean step, with its range (bench/peers/comparison.mjs, the code both runners
// share). Writes bench/results/peers.{json,md}, replacing only the rows of the runtime it ran.
import { execFileSync } from 'node:child_process';
import { existsSync, mkdirSync, readFileSync, writeFileSync } from 'node:fs';
import { createRequire } from 'node:module';
import os from 'node:os';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { describePoint, JOLT_SKIP, measurePoint, peerEngines, peerGrid, TABLE_HEAD, tableGrid, tableRows, warmUp } from './peers/comparison.mjs';

const here = path.dirname(fileURLToPath(import.meta.url));
const root = path.resolve(here, '..');
const preload = path.join(here, 'peers/node-pthreads.mjs');
const browser = process.argv.includes('--browser');

// Jolt's multithreaded loader needs the preload in every thread of Node (bench/peers/node-pthreads.mjs).
if (!browser && !process.execArgv.some((a) => a.includes('node-pthreads'))) {
  try {
    execFileSync(process.execPath, ['--import', preload, fileURLToPath(import.meta.url), ...process.argv.slice(2)],
      { stdio: 'inherit' });
    process.exit(0);
  } catch (e) {
    process.exit(e.status ?? 1);
  }
}

const args = process.argv.slice(2);
const opt = (name, fallback) => {
  const i = args.indexOf(`--${name}`);
  return i >= 0 ? args[i + 1] : fallback;
};
const list = (text) => text.split(',').map(Number);
const quick = args.includes('--quick');
const characters = list(opt('characters', quick ? '4' : '20,100,250,400'));
const threadCounts = list(opt('threads', quick ? '1,2' : '1,2'));
const legs = list(opt('legs', '4,2'));
const steps = Number(opt('steps', quick ? '4' : '120'));
const rounds = Number(opt('rounds', quick ? '1' : '3'));
const SETTLE = quick ? 2 : 30;
const out = opt('out', path.join(root, 'bench/results'));
// Jolt's PhysicsSettings overrides: "name=value,…", values numbers or true/false.
const joltSettings = Object.fromEntries((opt('jolt', '') || '').split(',').filter(Boolean).map((kv) => {
  const [k, v] = kv.split('=');
  return [k, v === 'true' ? true : v === 'false' ? false : Number(v)];
}));
if (browser && Object.keys(joltSettings).length) {
  console.error('gaitlab peers: --jolt is for Node runs only');
  process.exit(2);
}
for (const n of [...characters, ...threadCounts, steps, rounds]) {
  if (!Number.isInteger(n) || n < 1) {
    console.error(`gaitlab peers: ${n} is not a whole number >= 1`);
    process.exit(2);
  }
}

const grid = peerGrid({ legs, characters, threads: threadCounts });
const settings = { steps, rounds, settle: SETTLE, ...(Object.keys(joltSettings).length ? { jolt_settings: joltSettings } : {}) };
const started = Date.now();
let run;
if (browser) {
  // The performance page's section runs the same code (bench/peers/comparison.mjs) in its worker.
  const { runPeersInChromium } = await import('./peers/browser.mjs');
  run = await runPeersInChromium({ legs, characters, threads: threadCounts, ...settings },
    { onProgress: (text) => process.stderr.write(`  [chromium] ${text}\n`) });
  for (const p of run.points) console.error(describePoint(p));
} else {
  run = { machine: { cpus: os.cpus()[0]?.model ?? 'unknown', cores: os.availableParallelism(), node: process.version }, points: [] };
  const js = path.join(root, 'build/wasm/gaitlab-node.cjs');
  if (!existsSync(js)) {
    console.error('gaitlab peers: the WebAssembly build is missing (build/wasm); run `npm run build` first');
    process.exit(1);
  }
  const createGaitlab = createRequire(import.meta.url)(js);
  const G = await createGaitlab({ wasmBinary: readFileSync(path.join(root, 'build/wasm/gaitlab-node.wasm')), noExitRuntime: true });
  const JoltMT = await (await import('jolt-physics/wasm-multithread')).default();
  const JoltST = await (await import('jolt-physics/wasm')).default();
  const engines = peerEngines({ gaitlab: G, joltMT: JoltMT, joltST: JoltST }, { joltSettings });
  warmUp(engines, legs, threadCounts);
  for (const point of grid) {
    for (const p of measurePoint(engines, point, settings)) {
      run.points.push(p);
      console.error(describePoint(p));
    }
  }
  run.machine.loadavg = os.loadavg();
  G.PThread.terminateAllThreads();
  JoltMT.PThread?.terminateAllThreads?.();
}

// This run's rows replace only its own runtime's in the results file: the Node and the Chromium
// runs are made by separate commands and kept side by side.
const runtime = browser ? 'wasm-browser' : 'wasm-node';
const file = path.join(out, 'peers.json');
const before = existsSync(file) ? JSON.parse(readFileSync(file, 'utf8')) : null;
const keptRuns = Object.fromEntries(Object.entries(before?.runs ?? {}).filter(([r]) => r !== runtime));
const keptPoints = (before?.points ?? []).filter((p) => (p.runtime ?? 'wasm-node') !== runtime && keptRuns[p.runtime ?? 'wasm-node']);
const doc = {
  benchmark: 'peers',
  scene: 'ragdolls holding their standing pose with motors, ground-only contact, 1/120 s steps of two 1/240 s sub-steps (native/src/peers/reference_scene.h)',
  engines: { gaitlab: 'gaitlab (Bullet 3.24)', 'jolt-mt': 'Jolt, multithreaded build (SIMD)', jolt: 'Jolt, default build (no SIMD)' },
  runs: {
    ...keptRuns,
    [runtime]: { date: new Date().toISOString().replace(/\.\d+Z$/, 'Z'), machine: run.machine, settings, seconds: (Date.now() - started) / 1000, grid: { legs, characters, threads: threadCounts } },
  },
  points: [...keptPoints, ...run.points.map((p) => ({ runtime, ...p }))],
};

const RUNTIME_TITLE = { 'wasm-node': 'WebAssembly in Node', 'wasm-browser': 'WebAssembly in Chromium (the performance page\'s section, headless)' };
const md = ['# The peer benchmark: gaitlab\'s physics beside Jolt Physics', ''];
for (const r of ['wasm-node', 'wasm-browser']) {
  const info = doc.runs[r];
  if (!info) continue;
  const points = doc.points.filter((p) => (p.runtime ?? 'wasm-node') === r);
  const m = info.machine;
  md.push(`## ${RUNTIME_TITLE[r]}`, '',
    `${r === 'wasm-node' ? `Node ${m.node}` : m.browser}, ${m.cpus ?? 'this machine'}, ${m.cores} cores${m.loadavg ? `, load ${m.loadavg.map((x) => x.toFixed(1)).join(' / ')} at the end` : ''}, ${info.date}; ` +
      `ms per 1/120 s step, median of ${info.settings.rounds} rounds (range), ${info.settings.steps} steps each.`,
    '',
    `| ${TABLE_HEAD.join(' | ')} |`,
    `|${TABLE_HEAD.map(() => '---').join('|')}|`,
    ...tableRows(points, tableGrid(info.grid)).map((row) => `| ${row.join(' | ')} |`),
    '',
    ...[...new Set(points.filter((p) => p.skipped).map((p) => `—: ${p.engine === 'gaitlab' ? 'gaitlab' : 'Jolt'} ${p.skipped}${p.skipped === JOLT_SKIP ? '' : ` (${p.legs === 4 ? 'quadrupeds' : 'bipeds'} ${p.characters} × ${p.threads})`}.`))], '');
}
mkdirSync(out, { recursive: true });
writeFileSync(file, JSON.stringify(doc, null, 2) + '\n');
writeFileSync(path.join(out, 'peers.md'), md.join('\n'));
console.log(md.join('\n'));
process.exit(0);
