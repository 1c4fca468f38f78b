// Gait files and the parameter schema through the CLI, natively and as WebAssembly under Node
// (bench/wasm.mjs): `walk --params FILE` refuses a bad file naming the field (exit 2, nothing
// on stdout), a shipped preset walks exactly like the built-in defaults (they are the same
// numbers), and `schema --json` prints the same document from both builds.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { spawnSync } from 'node:child_process';
import { mkdtempSync, readFileSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { fileURLToPath } from 'node:url';
import path from 'node:path';

const root = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '../..');
const native = path.join(root, 'build/native/gaitlab');
const builds = [
  ['native', native, []],
  ['wasm', process.execPath, ['bench/wasm.mjs']],
];

function run(cmd, args) {
  const r = spawnSync(cmd, args, { cwd: root, encoding: 'utf8', timeout: 120_000 });
  return { status: r.status, stdout: r.stdout, stderr: r.stderr };
}

const preset = JSON.parse(readFileSync(path.join(root, 'public/presets/biped.json'), 'utf8'));
const dir = mkdtempSync(path.join(tmpdir(), 'gaitlab-params-'));

function writeGait(name, change) {
  const doc = structuredClone(preset);
  change(doc);
  const file = path.join(dir, name);
  writeFileSync(file, JSON.stringify(doc));
  return file;
}

const badFiles = [
  ['out of bounds', writeGait('period.json', (d) => { d.params.period = 40; }), /: period: 40\.0 is outside \[0\.3, 3\.0\]/],
  ['missing field', writeGait('missing.json', (d) => { delete d.params['left.dutyFactor']; }), /: left\.dutyFactor: missing/],
  ['unknown field', writeGait('unknown.json', (d) => { d.params['left.wobble'] = 1; }), /: left\.wobble: unknown parameter/],
  ['wrong knot count', writeGait('knots.json', (d) => { d.params['legFrame.pitch'] = [0, 0]; }), /: legFrame\.pitch: expected an array of 4/],
  ['wrong character', writeGait('character.json', (d) => { d.character = 'quadruped'; }), /: character: /],
];

for (const [what, file, message] of badFiles) {
  test(`walk --params refuses a file with a ${what}, naming the field`, () => {
    for (const [name, cmd, pre] of builds) {
      const r = run(cmd, [...pre, 'walk', '--character', 'biped', '--params', file, '--seconds', '0.1', '--json']);
      assert.equal(r.status, 2, `${name}: exit status`);
      assert.match(r.stderr, new RegExp(`^gaitlab: ${file.replace(/[.*+?^${}()|[\]\\]/g, '\\$&')}`), name);
      assert.match(r.stderr, message, name);
      assert.equal(r.stdout, '', name);
    }
  });
}

test('walk --params refuses malformed JSON and a missing file', () => {
  const broken = path.join(dir, 'broken.json');
  writeFileSync(broken, '{"format": "gaitlab-gait", ');
  for (const [name, cmd, pre] of builds) {
    let r = run(cmd, [...pre, 'walk', '--params', broken]);
    assert.equal(r.status, 2, name);
    assert.match(r.stderr, /broken\.json: not valid JSON/, name);
    r = run(cmd, [...pre, 'walk', '--params', path.join(dir, 'nowhere.json')]);
    assert.equal(r.status, 2, name);
    assert.match(r.stderr, /nowhere\.json: cannot be read/, name);
  }
});

test('a shipped preset walks exactly like the built-in defaults, natively and as WASM', () => {
  for (const character of ['biped', 'quadruped']) {
    const args = ['walk', '--character', character, '--seconds', '0.5', '--json'];
    const withPreset = [...args, '--params', `public/presets/${character}.json`];
    const hashes = builds.flatMap(([, cmd, pre]) => [
      JSON.parse(run(cmd, [...pre, ...args]).stdout).state_hash,
      JSON.parse(run(cmd, [...pre, ...withPreset]).stdout).state_hash,
    ]);
    assert.equal(hashes[0], hashes[1], `${character}: native, preset file vs defaults`);
    assert.equal(hashes[2], hashes[3], `${character}: wasm, preset file vs defaults`);
  }
});

test('walk --params takes the character from the file when --character is absent', () => {
  const r = run(native, ['walk', '--params', 'public/presets/quadruped.json', '--seconds', '0.1', '--json']);
  assert.equal(r.status, 0, r.stderr);
  const out = JSON.parse(r.stdout);
  assert.equal(out.character, 'quadruped');
  assert.equal(out.duty_factor_config.length, 4);
});

test('schema --json is the same document natively and as WASM, with the presets as defaults', () => {
  const [a, b] = builds.map(([, cmd, pre]) => run(cmd, [...pre, 'schema', '--json']));
  assert.equal(a.status, 0, a.stderr);
  assert.equal(a.stdout, b.stdout);
  const schema = JSON.parse(a.stdout);
  for (const character of ['biped', 'quadruped']) {
    const file = JSON.parse(readFileSync(path.join(root, `public/presets/${character}.json`), 'utf8'));
    assert.equal(file.version, schema.version, `${character} preset is of the schema's version`);
    const entries = schema.characters[character];
    assert.deepEqual(entries.map((e) => e.name), Object.keys(file.params));
    for (const e of entries) {
      // A per-leg or per-leg-frame parameter names its leg or leg frame too.
      const owner = Object.keys(e).filter((k) => k === 'leg' || k === 'legFrame');
      assert.ok(owner.length <= 1, e.name);
      assert.deepEqual(Object.keys(e).sort(), ['default', 'description', 'field', 'group', 'knots', 'max', 'min', 'name', 'unit', ...owner].sort());
      assert.deepEqual(e.default, file.params[e.name], e.name);
      assert.equal(Array.isArray(e.default) ? e.default.length : 1, e.knots, e.name);
    }
  }
  const one = JSON.parse(run(native, ['schema', '--character', 'quadruped', '--json']).stdout);
  assert.deepEqual(Object.keys(one.characters), ['quadruped']);
});
