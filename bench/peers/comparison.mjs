// The peer benchmark's measurement, shared by its two runners: Node (bench/peers.mjs) and the
// performance page's worker in a browser (web/src/bench/peers.worker.ts). Both hand it the same
// three WebAssembly modules (gaitlab's, Jolt's multithreaded build, Jolt's default build), so the
// engines, the alternation within rounds, the medians and the table are one piece of code.
//
// A point: for each round, every engine that runs at that size builds a fresh scene, steps
// `settle` fixed steps untimed (the first contacts), then `steps` timed; the engines' order is
// reversed every other round, so that the machine's load falls on both alike. The figure is the
// median over the rounds of the mean step, with the range (min–max) as its spread.
import { JoltScene } from './jolt-scene.mjs';

/** Legs -> GL_KIND_BIPED, GL_KIND_QUADRUPED (native/src/api/c_api.h). */
export const KIND = { 2: 0, 4: 1 };

/** The morphology of 2 or 4 legs as gaitlab describes it (gl_morphology_json). */
export function morphology(G, legs) {
  return JSON.parse(G.UTF8ToString(G._gl_morphology_json(KIND[legs])));
}

/** gaitlab's reference scene (native/src/peers/reference_scene.h) through the C ABI. */
export class GaitlabScene {
  constructor(G, legs, characters, threads) {
    this.G = G;
    this.h = G._gl_peer_scene_create(KIND[legs], characters, threads);
    if (!this.h) throw new Error(G.UTF8ToString(G._gl_last_error()));
  }
  step(steps) {
    if (this.G._gl_peer_scene_step(this.h, steps) < 0) throw new Error(this.G.UTF8ToString(this.G._gl_last_error()));
  }
  rootHeight() { return this.G._gl_peer_scene_root_height(this.h); }
  destroy() { this.G._gl_peer_scene_destroy(this.h); }
}

// JoltPhysics.js 1.1.0 gives its physics system a temporary allocator of fixed size (not a
// setting of its JoltSettings); a step that needs more aborts the module. Measured on the
// quadruped scene: 280 ragdolls (5040 bodies) step, 400 (7200 bodies) abort asking for 13.6 MB.
// Jolt is not run above the largest measured to pass.
export const JOLT_MAX_BODIES = 5040;
export const JOLT_SKIP = `not run: more than ${JOLT_MAX_BODIES} bodies, beyond JoltPhysics.js 1.1.0's fixed temporary allocator`;

/**
 * The engines compared, given the loaded modules: `gaitlab` (its C ABI), `joltMT` (the
 * jolt-physics package's SIMD multithreaded build; 1 thread = no worker threads) and `joltST`
 * (its default build, no SIMD; 1 thread only). `runs(legs, characters, threads)` says whether
 * the engine is timed at that point. `joltSettings` overrides fields of Jolt's PhysicsSettings
 * (jolt-scene.mjs), for experiments; none by default.
 */
export function peerEngines({ gaitlab, joltMT, joltST }, { joltSettings = {} } = {}) {
  const shapes = { 2: morphology(gaitlab, 2), 4: morphology(gaitlab, 4) };
  const joltFits = (l, n) => n * shapes[l].segments.length <= JOLT_MAX_BODIES;
  return [
    { name: 'gaitlab', label: 'gaitlab (Bullet 3.24)', make: (l, n, t) => new GaitlabScene(gaitlab, l, n, t), runs: () => true },
    { name: 'jolt-mt', label: 'Jolt, multithreaded build (SIMD)', make: (l, n, t) => new JoltScene(joltMT, shapes[l], n, t, { physicsSettings: joltSettings }), runs: joltFits },
    { name: 'jolt', label: 'Jolt, default build (no SIMD)', make: (l, n, t) => new JoltScene(joltST, shapes[l], n, t, { physicsSettings: joltSettings }),
      runs: (l, n, t) => t === 1 && joltFits(l, n) },
  ];
}

export function median(xs) {
  const s = [...xs].sort((a, b) => a - b);
  return s.length % 2 ? s[(s.length - 1) / 2] : (s[s.length / 2 - 1] + s[s.length / 2]) / 2;
}

/** One scene of `engine`: built, settled, `steps` steps timed (ms a step), destroyed. */
export function timeOnce(engine, legs, characters, threads, { steps, settle }) {
  const scene = engine.make(legs, characters, threads);
  try {
    scene.step(settle);
    const t0 = performance.now();
    scene.step(steps);
    const ms = (performance.now() - t0) / steps;
    return { ms, rootHeight: scene.rootHeight() };
  } finally {
    scene.destroy();
  }
}

/**
 * Untimed: a few small scenes of every engine on `threads` threads, so that the engines have
 * compiled their hot code with the optimising tier (a browser compiles WebAssembly lazily, then
 * tiers up) before the first point is timed.
 */
