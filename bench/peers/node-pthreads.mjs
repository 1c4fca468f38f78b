// Preloaded (`node --import`) into every thread of a Node process that runs the multithreaded
// build of the `jolt-physics` package. Its loader (JoltPhysics.js 1.1.0) decides whether it runs
// in a pthread worker with `await import("node:worker_threads").workerData`, which reads
// `.workerData` of the import's promise (undefined), so in Node a worker never starts its
// pthread and the main thread waits forever for the pool (the process exits with code 13).
// Here each such worker starts it itself. Node 20 also has no `navigator`, which the loader
// reads for the pool's size.
import { isMainThread, workerData } from 'node:worker_threads';
import os from 'node:os';

globalThis.navigator ??= { hardwareConcurrency: os.availableParallelism() };
if (!isMainThread && workerData === 'em-pthread') {
  const jolt = await import('jolt-physics/wasm-multithread');
  jolt.default();
}
