// The performance page (web/bench.html): the thesis's crowd experiment (Chapter 4) in this
// browser, in a worker running the WASM module with its thread pool. Live charts with standard-
// deviation bands (thesis Figures 5.3, 5.4), tables like the thesis's 6.1-6.3, the device, download
// of the results (JSON per bench/schema.json, CSV) and upload of another results file (e.g. a
// native run) to overlay on the charts.
//
// URL parameters preset the form, e.g. ?legs=2,4&characters=1,20,100&threads=1,2&modes=serial,full
// &steps=200&runs=3&frames=1&autorun=1. `window.gaitlabBench` is a read-only hook for automation
// (bench/run.mjs, tests/e2e): { state, document, error }.
import uPlot from 'uplot';
import 'uplot/dist/uPlot.min.css';
import './bench.css';
import {
  STEP_BUDGET_MS, capacity, curves, legsName, overlayDocuments, ratioTable, toCsv, validate,
  type BenchDocument, type Point, type TimeField,
} from '../../../bench/lib/analysis.mjs';
import { buildGrid, parseList, pointCost, type BenchEvent, type BenchInputs, type PointSpec } from './protocol';
import { CROWD_SHARDS, MAX_THREADS } from '../sim/gaitlab-wasm';
import { peersSection, type PeersHook } from './peers';
import { reloadWhenControlled } from '../isolation';

interface Hook {
  state: 'idle' | 'running' | 'done' | 'cancelled' | 'error';
  document: BenchDocument | null;
  error: string | null;
  /** "How many can this device run?": per type, the capacity found (null until measured). */
  capacity: { state: 'idle' | 'running' | 'done' | 'error'; biped: number | null; quadruped: number | null; seconds: number };
  /** The peer section: gaitlab's physics beside Jolt Physics (peers.ts). */
  peers: PeersHook;
}
declare global {
  interface Window {
    gaitlabBench: Hook;
  }
}
// On a static host, the reload into isolation that coi-serviceworker can miss (isolation.ts).
reloadWhenControlled();

const hook: Hook = { state: 'idle', document: null, error: null, capacity: { state: 'idle', biped: null, quadruped: null, seconds: 0 },
  peers: { state: 'idle', status: '', error: null, run: null } };
window.gaitlabBench = hook;

const COLOURS = ['#1f77b4', '#d62728', '#2ca02c', '#ff7f0e', '#9467bd', '#8c564b', '#e377c2', '#17becf'];
const cores = navigator.hardwareConcurrency || 0;

/** A new element with some properties (textContent, className, href…) and children. */
function el<K extends keyof HTMLElementTagNameMap>(tag: K, props: Record<string, unknown> = {}, ...children: (Node | string)[]): HTMLElementTagNameMap[K] {
  const e: HTMLElementTagNameMap[K] = document.createElement(tag);
  Object.assign(e, props);
  e.append(...children);
  return e;
}

// ---- the form ---------------------------------------------------------------------------------
const params = new URLSearchParams(location.search);
const field = (name: string, label: string, value: string, title = '') => {
  const input = el('input', { type: 'text', value: params.get(name) ?? value, title, name });
  return { input, label: el('label', {}, label, input) };
};
const legsField = field('legs', 'Leg counts (2, 4, mixed)', '2,4');
const charactersField = field('characters', 'Characters (list or A-B:STEP)', '1,10,20,50,100');
const threadsField = field('threads', 'Thread counts (1-5)', cores >= 4 ? '1,2,3,4' : '1,2');
const modesField = field('modes', 'Modes (serial, controller, full)', 'serial,controller,full');
const stepsField = field('steps', 'Steps per run (thesis: 800)', '200');
const runsField = field('runs', 'Runs per point (thesis: 20)', '3');
const framesBox = el('input', { type: 'checkbox', checked: params.get('frames') === '1' });
const startButton = el('button', { textContent: 'Run' });
const cancelButton = el('button', { textContent: 'Cancel', disabled: true });
const jsonButton = el('button', { textContent: 'Download JSON', disabled: true });
const csvButton = el('button', { textContent: 'Download CSV', disabled: true });
const uploadInput = el('input', { type: 'file', accept: '.json,application/json' });
const progress = el('progress', { max: 1, value: 0 });
const status = el('span', { textContent: 'Ready.' });
const threadWarning = el('p', { className: 'warn' });