export function warmUp(engines, legsList, threads) {
  for (const l of legsList) {
    for (const e of engines) {
      for (const t of threads) if (e.runs(l, 4, t)) timeOnce(e, l, 4, t, { steps: 60, settle: 0 });
    }
  }
}

/**
 * Measures one point ({ legs, characters, threads }) with every engine, alternating within
 * `rounds` rounds. Returns its elements of "points": one per engine, timed or `skipped` (Jolt's
 * default build is not listed at all above 1 thread).
 */
export function measurePoint(engines, { legs, characters, threads }, { steps, settle, rounds }) {
  const runs = {};
  const refused = {};
  for (let r = 0; r < rounds; ++r) {
    const order = engines.filter((e) => e.runs(legs, characters, threads) && !refused[e.name]);
    if (r % 2) order.reverse();
    for (const e of order) {
      runs[e.name] ??= [];
      // A scene the engine refuses to build (gaitlab's module: more than its memory holds now)
      // is reported as not run, with the engine's reason, rather than ending the whole run.
      try {
        runs[e.name].push(timeOnce(e, legs, characters, threads, { steps, settle }));
      } catch (error) {
        refused[e.name] = `not run: ${error instanceof Error ? error.message : String(error)}`;
      }
    }
  }
  const points = [];
  for (const e of engines) {
    const rs = runs[e.name]?.length ? runs[e.name] : undefined;
    if (refused[e.name] && !rs) {
      points.push({ engine: e.name, legs, characters, threads, skipped: refused[e.name] });
      continue;
    }
    if (!rs) {
      if (e.name !== 'jolt' || threads === 1) points.push({ engine: e.name, legs, characters, threads, skipped: JOLT_SKIP });
      continue;
    }
    const ms = rs.map((x) => x.ms);
    points.push({
      engine: e.name, legs, characters, threads,
      ms_per_step: median(ms), ms_min: Math.min(...ms), ms_max: Math.max(...ms),
      root_height_m: median(rs.map((x) => x.rootHeight)),
      // Fewer rounds than asked when the engine refused a later scene of the same size.
      ...(rs.length < rounds ? { rounds: rs.length, refused: refused[e.name] } : {}),
    });
  }
  return points;
}

/**
 * The points of a grid, in the order both runners measure them: per leg count, per crowd from the
 * largest down, per thread count. Largest first because gaitlab's module counts as room only the
 * heap above its break (README, "Limits"): after the largest crowd, every smaller one fits in
 * what it left, while 400 quadrupeds after 250 were refused.
 */
export function peerGrid({ legs, characters, threads }) {
  const grid = [];
  const crowds = [...characters].sort((a, b) => b - a);
  for (const l of legs) for (const n of crowds) for (const t of threads) grid.push({ legs: l, characters: n, threads: t });
  return grid;
}

/** The same points in the order a table shows them: crowds from the smallest up. */
export function tableGrid(grid) {
  return peerGrid(grid).sort((a, b) => (a.legs === b.legs ? a.characters - b.characters || a.threads - b.threads : 0));
}

/** One line of log for a point of `measurePoint`. */
export function describePoint(p) {
  const head = `${p.engine.padEnd(8)} ${p.legs === 4 ? 'quadrupeds' : 'bipeds    '} ${String(p.characters).padStart(4)} × ${p.threads} thread(s): `;
  return head + (p.skipped ?? `${p.ms_per_step.toFixed(2)} ms/step (${p.ms_min.toFixed(2)}–${p.ms_max.toFixed(2)}), root at ${p.root_height_m.toFixed(2)} m`);
}

export const TABLE_HEAD = ['characters', 'N', 'threads', 'gaitlab', 'Jolt multithreaded build (SIMD)', 'Jolt default build', 'gaitlab / Jolt (SIMD)'];

/** The comparison table's rows (cells as text), one per point of the grid, from `points`. */
export function tableRows(points, grid) {
  const cell = (p) => (!p ? '—' : p.rounds === 1 ? `${p.ms_per_step.toFixed(2)} (1 round)`
    : `${p.ms_per_step.toFixed(2)} (${p.ms_min.toFixed(2)}–${p.ms_max.toFixed(2)}${p.rounds ? `, ${p.rounds} rounds` : ''})`);
  return grid.map(({ legs: l, characters: n, threads: t }) => {
    const at = (e) => points.find((p) => p.engine === e && p.legs === l && p.characters === n && p.threads === t && !p.skipped);
    const g = at('gaitlab'), mt = at('jolt-mt'), st = at('jolt');
    return [l === 4 ? 'quadrupeds' : 'bipeds', String(n), String(t), cell(g), cell(mt), cell(st), g && mt ? (g.ms_per_step / mt.ms_per_step).toFixed(2) : '—'];
  });
}
