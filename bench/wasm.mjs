#!/usr/bin/env node
// Runs the gaitlab CLI compiled to WebAssembly under Node: `node bench/wasm.mjs walk ...` takes
// the same arguments and prints the same JSON as build/native/gaitlab, so native and WASM can be
// compared in one run (docs/design.md, contracts).
import { createRequire } from 'node:module';
import { readFileSync, existsSync } from 'node:fs';
import { fileURLToPath } from 'node:url';
import path from 'node:path';
import os from 'node:os';

const root = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '..');
const js = path.join(root, 'build/wasm/gaitlab-node.cjs');
const wasm = path.join(root, 'build/wasm/gaitlab-node.wasm');
if (!existsSync(js) || !existsSync(wasm)) {
  console.error('gaitlab: the WebAssembly build is missing (build/wasm); run `npm run build` first');
  process.exit(1);
}
const createGaitlab = createRequire(import.meta.url)(js);
// The module's pthread pool is sized when it loads, from the cores (native/src/api/
// pthread_pool.pre.js.in); a `--threads` asking for more (a list of counts for `bench`, one for
// `optimize`) sizes it for those, so that the CLI accepts here what it accepts natively (up to
// GL_MAX_THREADS; the CLI refuses more).
const args = process.argv.slice(2);
const at = args.indexOf('--threads');
const asked = at >= 0 ? Math.max(0, ...(args[at + 1] ?? '').split(/[^0-9]+/).filter(Boolean).map(Number)) : 0;
const poolThreads = Math.max(os.availableParallelism(), asked);
// Emscripten 3.1.6's loader breaks on Node's global fetch: hand it the binary instead.
const Module = await createGaitlab({ wasmBinary: readFileSync(wasm), noExitRuntime: true, poolThreads });
let status;
try {
  status = Module.callMain(args);
} catch (e) {
  status = typeof e?.status === 'number' ? e.status : 1;
  if (typeof e?.status !== 'number') console.error(e);
}
Module.PThread.terminateAllThreads();
process.exit(status ?? 0);
