#!/usr/bin/env node
// `npm run bench`: the thesis's experiment (Chapter 4) and our extensions, natively, as WASM in
// Node and as WASM in headless Chromium, one after the other on this machine; writes
//   bench/results/<machine>-<date>.json   every document (bench/schema.json), one per runtime
//   bench/results/<machine>-<date>-*.svg  the charts (thesis Figures 5.1-5.5, 6.1, 6.2 and ours)
//   bench/results/<machine>-<date>.md     the tables and the goals, for the README
//
//   node bench/run.mjs            reduced grid: a few minutes on 2 cores
//   node bench/run.mjs --full     the thesis's grid: 1..100 characters, 1-4 threads, 800 steps, 20 runs
//                                 (about 14 hours per runtime on 2 cores)
//   node bench/run.mjs --only native,node,chromium   a subset of the runtimes
//   node bench/run.mjs --out DIR  somewhere else than bench/results
//   node bench/run.mjs --tiny     a few seconds per runtime: checks the pipeline (tests/wasm)
//   node bench/run.mjs --peers    the peer benchmark instead (bench/peers.mjs: gaitlab's physics
//                                 beside Jolt Physics on one reference scene); other arguments
//                                 are passed on to it
//   node bench/run.mjs --readme   also replace the README's measured block (between the
//                                 <!-- bench:begin --> and <!-- bench:end --> markers) with this run's
//
// Real-time capacity: the largest crowd of each full-mode curve that still runs in real time is
// searched for by measurement beyond the grid (capacity probes: nextCapacityProbe in
// bench/lib/analysis.mjs, up to MAX_PROBES crowd sizes per curve, until the largest crowd within
// budget and the smallest over it are within 5 % of each other), not extrapolated.
import { spawn, spawnSync } from 'node:child_process';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import {
  STEP_BUDGET_MS, capacity, capacityBracket, curves, find, legsName, nextCapacityProbe, ratioTable, seriesKey, speedup, validate,
} from './lib/analysis.mjs';
import { barChart, lineChart } from './lib/svg.mjs';

const root = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '..');
const args = process.argv.slice(2);
if (args.includes('--peers')) {
  const peers = path.join(path.dirname(fileURLToPath(import.meta.url)), 'peers.mjs');
  const run = spawnSync(process.execPath, [peers, ...args.filter((a) => a !== '--peers')], { stdio: 'inherit' });
  process.exit(run.status ?? 1);
}
const flag = (name) => args.includes(name);
const value = (name, fallback) => (args.includes(name) ? args[args.indexOf(name) + 1] : fallback);

// The grids. The reduced one keeps the thesis's shape (both leg counts, serial against parallel,
// 1 to 100 characters) with fewer crowd sizes, steps and runs; the two-thread points are the ones
// this 2-core machine can answer.
const FULL = {
  legs: [2, 4], characters: Array.from({ length: 100 }, (_, i) => i + 1), threads: [1, 2, 3, 4],
  modes: ['serial', 'controller', 'full'], steps: 800, runs: 20, frames: false,
};
const REDUCED = {
  legs: [2, 4], characters: [1, 20, 50, 100], threads: [2],
  modes: ['serial', 'controller', 'full'], steps: 120, runs: 3, frames: false,
};
const TINY = {
  legs: [2, 4], characters: [1, 3], threads: [2], modes: ['serial', 'controller', 'full'], steps: 10, runs: 2, frames: false,
};
// Per-frame statistics (thesis Figures 5.1, 5.2: 20 characters, serial against 2 threads).
const FRAMES = { legs: [2, 4], characters: [20], threads: [2], modes: ['serial', 'controller', 'full'], steps: 800, runs: 3, frames: true };
if (!flag('--full')) FRAMES.steps = 240;
if (flag('--tiny')) Object.assign(FRAMES, { characters: [3], steps: 10, runs: 2 });

