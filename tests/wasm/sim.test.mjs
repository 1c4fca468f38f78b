// The WASM build in Node, with its pthread pool: the C ABI (native/src/api/c_api.h) and the
// render buffer (native/src/sim/render_buffer.h) as the browser uses them.
//
//   node --test tests/wasm
//
// Needs build/wasm/gaitlab-node.{cjs,wasm,worker.js} (npm run build).
import assert from 'node:assert/strict';
import fs from 'node:fs';
import { createRequire } from 'node:module';
import path from 'node:path';
import { after, before, describe, it } from 'node:test';
import { fileURLToPath } from 'node:url';

const repoDir = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '../..');
const wasmDir = path.join(repoDir, 'build', 'wasm');

const STEP = 1 / 120;
const KIND = { biped: 0, quadruped: 1, box: 2 };
// RenderHeader / BodyInfo byte offsets (render_buffer.h static_asserts them).
const H = { seq: 0, front: 4, capacity: 8, infoVersion: 12, bodyCount: 16, stepIndex: 24, simTime: 32, matrices: 48, info: 56 };
const INFO = { size: 24, rgba: 12, owner: 16 };

/** @type {any} */
let Module;

/** Loads the Node build. Emscripten 3.1.6's loader breaks on Node's global fetch: give it the bytes. */
async function loadModule() {
  const require = createRequire(import.meta.url);
  const createGaitlab = require(path.join(wasmDir, 'gaitlab-node.cjs'));
  return createGaitlab({
    wasmBinary: fs.readFileSync(path.join(wasmDir, 'gaitlab-node.wasm')),
    print: (text) => console.log(`[gaitlab] ${text}`),
    printErr: (text) => console.error(`[gaitlab] ${text}`),
  });
}

/** The front frame of a simulation's render buffer (no writer runs concurrently in this test). */
function readFrame(sim) {
  const header = Module._gl_sim_render_buffer(sim);
  assert.ok(header > 0 && header % 8 === 0, `render header address ${header} is 8-aligned`);
  const memory = Module.HEAPU8.buffer;
  const u32 = new Uint32Array(memory);
  const i32 = new Int32Array(memory);
  const f32 = new Float32Array(memory);
  const f64 = new Float64Array(memory);
  const word = (offset) => u32[(header + offset) >> 2];
  const front = word(H.front);
  assert.ok(front === 0 || front === 1, `front is 0 or 1, got ${front}`);
  assert.equal(word(H.seq) % 2, 0, 'no frame is being written between calls');
  const bodyCount = word(H.bodyCount + 4 * front);
  const matrices = (header + word(H.matrices + 4 * front)) >> 2;
  const info = header + word(H.info);
  const bodies = [];
  for (let i = 0; i < bodyCount; i++) {
    const m = f32.subarray(matrices + 16 * i, matrices + 16 * (i + 1));
    const at = info + i * INFO.size;
    bodies.push({
      position: [m[12], m[13], m[14]],
      matrix: Array.from(m),
      halfExtents: Array.from(f32.subarray(at >> 2, (at >> 2) + 3)),
      rgba: u32[(at + INFO.rgba) >> 2],
      owner: i32[(at + INFO.owner) >> 2],
    });
  }
  return {
    capacity: word(H.capacity),
    bodyCount,
    stepIndex: word(H.stepIndex + 4 * front),
    simTime: f64[(header + H.simTime + 8 * front) >> 3],
    bodies,
  };
}

/** A demo-scene simulation stepped `steps` times; returns its handle (destroy it). */
function demo({ threads, seed, steps }) {
  const sim = Module._gl_sim_create(threads, seed);
  assert.ok(sim, 'gl_sim_create returned a simulation');
  Module._gl_sim_demo_scene(sim, 6);
  if (steps > 0) Module._gl_sim_step(sim, steps);
  return sim;
}

const hashOf = (sim) => Module.UTF8ToString(Module._gl_sim_state_hash(sim));

