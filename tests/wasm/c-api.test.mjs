// The C ABI's contract (native/src/api/c_api.h) in the WASM build under Node: the settings
// structs sit at the offsets the header static_asserts (read from the header here, filled by
// the module's own gl_*_defaults), the module's thread limit is the header's, refusals return
// their failure value with a message, and a simulation's string survives calls on another.
import assert from 'node:assert/strict';
import fs from 'node:fs';
import { createRequire } from 'node:module';
import os from 'node:os';
import path from 'node:path';
import { after, before, describe, it } from 'node:test';
import { fileURLToPath } from 'node:url';

const repoDir = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '../..');
const wasmDir = path.join(repoDir, 'build', 'wasm');
const header = fs.readFileSync(path.join(repoDir, 'native/src/api/c_api.h'), 'utf8');

/** offsetof(struct, field) and sizeof(struct) as the header's static_asserts state them. */
function layout(struct) {
  const offsets = {};
  for (const m of header.matchAll(new RegExp(`offsetof\\(${struct},\\s*(\\w+)\\)\\s*==\\s*(\\d+)`, 'g'))) offsets[m[1]] = Number(m[2]);
  const size = Number(new RegExp(`sizeof\\(${struct}\\)\\s*==\\s*(\\d+)`).exec(header)[1]);
  return { offsets, size };
}

let Module;
const lastError = () => Module.UTF8ToString(Module._gl_last_error());

/** A struct filled by `defaults` (e.g. '_gl_bench_defaults'), read back as int32 / uint32 / float64 views at each field. */
function defaults(struct, fill) {
  const { offsets, size } = layout(struct);
  const p = Module._malloc(size);
  // Poison first, so that a field the library did not write shows.
  Module.HEAPU8.fill(0xa5, p, p + size);
  Module[fill](p);
  const at = (field) => p + offsets[field];
  const read = {
    i32: (field) => Module.HEAP32[at(field) >> 2],
    u32: (field) => Module.HEAPU32[at(field) >> 2],
    f64: (field, i = 0) => Module.HEAPF64[(at(field) >> 3) + i],
  };
  return { p, read, free: () => Module._free(p) };
}

