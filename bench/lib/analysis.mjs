// Reading gaitlab benchmark documents (bench/schema.json): validation, CSV, and the figures the
// thesis derives from its measurements (Chapter 6) plus ours. Shared by bench/run.mjs (Node) and
// the performance page (web/src/bench), so both compute every figure the same way.
import Ajv from 'ajv';
import schema from '../schema.json' with { type: 'json' };

/** The fixed step: 120 Hz (thesis §3.2). A step that takes longer runs slower than real time. */
export const STEP_BUDGET_MS = 1000 / 120;

const ajv = new Ajv({ allErrors: true, strict: false });
ajv.addSchema(schema);
const validateDocument = ajv.getSchema(schema.$id);
const validateResults = ajv.compile({ $ref: `${schema.$id}#/definitions/results` });

/**
 * Checks a document ('document': one run of `gaitlab bench --json` or the page) or a results
 * file ('results': what bench/run.mjs writes). Returns a list of problems, empty if valid.
 */
export function validate(value, kind = 'document') {
  const check = kind === 'results' ? validateResults : validateDocument;
  if (check(value)) return [];
  return check.errors.map((e) => `${e.instancePath || '/'} ${e.message}`);
}

/** The documents inside a results file, or the document itself. */
function documentsOf(value) {
  return value && value.schema === 'gaitlab-bench-results/1' ? value.runs : [value];
}

/**
 * What to overlay from a results file: one document per runtime, holding the points of all its
 * documents (the grid, the per-frame run, the capacity probes beyond the grid, the rounds in
 * turns); of points measured more than once (same legs, crowd, threads and mode), the first.
 */
export function overlayDocuments(value) {
  const byRuntime = new Map();
  const key = (p) => `${p.legs}/${p.characters}/${p.threads}/${p.mode}`;
  for (const doc of documentsOf(value)) {
    const merged = byRuntime.get(doc.machine.runtime);
    if (!merged) {
      byRuntime.set(doc.machine.runtime, { ...doc, points: [...doc.points] });
      continue;
    }
    const seen = new Set(merged.points.map(key));
    for (const p of doc.points) if (!seen.has(key(p))) merged.points.push(p), seen.add(key(p));
  }
  return [...byRuntime.values()];
}

export const CSV_COLUMNS = [
  'legs', 'characters', 'threads', 'mode', 'shards', 'steps', 'runs',
  'controller_ms_mean', 'controller_ms_sd', 'physics_ms_mean', 'physics_ms_sd',
  'step_ms_mean', 'step_ms_sd', 'step_ms_p50', 'step_ms_p99', 'step_ms_max',
  'step_ms_p99_median_over_runs',
  'controller_us_per_character', 'heap_bytes', 'scene_heap_bytes', 'rss_bytes', 'state_hash',
  'deterministic',
];

/** The CSV `gaitlab bench --csv` prints: two '#' lines (machine, inputs), a header, a row per point. */
export function toCsv(doc) {
  const rows = doc.points.map((p) => [
    p.legs, p.characters, p.threads, p.mode, p.shards, p.steps, p.runs,
    p.controller_ms.mean.toFixed(6), p.controller_ms.sd.toFixed(6),
    p.physics_ms.mean.toFixed(6), p.physics_ms.sd.toFixed(6),
    p.step_ms.mean.toFixed(6), p.step_ms.sd.toFixed(6), p.step_ms.p50.toFixed(6),
    p.step_ms.p99.toFixed(6), p.step_ms.max.toFixed(6),
    p.step_ms.p99_median_over_runs?.toFixed(6) ?? '', p.controller_us_per_character.toFixed(4),
    p.memory.heap_bytes, p.memory.scene_heap_bytes, p.memory.rss_bytes ?? '', p.state_hash,
    p.deterministic,
  ].join(','));
  return [`# ${JSON.stringify(doc.machine)}`, `# inputs ${JSON.stringify(doc.inputs)}`,
    CSV_COLUMNS.join(','), ...rows].join('\n') + '\n';
}

/** A series key: which curve a point belongs to. Serial is one curve whatever its thread count. */
export function seriesKey(p) {
  return p.mode === 'serial' ? 'serial' : `${p.mode} ${p.threads}T`;
}

/** Points of `doc` grouped by leg count and series, each sorted by crowd size. */
export function curves(doc, legs) {
  const out = new Map();
  for (const p of doc.points) {
    if (p.legs !== legs) continue;
    const k = seriesKey(p);
    if (!out.has(k)) out.set(k, []);
    out.get(k).push(p);
  }
  for (const list of out.values()) list.sort((a, b) => a.characters - b.characters);
  return out;
}

