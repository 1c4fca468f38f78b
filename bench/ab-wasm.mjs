#!/usr/bin/env node
// Two WebAssembly builds compared in one Node process: each steps its own crowd (the same crowd:
// same characters, same places, same goals) on one thread, 20 fixed steps at a time, the builds
// taking turns. Whatever else the machine does then slows both alike, which makes differences of
// a few per cent visible on a shared machine where separate runs vary by 15 %.
//
//   node bench/ab-wasm.mjs OLD_DIR [NEW_DIR=build/wasm] [LEGS=2] [CHARACTERS=100] [TURNS=60]
//
// A build directory holds gaitlab-node.cjs and gaitlab-node.wasm (`ninja -C DIR gaitlab_node`;
// copy them aside before rebuilding to keep the old one). Prints each build's median and least
// time per step, the state hashes after the same number of steps (equal when the builds compute
// the same), and the median over turns of new/old.
import { createRequire } from 'node:module';
import { existsSync, readFileSync } from 'node:fs';
import path from 'node:path';
import { fileURLToPath } from 'node:url';

const root = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '..');
const [oldDir, newDir = path.join(root, 'build/wasm'), legs = '2', characters = '100', turns = '60'] = process.argv.slice(2);
if (!oldDir || !['2', '4'].includes(legs) || !(+characters >= 1) || !(+turns >= 1)) {
  console.error('usage: node bench/ab-wasm.mjs OLD_DIR [NEW_DIR=build/wasm] [LEGS=2|4] [CHARACTERS=100] [TURNS=60]');
  process.exit(2);
}
const require = createRequire(import.meta.url);
const STEPS_PER_TURN = 20, SPACING = 4;

async function load(dir) {
  const js = path.resolve(dir, 'gaitlab-node.cjs'), wasm = path.resolve(dir, 'gaitlab-node.wasm');
  if (!existsSync(js) || !existsSync(wasm)) throw new Error(`${dir}: no gaitlab-node.cjs and gaitlab-node.wasm`);
  const M = await require(js)({ wasmBinary: readFileSync(wasm), noExitRuntime: true });
  const sim = M._gl_sim_create(1, 1);
  const kind = legs === '4' ? 1 : 0;
  const side = Math.ceil(Math.sqrt(+characters));
  for (let i = 0; i < +characters; i++) {
    const id = M._gl_sim_spawn(sim, kind, (i % side) * SPACING, Math.floor(i / side) * SPACING, 0);
    M._gl_sim_set_goal(sim, id, M._gl_cruise_speed(kind), 0);
  }
  M._gl_sim_step(sim, 120);  // untimed: V8's optimising tier, the crowd under way
  return { dir, M, sim, ms: [] };
}

const builds = [await load(oldDir), await load(newDir)];
for (let t = 0; t < +turns; t++) {
  // Alternate who goes first, so that neither always follows the other.
  for (const b of t % 2 ? [...builds].reverse() : builds) {
    const t0 = performance.now();
    b.M._gl_sim_step(b.sim, STEPS_PER_TURN);
    b.ms.push((performance.now() - t0) / STEPS_PER_TURN);
  }
}
const median = (a) => [...a].sort((x, y) => x - y)[a.length >> 1];
for (const [name, b] of [['old', builds[0]], ['new', builds[1]]]) {
  console.log(`${name} ${b.dir}: median ${median(b.ms).toFixed(3)} ms/step, least ${Math.min(...b.ms).toFixed(3)}, state hash ${b.M.UTF8ToString(b.M._gl_sim_state_hash(b.sim))}`);
}
console.log(`new/old, median over ${turns} turns: ${median(builds[1].ms.map((x, i) => x / builds[0].ms[i])).toFixed(3)}`);
for (const b of builds) b.M.PThread.terminateAllThreads();
process.exit(0);
