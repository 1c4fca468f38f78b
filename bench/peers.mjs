#!/usr/bin/env node
// The peer benchmark: gaitlab's physics beside Jolt Physics on the same reference scene
// (native/src/peers/reference_scene.h; bench/peers/jolt-scene.mjs builds it in Jolt), in one
// Node process, both as WebAssembly, engines alternating within every round so that the
// machine's load falls on both alike.
//
//   node bench/peers.mjs [--characters 20,100,400] [--threads 1,2] [--legs 4,2] [--steps 120]
//                        [--rounds 3] [--quick]
//   (also `npm run bench -- --peers`)
//
// Engines: gaitlab (Bullet 3.24 as gaitlab builds it: DiscreteWorld, its solver, one world per
// thread), Jolt's multithreaded build (SIMD; 1 thread = no worker threads) and Jolt's default
// single-threaded build (no SIMD; 1 thread only). Each point: a fresh scene, 30 steps to settle
// the first contacts, then `steps` fixed steps of 1/120 s timed; the figure is the median over
// the rounds of the mean step, with its range. Writes bench/results/peers.{json,md}.
import { execFileSync } from 'node:child_process';
import { existsSync, mkdirSync, readFileSync, writeFileSync } from 'node:fs';
import { createRequire } from 'node:module';
import os from 'node:os';
import path from 'node:path';
import { fileURLToPath } from 'node:url';

const here = path.dirname(fileURLToPath(import.meta.url));
const root = path.resolve(here, '..');
const preload = path.join(here, 'peers/node-pthreads.mjs');

