// The peer benchmark (bench/peers.mjs, `npm run bench -- --peers`): gaitlab's reference scene
// and the same scene built in Jolt Physics run side by side and give a complete results file.
// Nothing here judges a timing: that is the benchmark's business. It does check that the two
// engines simulate the same scene: the same ragdolls, standing at the same height at the start.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { spawnSync } from 'node:child_process';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { fileURLToPath } from 'node:url';

const root = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '../..');

test('npm run bench -- --peers --quick times every engine on both characters and writes peers.{json,md}', () => {
  const out = fs.mkdtempSync(path.join(os.tmpdir(), 'gaitlab-peers-'));
  const r = spawnSync(process.execPath, ['bench/run.mjs', '--peers', '--quick', '--out', out],
    { cwd: root, encoding: 'utf8', timeout: 180_000 });
  assert.equal(r.status, 0, r.stderr);
  const doc = JSON.parse(fs.readFileSync(path.join(out, 'peers.json'), 'utf8'));
  const key = (p) => `${p.engine} ${p.legs} ${p.threads}`;
  assert.deepEqual(doc.points.map(key).sort(), [
    'gaitlab 2 1', 'gaitlab 2 2', 'gaitlab 4 1', 'gaitlab 4 2',
    'jolt 2 1', 'jolt 4 1',
    'jolt-mt 2 1', 'jolt-mt 2 2', 'jolt-mt 4 1', 'jolt-mt 4 2',
  ]);
  for (const p of doc.points) {
    assert.equal(p.skipped, undefined, key(p));
    assert.ok(p.ms_per_step > 0 && p.ms_min <= p.ms_per_step && p.ms_per_step <= p.ms_max, key(p));
    // A few steps after the start every engine's ragdolls still stand where they were built:
    // the biped's root 1.16 m up, the quadruped's 0.525 m (native/src/body/morphology.cpp).
    assert.ok(Math.abs(p.root_height_m - (p.legs === 2 ? 1.16 : 0.525)) < 0.02, `${key(p)}: root at ${p.root_height_m}`);
  }
  const md = fs.readFileSync(path.join(out, 'peers.md'), 'utf8');
  assert.match(md, /\| quadrupeds \| 4 \| 2 \|/);
});