const grid = flag('--full') ? FULL : flag('--tiny') ? TINY : REDUCED;
// The largest crowd a capacity probe builds, within the WebAssembly heap (fixed at 256 MB) and
// the render buffer (2340 bipeds, 910 quadrupeds): 1200 bipeds (129 MB of heap, measured) or 600
// quadrupeds (about 0.26 MB each, the memory table). The tiny grid only checks that the probes
// run.
const probeCap = (legs) => (flag('--tiny') ? 5 : legs === 2 ? 1200 : 600);
const MAX_PROBES = 8;
const runtimes = value('--only', 'native,node,chromium').split(',');
const outDir = path.resolve(value('--out', path.join(root, 'bench', 'results')));

function cliArgs(g) {
  return ['bench', '--legs', g.legs.join(','), '--characters', g.characters.join(','), '--threads',
    g.threads.join(','), '--mode', g.modes.join(','), '--steps', String(g.steps), '--runs', String(g.runs),
    ...(g.frames ? ['--frames'] : []), '--json'];
}

/** Runs a CLI (native or Node WASM), passing its progress lines through; resolves to its document. */
function runCli(command, argv, label) {
  return new Promise((resolve, reject) => {
    const child = spawn(command, argv, { cwd: root, stdio: ['ignore', 'pipe', 'pipe'] });
    let out = '';
    let err = '';
    child.stdout.on('data', (d) => (out += d));
    child.stderr.on('data', (d) => {
      err += d;
      for (const line of String(d).split('\n').filter(Boolean)) process.stderr.write(`  [${label}] ${line}\n`);
    });
    child.on('error', reject);
    child.on('close', (code) => {
      if (code !== 0) return reject(new Error(`${label} exited with ${code}: ${err.trim().split('\n').pop()}`));
      try {
        resolve(JSON.parse(out));
      } catch (e) {
        reject(new Error(`${label} printed no JSON document: ${e.message}`));
      }
    });
  });
}

async function measure(runtime, g) {
  if (runtime === 'native') return runCli(path.join(root, 'build/native/gaitlab'), cliArgs(g), 'native');
  if (runtime === 'node') return runCli(process.execPath, [path.join(root, 'bench/wasm.mjs'), ...cliArgs(g)], 'wasm-node');
  if (runtime === 'chromium') {
    const { runInChromium } = await import('./browser.mjs');
    let last = '';
    return runInChromium(g, { onProgress: (t) => t !== last && process.stderr.write(`  [wasm-browser] ${(last = t)}\n`) });
  }
  throw new Error(`unknown runtime '${runtime}' (native, node, chromium)`);
}

// ---- run ------------------------------------------------------------------------------------------
const started = Date.now();
const docs = [];
const probeDocs = [];
for (const runtime of runtimes) {
  let gridDoc = null;
  for (const g of [grid, FRAMES]) {
    process.stderr.write(`bench: ${runtime}, ${g.frames ? 'per-frame' : 'grid'}: legs ${g.legs}, characters ${g.characters.length > 6 ? `${g.characters[0]}..${g.characters.at(-1)}` : g.characters}, threads ${g.threads}, ${g.modes}, ${g.steps} steps x ${g.runs} runs\n`);
    const doc = await measure(runtime, g);
    const problems = validate(doc);
    if (problems.length) throw new Error(`${runtime}: the document does not match bench/schema.json: ${problems.join('; ')}`);
    docs.push(doc);
    if (g === grid) gridDoc = doc;
  }
  // Capacity probes (see the top): per leg count and thread count, one crowd size at a time.
  for (const legs of grid.legs) {
    for (const threads of grid.threads) {
      const points = [...(curves(gridDoc, legs).get(`full ${threads}T`) ?? [])];
      for (let probe = 1, n; probe <= MAX_PROBES && (n = nextCapacityProbe(points, { cap: probeCap(legs) })) !== null; ++probe) {
        const g = { legs: [legs], characters: [n], threads: [threads], modes: ['full'], steps: grid.steps, runs: grid.runs, frames: false };
        process.stderr.write(`bench: ${runtime}, capacity probe ${probe}/${MAX_PROBES} at most: ${n} ${legsName(legs)}s, full ${threads}T\n`);
        const doc = await measure(runtime, g);
        const problems = validate(doc);
        if (problems.length) throw new Error(`${runtime}: the document does not match bench/schema.json: ${problems.join('; ')}`);
        probeDocs.push(doc);
        points.push(...doc.points);
      }
    }
  }
}