const root = document.getElementById('bench')!;
root.append(
  el('h1', {}, 'gaitlab performance'),
  el('p', { className: 'lead' },
    'The thesis’s experiment (crowds of 1–100 characters, serial against parallel) run here as WebAssembly with threads, ' +
    'timing the controller (as the thesis did), the physics and the whole 1/120 s step. ',
    el('a', { href: './' }, 'Back to the demo')),
);
// ---- "How many can this device run?" ----------------------------------------------------------
/**
 * The committed reference machine's capacities (README, Performance: bench/results/
 * amd-epyc-2c-2026-11-22.json, the capacity table): AMD EPYC, 2 cores, full mode on 2 threads.
 */
const REFERENCE = [
  { runtime: 'Chromium (WASM)', biped: 551, quadruped: 188 },
  { runtime: 'native', biped: 622, quadruped: 258 },
];
const capacityThreads = Math.max(1, Math.min(cores || 1, MAX_THREADS));
/**
 * Seconds each type's search may take: 50, so that both answer within two minutes with the
 * warm-ups; `?capacitySeconds=N` (1–50) shortens it (the end-to-end test).
 */
const capacitySeconds = Math.min(50, Math.max(1, Number(params.get('capacitySeconds')) || 50));
const capacityButton = el('button', { textContent: 'How many can this device run?', className: 'big-button' });
const capacityStatus = el('p', { className: 'lead' }, `Measures in at most two minutes, on ${capacityThreads} thread${capacityThreads === 1 ? '' : 's'} (all this device offers, up to ${MAX_THREADS}).`);
const answerFigure = (label: string) => {
  const value = el('div', { className: 'answer-value', textContent: '–' });
  const detail = el('div', { className: 'answer-detail', textContent: '' });
  return { value, detail, box: el('div', { className: 'answer' }, el('div', { className: 'answer-label' }, label), value, detail) };
};
const answers = { 2: answerFigure('bipeds'), 4: answerFigure('quadrupeds') };
answers[2].value.setAttribute('data-testid', 'capacity-biped');
answers[4].value.setAttribute('data-testid', 'capacity-quadruped');
root.append(el('section', { className: 'capacity' },
  el('h2', {}, 'How many characters can this device run in real time?'),
  el('p', { className: 'lead' }, 'The most characters whose whole step (controller and physics, all threads) fits the 1/120 s of a fixed step at 120 Hz.'),
  el('div', { className: 'buttons' }, capacityButton),
  capacityStatus,
  el('div', { className: 'answers' }, answers[2].box, answers[4].box),
  el('h3', {}, 'Reference machines (committed measurements)'),
  table(['machine', 'runtime', 'bipeds', 'quadrupeds'], REFERENCE.map((r) => ['AMD EPYC, 2 cores, 2 threads', r.runtime, r.biped, r.quadruped]), 2),
));

const device = el('dl', { className: 'device' });
root.append(el('section', {}, el('h2', {}, 'Device'), device));
root.append(peersSection(hook.peers, params));
const advanced = el('details', { className: 'advanced' });
root.append(advanced);
advanced.append(el('summary', {}, 'Advanced: the thesis’s full experiment, charts and tables'));
advanced.append(el('section', {},
  el('h2', {}, 'Experiment'),
  el('div', { className: 'form' }, legsField.label, charactersField.label, threadsField.label, modesField.label,
    stepsField.label, runsField.label, el('label', { className: 'inline' }, framesBox, 'per-frame statistics')),
  threadWarning,
  el('div', { className: 'buttons' }, startButton, cancelButton, progress, status),
  el('div', { className: 'buttons' }, jsonButton, csvButton, el('label', { className: 'inline' }, 'Overlay a results file:', uploadInput)),
));
const chartsSection = el('section', {}, el('h2', {}, 'Charts'), el('p', { className: 'lead' },
  'Mean per step with ±1 standard deviation bands (over every step of every run). Overlaid files are dashed.'));
const charts = el('div', { className: 'charts' });
chartsSection.append(charts);
const tablesSection = el('section', {}, el('h2', {}, 'Tables'));
advanced.append(chartsSection, tablesSection);
// A link that presets the form (?legs=…&autorun=1) opens the experiment.
if (['legs', 'characters', 'threads', 'modes', 'steps', 'runs', 'autorun'].some((k) => params.has(k))) advanced.open = true;