/** Least-squares line y = a + b x. */
export function fitLine(xs, ys) {
  const n = xs.length;
  if (n === 0) return { a: 0, b: 0, r2: 0 };
  const mx = xs.reduce((s, x) => s + x, 0) / n;
  const my = ys.reduce((s, y) => s + y, 0) / n;
  let sxx = 0, sxy = 0, syy = 0;
  for (let i = 0; i < n; i++) {
    sxx += (xs[i] - mx) ** 2;
    sxy += (xs[i] - mx) * (ys[i] - my);
    syy += (ys[i] - my) ** 2;
  }
  const b = sxx > 0 ? sxy / sxx : 0;
  return { a: my - b * mx, b, r2: sxx > 0 && syy > 0 ? (sxy * sxy) / (sxx * syy) : 1 };
}

/**
 * Real-time capacity of one curve: the most characters whose whole step still fits the 120 Hz
 * budget (1x real time). `measured` is the largest measured crowd within budget; `fitted`
 * extrapolates the linear trend of the step time (as the thesis's Figure 6.5 fits its data), and
 * `extrapolated` says whether it lies beyond the largest crowd measured.
 */
export function capacity(points) {
  const within = points.filter((p) => p.step_ms.mean <= STEP_BUDGET_MS);
  const measured = within.length ? Math.max(...within.map((p) => p.characters)) : 0;
  const line = fitLine(points.map((p) => p.characters), points.map((p) => p.step_ms.mean));
  const fitted = line.b > 0 ? Math.max(0, Math.floor((STEP_BUDGET_MS - line.a) / line.b)) : null;
  const largest = points.length ? Math.max(...points.map((p) => p.characters)) : 0;
  return { measured, fitted, extrapolated: fitted !== null && fitted > largest, line };
}

/**
 * The measured bracket of a curve's capacity: `within`, the largest crowd whose mean step fits the
 * budget, and `over`, the smallest larger crowd that does not (each a point, or null).
 */
export function capacityBracket(points) {
  const fits = (p) => p.step_ms.mean <= STEP_BUDGET_MS;
  const within = points.filter(fits).reduce((a, b) => (!a || b.characters > a.characters ? b : a), null);
  const over = points.filter((p) => !fits(p) && (!within || p.characters > within.characters))
    .reduce((a, b) => (!a || b.characters < a.characters ? b : a), null);
  return { within, over };
}

/**
 * The crowd size at which to measure a curve next, to find its real-time capacity by measurement
 * rather than by extrapolation (bench/run.mjs), or null once it is found. `points` are every point
 * of the curve measured so far. Until a crowd over budget has been measured, the next size is the
 * linear trend's capacity (at least 10 % beyond the largest crowd within budget); then it is
 * interpolated between the largest crowd within budget and the smallest one over it (kept inside
 * the middle 60 % of that bracket), until the two are within `tolerance` of each other. Never
 * above `cap` (what the runtime's memory holds).
 */
export function nextCapacityProbe(points, { cap = Infinity, tolerance = 0.05 } = {}) {
  const { within: lo, over: hi } = capacityBracket(points);
  if (!lo) return null;  // not even the smallest crowd runs in real time
  if (!hi) {
    if (lo.characters >= cap) return null;
    const c = capacity(points).fitted ?? 0;
    return Math.min(cap, Math.max(c, Math.ceil(1.1 * lo.characters)));
  }
  const gap = hi.characters - lo.characters;
  if (gap <= Math.max(1, tolerance * lo.characters)) return null;
  const t = (STEP_BUDGET_MS - lo.step_ms.mean) / (hi.step_ms.mean - lo.step_ms.mean);
  const next = Math.round(lo.characters + Math.min(0.8, Math.max(0.2, t)) * gap);
  return Math.min(hi.characters - 1, Math.max(lo.characters + 1, next));
}

/** The point of `doc` matching the given fields, or undefined. */
export function find(doc, { legs, characters, mode, threads }) {
  return doc.points.find((p) => p.legs === legs && p.characters === characters && p.mode === mode &&
    (threads === undefined || p.threads === threads || mode === 'serial'));
}

/**
 * Tables like the thesis's 6.1-6.3: for each series, the time at the smallest and the largest crowd
 * and their ratio ("1 : 75" = 75 times the one-character time for 100 characters).
 */
export function ratioTable(doc, legs, field = 'controller_ms') {
  const rows = [];
  for (const [series, list] of curves(doc, legs)) {
    const first = list[0], last = list[list.length - 1];
    if (!first || first === last) continue;
    rows.push({
      series, from: first.characters, to: last.characters,
      fromMs: first[field].mean, toMs: last[field].mean,
      ratio: first[field].mean > 0 ? last[field].mean / first[field].mean : null,
    });
  }
  return rows;
}

/** Speedup of `threads` over serial for the whole step (or `field`) at `characters`. */
export function speedup(doc, legs, characters, threads, mode = 'full', field = 'step_ms') {
  const s = find(doc, { legs, characters, mode: 'serial' });
  const p = find(doc, { legs, characters, mode, threads });
  return s && p && p[field].mean > 0 ? s[field].mean / p[field].mean : null;
}

/** Human-readable leg count. */
export function legsName(legs) {
  return legs === 2 ? 'biped' : legs === 4 ? 'quadruped' : 'mixed';
}