// WASM/native in turns (the ratio goal). The grids above measure each runtime a minute or more
// after the other, on a shared machine whose load changes meanwhile, so their ratio compares two
// different machines. Here native code and WebAssembly in Chromium measure the same points (the
// largest crowd, serial and full) one after the other, RATIO_ROUNDS times, and the goal takes the
// median of the rounds' ratios.
const most = Math.max(...grid.characters);
const RATIO_ROUNDS = flag('--tiny') ? 1 : 3;
const pairedDocs = [];
if (runtimes.includes('native') && runtimes.includes('chromium')) {
  const g = { legs: grid.legs, characters: [most], threads: grid.threads, modes: ['serial', 'full'], steps: grid.steps, runs: grid.runs, frames: false };
  for (let round = 1; round <= RATIO_ROUNDS; ++round) {
    for (const runtime of ['native', 'chromium']) {
      process.stderr.write(`bench: WASM/native in turns, round ${round}/${RATIO_ROUNDS}: ${runtime}, ${most} characters\n`);
      const doc = await measure(runtime, g);
      const problems = validate(doc);
      if (problems.length) throw new Error(`${runtime}: the document does not match bench/schema.json: ${problems.join('; ')}`);
      pairedDocs.push(doc);
    }
  }
}
const minutes = (Date.now() - started) / 60000;

// ---- results file -----------------------------------------------------------------------------------
const native0 = docs.find((d) => d.machine.runtime === 'native') ?? docs[0];
const cpu = native0.machine.cpu ?? os.cpus()[0]?.model ?? 'unknown-cpu';
const machineSlug = `${cpu}-${native0.machine.cores || os.cpus().length}c`.toLowerCase().replace(/[^a-z0-9]+/g, '-').replace(/^-|-$/g, '');
const date = new Date().toISOString().slice(0, 10);
const base = `${machineSlug}-${date}`;
fs.mkdirSync(outDir, { recursive: true });
const results = { schema: 'gaitlab-bench-results/1', date: new Date().toISOString(), runs: [...docs, ...probeDocs, ...pairedDocs] };
const problems = validate(results, 'results');
if (problems.length) throw new Error(`results file invalid: ${problems.join('; ')}`);
fs.writeFileSync(path.join(outDir, `${base}.json`), `${JSON.stringify(results)}\n`);

// ---- figures ---------------------------------------------------------------------------------------
const gridDocs = docs.filter((d) => !d.inputs.frames);
const frameDocs = docs.filter((d) => d.inputs.frames);
const byRuntime = (list, runtime) => list.find((d) => d.machine.runtime === runtime);
const native = byRuntime(gridDocs, 'native');
const nodeWasm = byRuntime(gridDocs, 'wasm-node');
const browser = byRuntime(gridDocs, 'wasm-browser');
const RUNTIME_NAME = { native: 'native', 'wasm-node': 'WASM (Node)', 'wasm-browser': 'WASM (Chromium)' };
const machineLine = (d) => `${d.machine.cpu ?? 'CPU not reported'}, ${d.machine.cores} logical cores`;
const svgs = [];
function writeSvg(name, svg, caption) {
  fs.writeFileSync(path.join(outDir, `${base}-${name}.svg`), svg);
  svgs.push({ file: `${base}-${name}.svg`, caption });
}
const pts = (list, field) => list.map((p) => ({ x: p.characters, y: p[field].mean, sd: p[field].sd }));

