// `gaitlab optimize` natively and as WebAssembly under Node (bench/wasm.mjs): the same
// arguments print the same JSON summary shape and write a gait file that loads back (with its
// provenance in meta); Ctrl-C stops after the current generation and still writes the best.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { spawn, spawnSync } from 'node:child_process';
import { mkdtempSync, readFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { fileURLToPath } from 'node:url';
import path from 'node:path';

const root = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '../..');
const native = path.join(root, 'build/native/gaitlab');
const dir = mkdtempSync(path.join(tmpdir(), 'gaitlab-optimize-'));

function run(cmd, args) {
  const r = spawnSync(cmd, args, { cwd: root, encoding: 'utf8', timeout: 300_000 });
  return { status: r.status, stdout: r.stdout, stderr: r.stderr };
}

const summaryKeys = ['best_objective', 'best_terms', 'candidates', 'character', 'determinism_mismatches',
  'evaluations', 'generations', 'history', 'interrupted', 'method', 'out', 'seconds',
  'seconds_per_generation', 'seed', 'start_objective', 'threads'];

for (const method of ['greedy', 'cmaes']) {
  test(`optimize --method ${method}: native and WASM print the same summary and write a loadable gait file`, () => {
    const summaries = [];
    for (const [name, cmd, pre] of [['native', native, []], ['wasm', process.execPath, ['bench/wasm.mjs']]]) {
      const out = path.join(dir, `${method}-${name}.json`);
      const r = run(cmd, [...pre, 'optimize', '--character', 'quadruped', '--method', method, '--generations', '2',
        '--candidates', '3', '--seconds', '1', '--seed', '5', '--threads', '2', '--out', out, '--json']);
      assert.equal(r.status, 0, `${name}: ${r.stderr}`);
      assert.match(r.stderr, /generation 2\/2 {2}best /, name);
      const s = JSON.parse(r.stdout);
      assert.deepEqual(Object.keys(s).sort(), summaryKeys, name);
      assert.equal(s.method, method);
      assert.equal(s.evaluations, 6);
      assert.equal(s.history.length, 2);
      // The start is the best until a candidate beats it, so neither method ends worse than it
      // (CMA-ES only samples around the start, and once wrote out a worse candidate).
      assert.ok(s.best_objective <= s.start_objective, name);
      assert.ok(s.history.every((h, i) => i === 0 || h.best_objective <= s.history[i - 1].best_objective), name);
      assert.equal(s.determinism_mismatches, 0, name);
      const file = JSON.parse(readFileSync(out, 'utf8'));
      assert.equal(file.format, 'gaitlab-gait');
      assert.equal(file.character, 'quadruped');
      assert.equal(file.meta.seed, 5);
      assert.equal(file.meta.objective, s.best_objective);
      assert.equal(file.meta.evaluations, 6);
      assert.match(file.meta.command, /^gaitlab optimize --character quadruped/);
      assert.match(file.meta.date, /^\d{4}-\d\d-\d\dT\d\d:\d\d:\d\dZ$/);
      // The result is a valid gait file for the CLI.
      const walk = run(native, ['walk', '--params', out, '--seconds', '0.2', '--json']);
      assert.equal(walk.status, 0, walk.stderr);
      summaries.push(s);
    }
    assert.deepEqual(Object.keys(summaries[0].best_terms).sort(), Object.keys(summaries[1].best_terms).sort());
  });
}

// The biped preset's keys: its primary and at least one more.
const bipedPreset = JSON.parse(readFileSync(path.join(root, 'public/presets/biped.json'), 'utf8'));
const bipedKeySpeeds = [bipedPreset.speed, ...bipedPreset.keys.map((k) => k.speed)].sort((a, b) => a - b);
// A number as the CLI prints it: a whole number with one decimal (0.0, 1.0), others as they are.
const cliNumber = (x) => (Number.isInteger(x) ? x.toFixed(1) : String(x));

test('optimize --key tunes one speed key and keeps the others as they were', () => {
  const out = path.join(dir, 'key.json');
  const key = bipedPreset.keys.at(-1).speed;
  const r = run(native, ['optimize', '--character', 'biped', '--key', String(key), '--generations', '2', '--candidates', '3',
    '--seconds', '1', '--speeds', String(key), '--seed', '3', '--out', out, '--json']);
  assert.equal(r.status, 0, r.stderr);
  const preset = bipedPreset;
  const file = JSON.parse(readFileSync(out, 'utf8'));
  assert.equal(file.version, preset.version);
  assert.equal(file.speed, preset.speed);
  assert.deepEqual(file.params, preset.params, 'the primary key is not the one tuned');
  assert.deepEqual(file.keys.map((k) => k.speed), preset.keys.map((k) => k.speed));
  assert.deepEqual(Object.keys(file.keys[0].params), Object.keys(preset.keys[0].params));
});

test('optimize --hold leaves the held parameters as they were', () => {
  const out = path.join(dir, 'held.json');
  const r = run(native, ['optimize', '--character', 'quadruped', '--hold', 'stepTrigger,front.pitch', '--generations', '2',
    '--candidates', '4', '--seconds', '1', '--seed', '5', '--out', out, '--json']);
  assert.equal(r.status, 0, r.stderr);
  const preset = JSON.parse(readFileSync(path.join(root, 'public/presets/quadruped.json'), 'utf8'));
  const file = JSON.parse(readFileSync(out, 'utf8'));
  for (const name of ['frontLeft.stepTrigger', 'frontRight.stepTrigger', 'backLeft.stepTrigger', 'backRight.stepTrigger', 'front.pitch'])
    assert.deepEqual(file.params[name], preset.params[name], name);
  assert.match(file.meta.command, /--hold stepTrigger,front\.pitch/);
});

