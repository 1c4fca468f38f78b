// The demo page: a sim worker simulates the demo scene in real time; this main thread only draws
// it, reading the newest transforms out of shared WASM memory each animation frame (DESIGN.md,
// data flow steps 2–3), and shows what it is doing.
import './style.css';
import * as THREE from 'three';
import { CrowdMesh } from './render/crowd-mesh';
import { Stage } from './render/stage';
import { defaultThreads, errorMessage, simOptionsFromQuery } from './sim/protocol';
import { SimClient } from './sim/sim-client';
import { Overlay } from './ui/overlay';
import { RateMeter } from './ui/rate-meter';

/** What `window.gaitlab.stats()` returns: the read-only test hook (DESIGN.md, contracts). */
export interface GaitlabStats {
  /** Simulated seconds of the frame on screen. */
  simTime: number;
  /** Simulated seconds per wall-clock second, smoothed (1 = real time). */
  realtimeFactor: number;
  /** Rendered frames per second, smoothed. */
  fps: number;
  /** Bodies in the frame on screen. */
  bodies: number;
  /** Threads of the simulation (0 until it exists). */
  threads: number;
  /** The sim worker has confirmed a pause. */
  paused: boolean;
  crossOriginIsolated: boolean;
  /** True once a simulated frame has been drawn. */
  ready: boolean;
  /** The problem shown on the page, if any. */
  error: string | null;
}

declare global {
  interface Window {
    gaitlab: { stats(): GaitlabStats };
  }
}

const canvas = document.querySelector<HTMLCanvasElement>('#scene');
if (!canvas) throw new Error('index.html has no <canvas id="scene">');

let client: SimClient | null = null;
/** Whether the worker has reported being paused (the button follows it, not the click). */
let paused = false;
const overlay = new Overlay(document.body, {
  onPauseToggle: () => (paused ? client?.resume() : client?.pause()),
  onReset: () => client?.reset(),
});

const state = { threads: 0, ready: false, error: null as string | null, stepMs: 0, lastStats: 0 };
/** Without statistics from the worker for this long, it is stuck (it reports 4 times a second). */
const STALL_MS = 15_000;
const fpsMeter = new RateMeter();
const realtimeMeter = new RateMeter();
let frames = 0;
const crowd = new CrowdMesh();

function showError(title: string, detail: string): void {
  state.error = `${title}: ${detail}`;
  overlay.showNotice(title, detail);
}

// Anything that goes wrong later is shown on the page as well as in the console.
window.addEventListener('error', (event) => showError('Unexpected error', errorMessage(event.error ?? event.message)));
window.addEventListener('unhandledrejection', (event) => showError('Unexpected error', errorMessage(event.reason)));

window.gaitlab = Object.freeze({
  stats: (): GaitlabStats => ({
    simTime: crowd.frame?.simTime ?? 0,
    realtimeFactor: realtimeMeter.rate,
    fps: fpsMeter.rate,
    bodies: crowd.frame?.bodyCount ?? 0,
    threads: state.threads,
    paused,
    crossOriginIsolated: window.crossOriginIsolated,
    ready: state.ready,
    error: state.error,
  }),
});

let stage: Stage | null = null;
try {
  stage = new Stage(canvas);
  stage.scene.add(crowd.group);
} catch (error) {
  showError('WebGL is not available', `${errorMessage(error)}\nThe demo needs a browser with WebGL 2.`);
}

if (!window.crossOriginIsolated) {
  // SharedArrayBuffer (hence WASM threads and the shared render buffer) needs isolation.
  showError(
    'This page must be served with cross-origin isolation',
    'The simulation uses WebAssembly threads, which browsers only allow when the page is sent with the headers ' +
      '"Cross-Origin-Opener-Policy: same-origin" and "Cross-Origin-Embedder-Policy: require-corp". ' +
      'Serve it with `npm start` (or `node scripts/serve.mjs`) rather than opening the file or using another server.',
  );
} else if (stage) {
  const options = simOptionsFromQuery(location.search, {
    wasmUrl: new URL(`${import.meta.env.BASE_URL}wasm/gaitlab.mjs`, location.href).href,
    threads: defaultThreads(navigator.hardwareConcurrency),
    seed: 1,
    characters: 6,
  });
  let framed = false;
  client = new SimClient(options, {
    onScene: (reader, info) => {
      crowd.attach(reader);
      state.threads = info.threads;
      state.lastStats = performance.now(); // the stall watchdog counts from here
      realtimeMeter.reset();
      overlay.setControlsEnabled(true);
      console.info(`gaitlab ${info.version}: scene ${info.generation}, ${reader.capacity} body slots, ${info.threads} threads`);
    },
    onRelease: () => crowd.detach(),
    onStats: (stats) => {
      state.stepMs = stats.stepMs;
      state.lastStats = performance.now();
      paused = stats.paused;
    },
    onError: (message) => showError('The simulation stopped', message),
  });

  const activeStage = stage;
  const frame = (): void => {
    const now = performance.now() / 1000;
    if (crowd.update() && !framed) {
      const bounds = crowd.bounds();
      if (bounds) {
        // Look at the whole scene once, when its first frame arrives.
        activeStage.frame(new THREE.Vector3(bounds.center.x, 0.6, bounds.center.z), bounds.radius);
        framed = true;
      }
    }
    if (crowd.frame) {
      state.ready = true;
      // Sampled on every display frame, new simulation frame or not: wall time passes either way.
      realtimeMeter.sample(crowd.frame.simTime, now);
    }
    activeStage.render();
    fpsMeter.sample(++frames, now);
    requestAnimationFrame(frame);
  };

  const resize = () => activeStage.resize();
  window.addEventListener('resize', resize);
  resize();
  requestAnimationFrame(frame);

  setInterval(() => {
    // A worker blocked inside the module (e.g. waiting on a pthread that cannot start) cannot
    // report an error itself: notice its silence. Hidden pages are skipped (timers throttle).
    const silent = performance.now() - state.lastStats;
    if (state.lastStats > 0 && !state.error && document.visibilityState === 'visible' && silent > STALL_MS) {
      showError('The simulation stopped responding', `The sim worker has sent nothing for ${(silent / 1000).toFixed(0)} s.`);
    }
    overlay.show({
      fps: fpsMeter.rate,
      realtimeFactor: realtimeMeter.rate,
      bodies: crowd.frame?.bodyCount ?? 0,
      threads: state.threads,
      stepMs: state.stepMs,
      paused,
    });
  }, 250);
}

// Without isolation (or WebGL) the page still draws the empty stage behind the notice, if it can.
if (stage && !client) {
  const still = stage;
  still.resize();
  still.render();
  window.addEventListener('resize', () => {
    still.resize();
    still.render();
  });
}