/** Thesis Figures 5.3 / 5.4 (and ours for the whole step): time against crowd size with ±sd bands. */
function perCharacterFigure(doc, legs, field, name, title) {
  if (!doc) return;
  const series = [...curves(doc, legs)].filter(([k]) => field !== 'controller_ms' || !k.startsWith('full'))
    .map(([k, list]) => ({ name: k, points: pts(list, field) }));
  if (!series.length) return;
  writeSvg(name, lineChart({
    title, subtitle: `${RUNTIME_NAME[doc.machine.runtime]}; ${machineLine(native0)}; mean ± sd over ${doc.inputs.runs} runs x ${doc.inputs.steps} steps`,
    xLabel: 'characters', yLabel: `${field.replace('_ms', '')} time per step (ms)`, series,
    hline: field === 'step_ms' ? { y: STEP_BUDGET_MS, label: '120 Hz budget' } : undefined,
  }), title);
}
perCharacterFigure(native, 2, 'controller_ms', 'fig5_3-biped-controller', 'Fig. 5.3: biped controller time (native)');
perCharacterFigure(native, 4, 'controller_ms', 'fig5_4-quadruped-controller', 'Fig. 5.4: quadruped controller time (native)');
perCharacterFigure(browser, 2, 'controller_ms', 'fig5_3-biped-controller-chromium', 'Fig. 5.3 as WASM in Chromium: biped controller time');
perCharacterFigure(browser, 4, 'controller_ms', 'fig5_4-quadruped-controller-chromium', 'Fig. 5.4 as WASM in Chromium: quadruped controller time');
for (const legs of [2, 4]) {
  for (const d of [native, browser]) {
    if (!d) continue;
    const where = d.machine.runtime === 'native' ? 'native' : 'chromium';
    perCharacterFigure(d, legs, 'step_ms', `step-${legsName(legs)}-${where}`, `Whole step, ${legsName(legs)}s (${RUNTIME_NAME[d.machine.runtime]})`);
  }
}

// Figure 5.5: every controller curve, both leg counts, no bands.
if (native) {
  const series = [2, 4].flatMap((legs) => [...curves(native, legs)].filter(([k]) => !k.startsWith('full'))
    .map(([k, list]) => ({ name: `${legsName(legs)} ${k}`, dash: legs === 2 ? '5 3' : undefined, points: pts(list, 'controller_ms').map(({ x, y }) => ({ x, y })) })));
  writeSvg('fig5_5-all-controller', lineChart({ title: 'Fig. 5.5: all controller results (native)', subtitle: machineLine(native), xLabel: 'characters', yLabel: 'controller time per step (ms)', series }), 'Fig. 5.5: all controller results');

  // Figures 6.1 / 6.2: slowdown normalised to the one-character time.
  const normalised = (legs, filter) => [...curves(native, legs)].filter(([k]) => filter(k)).map(([k, list]) => ({
    name: `${legsName(legs)} ${k}`, dash: legs === 2 ? '5 3' : undefined,
    points: list.map((p) => ({ x: p.characters, y: p.controller_ms.mean / list[0].controller_ms.mean })),
  }));
  writeSvg('fig6_1-serial-slowdown', lineChart({ title: 'Fig. 6.1: serial slowdown rate (native)', subtitle: 'controller time / 1-character controller time; 1:100 would be linear', xLabel: 'characters', yLabel: 'ratio to 1 character', series: [...normalised(2, (k) => k === 'serial'), ...normalised(4, (k) => k === 'serial')] }), 'Fig. 6.1: serial slowdown rate');
  writeSvg('fig6_2-parallel-slowdown', lineChart({ title: 'Fig. 6.2: parallel slowdown rate (native)', subtitle: 'controller mode; controller time / 1-character controller time', xLabel: 'characters', yLabel: 'ratio to 1 character', series: [...normalised(2, (k) => k.startsWith('controller')), ...normalised(4, (k) => k.startsWith('controller'))] }), 'Fig. 6.2: parallel slowdown rate');

  // Physics against controller share of the whole step (serial).
  const share = [2, 4].flatMap((legs) => {
    const list = curves(native, legs).get('serial') ?? [];
    return [
      { name: `${legsName(legs)} physics`, dash: legs === 2 ? '5 3' : undefined, color: legs === 2 ? '#1f77b4' : '#d62728', points: list.map((p) => ({ x: p.characters, y: (100 * p.physics_ms.mean) / p.step_ms.mean })) },
      { name: `${legsName(legs)} controller`, dash: legs === 2 ? '5 3' : undefined, color: legs === 2 ? '#2ca02c' : '#ff7f0e', points: list.map((p) => ({ x: p.characters, y: (100 * p.controller_ms.mean) / p.step_ms.mean })) },
    ];
  });
  writeSvg('share-physics-controller', lineChart({ title: 'Share of the step: physics against controller (native, serial)', subtitle: machineLine(native), xLabel: 'characters', yLabel: '% of the whole step', series: share }), 'Physics vs controller share of the step');
}

