// Thread counts above the cores in the WASM build: a module whose pthread pool is sized for 16
// threads (the loader's `poolThreads`, native/src/api/pthread_pool.pre.js.in) on a machine with
// fewer cores computes the same crowd, bit for bit, on every thread count and in every mode
// (docs/parallel.md: the thread count only decides which thread steps which shard).
//
//   node --test tests/wasm/threads.test.mjs
//
// Needs build/wasm/gaitlab-node.{cjs,wasm,worker.js} (npm run build).
import assert from 'node:assert/strict';
import fs from 'node:fs';
import { createRequire } from 'node:module';
import path from 'node:path';
import { after, before, describe, it } from 'node:test';
import { fileURLToPath } from 'node:url';

const wasmDir = path.join(path.resolve(path.dirname(fileURLToPath(import.meta.url)), '../..'), 'build', 'wasm');
const THREADS = [1, 2, 3, 8, 16];
// gl_bench_settings (c_api.h's static_asserts): i32 legs, characters, threads, mode, steps, runs,
// shards, u32 seed, f64 spacing, i32 frames; 48 bytes.
const B = { legs: 0, characters: 4, threads: 8, mode: 12, steps: 16, runs: 20, shards: 24, size: 48 };
const MODE = { serial: 0, controller: 1, full: 2 };
const LEGS_MIXED = 0;

/** @type {any} */
let Module;

describe('thread counts above the cores (WASM)', () => {
  before(async () => {
    const createGaitlab = createRequire(import.meta.url)(path.join(wasmDir, 'gaitlab-node.cjs'));
    Module = await createGaitlab({ wasmBinary: fs.readFileSync(path.join(wasmDir, 'gaitlab-node.wasm')), poolThreads: 16 });
  });
  after(() => Module?.PThread?.terminateAllThreads());

  it('sizes its pool from the loader\'s poolThreads', () => {
    assert.equal(Module._gl_pool_threads(), 16);
    assert.equal(Module.PThread.unusedWorkers.length, 15);
  });

  it('gives one state hash for a sharded crowd in every mode on 1, 2, 3, 8 and 16 threads', () => {
    const b = Module._malloc(B.size);
    const hashes = new Map();
    try {
      for (const [mode, code] of Object.entries(MODE)) {
        for (const threads of mode === 'serial' ? [1] : THREADS) {
          Module._gl_bench_defaults(b);
          const set = (field, value) => { Module.HEAP32[(b + B[field]) >> 2] = value; };
          set('legs', LEGS_MIXED);
          set('characters', 7);
          set('threads', threads);
          set('mode', code);
          set('steps', 60);
          set('runs', 1);
          set('shards', 3);
          const text = Module._gl_bench_point(b);
          assert.notEqual(text, 0, Module.UTF8ToString(Module._gl_last_error()));
          const point = JSON.parse(Module.UTF8ToString(text));
          assert.equal(point.threads, threads);
          assert.equal(point.shards, 3);
          hashes.set(`${mode} on ${threads}`, point.state_hash);
        }
      }
    } finally {
      Module._free(b);
    }
    const reference = hashes.get('serial on 1');
    assert.match(reference, /^[0-9a-f]{16}$/);
    for (const [run, hash] of hashes) assert.equal(hash, reference, run);
  });

  it('gives one state hash for the demo scene with thrown boxes on 1, 2, 3, 8 and 16 threads', () => {
    const hashes = THREADS.map((threads) => {
      const sim = Module._gl_sim_create(threads, 3);
      assert.notEqual(sim, 0, Module.UTF8ToString(Module._gl_last_error()));
      try {
        assert.equal(Module._gl_sim_threads(sim), threads);
        Module._gl_sim_demo_scene(sim, 6);
        Module._gl_sim_spawn(sim, 2, 0.5, 0.2, 0.3);
        Module._gl_sim_step(sim, 60);
        return Module.UTF8ToString(Module._gl_sim_state_hash(sim));
      } finally {
        Module._gl_sim_destroy(sim);
      }
    });
    assert.deepEqual(hashes, THREADS.map(() => hashes[0]));
  });
});
