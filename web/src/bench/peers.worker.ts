// The peer benchmark's worker: loads gaitlab's WASM module and the two builds of the jolt-physics
// package (its SIMD multithreaded build and its default build), then measures point by point with
// the code the Node benchmark runs (bench/peers/comparison.mjs), so that Chromium and Node time
// the same thing. Like the benchmark worker it is the modules' "main thread": a point blocks it
// while the modules' own thread pools work.
import { describePoint, measurePoint, peerEngines, peerGrid, warmUp } from '../../../bench/peers/comparison.mjs';
import { loadGaitlab } from '../sim/gaitlab-wasm';
import type { PeersCommand, PeersEvent } from './peers-protocol';

interface WorkerScope {
  postMessage(message: PeersEvent): void;
  onmessage: ((event: MessageEvent<PeersCommand>) => void) | null;
}
const scope = self as unknown as WorkerScope;
const post = (event: PeersEvent) => scope.postMessage(event);
let cancelled = false;

/** An Emscripten ES6 factory served as it is (not bundled: it finds its .wasm beside itself). */
async function loadFactory(url: string): Promise<unknown> {
  const glue = (await import(/* @vite-ignore */ url)) as { default: () => Promise<unknown> };
  return glue.default();
}

async function run(command: Extract<PeersCommand, { type: 'run' }>): Promise<void> {
  if (!crossOriginIsolated) throw new Error('the page is not cross-origin isolated: no WASM threads');
  post({ type: 'status', message: 'loading gaitlab and Jolt Physics' });
  const gaitlab = await loadGaitlab(command.urls.gaitlab, {
    printErr: (text) => console.warn(`[gaitlab] ${text}`),
    onAbort: (what) => post({ type: 'error', message: `the gaitlab module aborted: ${String(what)}` }),
  });
  const [joltMT, joltST] = await Promise.all([loadFactory(command.urls.joltMT), loadFactory(command.urls.joltST)]);
  const engines = peerEngines({ gaitlab, joltMT, joltST });
  post({ type: 'status', message: 'warming up (untimed)' });
  await new Promise((resolve) => setTimeout(resolve, 0));
  warmUp(engines, command.grid.legs, command.grid.threads);
  const grid = peerGrid(command.grid);
  for (let i = 0; i < grid.length; ++i) {
    // Let a 'cancel' message in between points.
    await new Promise((resolve) => setTimeout(resolve, 0));
    if (cancelled) break;
    const t0 = performance.now();
    const points = measurePoint(engines, grid[i], command.settings);
    for (const p of points) console.info(describePoint(p));
    post({ type: 'points', index: i, points, seconds: (performance.now() - t0) / 1000 });
  }
  post({ type: 'done', cancelled });
}

scope.onmessage = (event) => {
  const command = event.data;
  if (command.type === 'cancel') {
    cancelled = true;
  } else {
    cancelled = false;
    run(command).catch((error: unknown) => post({ type: 'error', message: error instanceof Error ? error.message : String(error) }));
  }
};
