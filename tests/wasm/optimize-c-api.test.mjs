// The C API's generation-at-a-time search (gl_opt_*) driven from JavaScript the way the optimize
// panel's worker drives it (web/src/optimize/optimizer.worker.ts), in the WASM module under
// Node with its thread pool; and the settings table the panel checks its form against
// (gl_opt_settings_json).
import assert from 'node:assert/strict';
import fs from 'node:fs';
import { createRequire } from 'node:module';
import path from 'node:path';
import { after, before, describe, it } from 'node:test';
import { fileURLToPath } from 'node:url';

const repoDir = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '../..');
const wasmDir = path.join(repoDir, 'build', 'wasm');
const KIND = { biped: 0, quadruped: 1, box: 2 };

let Module;

/** A copy of `text` in module memory (free it). */
function cString(text) {
  const bytes = Module.lengthBytesUTF8(text) + 1;
  const pointer = Module._malloc(bytes);
  Module.stringToUTF8(text, pointer, bytes);
  return pointer;
}

/** gl_opt_settings's fields (c_api.h static_asserts the offsets; tests/wasm/c-api.test.mjs reads them from there). */
const OPT = { kind: 0, method: 4, candidates: 8, threads: 12, seed: 16, size: 20 };

/** gl_opt_create with JS values, the search's settings struct from gl_opt_defaults; returns the handle (0 on refusal). */
function create({ kind = KIND.biped, method = 0, candidates = 3, seed = 1, threads = 2, start = null, settings = null }) {
  const o = Module._malloc(OPT.size);
  Module._gl_opt_defaults(o);
  Module.HEAP32[(o + OPT.kind) >> 2] = kind;
  Module.HEAP32[(o + OPT.method) >> 2] = method;
  Module.HEAP32[(o + OPT.candidates) >> 2] = candidates;
  Module.HEAP32[(o + OPT.threads) >> 2] = threads;
  Module.HEAPU32[(o + OPT.seed) >> 2] = seed;
  const s = settings === null ? 0 : cString(JSON.stringify(settings));
  const p = start === null ? 0 : cString(start);
  try {
    return Module._gl_opt_create(o, p, s);
  } finally {
    Module._free(o);
    if (s) Module._free(s);
    if (p) Module._free(p);
  }
}

const lastError = () => Module.UTF8ToString(Module._gl_last_error());

describe('gl_opt_* from JavaScript', () => {
  before(async () => {
    const require = createRequire(import.meta.url);
    const createGaitlab = require(path.join(wasmDir, 'gaitlab-node.cjs'));
    Module = await createGaitlab({ wasmBinary: fs.readFileSync(path.join(wasmDir, 'gaitlab-node.wasm')) });
  });

  after(() => {
    Module?.PThread?.terminateAllThreads();
  });

  it('describes every objective setting with bounds and a default that gl_opt_create accepts', () => {
    const table = JSON.parse(Module.UTF8ToString(Module._gl_opt_settings_json()));
    assert.ok(table.settings.length >= 10);
    for (const s of table.settings) {
      assert.ok(s.min <= s.default && s.default <= s.max, JSON.stringify(s));
      assert.equal(typeof s.description, 'string');
      const opt = create({ candidates: 2, settings: { [s.name]: s.default } });
      assert.ok(opt, `${s.name}: ${opt ? '' : lastError()}`);
      Module._gl_opt_destroy(opt);
      // Just outside its bounds it is refused, naming the setting.
      assert.equal(create({ candidates: 2, settings: { [s.name]: s.max + 1 } }), 0);
      assert.match(lastError(), new RegExp(`^${s.name}: `));
    }
    assert.deepEqual(table.speeds.default, [1]);
    assert.equal(create({ settings: { speeds: [table.speeds.max + 1] } }), 0);
    assert.match(lastError(), /speeds: .* is outside/);
  });

  it('runs generations, each best no worse than the last, and gives the best as a gait file', () => {
    const start = Module.UTF8ToString(Module._gl_preset_json(KIND.quadruped));
    const opt = create({ kind: KIND.quadruped, seed: 4, start, settings: { seconds: 0.5, warmup: 0, speeds: [0.8] } });
    assert.ok(opt, lastError());
    const bests = [];
    for (let g = 0; g < 3; g++) bests.push(Module._gl_opt_step(opt));
    assert.ok(bests.every((b, i) => Number.isFinite(b) && (i === 0 || b <= bests[i - 1])), bests.join(', '));
    assert.equal(Module._gl_opt_generation(opt), 3);
    assert.equal(Module._gl_opt_evaluations(opt), 9);
    const best = JSON.parse(Module.UTF8ToString(Module._gl_opt_best_json(opt)));
    assert.equal(best.format, 'gaitlab-gait');
    assert.equal(best.character, 'quadruped');
    assert.equal(best.meta.objective, bests[2]);
    assert.equal(best.meta.seed, 4);
    Module._gl_opt_destroy(opt);
  });
});
