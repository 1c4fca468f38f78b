// `gaitlab walk --creature FILE`, natively and as WebAssembly under Node: the shipped creature
// files walk exactly as the built-in bodies (same state hash); a body the controller cannot walk
// yet, a body that contradicts --character and a bad file are refused with the file and the
// field named (exit status 2).
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

test('creatures the controller cannot walk yet, or that contradict --character, are refused', () => {
  const quadruped = JSON.parse(fs.readFileSync(shipped('quadruped'), 'utf8'));
  const middle = structuredClone(quadruped.legFrames[0]);
  Object.assign(middle, { name: 'legframe.middle', z: 0 });
  middle.legs.name = 'middle';
  const hexapod = structuredClone(quadruped);
  hexapod.legFrames = [quadruped.legFrames[0], middle, quadruped.legFrames[1]];
  hexapod.spine = [{ ...quadruped.spine[0], to: 0.12, links: 2 }, { ...quadruped.spine[0], from: -0.12, links: 2 }];
  const six = path.join(tmp, 'hexapod.json');
  fs.writeFileSync(six, JSON.stringify(hexapod));
  let r = run([...walk, '--creature', six]);
  assert.equal(r.status, 2, r.stderr);
  assert.match(r.stderr, /hexapod\.json: legFrames: 3 leg frames; the controller walks bodies of one or two so far/);

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