// Per-frame (thesis Figures 5.1, 5.2).
const frameNative = byRuntime(frameDocs, 'native');
if (frameNative) {
  for (const legs of [2, 4]) {
    for (const [field, label] of [['controller_ms', 'controller'], ['step_ms', 'whole step']]) {
      const series = frameNative.points.filter((p) => p.legs === legs && p.frames && (field === 'step_ms' || p.mode !== 'full')).map((p) => ({
        name: seriesKey(p), points: p.frames[field].mean.map((y, i) => ({ x: i, y, sd: p.frames[field].sd[i] })),
      }));
      const fig = legs === 2 ? '5_1' : '5_2';
      writeSvg(`fig${fig}-${legsName(legs)}-frames-${field.replace('_ms', '')}`, lineChart({
        title: `Fig. ${fig.replace('_', '.')}: ${frameNative.points[0].characters} ${legsName(legs)}s per frame, ${label} (native)`,
        subtitle: `mean ± sd over ${frameNative.inputs.runs} runs`, xLabel: 'frame (step)', yLabel: `${label} time (ms)`, series,
      }), `Fig. ${fig.replace('_', '.')}: per frame, ${label}`);
    }
  }
}

// WASM / native ratio of the whole step.
if (native && (nodeWasm || browser)) {
  const series = [];
  for (const d of [nodeWasm, browser].filter(Boolean)) {
    for (const legs of [2, 4]) {
      for (const [k, list] of curves(d, legs)) {
        if (k.startsWith('controller')) continue;
        series.push({
          name: `${RUNTIME_NAME[d.machine.runtime]} ${legsName(legs)} ${k}`, dash: d === nodeWasm ? '5 3' : undefined,
          points: list.map((p) => {
            const n = find(native, p);
            return n ? { x: p.characters, y: p.step_ms.mean / n.step_ms.mean } : null;
          }).filter(Boolean),
        });
      }
    }
  }
  writeSvg('wasm-native-ratio', lineChart({ title: 'WASM / native, whole step', subtitle: 'time ratio, same machine, same run of npm run bench', xLabel: 'characters', yLabel: 'WASM time / native time', series, hline: { y: 1.2, label: 'goal 1.2' } }), 'WASM/native ratio');
}

// Real-time capacity per thread count and mode, from the grid's points and the probes'.
const capacityOf = (d, legs, key) => {
  const list = d && curves(d, legs).get(key);
  if (!list) return null;
  const probes = probeDocs.filter((p) => p.machine.runtime === d.machine.runtime).flatMap((p) => curves(p, legs).get(key) ?? []);
  const all = [...list, ...probes];
  return { ...capacity(all), ...capacityBracket(all), trend: capacity(list), probes: probes.sort((a, b) => a.characters - b.characters) };
};
const crowdAt = (p) => (p ? `${p.characters} (${p.step_ms.mean.toFixed(2)} ms)` : '–');
{
  const keys = [...new Set(gridDocs.flatMap((d) => [2, 4].flatMap((l) => [...curves(d, l).keys()])))];
  const bars = [];
  for (const d of [native, nodeWasm, browser].filter(Boolean)) {
    for (const legs of [2, 4]) {
      bars.push({ name: `${RUNTIME_NAME[d.machine.runtime]} ${legsName(legs)}`, values: keys.map((k) => {
        const c = capacityOf(d, legs, k);
        return !c ? null : c.probes.length ? c.within?.characters ?? 0 : c.fitted;
      }) });
    }
  }
  writeSvg('realtime-capacity', barChart({ title: 'Real-time capacity at 120 Hz (characters)', subtitle: 'largest crowd whose mean whole step fits 8.33 ms: measured (full mode, searched beyond the grid), else the linear trend of the grid', xLabel: 'mode and threads', yLabel: 'characters at 1x real time', groups: keys, bars }), 'Real-time capacity at 120 Hz');
}

