// The performance page's peer section: gaitlab's physics beside Jolt Physics on the peer
// benchmark's reference scene (docs/peers.md), in this browser, in one run: gaitlab's module,
// Jolt's SIMD multithreaded build and its default build, engines alternating within rounds, medians
// of the rounds with their range, shown as the same table as bench/results/peers.md.
//
// URL parameters preset it, e.g. ?peerLegs=4&peerCharacters=20,100&peerThreads=1,2&peerSteps=120
// &peerRounds=3&peerAutorun=1. `window.gaitlabBench.peers` is its read-only hook for automation
// (bench/peers/browser.mjs, tests/e2e): { state, status, error, run }.
import { TABLE_HEAD, peerGrid, tableGrid, tableRows, type PeerGrid, type PeerPoint, type PeerSettings } from '../../../bench/peers/comparison.mjs';
import { parseList } from './protocol';
import type { PeersEvent } from './peers-protocol';

export interface PeersHook {
  state: 'idle' | 'running' | 'done' | 'cancelled' | 'error';
  /** The status line as shown. */
  status: string;
  error: string | null;
  /** The run so far: the device and every engine's result per point (comparison.mjs's points). */
  run: { machine: Record<string, unknown>; grid: PeerGrid; settings: PeerSettings; points: PeerPoint[] } | null;
}

/** Where the page serves the modules: gaitlab's under /wasm, the jolt-physics package's under /jolt (vite.config.ts). */
const moduleUrl = (path: string) => new URL(`${import.meta.env.BASE_URL}${path}`, location.href).href;

function el<K extends keyof HTMLElementTagNameMap>(tag: K, props: Record<string, unknown> = {}, ...children: (Node | string)[]): HTMLElementTagNameMap[K] {
  const e = document.createElement(tag);
  Object.assign(e, props);
  e.append(...children);
  return e;
}