describe('gaitlab WASM module in Node', () => {
  before(async () => {
    Module = await loadModule();
  });

  after(() => {
    // Pool workers keep Node alive: end them (all simulations are destroyed by now).
    Module?.PThread?.terminateAllThreads();
  });

  it('reports a version and uses shared memory', () => {
    assert.match(Module.UTF8ToString(Module._gl_version()), /^\d+\.\d+\.\d+$/);
    assert.ok(Module.HEAPU8.buffer instanceof SharedArrayBuffer, 'memory is a SharedArrayBuffer');
  });

  it('steps the demo scene on 2 threads: time advances, bodies fall and settle', () => {
    const sim = demo({ threads: 2, seed: 1, steps: 0 });
    try {
      Module._gl_sim_step(sim, 0); // publishes the scene as spawned
      assert.equal(Module._gl_sim_threads(sim), 2);
      const start = readFrame(sim);
      const bodies = Module._gl_sim_body_count(sim);
      assert.ok(bodies > 0, 'the demo scene has bodies');
      assert.equal(start.bodyCount, bodies, 'the render buffer holds every body');
      assert.ok(start.capacity >= bodies);
      assert.ok(start.bodies.some((b) => b.owner === -1), 'the demo scene has props');
      assert.ok(start.bodies.some((b) => b.owner >= 0), 'the demo scene has characters');

      Module._gl_sim_step(sim, 240);
      assert.ok(Math.abs(Module._gl_sim_time(sim) - 240 * STEP) < 1e-9, `simTime ${Module._gl_sim_time(sim)} ≈ 2 s`);
      assert.equal(Module._gl_sim_step_index(sim) >>> 0, 240);

      const end = readFrame(sim);
      assert.equal(end.stepIndex, 240);
      assert.ok(Math.abs(end.simTime - 2) < 1e-9);
      assert.equal(end.bodyCount, bodies);
      /** Highest body of each character, by owner id. */
      const top = (frame) => {
        const heights = new Map();
        for (const b of frame.bodies) if (b.owner >= 0) heights.set(b.owner, Math.max(heights.get(b.owner) ?? -Infinity, b.position[1]));
        return heights;
      };
      const topBefore = top(start);
      for (const [owner, height] of top(end)) {
        // A character may stand, walk (its feet swing up) or fall, but not rise as a whole.
        assert.ok(height <= topBefore.get(owner) + 0.1, `character ${owner} did not fly up (top ${topBefore.get(owner)} → ${height})`);
      }
      for (let i = 0; i < bodies; i++) {
        const before = start.bodies[i];
        const after = end.bodies[i];
        const y = after.position[1];
        assert.ok(after.matrix.every(Number.isFinite), `body ${i} has a finite transform`);
        assert.ok(y > -0.5 && y < 3, `body ${i} is above the ground and not launched (y = ${y})`);
        assert.deepEqual(after.halfExtents, before.halfExtents, 'BodyInfo does not change while stepping');
        if (after.owner === -1) {
          // Props are dropped from above the ground and come to rest on it.
          assert.ok(y < before.position[1] - 0.5, `prop ${i} fell (y ${before.position[1]} → ${y})`);
          assert.ok(y < after.halfExtents[1] * 2 + 0.5, `prop ${i} lies near the ground (y = ${y})`);
        }
      }
      // The box scale is baked into the matrices: column lengths are the full extents.
      for (const body of end.bodies) {
        for (let col = 0; col < 3; col++) {
          const [x, y, z] = body.matrix.slice(col * 4, col * 4 + 3);
          assert.ok(Math.abs(Math.hypot(x, y, z) - 2 * body.halfExtents[col]) < 1e-4, 'matrix column = 2 × half extent');
        }
      }
    } finally {
      Module._gl_sim_destroy(sim);
    }
  });

  it('gives bit-identical state for the same seed, whatever the thread count', () => {
    // One at a time: the module's pthread pool is sized from this machine's cores (at least 2
    // threads), and each simulation gives its workers back when destroyed.
    const run = (options) => {
      const sim = demo(options);
      try {
        return hashOf(sim);
      } finally {
        Module._gl_sim_destroy(sim);
      }
    };
    const hash = run({ threads: 2, seed: 7, steps: 240 });
    assert.match(hash, /^[0-9a-f]{16}$/);
    assert.equal(run({ threads: 2, seed: 7, steps: 240 }), hash, 'same seed, same threads');
    assert.equal(run({ threads: 1, seed: 7, steps: 240 }), hash, 'same seed, 1 thread vs 2');
    assert.notEqual(run({ threads: 2, seed: 8, steps: 240 }), hash, 'another seed gives another scene');
  });

  it('gives each kind its cruise speed, the demo start goal (a dog walks slower than a human)', () => {
    assert.equal(Module._gl_cruise_speed(KIND.biped), 1.0);
    assert.equal(Module._gl_cruise_speed(KIND.quadruped), 0.4);
    // Not a character: refused, NaN (c_api.h's rule for doubles), with a message naming the kind.
    assert.ok(Number.isNaN(Module._gl_cruise_speed(KIND.box)));
    assert.match(Module.UTF8ToString(Module._gl_last_error()), /^kind: 2 /);
  });

  it('gives each kind the top of its preset gait: its fastest speed key, as the preset file says', () => {
    for (const [name, kind] of [['biped', KIND.biped], ['quadruped', KIND.quadruped]]) {
      const preset = JSON.parse(fs.readFileSync(path.join(repoDir, `public/presets/${name}.json`), 'utf8'));
      const speeds = [preset.speed ?? 0, ...(preset.keys ?? []).map((k) => k.speed)];
      assert.equal(Module._gl_top_speed(kind), Math.max(...speeds), name);
      assert.ok(Module._gl_top_speed(kind) > Module._gl_cruise_speed(kind), name);
    }
    assert.ok(Number.isNaN(Module._gl_top_speed(KIND.box)));
    assert.match(Module.UTF8ToString(Module._gl_last_error()), /^kind: 2 /);
  });

  it('spawns single things and refuses unknown kinds', () => {
    const sim = Module._gl_sim_create(1, 3);
    try {
      assert.equal(Module._gl_sim_body_count(sim), 0);
      assert.ok(Module._gl_sim_spawn(sim, KIND.box, 1, 2, 0.5) >= 0);
      assert.equal(Module._gl_sim_body_count(sim), 1);
      assert.ok(Module._gl_sim_spawn(sim, KIND.biped, -2, 0, 0) >= 0);
      assert.ok(Module._gl_sim_body_count(sim) > 1);
      assert.equal(Module._gl_sim_spawn(sim, 99, 0, 0, 0), -1, 'GL_ERR_ARGUMENT');
      Module._gl_sim_step(sim, 1);
      const frame = readFrame(sim);
      assert.equal(frame.bodyCount, Module._gl_sim_body_count(sim));
      const box = frame.bodies[0];
      assert.equal(box.owner, -1);
      assert.ok(Math.abs(box.position[0] - 1) < 1e-3 && Math.abs(box.position[2] - 2) < 1e-3, 'the box is where it was spawned');
    } finally {
      Module._gl_sim_destroy(sim);
    }
  });
});