// ---- tables and goals (markdown) ---------------------------------------------------------------------
const f = (v, digits = 3) => (v === null || v === undefined || Number.isNaN(v) ? '–' : v.toFixed(digits));
const md = [];
const capacityTable = () => {
  const rows = ['**Real-time capacity at 120 Hz** (most characters whose mean whole step fits 8.33 ms), full mode', '',
    '| runtime | legs | threads | largest crowd measured within budget (mean step) | smallest crowd measured over it | crowds measured beyond the grid | linear trend of the grid |', '|---|---|---|---|---|---|---|'];
  for (const d of gridDocs) {
    for (const legs of [2, 4]) {
      for (const key of [...curves(d, legs).keys()].filter((k) => k.startsWith('full'))) {
        const c = capacityOf(d, legs, key);
        rows.push(`| ${RUNTIME_NAME[d.machine.runtime]} | ${legsName(legs)} | ${key.replace('full ', '')} | **${crowdAt(c.within)}** | ${crowdAt(c.over)} | ${c.probes.map((p) => p.characters).join(', ') || '–'} | ${c.trend.fitted ?? '–'} |`);
      }
    }
  }
  return [...rows, ''];
};
md.push(`Measured by \`npm run bench\`${flag('--full') ? ' --full' : ''} on ${date} in ${minutes.toFixed(1)} minutes.`, '');
md.push('| runtime | CPU | logical cores | version | load average at start |', '|---|---|---|---|---|');
for (const d of gridDocs) md.push(`| ${RUNTIME_NAME[d.machine.runtime]} | ${d.machine.cpu ?? native0.machine.cpu} | ${d.machine.cores} | ${d.machine.runtime_version ?? d.machine.compiler} | ${d.machine.load_average ?? '–'} |`);
md.push('', `Grid: legs ${grid.legs.join(', ')}; characters ${grid.characters.length > 8 ? `${grid.characters[0]}–${grid.characters.at(-1)}` : grid.characters.join(', ')}; threads ${grid.threads.join(', ')} (serial: 1); ${grid.steps} steps × ${grid.runs} runs per point; ${native0.inputs.shards} physics shards; characters ${native0.inputs.spacing_m} m apart.`, '');

for (const d of gridDocs) {
  md.push(`**Controller time per step, ms (thesis Tables 6.1–6.3), ${RUNTIME_NAME[d.machine.runtime]}**`, '');
  md.push('| legs | series | 1 character | 100 characters | ratio | µs per character (100) |', '|---|---|---|---|---|---|');
  for (const legs of [2, 4]) {
    for (const r of ratioTable(d, legs, 'controller_ms')) {
      const last = (curves(d, legs).get(r.series) ?? []).at(-1);
      md.push(`| ${legsName(legs)} | ${r.series} | ${f(r.fromMs, 4)} | ${f(r.toMs, 4)} | 1 : ${f(r.ratio, 0)} | ${f(last?.controller_us_per_character, 2)} |`);
    }
  }
  md.push('');
}
for (const d of gridDocs) {
  md.push(`**Whole step, ms, ${RUNTIME_NAME[d.machine.runtime]}** (physics share in brackets)`, '');
  md.push('| legs | series | ' + grid.characters.slice(0, 8).map((n) => `${n}`).join(' | ') + ' |', '|---|---|' + grid.characters.slice(0, 8).map(() => '---').join('|') + '|');
  for (const legs of [2, 4]) {
    for (const [k, list] of curves(d, legs)) {
      md.push(`| ${legsName(legs)} | ${k} | ` + grid.characters.slice(0, 8).map((n) => {
        const p = list.find((q) => q.characters === n);
        return p ? `${f(p.step_ms.mean, 2)} (${f((100 * p.physics_ms.mean) / p.step_ms.mean, 0)} %)` : '–';
      }).join(' | ') + ' |');
    }
  }
  md.push('');
}