function showDevice(machine: Record<string, unknown> | null): void {
  const rows: [string, string][] = [
    ['navigator.hardwareConcurrency', String(cores)],
    ['crossOriginIsolated', String(crossOriginIsolated)],
    ['user agent', navigator.userAgent],
  ];
  if (machine) rows.push(['module', `gaitlab ${machine.gaitlab}, ${machine.compiler}`]);
  device.replaceChildren(...rows.flatMap(([k, v]) => [el('dt', {}, k), el('dd', {}, v)]));
  if (!crossOriginIsolated) device.append(el('dd', { className: 'error' }, 'Not cross-origin isolated: WASM threads are unavailable.'));
}
showDevice(null);

function readInputs(): BenchInputs {
  const legs = legsField.input.value.split(',').map((s) => s.trim()).map((s) => {
    if (s === '2' || s === '4') return Number(s) as 2 | 4;
    if (s === 'mixed') return 'mixed' as const;
    throw new Error(`leg count '${s}' is not 2, 4 or mixed`);
  });
  const modes = modesField.input.value.split(',').map((s) => s.trim()).map((s) => {
    if (s === 'serial' || s === 'controller' || s === 'full') return s;
    throw new Error(`mode '${s}' is not serial, controller or full`);
  });
  const steps = parseList(stepsField.input.value, 1, 100000);
  const runs = parseList(runsField.input.value, 1, 1000);
  return {
    legs, modes,
    characters: parseList(charactersField.input.value, 1, 2000),
    threads: parseList(threadsField.input.value, 1, MAX_THREADS),
    steps: steps[0], runs: runs[0], shards: CROWD_SHARDS, spacing_m: 4, seed: 1, step_hz: 120,
    frames: framesBox.checked,
  };
}

function flagThreads(): void {
  try {
    const above = readInputs().threads.filter((t) => t > cores);
    threadWarning.textContent = above.length
      ? `Thread count ${above.join(', ')} is above this device’s ${cores} logical cores: allowed, but those threads share cores and the results are flagged.`
      : '';
  } catch {
    threadWarning.textContent = '';
  }
}
threadsField.input.addEventListener('input', flagThreads);
flagThreads();

// ---- charts -----------------------------------------------------------------------------------
interface Overlay { name: string; doc: BenchDocument }
let current: BenchDocument | null = null;
const overlays: Overlay[] = [];
const plots = new Map<string, uPlot>();
/** One element per chart, kept across redraws so that charts keep their places. */
const holders = new Map<string, HTMLDivElement>();

/** A chart of `field` against crowd size for one leg count: every series with its ±sd band. */
function chartData(legs: Point['legs'], fieldName: TimeField) {
  const sources: { doc: BenchDocument; prefix: string; dash: boolean }[] = [];
  if (current) sources.push({ doc: current, prefix: '', dash: false });
  for (const o of overlays) sources.push({ doc: o.doc, prefix: `${o.name}: `, dash: true });
  const xs = [...new Set(sources.flatMap((s) => s.doc.points.filter((p) => p.legs === legs).map((p) => p.characters)))].sort((a, b) => a - b);
  const series: uPlot.Series[] = [{ label: 'characters' }];
  const data: (number | null)[][] = [xs];
  const bands: uPlot.Band[] = [];
  let colour = 0;
  for (const s of sources) {
    for (const [key, list] of curves(s.doc, legs)) {
      const byN = new Map(list.map((p) => [p.characters, p[fieldName]]));
      const c = COLOURS[colour++ % COLOURS.length];
      const mean = xs.map((x) => byN.get(x)?.mean ?? null);
      const hi = xs.map((x) => { const v = byN.get(x); return v ? v.mean + v.sd : null; });
      const lo = xs.map((x) => { const v = byN.get(x); return v ? Math.max(0, v.mean - v.sd) : null; });
      const flagged = list.some((p) => p.threads > cores && s.prefix === '') ? ' (threads > cores)' : '';
      series.push({ label: `${s.prefix}${key}${flagged}`, stroke: c, width: 2, dash: s.dash ? [6, 4] : undefined, spanGaps: true });
      series.push({ label: '+sd', stroke: 'transparent', spanGaps: true, show: true });
      series.push({ label: '−sd', stroke: 'transparent', spanGaps: true });
      data.push(mean, hi, lo);
      const i = series.length - 1;
      bands.push({ series: [i - 1, i], fill: `${c}26` });
    }
  }
  return { series, data, bands };
}

