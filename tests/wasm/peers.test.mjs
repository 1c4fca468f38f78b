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

test('the reference scene is refused, not aborted, when the module cannot hold it', async () => {
  const { createRequire } = await import('node:module');
  const createGaitlab = createRequire(import.meta.url)(path.join(root, 'build/wasm/gaitlab-node.cjs'));
  const G = await createGaitlab({ wasmBinary: fs.readFileSync(path.join(root, 'build/wasm/gaitlab-node.wasm')), noExitRuntime: true });
  try {
    // 400 quadrupeds are charged about 130 MB of the 256 MB heap: a third scene cannot fit.
    const scenes = [];
    let refused = null;
    for (let i = 0; i < 4 && !refused; ++i) {
      const h = G._gl_peer_scene_create(1, 400, 1);
      if (h) scenes.push(h);
      else refused = G.UTF8ToString(G._gl_last_error());
    }
    assert.match(refused ?? '', /do not fit in the module's memory/);
    assert.ok(scenes.length >= 1, 'one scene of 400 quadrupeds fits');
    assert.equal(G._gl_peer_scene_step(scenes[0], 1), 0, 'the module still steps');
    assert.equal(G._gl_peer_scene_step(scenes[0], 2 ** 31 - 1), -1, 'a step count that would not return is refused');
    for (const h of scenes) G._gl_peer_scene_destroy(h);
    assert.equal(G._gl_peer_scene_create(1, 0, 1), 0);
    assert.match(G.UTF8ToString(G._gl_last_error()), /characters: 0 is outside \[1, 400\]/);
  } finally {
    G.PThread.terminateAllThreads();
  }
});