// The crowd benchmark's goals.
const ratio = (a, b) => (a && b && b > 0 ? a / b : null);
const stepAt = (d, legs, mode, threads) => d && find(d, { legs, characters: most, mode, threads })?.step_ms.mean;
const goals = [];
for (const [mode, threads] of [['serial', 1], ['full', 2]]) {
  for (const legs of [2, 4]) {
    const inGrid = f(ratio(stepAt(browser, legs, mode, threads), stepAt(native, legs, mode, threads)), 2);
    const rounds = [];
    for (let i = 0; i + 1 < pairedDocs.length; i += 2) {
      const r = ratio(stepAt(pairedDocs[i + 1], legs, mode, threads), stepAt(pairedDocs[i], legs, mode, threads));
      if (r !== null) rounds.push(r);
    }
    rounds.sort((a, b) => a - b);
    const measured = rounds.length
      ? `${f(rounds[(rounds.length - 1) >> 1], 2)} (${f(rounds[0], 2)}–${f(rounds.at(-1), 2)}), median of ${rounds.length} rounds in turns; the grids' points: ${inGrid}`
      : inGrid;
    goals.push([`whole step WASM-Chromium / native, ${most} ${legsName(legs)}s, ${mode}${mode === 'full' ? ' 2T' : ''}`, '≤ 1.2', measured]);
  }
}
for (const [d, name] of [[native, 'native'], [browser, 'Chromium']]) {
  goals.push([`whole-step speedup, 2 threads (full) over serial, ${most} quadrupeds, ${name}`, '≥ 1.7', f(d && speedup(d, 4, most, 2, 'full'), 2)]);
}
for (const legs of [2, 4]) {
  const p = browser && find(browser, { legs, characters: most, mode: 'serial' });
  goals.push([`controller µs per character per step, WASM in Chromium, ${legsName(legs)}, serial, ${most}`, legs === 2 ? '≤ 3.3' : '≤ 10', f(p?.controller_us_per_character, 2)]);
}
for (const legs of [2, 4]) {
  const c = capacityOf(browser, legs, 'full 2T');
  goals.push([`real-time capacity at 120 Hz, Chromium, 2 threads (full), ${legsName(legs)}s`, legs === 2 ? '≥ 1000' : '≥ 350',
    c ? `${c.within?.characters ?? 0} measured (${c.within ? `${f(c.within.step_ms.mean, 2)} ms a step` : 'none within budget'}; ${c.over ? `${crowdAt(c.over)} is over` : `no larger crowd measured${c.within?.characters >= probeCap(legs) ? `: ${probeCap(legs)} is the most the benchmark builds` : ''}`}); the grid's linear trend said ${c.trend.fitted ?? '–'}` : '–']);
}
{
  let worst = null;
  for (const d of gridDocs) {
    for (const p of d.points.filter((q) => q.characters === most)) {
      const r = p.step_ms.p99 / p.step_ms.p50;
      if (!worst || r > worst.r) worst = { r, p, d };
    }
  }
  const medianOf = (xs) => (xs.length ? [...xs].sort((a, b) => a - b)[Math.floor(xs.length / 2)] : null);
  const atMost = gridDocs.flatMap((d) => d.points.filter((q) => q.characters === most));
  const all = atMost.map((p) => p.step_ms.p99 / p.step_ms.p50);
  // The same tail with each step's median over the runs: what recurs in every run (the
  // simulation's own spikes), without what hit one run only (the machine; docs/parallel.md).
  const recurring = atMost.filter((p) => p.step_ms.p99_median_over_runs !== undefined)
    .map((p) => p.step_ms.p99_median_over_runs / p.step_ms.p50);
  goals.push([`99th-percentile / median step at ${most} characters`, '≤ 1.3 (counting spikes that recur in every run)',
    worst ? `median over series ${f(medianOf(all), 2)}; worst ${f(worst.r, 2)} (${RUNTIME_NAME[worst.d.machine.runtime]} ${legsName(worst.p.legs)} ${seriesKey(worst.p)})` +
      (recurring.length ? `; spikes that recur in every run (p99 of the per-step medians over runs): median over series ${f(medianOf(recurring), 2)}, worst ${f(Math.max(...recurring), 2)}` : '') : '–']);
}
md.push(...capacityTable());
md.push('**Goals of the crowd benchmark, this run**', '', '| goal | target | measured |', '|---|---|---|', ...goals.map((g) => `| ${g.join(' | ')} |`), '');