function drawCharts(): void {
  const docs = [current, ...overlays.map((o) => o.doc)].filter((d): d is BenchDocument => d !== null);
  const legsSet = [...new Set(docs.flatMap((d) => d.points.map((p) => p.legs)))];
  const wanted: [string, Point['legs'], TimeField, string][] = [];
  for (const legs of legsSet) {
    wanted.push([`${legs}-controller_ms`, legs, 'controller_ms', `${legsName(legs)}: controller per step (ms)`]);
    wanted.push([`${legs}-step_ms`, legs, 'step_ms', `${legsName(legs)}: whole step (ms), 120 Hz budget ${STEP_BUDGET_MS.toFixed(2)} ms`]);
  }
  for (const [key, plot] of plots) {
    if (!wanted.some(([k]) => k === key)) {
      plot.destroy();
      plots.delete(key);
      holders.get(key)?.remove();
      holders.delete(key);
    }
  }
  for (const [key, legs, fieldName, title] of wanted) {
    const { series, data, bands } = chartData(legs, fieldName);
    plots.get(key)?.destroy();
    let holder = holders.get(key);
    if (!holder) {
      holder = el('div');
      holders.set(key, holder);
      charts.append(holder);
    }
    const opts: uPlot.Options = {
      title, width: 540, height: 300, series, bands,
      scales: { x: { time: false } },
      axes: [{ label: 'characters' }, { label: 'ms' }],
      legend: { live: false },
    };
    const plot = new uPlot(opts, data as uPlot.AlignedData, holder);
    // Hide the ±sd helper series from the legend: they only bound the bands.
    plot.root.querySelectorAll<HTMLElement>('.u-legend .u-series').forEach((row) => {
      if (/^[+−]sd$/.test(row.textContent?.trim() ?? '')) row.style.display = 'none';
    });
    plots.set(key, plot);
  }
}

// ---- tables -----------------------------------------------------------------------------------
function table(head: string[], rows: (string | number)[][], textColumns = 1): HTMLTableElement {
  const t = el('table');
  t.append(el('tr', {}, ...head.map((h, i) => el('th', { className: i < textColumns ? 'text' : '' }, h))));
  for (const r of rows) t.append(el('tr', {}, ...r.map((v, i) => el('td', { className: i < textColumns ? 'text' : '' }, String(v)))));
  return t;
}

function drawTables(): void {
  tablesSection.replaceChildren(el('h2', {}, 'Tables'));
  if (!current) return;
  const doc = current;
  for (const legs of [...new Set(doc.points.map((p) => p.legs))]) {
    for (const [fieldName, what] of [['controller_ms', 'controller (thesis Tables 6.1–6.3)'], ['step_ms', 'whole step']] as const) {
      const rows = ratioTable(doc, legs, fieldName).map((r) => [r.series, `${r.fromMs.toFixed(4)} ms (${r.from})`,
        `${r.toMs.toFixed(4)} ms (${r.to})`, r.ratio === null ? '–' : `1 : ${r.ratio.toFixed(0)}`]);
      tablesSection.append(el('h3', {}, `${legsName(legs)}: ${what}`),
        table(['series', 'fewest characters', 'most characters', 'ratio'], rows));
    }
    const cap = [...curves(doc, legs)].map(([series, list]) => {
      const c = capacity(list);
      return [series, c.measured, c.fitted === null ? '–' : `${c.fitted}${c.extrapolated ? ' (extrapolated)' : ''}`];
    });
    tablesSection.append(el('h3', {}, `${legsName(legs)}: real-time capacity at 120 Hz`),
      table(['series', 'most measured within budget', 'linear trend'], cap));
  }
  const rows = doc.points.map((p) => [legsName(p.legs), p.mode, p.threads + (p.threads > cores ? ' ⚠' : ''), p.characters,
    p.controller_ms.mean.toFixed(4), p.controller_ms.sd.toFixed(4), p.physics_ms.mean.toFixed(3), p.step_ms.mean.toFixed(3),
    p.step_ms.sd.toFixed(3), p.step_ms.p99.toFixed(3), p.step_ms.p99_median_over_runs?.toFixed(3) ?? '–',
    p.controller_us_per_character.toFixed(2),
    (p.memory.heap_bytes / 1048576).toFixed(1), p.deterministic ? 'yes' : 'NO']);
  tablesSection.append(el('h3', {}, 'Every point (ms per step; ⚠ = more threads than logical cores)'), table(
    ['legs', 'mode', 'threads', 'N', 'controller', 'sd', 'physics', 'step', 'sd', 'p99', 'p99 of per-step medians', 'µs/char', 'heap MB', 'same state'], rows, 2));
}