/** The section, wired to `hook`; runs at once when the URL says peerAutorun=1. */
export function peersSection(hook: PeersHook, params: URLSearchParams): HTMLElement {
  const field = (name: string, label: string, value: string) => {
    const input = el('input', { type: 'text', value: params.get(name) ?? value, name });
    return { input, label: el('label', {}, label, input) };
  };
  const legsField = field('peerLegs', 'Leg counts (4, 2)', '4,2');
  const charactersField = field('peerCharacters', 'Characters (20–400)', '20,100,250,400');
  const threadsField = field('peerThreads', 'Thread counts', '1,2');
  const stepsField = field('peerSteps', 'Timed steps per round', '120');
  const roundsField = field('peerRounds', 'Rounds', '3');
  const settle = Math.max(0, Number(params.get('peerSettle') ?? 30) || 0);
  const runButton = el('button', { textContent: 'Compare' });
  const cancelButton = el('button', { textContent: 'Cancel comparison', disabled: true });
  const progress = el('progress', { max: 1, value: 0 });
  const status = el('span', { textContent: 'Ready.' });
  const results = el('div');
  let worker: Worker | null = null;

  const setStatus = (text: string) => {
    status.textContent = text;
    hook.status = text;
  };
  const draw = () => {
    if (!hook.run) return;
    // The points measured so far, in the grid's order.
    const points = hook.run.points;
    const measured = tableGrid(hook.run.grid).filter((g) => points.some((p) => p.legs === g.legs && p.characters === g.characters && p.threads === g.threads));
    const t = el('table');
    t.append(el('tr', {}, ...TABLE_HEAD.map((h, i) => el('th', { className: i < 1 ? 'text' : '' }, h))));
    for (const r of tableRows(points, measured)) t.append(el('tr', {}, ...r.map((v, i) => el('td', { className: i < 1 ? 'text' : '' }, v))));
    const notes = [...new Set(points.filter((p) => p.skipped).map((p) => `—: ${p.engine === 'gaitlab' ? 'gaitlab' : 'Jolt'} ${p.skipped}.`))];
    results.replaceChildren(t, ...notes.map((n) => el('p', { className: 'lead' }, n)));
  };
  const finish = (state: PeersHook['state'], text: string) => {
    hook.state = state;
    setStatus(text);
    runButton.disabled = false;
    cancelButton.disabled = true;
    worker?.terminate();
    worker = null;
  };

  const start = () => {
    let grid: PeerGrid;
    let settings: PeerSettings;
    try {
      grid = {
        legs: parseList(legsField.input.value, 2, 4).map((l) => {
          if (l !== 2 && l !== 4) throw new Error(`leg count ${l} is not 2 or 4`);
          return l;
        }),
        characters: parseList(charactersField.input.value, 1, 400),
        threads: parseList(threadsField.input.value, 1, 16),
      };
      settings = { steps: parseList(stepsField.input.value, 1, 12000)[0], rounds: parseList(roundsField.input.value, 1, 99)[0], settle };
    } catch (error) {
      setStatus(error instanceof Error ? error.message : String(error));
      return;
    }
    const total = peerGrid(grid).length;
    hook.state = 'running';
    hook.error = null;
    hook.run = {
      machine: { cores: navigator.hardwareConcurrency, user_agent: navigator.userAgent, cross_origin_isolated: crossOriginIsolated },
      grid, settings, points: [],
    };
    runButton.disabled = true;
    cancelButton.disabled = false;
    progress.value = 0;
    results.replaceChildren();
    setStatus(`Starting ${total} points…`);
    worker = new Worker(new URL('./peers.worker.ts', import.meta.url), { type: 'module', name: 'gaitlab-peers' });
    worker.onerror = (event) => fail(event.message || 'the peer benchmark worker failed to start');
    worker.onmessage = (event: MessageEvent<PeersEvent>) => {
      const e = event.data;
      if (!hook.run) return;
      if (e.type === 'status') setStatus(`${e.message[0].toUpperCase()}${e.message.slice(1)}…`);
      else if (e.type === 'points') {
        hook.run.points.push(...e.points);
        progress.value = (e.index + 1) / total;
        const p = e.points[0];
        setStatus(`${e.index + 1}/${total} points (last: ${p.characters} ${p.legs === 4 ? 'quadrupeds' : 'bipeds'} on ${p.threads} thread${p.threads === 1 ? '' : 's'}, ${e.seconds.toFixed(1)} s)`);
        draw();
      } else if (e.type === 'done') {
        finish(e.cancelled ? 'cancelled' : 'done', e.cancelled ? 'Cancelled.' : `Done: ${total} points.`);
      } else if (e.type === 'error') fail(e.message);
    };
    worker.postMessage({
      type: 'run',
      urls: { gaitlab: moduleUrl('wasm/gaitlab.mjs'), joltMT: moduleUrl('jolt/jolt-physics.multithread.wasm.js'), joltST: moduleUrl('jolt/jolt-physics.wasm.js') },
      grid, settings,
    });
  };
  const fail = (message: string) => {
    hook.error = message;
    finish('error', `Error: ${message}`);
  };
  runButton.onclick = start;
  cancelButton.onclick = () => {
    // The worker stops between points.
    worker?.postMessage({ type: 'cancel' });
    setStatus('Cancelling after the current point…');
    cancelButton.disabled = true;
  };
  if (params.get('peerAutorun') === '1') queueMicrotask(start);

  return el('section', { className: 'peers' },
    el('h2', {}, 'Beside Jolt Physics'),
    el('p', { className: 'lead' },
      'gaitlab’s physics (Bullet 3.24 as gaitlab builds it) and Jolt Physics (the jolt-physics package: its SIMD multithreaded build and its default build) ' +
      'step the same scene here, in one run: passive ragdolls of gaitlab’s characters holding their standing pose with motors, ground-only contact, ' +
      '1/120 s steps of two 1/240 s sub-steps. Milliseconds per step, median of the rounds (range); the engines alternate within each round.'),
    el('div', { className: 'form' }, legsField.label, charactersField.label, threadsField.label, stepsField.label, roundsField.label),
    el('div', { className: 'buttons' }, runButton, cancelButton, progress, status),
    results,
  );
}