md.push('**Memory** (allocator bytes in use with the simulation alive; resident set of the process)', '', '| runtime | legs | characters | heap MB | scene MB | RSS MB |', '|---|---|---|---|---|---|');
for (const d of gridDocs) {
  for (const legs of [2, 4]) {
    for (const n of [Math.min(...grid.characters), most]) {
      const p = find(d, { legs, characters: n, mode: 'serial' });
      if (p) md.push(`| ${RUNTIME_NAME[d.machine.runtime]} | ${legsName(legs)} | ${n} | ${f(p.memory.heap_bytes / 1048576, 1)} | ${f(p.memory.scene_heap_bytes / 1048576, 1)} | ${p.memory.rss_bytes === null ? '–' : f(p.memory.rss_bytes / 1048576, 0)} |`);
    }
  }
}
md.push('', `Same state in every mode and thread count: ${gridDocs.every((d) => [2, 4].every((legs) => grid.characters.every((n) => new Set(d.points.filter((p) => p.legs === legs && p.characters === n).map((p) => p.state_hash)).size <= 1))) ? 'yes' : 'NO'} (state hash per crowd, every runtime); every run of a point ended in the same state: ${docs.every((d) => d.points.every((p) => p.deterministic)) ? 'yes' : 'NO'}.`, '');
const chartList = (prefix) => ['Charts:', '', ...svgs.map((s) => `- [${s.caption}](${prefix}${s.file})`), ''];
fs.writeFileSync(path.join(outDir, `${base}.md`), [...md, ...chartList('')].join('\n'));
if (flag('--readme')) {
  // The README shows the figures of one run, written here so that none is typed in by hand.
  const readme = path.join(root, 'README.md');
  const text = fs.readFileSync(readme, 'utf8');
  const begin = '<!-- bench:begin -->', end = '<!-- bench:end -->';
  if (!text.includes(begin) || !text.includes(end)) throw new Error(`README.md has no ${begin} ... ${end} block`);
  const rel = `${path.relative(root, outDir).split(path.sep).join('/')}/`;
  const embedded = [...md, `Results file: [${rel}${base}.json](${rel}${base}.json).`, '',
    ...['share-physics-controller', 'step-quadruped-native', 'realtime-capacity', 'wasm-native-ratio', 'fig5_4-quadruped-controller']
      .map((name) => svgs.find((s) => s.file.endsWith(`-${name}.svg`)))
      .filter(Boolean).map((s) => `![${s.caption}](${rel}${s.file})`), '', ...chartList(rel)];
  fs.writeFileSync(readme, text.slice(0, text.indexOf(begin) + begin.length) + '\n' + embedded.join('\n') + '\n' + text.slice(text.indexOf(end)));
}
process.stdout.write([...md, ...chartList('')].join('\n'));
process.stderr.write(`\nbench: wrote ${path.relative(root, path.join(outDir, base))}.{json,md} and ${svgs.length} charts in ${minutes.toFixed(1)} minutes\n`);
