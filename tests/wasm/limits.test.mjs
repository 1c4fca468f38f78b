// The limits in the WebAssembly build under Node (native/src/api/limits.h, sim/capacity.h): a
// gait nested thousands deep or far too long is refused (it threw RangeError or ran the module
// out of memory before), NaN and huge numbers are refused at the ABI and never reach a
// character, the heap's room is counted from real memory (a spawn costs no more than it is
// charged, and the module refuses before its fixed heap runs out instead of aborting), and a
// second simulation that needs more of the fixed pthread pool than is free is refused, not
// aborted. Random ABI calls with hostile arguments each return a result or a refusal.
import assert from 'node:assert/strict';
import fs from 'node:fs';
import { createRequire } from 'node:module';
import path from 'node:path';
import { after, before, describe, it } from 'node:test';
import { fileURLToPath } from 'node:url';

const repoDir = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '../..');
const wasmDir = path.join(repoDir, 'build', 'wasm');
const KIND = { biped: 0, quadruped: 1, box: 2 };
const ERR = { argument: -1, full: -5 };
// GL_INFO_FIELDS, counted from the header's enum (a field added there grows every record).
const header = fs.readFileSync(path.join(repoDir, 'native/src/api/c_api.h'), 'utf8');
const INFO_FIELDS = /enum \{\s*(GL_INFO_ID[\s\S]*?)GL_INFO_FIELDS/.exec(header)[1]
  .replace(/\/\/.*$/gm, '').split(',').map((name) => name.trim()).filter((name) => name !== '').length;

// The costs sim/capacity.h charges, read from the header so the test follows it.
const capacity = fs.readFileSync(path.join(repoDir, 'native/src/sim/capacity.h'), 'utf8');
const bytesOf = (name) => Function(`return ${new RegExp(`${name} = ([^;]+);`).exec(capacity)[1]}`)();
const COST = { [KIND.biped]: bytesOf('kBipedBytes'), [KIND.quadruped]: bytesOf('kQuadrupedBytes'), [KIND.box]: bytesOf('kBoxBytes') };

let Module;
const lastError = () => Module.UTF8ToString(Module._gl_last_error());

function withString(text, call) {
  const bytes = Module.lengthBytesUTF8(text) + 1;
  const pointer = Module._malloc(bytes);
  Module.stringToUTF8(text, pointer, bytes);
  try {
    return call(pointer);
  } finally {
    Module._free(pointer);
  }
}

function infos(sim) {
  const n = Module._gl_sim_character_count(sim);
  const p = Module._malloc(Math.max(1, n) * INFO_FIELDS * 8);
  Module._gl_sim_character_info(sim, p, n);
  const out = Array.from(new Float64Array(Module.HEAPF64.buffer, p, n * INFO_FIELDS));
  Module._free(p);
  return out;
}

before(async () => {
  const require = createRequire(import.meta.url);
  const createGaitlab = require(path.join(wasmDir, 'gaitlab-node.cjs'));
  Module = await createGaitlab({ wasmBinary: fs.readFileSync(path.join(wasmDir, 'gaitlab-node.wasm')) });
});

after(() => {
  Module?.PThread?.terminateAllThreads();
});

describe('gait files in WebAssembly', () => {
  it('refuses deep and huge gaits with a message, and goes on working', () => {
    const preset = Module.UTF8ToString(Module._gl_preset_json(KIND.biped));
    for (const field of ['format', 'version', 'character', 'params', 'meta']) {
      const deep = preset.replace(/^\{/, `{"${field}":${'['.repeat(100000)}${']'.repeat(100000)},`);
      assert.equal(withString(deep, (p) => Module._gl_gait_normalize(p)), 0, field);
      assert.match(lastError(), /nested deeper than 16 levels/);
    }
    // 50 MB aborted the module (out of memory) before: now refused after a look at its length.
    const huge = preset + ' '.repeat(50 << 20);
    assert.equal(withString(huge, (p) => Module._gl_gait_normalize(p)), 0);
    assert.match(lastError(), /bytes long; at most 262144/);
    assert.notEqual(withString(preset, (p) => Module._gl_gait_normalize(p)), 0);
  });
});

describe('the C ABI in WebAssembly', () => {
  it('refuses NaN and huge numbers naming them, and never leaves a character that is not finite', () => {
    const sim = Module._gl_sim_create(1, 5);
    assert.equal(Module._gl_sim_add_characters(sim, 3, 2), 2);
    assert.equal(Module._gl_sim_set_goal(sim, -1, NaN, 0), ERR.argument);
    assert.match(lastError(), /^goal speed: NaN is not finite/);
    assert.equal(Module._gl_sim_spawn(sim, KIND.box, Infinity, 0, 0), ERR.argument);
    assert.match(lastError(), /^x: Infinity/);
    // Random calls, hostile arguments: a result or a refusal each, and every character finite.
    let seed = 12345;
    const next = () => ((seed = (Math.imul(seed, 1103515245) + 12345) >>> 0) / 4294967296);
    const specials = [NaN, Infinity, -Infinity, 1e300, -1e300, 1e9, -1, 0, 2 ** 31, 6];
    const num = () => (next() < 0.4 ? specials[Math.floor(next() * specials.length)] : next() * 8 - 4);
    for (let i = 0; i < 300; i++) {
      const info = infos(sim);
      const id = info.length && next() < 0.8 ? info[Math.floor(next() * (info.length / INFO_FIELDS)) * INFO_FIELDS] : Math.floor(num());
      let r;
      switch (Math.floor(next() * 6)) {
        case 0: r = Module._gl_sim_set_goal(sim, id, num(), num()); break;
        case 1: r = Module._gl_sim_spawn(sim, Math.floor(next() * 4), num(), num(), num()); break;
        case 2: r = Module._gl_sim_step(sim, next() < 0.5 ? 2 : Math.floor(num())); break;
        case 3: r = Module._gl_sim_set_auto_reset(sim, num()); break;
        case 4: r = Module._gl_sim_room(sim, Math.floor(num())); break;
        default: r = Module._gl_sim_reset_character(sim, id); break;
      }
      if (r < 0) assert.ok(lastError().length > 0);
      for (const v of infos(sim)) assert.ok(Number.isFinite(v), `call ${i}`);
      if (Module._gl_sim_character_count(sim) > 8) Module._gl_sim_remove_character(sim, infos(sim)[0]);
    }
    Module._gl_sim_destroy(sim);
  });

  it('charges each character at least the heap it really takes', () => {
    // The benchmark's own measurement (gl_bench_point, memory.scene_heap_bytes): a crowd of 21
    // against a crowd of 1, after 2 s of walking.
    const sceneHeap = (legs, characters) => {
      const p = Module._malloc(48);
      Module._gl_bench_defaults(p);
      const i32 = new Int32Array(Module.HEAP32.buffer, p, 12);
      Object.assign(i32, { 0: legs, 1: characters, 2: 1, 3: 0, 4: 240, 5: 1, 6: 1 });
      const text = Module.UTF8ToString(Module._gl_bench_point(p));
      Module._free(p);
      return JSON.parse(text).memory.scene_heap_bytes;
    };
    for (const [legs, kind] of [[2, KIND.biped], [4, KIND.quadruped]]) {
      const each = (sceneHeap(legs, 21) - sceneHeap(legs, 1)) / 20;
      assert.ok(each > 0 && each <= COST[kind], `a character of ${legs} legs takes ${each} bytes, charged ${COST[kind]}`);
    }
  });

  it('fills the heap to the room it states, then refuses with the reason instead of aborting', () => {
    // The benchmark never promises a crowd that a new simulation could not hold.
    const promised = Module._gl_bench_max_characters(2);
    const sim = Module._gl_sim_create(1, 2);
    const room = Module._gl_sim_room(sim, KIND.biped);
    assert.ok(room > 100 && room < 2000, `room ${room}`);
    assert.ok(promised > 0 && promised <= room, `promised ${promised}, room ${room}`);
    let added = 0;
    for (let n; (n = Module._gl_sim_add_characters(sim, KIND.biped, 64)) > 0;) added += n;
    // gl_sim_room is an estimate from the heap left now; the solver pools' old copies make the
    // last few hundred cost more than that, or less once big freed blocks are reused (README,
    // "Limits"): each spawn checks again.
    assert.ok(added > 100, `added ${added}, room ${room}`);
    assert.equal(Module._gl_sim_room(sim, KIND.biped), 0);
    assert.equal(Module._gl_sim_spawn(sim, KIND.biped, 0, 0, 0), ERR.full);
    assert.match(lastError(), /^no room: /);
    Module._gl_sim_step(sim, 2); // the reserve still covers a step of a full scene
    Module._gl_sim_destroy(sim);
  });

  it('refuses a simulation that needs more of the pthread pool than is free', () => {
    const a = Module._gl_sim_create(Module._gl_pool_threads(), 1); // every worker of the pool
    assert.notEqual(a, 0);
    assert.equal(Module._gl_sim_create(2, 1), 0);
    assert.match(lastError(), /^threads: 2 needs 1 pool threads and only 0/);
    Module._gl_sim_step(a, 2);
    Module._gl_sim_destroy(a);
    const b = Module._gl_sim_create(2, 1);
    assert.notEqual(b, 0);
    Module._gl_sim_destroy(b);
  });
});
