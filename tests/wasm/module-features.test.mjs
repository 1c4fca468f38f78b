// The browser module is threaded WebAssembly with SIMD (foundation issue): it imports a shared
// memory (what pthreads need) and its code uses 128-bit SIMD instructions (-msimd128).
// Read with binaryen's wasm-dis, which Debian's emscripten package brings.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { spawnSync } from 'node:child_process';
import { fileURLToPath } from 'node:url';
import path from 'node:path';

const root = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '../..');

for (const file of ['build/wasm/gaitlab.wasm', 'build/wasm/gaitlab-node.wasm']) {
  test(`${file} imports a shared memory and uses SIMD`, () => {
    const r = spawnSync('wasm-dis', [path.join(root, file)], {
      encoding: 'utf8', maxBuffer: 1 << 30, timeout: 120_000,
    });
    assert.equal(r.status, 0, r.stderr);
    assert.match(r.stdout, /\(import "[^"]*" "[^"]*" \(memory \$\S+ \(shared \d+ \d+\)\)\)/);
    const simd = r.stdout.match(/\b(v128|[if](8|16|32|64)x\d+)\.\w+/g) ?? [];
    assert.ok(simd.length > 100, `only ${simd.length} SIMD instructions`);
  });
}