// ---- running ----------------------------------------------------------------------------------
let worker: Worker | null = null;

function download(name: string, text: string, type: string): void {
  const a = el('a', { href: URL.createObjectURL(new Blob([text], { type })), download: name });
  document.body.append(a);
  a.click();
  a.remove();
}
jsonButton.onclick = () => current && download(`gaitlab-bench-${current.date.replace(/[:]/g, '-')}.json`, JSON.stringify(current, null, 1), 'application/json');
csvButton.onclick = () => current && download(`gaitlab-bench-${current.date.replace(/[:]/g, '-')}.csv`, toCsv(current), 'text/csv');

uploadInput.onchange = async () => {
  const file = uploadInput.files?.[0];
  if (!file) return;
  try {
    const value: unknown = JSON.parse(await file.text());
    const kind = (value as { schema?: string })?.schema === 'gaitlab-bench-results/1' ? 'results' : 'document';
    const problems = validate(value, kind);
    if (problems.length) throw new Error(problems.slice(0, 3).join('; '));
    for (const doc of overlayDocuments(value)) overlays.push({ name: `${file.name} ${doc.machine.runtime}`, doc });
    status.textContent = `Overlaid ${file.name}.`;
    drawCharts();
  } catch (error) {
    status.textContent = `Cannot overlay ${file.name}: ${error instanceof Error ? error.message : String(error)}`;
  }
};

function finish(state: Hook['state'], message: string): void {
  hook.state = state;
  status.textContent = message;
  startButton.disabled = false;
  cancelButton.disabled = true;
  jsonButton.disabled = csvButton.disabled = !current || current.points.length === 0;
  worker?.terminate();
  worker = null;
}

function start(): void {
  let inputs: BenchInputs;
  try {
    inputs = readInputs();
  } catch (error) {
    status.textContent = error instanceof Error ? error.message : String(error);
    return;
  }
  const grid: PointSpec[] = buildGrid(inputs);
  const costs = grid.map((p) => pointCost(p, inputs));
  const total = costs.reduce((a, b) => a + b, 0);
  let done = 0;
  let seconds = 0;
  current = { schema: 'gaitlab-bench/1', date: new Date().toISOString().replace(/\.\d+Z$/, 'Z'), machine: { runtime: 'wasm-browser', cores }, inputs: { ...inputs }, points: [] };
  hook.state = 'running';
  hook.document = null;
  hook.error = null;
  startButton.disabled = true;
  cancelButton.disabled = false;
  jsonButton.disabled = csvButton.disabled = true;
  progress.value = 0;
  status.textContent = `Starting ${grid.length} points…`;
  worker = new Worker(new URL('./bench.worker.ts', import.meta.url), { type: 'module', name: 'gaitlab-bench' });
  worker.onerror = (event) => fail(event.message || 'the benchmark worker failed to start');
  worker.onmessage = (event: MessageEvent<BenchEvent>) => {
    const e = event.data;
    if (!current) return;
    if (e.type === 'machine') {
      current.machine = { ...e.machine, cross_origin_isolated: crossOriginIsolated, hardware_concurrency: cores } as unknown as BenchDocument['machine'];
      showDevice(e.machine);
    } else if (e.type === 'status') {
      status.textContent = `${e.message[0].toUpperCase()}${e.message.slice(1)}…`;
    } else if (e.type === 'point') {
      current.points.push(e.point as unknown as Point);
      done += costs[e.index];
      seconds += e.seconds;
      progress.value = done / total;
      const left = (seconds / done) * (total - done);
      const p = grid[e.index];
      status.textContent = `${e.index + 1}/${grid.length} points (last: ${legsName(p.legs)} ×${p.characters}, ${p.mode} ${p.threads}T); about ${left < 90 ? `${left.toFixed(0)} s` : `${(left / 60).toFixed(1)} min`} left`;
      drawCharts();
      drawTables();
    } else if (e.type === 'done') {
      const problems = validate(current);
      hook.document = current;
      if (problems.length) return fail(`the results do not match bench/schema.json: ${problems.join('; ')}`);
      drawCharts();
      drawTables();
      finish(e.cancelled ? 'cancelled' : 'done', e.cancelled ? `Cancelled after ${current.points.length} points.` : `Done: ${current.points.length} points in ${formatSeconds(seconds)}.`);
    } else if (e.type === 'error') {
      fail(e.message);
    }
  };
  worker.postMessage({ type: 'run', wasmUrl: new URL(`${import.meta.env.BASE_URL}wasm/gaitlab.mjs`, location.href).href, inputs, grid });
}

