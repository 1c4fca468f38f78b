// `gaitlab bench` natively and as WebAssembly under Node print the same document, valid against
// bench/schema.json; `npm run bench`'s driver (bench/run.mjs --tiny) runs a tiny grid natively, in
// Node and in headless Chromium and writes a valid results file, its tables and its charts.
// Nothing here judges a timing: that is the benchmark's business.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { spawnSync } from 'node:child_process';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { STEP_BUDGET_MS, nextCapacityProbe, overlayDocuments, toCsv, validate } from '../../bench/lib/analysis.mjs';

const root = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '../..');
const native = path.join(root, 'build/native/gaitlab');

function run(cmd, args, timeout = 120_000) {
  const r = spawnSync(cmd, args, { cwd: root, encoding: 'utf8', timeout });
  return { status: r.status, stdout: r.stdout, stderr: r.stderr };
}

const tiny = ['bench', '--legs', '2,4', '--characters', '1-3:2', '--threads', '1,2', '--mode', 'serial,controller,full',
  '--steps', '6', '--runs', '2', '--frames'];

test('native and WASM `bench --json` print documents valid against bench/schema.json', () => {
  const docs = [];
  for (const [cmd, pre] of [[native, []], [process.execPath, ['bench/wasm.mjs']]]) {
    const r = run(cmd, [...pre, ...tiny, '--json']);
    assert.equal(r.status, 0, r.stderr);
    // An untimed warm-up comes first (sim::warmUp: a WASM engine's optimising tier), then the grid.
    assert.match(r.stderr, /^bench: warming up \(untimed\)\nbench 1\//m);
    const doc = JSON.parse(r.stdout);
    assert.deepEqual(validate(doc), []);
    docs.push(doc);
  }
  const [a, b] = docs;
  assert.equal(a.machine.runtime, 'native');
  assert.equal(b.machine.runtime, 'wasm-node');
  assert.deepEqual(a.inputs, b.inputs);
  // legs 2,4 x (serial once + controller and full on 1 and 2 threads) x characters 1, 3.
  assert.equal(a.points.length, 2 * 5 * 2);
  assert.deepEqual(a.points.map((p) => [p.legs, p.mode, p.threads, p.characters]),
    b.points.map((p) => [p.legs, p.mode, p.threads, p.characters]));
  for (const doc of docs) {
    for (const p of doc.points) {
      assert.ok(p.deterministic, 'every run of a point ends in the same state');
      assert.equal(p.frames.step_ms.mean.length, 6);
      assert.ok(p.step_ms.p99_median_over_runs <= p.step_ms.max, 'the tail of the per-step medians lies within the steps');
      // The same crowd gives the same state in every mode and thread count.
      const same = doc.points.filter((q) => q.legs === p.legs && q.characters === p.characters);
      assert.ok(same.every((q) => q.state_hash === p.state_hash), `state differs across modes: ${p.legs} legs x ${p.characters}`);
    }
  }
});

test('a crowd of a creature, and a mixed crowd of creatures (`bench --creature`): the same state in every mode and thread count, natively and as WASM', () => {
  const args = ['bench', '--creature', 'public/creatures/insect.json', '--characters', '3', '--threads', '1,2',
    '--mode', 'serial,controller,full', '--steps', '24', '--runs', '2', '--json'];
  for (const [cmd, pre] of [[native, []], [process.execPath, ['bench/wasm.mjs']]]) {
    const r = run(cmd, [...pre, ...args]);
    assert.equal(r.status, 0, r.stderr);
    const doc = JSON.parse(r.stdout);
    assert.deepEqual(validate(doc), []);
    assert.equal(doc.inputs.creature, 'insect');
    assert.deepEqual(doc.inputs.legs, [6]);
    assert.equal(doc.points.length, 5);
    for (const p of doc.points) {
      assert.equal(p.creature, 'insect');
      assert.equal(p.legs, 6);
      assert.ok(p.deterministic);
      assert.equal(p.state_hash, doc.points[0].state_hash, `${p.mode} on ${p.threads} threads`);
    }
  }
  // A mixed crowd of any creatures, in turn: an insect, a spider, a dragon, an insect...
  const mixed = ['bench', '--creature', 'public/creatures/insect.json,public/creatures/spider.json,public/creatures/dragon.json',
    '--characters', '4', '--threads', '1,2', '--mode', 'serial,full', '--steps', '24', '--runs', '1', '--json'];
  const hashes = [];
  for (const [cmd, pre] of [[native, []], [process.execPath, ['bench/wasm.mjs']]]) {
    const r = run(cmd, [...pre, ...mixed]);
    assert.equal(r.status, 0, r.stderr);
    const doc = JSON.parse(r.stdout);
    assert.deepEqual(validate(doc), []);
    assert.equal(doc.inputs.creature, 'insect+spider+dragon');
    assert.deepEqual(doc.inputs.legs, ['mixed']);
    assert.equal(doc.points.length, 3);
    for (const p of doc.points) {
      assert.equal(p.creature, 'insect+spider+dragon');
      assert.ok(p.deterministic);
      assert.equal(p.state_hash, doc.points[0].state_hash, `${p.mode} on ${p.threads} threads`);
    }
    hashes.push(doc.points[0].state_hash);
  }
  assert.equal(hashes[1], hashes[0], 'the same state natively and as WASM');
  const both = run(native, ['bench', '--creature', 'public/creatures/insect.json', '--legs', '2']);
  assert.equal(both.status, 2);
  assert.match(both.stderr, /--creature and --legs: give one of them/);
});

test('`bench --csv` prints the machine, a header and a row per point, like the JS writer', () => {
  const r = run(native, ['bench', '--legs', '2', '--characters', '2', '--threads', '2', '--mode', 'serial,full', '--steps', '3', '--runs', '1', '--csv']);
  assert.equal(r.status, 0, r.stderr);
  const lines = r.stdout.trim().split('\n');
  assert.match(lines[0], /^# \{.*"runtime":"native"/);
  assert.match(lines[1], /^# inputs /);
  const j = run(native, ['bench', '--legs', '2', '--characters', '2', '--threads', '2', '--mode', 'serial,full', '--steps', '3', '--runs', '1', '--json']);
  const fromJs = toCsv(JSON.parse(j.stdout)).trim().split('\n');
  assert.equal(lines[2], fromJs[2], 'the same columns');
  assert.equal(lines.length, 3 + 2);
  assert.deepEqual(lines.slice(3).map((l) => l.split(',').length), [fromJs[2].split(',').length, fromJs[2].split(',').length]);
});

for (const [args, message] of [
  [['--legs', '3'], /--legs: '3' is not 2, 4 or mixed/],
  [['--characters', '0-5'], /--characters: '0-5' is not a range/],
  // Up to GL_MAX_THREADS natively and in WebAssembly (bench/wasm.mjs sizes the pool for --threads).
  [['--threads', '17'], /--threads: '17' is not a number in \[1, 16\]/],
  [['--mode', 'parallel'], /--mode: 'parallel' is not serial, controller or full/],
  [['--steps', 'x'], /--steps: 'x' is not a number/],
  [['--json', '--csv'], /exclusive/],
  [['--legs', '4', '--characters', '911'], /911 quadrupeds is more than a simulation holds \((910|[1-8]\d\d)\)/], // natively the render buffer's 910; in WebAssembly the heap's fewer
]) {
  test(`bench refuses ${args.join(' ')}`, () => {
    for (const [cmd, pre] of [[native, []], [process.execPath, ['bench/wasm.mjs']]]) {
      const r = run(cmd, [...pre, 'bench', ...args]);
      assert.equal(r.status, 2);
      assert.match(r.stderr, message);
      assert.equal(r.stdout, '');
    }
  });
}

test('bench/run.mjs --tiny: native, WASM in Node and in Chromium, a valid results file and charts', () => {
  const out = fs.mkdtempSync(path.join(os.tmpdir(), 'gaitlab-bench-'));
  try {
    const r = run(process.execPath, ['bench/run.mjs', '--tiny', '--out', out], 240_000);
    assert.equal(r.status, 0, r.stderr);
    const files = fs.readdirSync(out);
    const json = files.find((f) => f.endsWith('.json'));
    assert.ok(json, 'a results file');
    const results = JSON.parse(fs.readFileSync(path.join(out, json), 'utf8'));
    assert.deepEqual(validate(results, 'results'), []);
    assert.deepEqual([...new Set(results.runs.map((d) => d.machine.runtime))], ['native', 'wasm-node', 'wasm-browser']);
    // Every runtime measured its capacity beyond the grid (capped at 5 characters for --tiny).
    for (const runtime of ['native', 'wasm-node', 'wasm-browser']) {
      const probes = results.runs.filter((d) => d.machine.runtime === runtime && d.points.every((p) => p.characters === 5 && p.mode === 'full'));
      assert.deepEqual(probes.map((d) => d.inputs.legs).sort(), [[2], [4]], `${runtime}: a capacity probe per leg count`);
    }
    const browser = results.runs.find((d) => d.machine.runtime === 'wasm-browser');
    assert.equal(browser.machine.cross_origin_isolated, true);
    const svgs = files.filter((f) => f.endsWith('.svg'));
    for (const fig of ['fig5_1', 'fig5_2', 'fig5_3', 'fig5_4', 'fig5_5', 'fig6_1', 'fig6_2', 'share-physics-controller', 'wasm-native-ratio', 'realtime-capacity']) {
      assert.ok(svgs.some((f) => f.includes(fig)), `chart ${fig}`);
    }
    for (const f of svgs) assert.match(fs.readFileSync(path.join(out, f), 'utf8'), /^<svg [^>]*xmlns="http:\/\/www.w3.org\/2000\/svg"[\s\S]*<\/svg>\s*$/);
    const md = fs.readFileSync(path.join(out, files.find((f) => f.endsWith('.md'))), 'utf8');
    assert.match(md, /Goals of the crowd benchmark/);
    assert.match(md, /\| native \| biped \| 2T \| \*\*5 \([\d.]+ ms\)\*\* \| – \| 5 \|/, 'the capacity table lists the probe');
    assert.match(md, /spikes that recur in every run/);
    // The WASM/native goal from native and Chromium measuring the largest crowd in turns.
    const paired = results.runs.filter((d) => d.points.every((p) => p.characters === 3) && d.inputs.modes.join() === 'serial,full');
    assert.deepEqual(paired.map((d) => d.machine.runtime), ['native', 'wasm-browser']);
    assert.match(md, /whole step WASM-Chromium \/ native, 3 bipeds, serial \| ≤ 1.2 \| [\d.]+ \([\d.]+–[\d.]+\), median of 1 rounds in turns; the grids' points: [\d.]+ \|/);
    assert.match(md, /Same state in every mode and thread count: yes/);
  } finally {
    fs.rmSync(out, { recursive: true, force: true });
  }
});

// The capacity search of bench/run.mjs against step-time models whose capacity is known: it must
// bracket the capacity within 5 % in a few probes, also when the grid's linear trend is wrong.
for (const [name, stepMs, capacity] of [
  ['linear', (n) => 0.3 + 0.02 * n, Math.floor((STEP_BUDGET_MS - 0.3) / 0.02)],
  // Cost per character grows with the crowd (e.g. caches): the grid's trend overestimates.
  ['superlinear', (n) => 0.02 * n + 0.00002 * n * n, 316],
  ['never in real time', () => 9, 0],
]) {
  test(`nextCapacityProbe finds the capacity of a ${name} step time`, () => {
    const point = (n) => ({ characters: n, step_ms: { mean: stepMs(n) } });
    const points = [1, 20, 50, 100].map(point);
    let probes = 0;
    for (let n; (n = nextCapacityProbe(points, { cap: 1000 })) !== null; ++probes) {
      assert.ok(probes < 8, `more than 8 probes: ${points.map((p) => p.characters)}`);
      assert.ok(!points.some((p) => p.characters === n), `measures ${n} twice`);
      points.push(point(n));
    }
    const within = Math.max(0, ...points.filter((p) => p.step_ms.mean <= STEP_BUDGET_MS).map((p) => p.characters));
    assert.ok(within <= capacity, `${within} reported within budget, capacity ${capacity}`);
    if (capacity > 0) assert.ok(within >= 0.95 * capacity, `${within} is not within 5 % of ${capacity}`);
  });
}

test('nextCapacityProbe stops at the largest crowd the benchmark builds', () => {
  const points = [1, 20, 50, 100].map((n) => ({ characters: n, step_ms: { mean: 0.001 * n } }));
  assert.equal(nextCapacityProbe(points, { cap: 300 }), 300);
  points.push({ characters: 300, step_ms: { mean: 0.3 } });
  assert.equal(nextCapacityProbe(points, { cap: 300 }), null);
});

test('bench/ab-wasm.mjs steps the same crowd with two builds in turns and reports equal hashes for one build', () => {
  const r = run(process.execPath, ['bench/ab-wasm.mjs', 'build/wasm', 'build/wasm', '4', '2', '3']);
  assert.equal(r.status, 0, r.stderr);
  const hashes = [...r.stdout.matchAll(/state hash ([0-9a-f]{16})/g)].map((m) => m[1]);
  assert.equal(hashes.length, 2, r.stdout);
  assert.equal(hashes[0], hashes[1]);
  assert.match(r.stdout, /new\/old, median over 3 turns: \d+\.\d{3}/);
  const bad = run(process.execPath, ['bench/ab-wasm.mjs', 'build/wasm', 'build/wasm', '3']);
  assert.equal(bad.status, 2);
  assert.match(bad.stderr, /usage/);
});

test('overlayDocuments gives one document per runtime with every point measured, the first of repeats', () => {
  const point = (characters, mode, mean) => ({ legs: 2, characters, threads: mode === 'serial' ? 1 : 2, mode, step_ms: { mean } });
  const doc = (runtime, points) => ({ machine: { runtime }, inputs: {}, points });
  const results = {
    schema: 'gaitlab-bench-results/1',
    runs: [
      doc('native', [point(1, 'serial', 1), point(100, 'full', 2)]),  // the grid
      doc('wasm-browser', [point(1, 'serial', 3), point(100, 'full', 4)]),
      doc('native', [point(400, 'full', 8)]),  // a capacity probe
      doc('native', [point(100, 'full', 9)]),  // a round in turns: a repeat
    ],
  };
  const docs = overlayDocuments(results);
  assert.deepEqual(docs.map((d) => d.machine.runtime), ['native', 'wasm-browser']);
  assert.deepEqual(docs[0].points.map((p) => [p.characters, p.step_ms.mean]), [[1, 1], [100, 2], [400, 8]]);
  assert.equal(results.runs[0].points.length, 2, 'the results file is left as it was');
  const single = doc('native', [point(1, 'serial', 1)]);
  assert.deepEqual(overlayDocuments(single), [single]);
});
