// The `gaitlab` CLI natively and as WebAssembly under Node (bench/wasm.mjs): the same
// arguments give the same JSON document; bad input is refused on stderr with a non-zero exit.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { spawnSync } from 'node:child_process';
import { fileURLToPath } from 'node:url';
import path from 'node:path';

const root = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '../..');
const native = path.join(root, 'build/native/gaitlab');
const wasm = ['bench/wasm.mjs'];

function run(cmd, args) {
  const r = spawnSync(cmd, args, { cwd: root, encoding: 'utf8', timeout: 120_000 });
  return { status: r.status, stdout: r.stdout, stderr: r.stderr };
}

const walkArgs = ['walk', '--character', 'quadruped', '--seconds', '1', '--speed', '0.8', '--json'];
const keys = ['fell', 'fall_time_s', 'distance_m', 'mean_speed_m_s', 'goal_speed_m_s',
  'heading_drift_deg', 'yaw_rate_rad_s', 'duty_factor_measured', 'duty_factor_config', 'footfall',
  'pushes_applied', 'pushes_survived', 'controller_us_per_step'];

test('native and WASM `walk` print the same JSON document shape', () => {
  const a = run(native, walkArgs);
  const b = run(process.execPath, [...wasm, ...walkArgs]);
  assert.equal(a.status, 0, a.stderr);
  assert.equal(b.status, 0, b.stderr);
  const ja = JSON.parse(a.stdout);
  const jb = JSON.parse(b.stdout);
  for (const k of keys) {
    assert.ok(k in ja, `native output lacks ${k}`);
    assert.ok(k in jb, `wasm output lacks ${k}`);
  }
  assert.deepEqual(Object.keys(ja).sort(), Object.keys(jb).sort());
  assert.equal(ja.goal_speed_m_s, 0.8);
  assert.equal(ja.duty_factor_config.length, 4, 'a quadruped has four legs');
  // The preset at 0.8 m/s trots (native/src/gait/footfall.h), in both builds.
  assert.equal(ja.footfall, 'trot');
  assert.equal(jb.footfall, 'trot');
  assert.ok(ja.controller_us_per_step > 0 && jb.controller_us_per_step > 0);
});

test('`walk --box-hits` runs the box-hit trial, natively and as WASM, hit for hit the same', () => {
  const args = ['walk', '--character', 'biped', '--speed', '0.5', '--box-hits', '3', '--seed', '4', '--json'];
  const a = run(native, args);
  const b = run(process.execPath, [...wasm, ...args]);
  assert.equal(a.status, 0, a.stderr);
  assert.equal(b.status, 0, b.stderr);
  const ja = JSON.parse(a.stdout);
  assert.equal(ja.box_hits, 3);
  assert.equal(ja.hits.length, 3);
  assert.ok(ja.box_throws >= 3);
  assert.equal(ja.box_hit_falls, ja.hits.filter((h) => h.fell).length);
  assert.deepEqual(JSON.parse(b.stdout).hits.map((h) => h.segment), ja.hits.map((h) => h.segment));
});

test('`walk --box-hits --get-up` watches each fall for the quadruped getting up, natively and as WASM', () => {
  const args = ['walk', '--character', 'quadruped', '--speed', '0.4', '--box-hits', '3', '--seed', '7', '--get-up', '10', '--json'];
  for (const [cmd, pre] of [[native, []], [process.execPath, wasm]]) {
    const r = run(cmd, [...pre, ...args]);
    assert.equal(r.status, 0, r.stderr);
    const j = JSON.parse(r.stdout);
    assert.equal(j.get_up_watch_s, 10);
    const falls = j.hits.filter((h) => h.fell);
    assert.ok(falls.length >= 2, `the demo's box knocks the dog over (${falls.length} of 3)`);
    assert.equal(j.box_hit_get_ups, falls.filter((h) => h.got_up_after_s !== null).length);
    // The roll after a fall is chaotic: the two builds' floating point part within it, so each
    // is judged on its own.
    assert.ok(j.box_hit_get_ups >= falls.length - 1, `it got up from ${j.box_hit_get_ups} of ${falls.length} falls`);
    for (const h of falls) if (h.got_up_after_s !== null) assert.ok(h.got_up_after_s >= 0 && h.got_up_after_s <= 10);
    for (const h of j.hits.filter((x) => !x.fell)) assert.equal(h.got_up_after_s, undefined, 'a hit it stood is not watched');
  }
});

test('--version works natively and as WASM', () => {
  assert.match(run(native, ['--version']).stdout, /^gaitlab \d+\.\d+\.\d+/);
  assert.match(run(process.execPath, [...wasm, '--version']).stdout, /^gaitlab \d+\.\d+\.\d+/);
});

for (const [args, message] of [
  [['walk', '--character', 'horse'], /--character: 'horse' is not biped, quadruped, hexapod or octopod/],
  [['walk', '--speed', 'fast'], /--speed: 'fast' is not a number/],
  [['walk', '--seconds', 'nan'], /--seconds: 'nan' is not a number/],
  [['walk', '--speed', '99'], /--speed: 99 is outside/],
  [['walk', '--bogus'], /unknown option '--bogus'/],
  [['walk', '--seed'], /option --seed needs a value/],
  [['walk', '--box-hits', '0'], /--box-hits: 0 is outside/],
  [['walk', '--box-hits', '2', '--get-up', '99'], /--get-up: 99 is outside/],
  [['walk', '--get-up', '5'], /--get-up watches the box-hit trial's falls: give --box-hits too/],
  [['walk', '--start-phase', '1.5'], /--start-phase: 1.5 is outside/],
  [['fly'], /unknown command 'fly'/],
]) {
  test(`refuses ${args.join(' ')}`, () => {
    for (const [cmd, pre] of [[native, []], [process.execPath, wasm]]) {
      const r = run(cmd, [...pre, ...args]);
      assert.notEqual(r.status, 0);
      assert.match(r.stderr, message);
      assert.equal(r.stdout, '');
    }
  });
}