function fail(message: string): void {
  hook.error = message;
  finish('error', `Error: ${message}`);
  status.className = 'error';
}

/** "0.4 s", "12 s", "2.5 min": never "0 s" for a run that took time. */
function formatSeconds(seconds: number): string {
  if (seconds < 10) return `${seconds.toFixed(1)} s`;
  return seconds < 90 ? `${seconds.toFixed(0)} s` : `${(seconds / 60).toFixed(1)} min`;
}

function measureCapacity(): void {
  if (worker) return;
  hook.capacity = { state: 'running', biped: null, quadruped: null, seconds: 0 };
  capacityButton.disabled = startButton.disabled = true;
  for (const a of Object.values(answers)) {
    a.value.textContent = '…';
    a.detail.textContent = '';
  }
  const t0 = performance.now();
  capacityStatus.textContent = 'Loading the module…';
  const done = (state: 'done' | 'error', message: string) => {
    hook.capacity.state = state;
    hook.capacity.seconds = (performance.now() - t0) / 1000;
    capacityStatus.textContent = message;
    capacityButton.disabled = startButton.disabled = false;
    worker?.terminate();
    worker = null;
  };
  worker = new Worker(new URL('./bench.worker.ts', import.meta.url), { type: 'module', name: 'gaitlab-bench' });
  worker.onerror = (event) => done('error', `Error: ${event.message || 'the benchmark worker failed to start'}`);
  worker.onmessage = (event: MessageEvent<BenchEvent>) => {
    const e = event.data;
    if (e.type === 'machine') showDevice(e.machine);
    else if (e.type === 'status') capacityStatus.textContent = `${e.message[0].toUpperCase()}${e.message.slice(1)}…`;
    else if (e.type === 'capacityProbe') {
      capacityStatus.textContent = `${e.characters} ${e.legs === 2 ? 'bipeds' : 'quadrupeds'}: ${e.stepMs.toFixed(2)} ms a step (${e.stepMs <= STEP_BUDGET_MS ? 'within' : 'over'} ${STEP_BUDGET_MS.toFixed(2)} ms)`;
    } else if (e.type === 'capacity') {
      const a = answers[e.legs];
      a.value.textContent = String(e.within?.characters ?? 0);
      a.detail.textContent = [
        e.within ? `${e.within.stepMs.toFixed(2)} ms a step` : 'not even the smallest crowd tried fits',
        e.over ? `${e.over.characters} took ${e.over.stepMs.toFixed(2)} ms` : e.stopped ? 'at least: the time limit ended the search' : 'the largest crowd tried fits',
        `measured in ${formatSeconds(e.seconds)}`,
      ].join(' · ');
      hook.capacity[e.legs === 2 ? 'biped' : 'quadruped'] = e.within?.characters ?? 0;
    } else if (e.type === 'done') {
      done('done', `Done in ${formatSeconds((performance.now() - t0) / 1000)}, full mode on ${capacityThreads} thread${capacityThreads === 1 ? '' : 's'}.`);
    } else if (e.type === 'error') {
      done('error', `Error: ${e.message}`);
    }
  };
  worker.postMessage({ type: 'capacity', wasmUrl: new URL(`${import.meta.env.BASE_URL}wasm/gaitlab.mjs`, location.href).href, threads: capacityThreads, secondsPerType: capacitySeconds });
}
capacityButton.onclick = measureCapacity;

startButton.onclick = start;
cancelButton.onclick = () => {
  // The worker stops between points; a cancel during a long point waits for it to end.
  worker?.postMessage({ type: 'cancel' });
  status.textContent = 'Cancelling after the current point…';
  cancelButton.disabled = true;
};

if (params.get('autorun') === '1') start();
