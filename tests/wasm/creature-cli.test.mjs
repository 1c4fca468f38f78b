// `gaitlab walk --creature FILE` and `gaitlab optimize --creature FILE`, natively and as
// WebAssembly under Node: the biped's and the quadruped's creature files walk exactly as the
// built-in bodies (same state hash); a six-legged creature is a hexapod and walks the gait derived
// from its body; a search tunes that gait for the body and writes a hexapod's gait file, which the
// body then walks; a gait file of another kind, a body that contradicts --character and a bad file
// are refused with the file and the field named (exit status 2).
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { spawnSync } from 'node:child_process';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { fileURLToPath } from 'node:url';

const root = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '../..');
const native = path.join(root, 'build/native/gaitlab');
const tmp = fs.mkdtempSync(path.join(os.tmpdir(), 'gaitlab-creature-'));

function run(args, cmd = native) {
  const r = spawnSync(cmd, cmd === native ? args : ['bench/wasm.mjs', ...args], { cwd: root, encoding: 'utf8', timeout: 120_000 });
  return { status: r.status, stdout: r.stdout, stderr: r.stderr };
}
const walk = ['walk', '--json', '--seconds', '2', '--speed', '0.8'];
const shipped = (name) => path.join(root, 'public/creatures', `${name}.json`);

test('the shipped creature files walk as the built-in bodies, natively and as WASM', () => {
  for (const name of ['biped', 'quadruped']) {
    for (const cmd of [native, process.execPath]) {
      const builtIn = run([...walk, '--character', name], cmd);
      assert.equal(builtIn.status, 0, builtIn.stderr);
      const fromFile = run([...walk, '--creature', shipped(name)], cmd);
      assert.equal(fromFile.status, 0, fromFile.stderr);
      const a = JSON.parse(builtIn.stdout), b = JSON.parse(fromFile.stdout);
      assert.equal(b.character, name);
      assert.equal(b.state_hash, a.state_hash, `${name} from its creature file`);
    }
  }
});

test('a six-legged creature walks its derived gait, natively and as WASM', () => {
  for (const cmd of [native, process.execPath]) {
    const r = run(['walk', '--json', '--seconds', '12', '--speed', '0.4', '--creature', shipped('insect')], cmd);
    assert.equal(r.status, 0, r.stderr);
    const out = JSON.parse(r.stdout);
    assert.equal(out.fell, false);
    assert.equal(out.duty_factor_measured.length, 6);
    assert.ok(Math.abs(out.mean_speed_m_s - 0.4) < 0.15 * 0.4, `${out.mean_speed_m_s} m/s`);
  }
});

test("a search tunes a creature's own gait and writes a gait file it walks, natively and as WASM", () => {
  for (const cmd of [native, process.execPath]) {
    const out = path.join(tmp, `dragon-${cmd === native ? 'native' : 'wasm'}.json`);
    const search = ['optimize', '--json', '--creature', shipped('dragon'), '--generations', '2', '--candidates', '3',
      '--seconds', '2', '--speeds', '0.4', '--threads', '1', '--out', out];
    const r = run(search, cmd);
    assert.equal(r.status, 0, r.stderr);
    const summary = JSON.parse(r.stdout);
    assert.equal(summary.character, 'hexapod');
    assert.equal(summary.evaluations, 6);
    assert.ok(summary.best_objective <= summary.start_objective, `${summary.best_objective} > ${summary.start_objective}`);
    const file = JSON.parse(fs.readFileSync(out, 'utf8'));
    assert.equal(file.character, 'hexapod');
    assert.equal(file.meta.start, 'derived');
    assert.ok('middleLeft.dutyFactor' in file.params);
    // The same search from the same seed, on either build, finds the same gait.
    if (cmd !== native) assert.deepEqual(file.params, JSON.parse(fs.readFileSync(path.join(tmp, 'dragon-native.json'), 'utf8')).params);
    const w = run(['walk', '--json', '--seconds', '3', '--speed', '0.4', '--creature', shipped('dragon'), '--params', out], cmd);
    assert.equal(w.status, 0, w.stderr);
    assert.equal(JSON.parse(w.stdout).duty_factor_measured.length, 6);
  }
});

test('gait files for other kinds, bodies that contradict --character and bad files are refused', () => {
  let r = run([...walk, '--creature', shipped('insect'), '--params', path.join(root, 'public/presets/quadruped.json')]);
  assert.equal(r.status, 2, r.stderr);
  assert.match(r.stderr, /quadruped\.json: character: the file is for a quadruped, not a hexapod/);

  r = run([...walk, '--creature', shipped('insect'), '--character', 'quadruped']);
  assert.equal(r.status, 2, r.stderr);
  assert.match(r.stderr, /insect\.json: a body of 3 leg frames walks as a hexapod, not as the quadruped --character names/);

  const quadruped = JSON.parse(fs.readFileSync(shipped('quadruped'), 'utf8'));
  r = run([...walk, '--creature', shipped('quadruped'), '--character', 'biped']);
  assert.equal(r.status, 2, r.stderr);
  assert.match(r.stderr, /walks as a quadruped, not as the biped --character names/);

  const bad = structuredClone(quadruped);
  bad.legFrames[1].legs.foot.mass = 0;
  const file = path.join(tmp, 'bad.json');
  fs.writeFileSync(file, JSON.stringify(bad));
  r = run([...walk, '--creature', file]);
  assert.equal(r.status, 2, r.stderr);
  assert.match(r.stderr, /bad\.json: legFrames\[1\]\.legs\.foot\.mass: 0(\.0)? is outside \[0\.01, 500\.0\]/);
});