test('optimize --step-size and --perturb-probability bound how far a greedy search moves', () => {
  // Two generations from the preset: the best is at most two moves from where it started, and
  // every parameter moves with probability 1 by at most the step times its schema range.
  const schema = JSON.parse(run(native, ['schema', '--character', 'quadruped', '--json']).stdout);
  const ranges = new Map(schema.characters.quadruped.map((p) => [p.name, p.max - p.min]));
  const preset = JSON.parse(readFileSync(path.join(root, 'public/presets/quadruped.json'), 'utf8'));
  const out = path.join(dir, 'small-steps.json');
  const step = 0.002;
  const r = run(native, ['optimize', '--character', 'quadruped', '--step-size', String(step), '--perturb-probability', '1',
    '--generations', '2', '--candidates', '4', '--seconds', '1', '--seed', '2', '--out', out, '--json']);
  assert.equal(r.status, 0, r.stderr);
  const s = JSON.parse(r.stdout);
  assert.ok(s.best_objective < s.start_objective, 'the search found a better candidate, so the best moved');
  const file = JSON.parse(readFileSync(out, 'utf8'));
  let moved = 0;
  for (const [name, value] of Object.entries(file.params)) {
    const start = preset.params[name];
    const range = ranges.get(name);
    assert.ok(range !== undefined, name);
    const values = Array.isArray(value) ? value.flat() : [value];
    const starts = Array.isArray(start) ? start.flat() : [start];
    values.forEach((v, i) => {
      const d = Math.abs(v - starts[i]);
      assert.ok(d <= 2 * step * range * (1 + 1e-9) + 1e-12, `${name}: moved ${d}, more than two steps of ${step * range}`);
      if (d > 0) ++moved;
    });
  }
  assert.ok(moved > 10, `with probability 1 nearly every parameter moves (${moved} did)`);
});

test('optimize refuses bad options', () => {
  for (const [args, message] of [
    [['optimize', '--generations', '1'], /--out FILE is required/],
    [['optimize', '--method', 'annealing', '--out', '/tmp/x.json'], /--method: 'annealing' is not greedy or cmaes/],
    [['optimize', '--objective', 'wr=-1', '--out', '/tmp/x.json'], /--objective: wr: -1\.0 is outside/],
    [['optimize', '--objective', 'colour=1', '--out', '/tmp/x.json'], /unknown objective setting 'colour'/],
    [['optimize', '--speeds', '1,fast', '--out', '/tmp/x.json'], /--speeds: 'fast' is not a speed/],
    [['optimize', '--grounds', 'flat,hill', '--out', '/tmp/x.json'], /--grounds: 'hill' is not flat, slope or bumps/],
    [['optimize', '--grounds', 'slope@down', '--out', '/tmp/x.json'], /--grounds: 'slope@down': the heading after '@' is not a number/],
    [['optimize', '--candidates', '1', '--out', '/tmp/x.json'], /--candidates: 1 is outside/],
    [['optimize', '--step-size', '0', '--out', '/tmp/x.json'], /--step-size: 0 is outside \[0\.001, 1(\.0)?\]/],
    [['optimize', '--perturb-probability', 'often', '--out', '/tmp/x.json'], /--perturb-probability: 'often' is not a number/],
    [['optimize', '--hold', 'stepTrigger,bogus', '--out', '/tmp/x.json'], /--hold: 'bogus' is not a parameter of the biped/],
    [['optimize', '--hold', 'stepTrigger,', '--out', '/tmp/x.json'], /--hold: expected NAME,\.\.\. \(an empty name/],
    [['optimize', '--key', '1.2', '--out', '/tmp/x.json'],
      new RegExp(`--key: the gait has no key at 1\\.2 m/s; its keys are at ${bipedKeySpeeds.map(cliNumber).join(', ').replaceAll('.', '\\.')} m/s`)],
  ]) {
    const r = run(native, args);
    assert.equal(r.status, 2, args.join(' '));
    assert.match(r.stderr, message);
    assert.equal(r.stdout, '');
  }
});

test('Ctrl-C stops after the current generation and writes the best so far', async () => {
  const out = path.join(dir, 'interrupted.json');
  const child = spawn(native, ['optimize', '--generations', '100000', '--candidates', '2', '--seconds', '0.5',
    '--out', out, '--json'], { cwd: root });
  let stderr = '';
  let stdout = '';
  child.stdout.on('data', (d) => { stdout += d; });
  const status = await new Promise((resolve) => {
    child.stderr.on('data', (d) => {
      stderr += d;
      if (/generation 2\//.test(stderr) && !child.killed) child.kill('SIGINT');
    });
    child.on('exit', (code) => resolve(code));
  });
  assert.equal(status, 0, stderr);
  assert.match(stderr, /interrupted; writing the best so far/);
  const s = JSON.parse(stdout);
  assert.equal(s.interrupted, true);
  assert.ok(s.generations >= 2 && s.generations < 100000);
  const file = JSON.parse(readFileSync(out, 'utf8'));
  assert.equal(file.meta.interrupted, true);
  assert.equal(file.meta.generations, s.generations);
});
