// Terrain in the WASM build: `walk --terrain` natively and as WebAssembly walks on the same
// ground (bit-identical samples: terrain_hash), refuses an unknown terrain alike, and the C API
// hands the page the samples the physics collides with.
//
//   node --test tests/wasm
//
// Needs build/native/gaitlab and build/wasm/gaitlab-node.{cjs,wasm,worker.js} (npm run build).
import assert from 'node:assert/strict';
import { spawnSync } from 'node:child_process';
import fs from 'node:fs';
import { createRequire } from 'node:module';
import path from 'node:path';
import { after, before, describe, it } from 'node:test';
import { fileURLToPath } from 'node:url';

const root = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '../..');
const native = path.join(root, 'build/native/gaitlab');
const builds = [['native', native, []], ['wasm', process.execPath, ['bench/wasm.mjs']]];

function run(cmd, args) {
  const r = spawnSync(cmd, args, { cwd: root, encoding: 'utf8', timeout: 180_000 });
  return { status: r.status, stdout: r.stdout, stderr: r.stderr };
}

describe('gaitlab walk --terrain', () => {
  for (const terrain of ['slope', 'bumps']) {
    it(`${terrain}: the same JSON document on the same ground natively and as WASM`, () => {
      const args = ['walk', '--character', 'biped', '--terrain', terrain, '--seconds', '1', '--seed', '3', '--json'];
      const [a, b] = builds.map(([, cmd, pre]) => run(cmd, [...pre, ...args]));
      assert.equal(a.status, 0, a.stderr);
      assert.equal(b.status, 0, b.stderr);
      const ja = JSON.parse(a.stdout);
      const jb = JSON.parse(b.stdout);
      assert.deepEqual(Object.keys(ja).sort(), Object.keys(jb).sort());
      assert.equal(ja.terrain, terrain);
      assert.equal(jb.terrain, terrain);
      // The same samples, bit for bit (no libm in the terrain's formulas). The walk itself may
      // part by rounding, as on flat ground (sin/cos differ between glibc and Emscripten's libc).
      assert.match(ja.terrain_hash, /^[0-9a-f]{16}$/);
      assert.equal(jb.terrain_hash, ja.terrain_hash);
      for (const j of [ja, jb]) assert.equal(j.seconds, j.fell ? j.fall_time_s : 1);
    });
  }

  it('the bumps follow the seed; flat is the default and reported', () => {
    const hash = (extra) => JSON.parse(run(native, ['walk', '--seconds', '0.05', '--json', ...extra]).stdout);
    const flat = hash([]);
    assert.equal(flat.terrain, 'flat');
    assert.notEqual(hash(['--terrain', 'bumps', '--seed', '1']).terrain_hash, hash(['--terrain', 'bumps', '--seed', '2']).terrain_hash);
    assert.equal(hash(['--terrain', 'bumps', '--seed', '2']).terrain_hash, hash(['--terrain', 'bumps', '--seed', '2']).terrain_hash);
    assert.equal(hash(['--terrain', 'flat']).state_hash, flat.state_hash);
  });

  it('refuses an unknown terrain with a usage error, natively and as WASM', () => {
    for (const [name, cmd, pre] of builds) {
      const r = run(cmd, [...pre, 'walk', '--terrain', 'ice']);
      assert.equal(r.status, 2, name);
      assert.match(r.stderr, /--terrain: 'ice' is not flat, slope or bumps/, name);
      assert.equal(r.stdout, '', name);
    }
  });
});

describe('terrain through the C API (WASM)', () => {
  /** @type {any} */
  let Module;
  before(async () => {
    const require = createRequire(import.meta.url);
    const createGaitlab = require(path.join(root, 'build/wasm/gaitlab-node.cjs'));
    Module = await createGaitlab({ wasmBinary: fs.readFileSync(path.join(root, 'build/wasm/gaitlab-node.wasm')) });
  });
  after(() => Module?.PThread?.terminateAllThreads());

  it('gives the samples the ray casts hit, for the renderer to draw', () => {
    const sim = Module._gl_sim_create(1, 4);
    try {
      assert.equal(Module._gl_sim_set_terrain(sim, 9), -1, 'unknown kind refused');
      assert.equal(Module._gl_sim_terrain_heights(sim), 0, 'flat: no samples');
      const id = Module._gl_sim_spawn(sim, 0, 1.2, 0.7, 0);
      assert.equal(Module._gl_sim_set_terrain(sim, 2), 0);
      const out = Module._malloc(7 * 8);
      Module._gl_sim_terrain_grid(sim, out);
      const [kind, columns, rows, spacing, originX, originZ, plane] = Module.HEAPF64.slice(out >> 3, (out >> 3) + 7);
      Module._free(out);
      assert.equal(kind, 2);
      assert.equal(columns, 1921);
      assert.equal(rows, 1921);
      assert.equal(spacing, 0.125);
      assert.equal(originX, -120);
      const heights = new Float32Array(Module.HEAPU8.buffer, Module._gl_sim_terrain_heights(sim), columns * rows);
      // Drawn as the page draws it (web/src/sim/terrain-grid.ts): each cell's two triangles.
      const drawn = (x, z) => {
        const u = (x - originX) / spacing, v = (z - originZ) / spacing;
        const c = Math.floor(u), r = Math.floor(v), fx = u - c, fz = v - r;
        const at = (cc, rr) => heights[rr * columns + cc];
        return fx + fz <= 1
          ? at(c, r) + fx * (at(c + 1, r) - at(c, r)) + fz * (at(c, r + 1) - at(c, r))
          : at(c + 1, r + 1) + (1 - fx) * (at(c, r + 1) - at(c + 1, r + 1)) + (1 - fz) * (at(c + 1, r) - at(c + 1, r + 1));
      };
      for (let i = 0; i < 200; i++) {
        const x = Math.sin(i * 12.9898) * 40, z = Math.cos(i * 78.233) * 40;
        assert.ok(Math.abs(Module._gl_sim_ground_height(sim, x, z) - drawn(x, z)) < 3e-5, `(${x.toFixed(2)}, ${z.toFixed(2)})`);
      }
      assert.ok(Math.abs(Module._gl_sim_ground_height(sim, 300, 0) - plane) < 3e-5, 'the plane beyond the grid');
      // The character was re-placed standing on the new ground (its leg frame's rest height is
      // 1.17 m) and keeps its id.
      assert.equal(Module._gl_sim_character_count(sim), 1);
      const info = Module._malloc(12 * 8);
      Module._gl_sim_character_info(sim, info, 1);
      const [cid, , x, y, z] = Module.HEAPF64.slice(info >> 3, (info >> 3) + 5);
      Module._free(info);
      assert.equal(cid, id);
      const above = y - drawn(x, z);
      assert.ok(above > 1.12 && above < 1.22, `its leg frame stands ${above.toFixed(3)} m above the bumps`);
      Module._gl_sim_step(sim, 12);
    } finally {
      Module._gl_sim_destroy(sim);
    }
  });
});