// Jolt's multithreaded loader needs the preload in every thread (bench/peers/node-pthreads.mjs).
if (!process.execArgv.some((a) => a.includes('node-pthreads'))) {
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
for (const n of [...characters, ...threadCounts, steps, rounds]) {
  if (!Number.isInteger(n) || n < 1) {
    console.error(`gaitlab peers: ${n} is not a whole number >= 1`);
    process.exit(2);
  }
}

// ---- gaitlab, as WebAssembly -------------------------------------------------------------------
const js = path.join(root, 'build/wasm/gaitlab-node.cjs');
if (!existsSync(js)) {
  console.error('gaitlab peers: the WebAssembly build is missing (build/wasm); run `npm run build` first');
  process.exit(1);
}
const createGaitlab = createRequire(import.meta.url)(js);
const G = await createGaitlab({ wasmBinary: readFileSync(path.join(root, 'build/wasm/gaitlab-node.wasm')), noExitRuntime: true });
const KIND = { 2: 0, 4: 1 };  // legs -> GL_KIND_BIPED, GL_KIND_QUADRUPED
const morphology = (l) => JSON.parse(G.UTF8ToString(G._gl_morphology_json(KIND[l])));

class GaitlabScene {
  constructor(l, n, threads) {
    this.h = G._gl_peer_scene_create(KIND[l], n, threads);
    if (!this.h) throw new Error(G.UTF8ToString(G._gl_last_error()));
  }
  step(k) { G._gl_peer_scene_step(this.h, k); }
  rootHeight() { return G._gl_peer_scene_root_height(this.h); }
  destroy() { G._gl_peer_scene_destroy(this.h); }
}

// ---- Jolt Physics -------------------------------------------------------------------------------
const { JoltScene } = await import('./peers/jolt-scene.mjs');
const JoltMT = await (await import('jolt-physics/wasm-multithread')).default();
const JoltST = await (await import('jolt-physics/wasm')).default();

// JoltPhysics.js 1.1.0 gives its physics system a temporary allocator of fixed size (not a
// setting of its JoltSettings); a step that needs more aborts the module. Measured on the
// quadruped scene: 280 ragdolls (5040 bodies) step, 400 (7200 bodies) abort asking for 13.6 MB.
// Jolt is not run above the largest measured to pass.
const JOLT_MAX_BODIES = 5040;
const joltFits = (l, n) => n * morphology(l).segments.length <= JOLT_MAX_BODIES;
const JOLT_SKIP = `not run: more than ${JOLT_MAX_BODIES} bodies, beyond JoltPhysics.js 1.1.0's fixed temporary allocator`;

const ENGINES = [
  { name: 'gaitlab', label: 'gaitlab (Bullet 3.24)', make: (l, n, t) => new GaitlabScene(l, n, t), runs: () => true },
  { name: 'jolt-mt', label: 'Jolt, multithreaded build (SIMD)', make: (l, n, t) => new JoltScene(JoltMT, morphology(l), n, t), runs: joltFits },
  { name: 'jolt', label: 'Jolt, default build (no SIMD)', make: (l, n, t) => new JoltScene(JoltST, morphology(l), n, t),
    runs: (l, n, t) => t === 1 && joltFits(l, n) },
];

function timeOnce(engine, l, n, t) {
  const scene = engine.make(l, n, t);
  try {
    scene.step(SETTLE);
    const t0 = performance.now();
    scene.step(steps);
    const ms = (performance.now() - t0) / steps;
    return { ms, rootHeight: scene.rootHeight() };
  } finally {
    scene.destroy();
  }
}

const median = (xs) => {
  const s = [...xs].sort((a, b) => a - b);
  return s.length % 2 ? s[(s.length - 1) / 2] : (s[s.length / 2 - 1] + s[s.length / 2]) / 2;
};

const points = [];
const started = Date.now();
for (const l of legs) {
  for (const n of characters) {
    for (const t of threadCounts) {
      const runs = {};
      for (let r = 0; r < rounds; ++r) {
        // Alternate the engines' order from round to round.
        const order = ENGINES.filter((e) => e.runs(l, n, t));
        if (r % 2) order.reverse();
        for (const e of order) (runs[e.name] ??= []).push(timeOnce(e, l, n, t));
      }
      for (const e of ENGINES) {
        if (!runs[e.name] && (e.name !== 'jolt' || t === 1)) {
          points.push({ engine: e.name, legs: l, characters: n, threads: t, skipped: JOLT_SKIP });
          console.error(`${e.name.padEnd(8)} ${l === 4 ? 'quadrupeds' : 'bipeds    '} ${String(n).padStart(4)} × ${t} thread(s): ${JOLT_SKIP}`);
        }
      }
      for (const [name, rs] of Object.entries(runs)) {
        const ms = rs.map((x) => x.ms);
        const p = {
          engine: name, legs: l, characters: n, threads: t,
          ms_per_step: median(ms), ms_min: Math.min(...ms), ms_max: Math.max(...ms),
          root_height_m: median(rs.map((x) => x.rootHeight)),
        };
        points.push(p);
        console.error(`${name.padEnd(8)} ${l === 4 ? 'quadrupeds' : 'bipeds    '} ${String(n).padStart(4)} × ${t} thread(s): ` +
          `${p.ms_per_step.toFixed(2)} ms/step (${p.ms_min.toFixed(2)}–${p.ms_max.toFixed(2)}), root at ${p.root_height_m.toFixed(2)} m`);
      }
    }
  }
}

const doc = {
  benchmark: 'peers',
  scene: 'ragdolls holding their standing pose with motors, ground-only contact, 1/120 s steps of two 1/240 s sub-steps (native/src/peers/reference_scene.h)',
  machine: { cpus: os.cpus()[0]?.model ?? 'unknown', cores: os.availableParallelism(), loadavg: os.loadavg(), node: process.version },
  settings: { steps, rounds, settle_steps: SETTLE },
  engines: Object.fromEntries(ENGINES.map((e) => [e.name, e.label])),
  seconds: (Date.now() - started) / 1000,
  points,
};

const rows = [];
for (const l of legs) {
  for (const n of characters) {
    for (const t of threadCounts) {
      const at = (e) => points.find((p) => p.engine === e && p.legs === l && p.characters === n && p.threads === t && !p.skipped);
      const g = at('gaitlab'), mt = at('jolt-mt'), st = at('jolt');
      const cell = (p) => (p ? `${p.ms_per_step.toFixed(2)} (${p.ms_min.toFixed(2)}–${p.ms_max.toFixed(2)})` : '—');
      rows.push(`| ${l === 4 ? 'quadrupeds' : 'bipeds'} | ${n} | ${t} | ${cell(g)} | ${cell(mt)} | ${cell(st)} | ${g && mt ? (g.ms_per_step / mt.ms_per_step).toFixed(2) : '—'} |`);
    }
  }
}
const md = [
  '# The peer benchmark: gaitlab\'s physics beside Jolt Physics',
  '',
  `WebAssembly in Node ${process.version}, ${doc.machine.cpus}, ${doc.machine.cores} cores, load ${doc.machine.loadavg.map((x) => x.toFixed(1)).join(' / ')} at the end; ` +
    `ms per 1/120 s step, median of ${rounds} rounds (range), ${steps} steps each.`,
  '',
  '| characters | N | threads | gaitlab | Jolt multithreaded build (SIMD) | Jolt default build | gaitlab / Jolt (SIMD) |',
  '|---|---|---|---|---|---|---|',
  ...rows,
  '',
  ...(points.some((p) => p.skipped) ? [`—: Jolt ${JOLT_SKIP}.`, ''] : []),
].join('\n');
mkdirSync(out, { recursive: true });
writeFileSync(path.join(out, 'peers.json'), JSON.stringify(doc, null, 2) + '\n');
writeFileSync(path.join(out, 'peers.md'), md);
console.log(md);
G.PThread.terminateAllThreads();
JoltMT.PThread?.terminateAllThreads?.();
process.exit(0);
