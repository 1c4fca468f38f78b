// The module as the page's only judge of gaits (gl_gait_normalize, gl_sim_patch_params), in the
// WASM build under Node: every check a share link's or an imported file's gait gets — each bad
// gait refused with the field named — the migration of older schema versions, and edits as patches refused
// all or nothing with the parameter named. (The link codec itself, without the module, is
// tests/web/share/link.test.ts.)
import assert from 'node:assert/strict';
import fs from 'node:fs';
import { createRequire } from 'node:module';
import path from 'node:path';
import { after, before, describe, it } from 'node:test';
import { fileURLToPath } from 'node:url';

const repoDir = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '../..');
const wasmDir = path.join(repoDir, 'build', 'wasm');
const KIND = { biped: 0, quadruped: 1, box: 2 };
const GL_ERR_INVALID_PARAMS = -4; // native/src/api/c_api.h

let Module;

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

const lastError = () => Module.UTF8ToString(Module._gl_last_error());

/** The module's answer for a gait file's text: { gait } or { error }. */
function normalize(text) {
  const out = withString(text, (p) => Module._gl_gait_normalize(p));
  return out ? { gait: JSON.parse(Module.UTF8ToString(out)) } : { error: lastError() };
}

const preset = (kind) => JSON.parse(Module.UTF8ToString(Module._gl_preset_json(kind)));

/** The biped preset changed by `edit`, as text (JSON.stringify cannot write 1e999: `raw` replaces text). */
function edited(edit, raw = null) {
  const g = preset(KIND.biped);
  edit(g);
  const text = JSON.stringify(g);
  return raw ? text.replace(raw[0], raw[1]) : text;
}

before(async () => {
  const require = createRequire(import.meta.url);
  const createGaitlab = require(path.join(wasmDir, 'gaitlab-node.cjs'));
  Module = await createGaitlab({ wasmBinary: fs.readFileSync(path.join(wasmDir, 'gaitlab-node.wasm')) });
});

after(() => {
  Module?.PThread?.terminateAllThreads();
});

describe('gl_gait_normalize: the gait in a share link or an imported file', () => {
  it('gives the presets back as they are', () => {
    for (const kind of [KIND.biped, KIND.quadruped]) {
      const { gait, error } = normalize(JSON.stringify(preset(kind)));
      assert.equal(error, undefined);
      assert.deepEqual(gait, preset(kind));
    }
  });

  it('keeps meta and writes every value back bit for bit', () => {
    const g = preset(KIND.quadruped);
    g.meta = { author: 'x' };
    const names = Object.keys(g.params);
    // Values with long expansions, inside the bounds: the module's text must read back to the same doubles.
    g.params.period = 0.1 + 0.2 + 0.7000000000000001;
    const { gait } = normalize(JSON.stringify(g));
    assert.deepEqual(gait.meta, { author: 'x' });
    assert.deepEqual(Object.keys(gait.params), names);
    assert.ok(Object.is(gait.params.period, g.params.period));
  });

  it('refuses JSON that is not a gait, naming the field', () => {
    const cases = [
      [edited((g) => (g.format = 'something-else')), /^format: expected "gaitlab-gait"/],
      [edited((g) => (g.character = 'octopus')), /^character: expected "biped" or "quadruped" or "hexapod" or "octopod", got "octopus"/],
      [edited((g) => (g.params = [1, 2])), /^params: expected an object, got an array of 2/],
      [edited((g) => (g.params['no.such.param'] = 1)), /^no\.such\.param: unknown parameter for a biped/],
      [edited((g) => (g.params.period = '0.8')), /^period: expected a number, got a string/],
      [edited((g) => (g.params['legFrame.pitch'] = [0, 0, 0])), /^legFrame\.pitch: expected an array of 4 numbers/],
      [edited((g) => (g.params['legFrame.pitch'] = 0.1)), /^legFrame\.pitch: expected an array of 4 numbers/],
      [edited((g) => delete g.params.period), /^period: missing/],
      [edited((g) => (g.meta = 3)), /^meta: expected an object/],
      [edited((g) => (g.extra = 1)), /^extra: unknown field/],
      ['null', /expected a JSON object, got null/],
      ['3', /expected a JSON object, got a number/],
      ['"gait"', /expected a JSON object, got a string/],
      ['[1]', /expected a JSON object, got an array of 1/],
      ['{"format": "gaitlab-gait", ', /not valid JSON/],
    ];
    for (const [text, message] of cases) {
      const { gait, error } = normalize(text);
      assert.equal(gait, undefined, text.slice(0, 80));
      assert.match(error, message);
    }
  });

  it('refuses values out of bounds, naming the parameter and its bounds', () => {
    assert.equal(normalize(edited((g) => (g.params.period = 7.5))).error, 'period: 7.5 is outside [0.3, 3.0]');
    assert.equal(normalize(edited((g) => (g.params['legFrame.stepHeight'] = [0, 0.1, -0.01, 0]))).error,
      'legFrame.stepHeight[2]: -0.01 is outside [0.0, 0.25]');
  });

  it('refuses values that are not finite', () => {
    // JSON has no infinity; 1e999 is beyond a double's range, which the parser refuses with the number named.
    const text = edited((g) => (g.params.period = 12345.5), ['12345.5', '1e999']);
    assert.match(normalize(text).error, /^not valid JSON: .*number overflow parsing '1e999'/);
  });

  it('refuses a schema version newer than its own, and migrates a schema-1 gait to the current schema', () => {
    assert.match(normalize(edited((g) => (g.version = 15))).error, /^version: expected 1 to 14, got 15/);
    const current = preset(KIND.biped);
    const old = edited((g) => {
      g.version = 1;
      delete g.speed; // speed keys came with schema 4
      delete g.keys;
      delete g.params['gains.swingTargetRate'];
      g.params['legFrame.supportGain'] = 800;
    });
    const { gait, error } = normalize(old);
    assert.equal(error, undefined);
    assert.equal(gait.version, current.version);
    assert.deepEqual(gait.params, { ...current.params, 'gains.swingTargetRate': 0 });
    assert.equal(gait.keys, undefined);
  });
});

describe('gl_sim_patch_params: an edit as a patch', () => {
  let sim;
  before(() => {
    sim = Module._gl_sim_create(1, 1);
  });

  after(() => {
    if (sim) Module._gl_sim_destroy(sim);
  });

  it('changes what it names, or nothing, naming the refused parameter', () => {
    const id = Module._gl_sim_spawn(sim, KIND.biped, 0, 0, 0);
    const params = () => JSON.parse(Module.UTF8ToString(Module._gl_sim_get_params(sim, id))).params;
    const patch = (p) => withString(JSON.stringify(p), (s) => Module._gl_sim_patch_params(sim, id, KIND.biped, s));
    const start = params();
    assert.equal(patch({ period: 1.1 }), 0);
    assert.deepEqual(params(), { ...start, period: 1.1 });
    assert.equal(patch({ period: 0.9, 'left.dutyFactor': 0.95 }), GL_ERR_INVALID_PARAMS);
    assert.equal(lastError(), 'left.dutyFactor: 0.95 is outside [0.2, 0.9]');
    assert.deepEqual(params(), { ...start, period: 1.1 }, 'nothing of a refused patch applies');
  });
});