describe('the C ABI contract in WASM', () => {
  before(async () => {
    const require = createRequire(import.meta.url);
    const createGaitlab = require(path.join(wasmDir, 'gaitlab-node.cjs'));
    Module = await createGaitlab({ wasmBinary: fs.readFileSync(path.join(wasmDir, 'gaitlab-node.wasm')) });
  });

  after(() => Module?.PThread?.terminateAllThreads());

  it('has the header\'s thread limit, a pool sized from the cores, and refuses more threads than the pool serves', () => {
    const most = Number(/^#define GL_MAX_THREADS (\d+)$/m.exec(header)[1]);
    assert.equal(Module._gl_max_threads(), most);
    // One worker per core beyond the caller's, at least one (pthread_pool.pre.js.in).
    const pool = Math.min(most, Math.max(2, os.cpus().length));
    assert.equal(Module._gl_pool_threads(), pool);
    assert.equal(Module._gl_default_threads(), Math.min(pool, os.cpus().length));
    const sim = Module._gl_sim_create(pool, 1);
    assert.notEqual(sim, 0, 'the pool starts every thread it serves');
    assert.equal(Module._gl_sim_threads(sim), pool);
    Module._gl_sim_step(sim, 1);
    Module._gl_sim_destroy(sim);
    if (pool < most) {
      // Refused at once, never a hang or an abort: a pthread beyond the pool cannot start.
      assert.equal(Module._gl_sim_create(99, 1), 0, 'clamped to GL_MAX_THREADS, more than the pool serves');
      assert.match(Module.UTF8ToString(Module._gl_last_error()), /^threads: 16 needs 15 pool threads and only \d+ of the module's \d+ are free/);
    }
  });

  it('fills each settings struct at the header\'s offsets', () => {
    const bench = defaults('gl_bench_settings', '_gl_bench_defaults');
    try {
      // sim::PointSpec's defaults: 2 legs, 1 character, 1 thread, serial, 800 steps, 20 runs, 16 shards, seed 1, 4 m, no frames.
      assert.deepEqual(
        ['legs', 'characters', 'threads', 'mode', 'steps', 'runs', 'shards', 'frames'].map(bench.read.i32),
        [2, 1, 1, 0, 800, 20, 16, 0]);
      assert.equal(bench.read.u32('seed'), 1);
      assert.equal(bench.read.f64('spacing'), 4);
    } finally {
      bench.free();
    }
    const opt = defaults('gl_opt_settings', '_gl_opt_defaults');
    assert.deepEqual(['kind', 'method', 'candidates', 'threads'].map(opt.read.i32), [0, 0, 10, 1]);
    assert.equal(opt.read.u32('seed'), 1);
    opt.free();
    const drag = defaults('gl_drag_settings', '_gl_drag_defaults');
    assert.deepEqual(['id', 'segment'].map(drag.read.i32), [-1, 0]);
    assert.deepEqual([0, 1, 2].map((i) => drag.read.f64('local', i)).concat([0, 1, 2].map((i) => drag.read.f64('target', i))), [0, 0, 0, 0, 0, 0]);
    drag.free();
    const thrown = defaults('gl_throw_settings', '_gl_throw_defaults');
    assert.deepEqual([0, 1, 2].map((i) => thrown.read.f64('from', i)), [0, 1, 0]);
    assert.deepEqual([0, 1, 2].map((i) => thrown.read.f64('velocity', i)), [0, 0, 0]);
    assert.equal(thrown.read.f64('half'), 0.12);
    thrown.free();
    const aimed = defaults('gl_throw_at_settings', '_gl_throw_at_defaults');
    assert.deepEqual(['id', 'segment'].map(aimed.read.i32), [-1, 0]);
    assert.deepEqual([0, 1, 2].map((i) => aimed.read.f64('from', i)).concat([0, 1, 2].map((i) => aimed.read.f64('local', i))), [0, 1, 0, 0, 0, 0]);
    assert.deepEqual(['speed', 'half'].map((f) => aimed.read.f64(f)), [14, 0.12]);
    aimed.free();
  });

  it('runs a benchmark point from a settings struct, and refuses one out of range with a message', () => {
    const bench = defaults('gl_bench_settings', '_gl_bench_defaults');
    const { offsets } = layout('gl_bench_settings');
    try {
      Module.HEAP32[(bench.p + offsets.steps) >> 2] = 3;
      Module.HEAP32[(bench.p + offsets.runs) >> 2] = 1;
      Module.HEAP32[(bench.p + offsets.mode) >> 2] = 2;
      Module.HEAP32[(bench.p + offsets.threads) >> 2] = 2;
      const point = JSON.parse(Module.UTF8ToString(Module._gl_bench_point(bench.p)));
      assert.equal(point.steps, 3);
      assert.equal(point.mode, 'full');
      assert.equal(point.threads, 2);
      Module.HEAP32[(bench.p + offsets.shards) >> 2] = 0;
      assert.equal(Module._gl_bench_point(bench.p), 0);
      assert.equal(lastError(), 'shards: 0 is outside [1, 64]');
    } finally {
      bench.free();
    }
  });

  it('refuses with a negative code, NULL or NaN, and names the argument', () => {
    const sim = Module._gl_sim_create(1, 1);
    try {
      assert.equal(Module._gl_sim_step(sim, -1), -1);
      assert.equal(lastError(), 'steps: -1 is outside [0, 12000]');
      assert.equal(Module._gl_sim_set_goal(sim, 42, 1, 0), -3);
      assert.equal(lastError(), 'id: no character has id 42');
      assert.equal(Module._gl_sim_get_params(sim, 42), 0);
      assert.equal(lastError(), 'id: no character has id 42');
      assert.equal(Module._gl_preset_json(7), 0);
      assert.match(lastError(), /^kind: 7 /);
      assert.ok(Number.isNaN(Module._gl_cruise_speed(7)));
      assert.equal(Module._gl_bench_warm_up(3, 1), -1);
      assert.match(lastError(), /^legs: 3 /);
      // A throw at a character: refused for one that does not exist, aimed and thrown at one that does.
      const aimed = defaults('gl_throw_at_settings', '_gl_throw_at_defaults');
      try {
        assert.equal(Module._gl_sim_throw_at(sim, aimed.p), -3);
        assert.equal(lastError(), 'id: no character has id -1');
        const id = Module._gl_sim_spawn(sim, 0, 0, 0, 0);
        Module.HEAP32[(aimed.p + layout('gl_throw_at_settings').offsets.id) >> 2] = id;
        Module.HEAPF64[(aimed.p + layout('gl_throw_at_settings').offsets.from) / 8 + 2] = -8;
        assert.ok(Module._gl_sim_throw_at(sim, aimed.p) >= 0, lastError());
        Module.HEAPF64[(aimed.p + layout('gl_throw_at_settings').offsets.speed) / 8] = NaN;
        assert.equal(Module._gl_sim_throw_at(sim, aimed.p), -1);
        assert.equal(lastError(), 'speed: NaN is not finite');
      } finally {
        aimed.free();
      }
    } finally {
      Module._gl_sim_destroy(sim);
    }
  });

  it('keeps a simulation\'s string through calls on another simulation', () => {
    const a = Module._gl_sim_create(1, 1);
    const b = Module._gl_sim_create(1, 2);
    try {
      Module._gl_sim_demo_scene(a, 2);
      Module._gl_sim_demo_scene(b, 2);
      Module._gl_sim_step(b, 10);
      const pointer = Module._gl_sim_state_hash(a);
      const hash = Module.UTF8ToString(pointer);
      assert.notEqual(Module.UTF8ToString(Module._gl_sim_state_hash(b)), hash);
      Module._gl_sim_get_params(b, 0);
      assert.equal(Module.UTF8ToString(pointer), hash, 'simulation b\'s calls left simulation a\'s string alone');
    } finally {
      Module._gl_sim_destroy(a);
      Module._gl_sim_destroy(b);
    }
  });
});
