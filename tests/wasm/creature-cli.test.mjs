// `gaitlab walk --creature FILE`, natively and as WebAssembly under Node: the biped's and the
// quadruped's creature files walk exactly as the built-in bodies (same state hash); a six-legged
// creature walks the gait derived from its body; a gait file for it, a body that contradicts
// --character and a bad file are refused with the file and the field named (exit status 2).
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

test('gait files for other bodies, bodies that contradict --character and bad files are refused', () => {
  let r = run([...walk, '--creature', shipped('insect'), '--params', path.join(root, 'public/presets/quadruped.json')]);
  assert.equal(r.status, 2, r.stderr);
  assert.match(r.stderr, /gait files are for bodies of one or two leg frames; this one walks the gait derived from it/);

  r = run([...walk, '--creature', shipped('insect'), '--character', 'quadruped']);
  assert.equal(r.status, 2, r.stderr);
  assert.match(r.stderr, /insect\.json: a body of 3 leg frames is neither a biped nor a quadruped: leave out --character/);

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
