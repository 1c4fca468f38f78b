#!/usr/bin/env node
// Compares the thesis's greedy stochastic search (§3.3) with CMA-ES on the same evaluation
// budget, and times a generation natively and as WebAssembly at 1 and 2
// threads. Every figure comes from running `gaitlab optimize`; nothing is typed in.
//
//   node bench/optimizers.mjs [--generations N] [--candidates K] [--seconds S] [--seeds 1,2,3]
//   node bench/optimizers.mjs --plot-only 1     (redraws the SVG from the existing results)
//
// Writes bench/results/optimizers.json (machine, inputs, every run's best objective after each
// generation) and bench/results/optimizers.svg (best objective against evaluations, median
// over seeds, per character and method).
import { spawnSync } from 'node:child_process';
import { mkdirSync, mkdtempSync, readFileSync, writeFileSync } from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { fileURLToPath } from 'node:url';

const root = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '..');
const native = path.join(root, 'build/native/gaitlab');
const results = path.join(root, 'bench/results');
const scratch = mkdtempSync(path.join(os.tmpdir(), 'gaitlab-bench-opt-'));

const args = Object.fromEntries(process.argv.slice(2).reduce((pairs, a, i, all) =>
  (a.startsWith('--') ? [...pairs, [a.slice(2), all[i + 1]]] : pairs), []));
const generations = Number(args.generations ?? 30);
const candidates = Number(args.candidates ?? 10);
const seconds = Number(args.seconds ?? 4);
const seeds = (args.seeds ?? '1,2,3').split(',').map(Number);
const characters = ['biped', 'quadruped'];
const methods = ['greedy', 'cmaes'];

function optimize(cmd, pre, character, method, seed, threads, gens = generations) {
  const out = path.join(scratch, `${character}-${method}-${seed}-${threads}.json`);
  const argv = [...pre, 'optimize', '--character', character, '--method', method, '--generations', String(gens),
    '--candidates', String(candidates), '--seconds', String(seconds), '--seed', String(seed),
    '--threads', String(threads), '--out', out, '--json'];
  const r = spawnSync(cmd, argv, { cwd: root, encoding: 'utf8', maxBuffer: 1 << 26 });
  if (r.status !== 0) throw new Error(`${cmd} ${argv.join(' ')} failed:\n${r.stderr}`);
  return JSON.parse(r.stdout);
}

let doc;
if (args['plot-only']) {
  doc = JSON.parse(readFileSync(path.join(results, 'optimizers.json'), 'utf8'));
} else {
  const machine = {
    cpu: os.cpus()[0]?.model ?? 'unknown',
    cores: os.cpus().length,
    node: process.version,
    platform: `${os.platform()} ${os.release()}`,
    // Thread speedups mean little on a machine busy with other work: say how busy it was.
    load_average_at_start: os.loadavg(),
  };
  console.error(`machine: ${machine.cpu}, ${machine.cores} cores, Node ${machine.node}, load ${machine.load_average_at_start[0].toFixed(1)}`);

  // ---- objective against evaluations -------------------------------------------------------------
  const runs = [];
  for (const character of characters) {
    for (const method of methods) {
      for (const seed of seeds) {
        const s = optimize(native, [], character, method, seed, Math.min(2, machine.cores));
        console.error(`${character} ${method} seed ${seed}: ${s.start_objective.toFixed(3)} -> ${s.best_objective.toFixed(3)}` +
          ` in ${s.evaluations} evaluations (${s.seconds_per_generation.toFixed(2)} s/generation)`);
        runs.push({ character, method, seed, start_objective: s.start_objective, best_objective: s.best_objective,
          best_terms: s.best_terms, evaluations: s.evaluations,
          history: s.history.map((h) => ({ evaluations: h.evaluations, best_objective: h.best_objective })) });
      }
    }
  }

  // ---- time per generation: native and WASM, 1 and 2 threads --------------------------------------
  const timingGenerations = 4;
  const timing = [];
  for (const [build, cmd, pre] of [['native', native, []], ['wasm', process.execPath, ['bench/wasm.mjs']]]) {
    for (const threads of [1, 2]) {
      const s = optimize(cmd, pre, 'biped', 'greedy', 1, threads, timingGenerations);
      timing.push({ build, threads, character: 'biped', candidates, seconds_per_generation: s.seconds_per_generation,
        best_objective: s.best_objective });
      console.error(`${build}, ${threads} thread(s): ${s.seconds_per_generation.toFixed(3)} s/generation`);
    }
  }
  const per = (b, t) => timing.find((x) => x.build === b && x.threads === t).seconds_per_generation;
  const speedup = { native: per('native', 1) / per('native', 2), wasm: per('wasm', 1) / per('wasm', 2),
    wasm_over_native_1_thread: per('wasm', 1) / per('native', 1) };
  // The search must not depend on the thread count.
  for (const b of ['native', 'wasm']) {
    const [a, c] = timing.filter((x) => x.build === b);
    if (a.best_objective !== c.best_objective) throw new Error(`${b}: 1 and 2 threads found different results`);
  }

  machine.load_average_at_end = os.loadavg();
  mkdirSync(results, { recursive: true });
  doc = { benchmark: 'optimizers', date: new Date().toISOString(), machine,
    inputs: { generations, candidates, episode_seconds: seconds, seeds, characters, methods,
      objective: 'gaitlab optimize defaults (native/src/optimize/objective.h)' },
    runs, timing, speedup };
  writeFileSync(path.join(results, 'optimizers.json'), `${JSON.stringify(doc, null, 2)}\n`);
}
const { runs, machine } = doc;
const { seeds: plotSeeds, candidates: perGeneration, episode_seconds: episodeSeconds } = doc.inputs;

// ---- plot: median best objective against evaluations --------------------------------------------
const median = (xs) => { const s = [...xs].sort((a, b) => a - b); const m = s.length >> 1; return s.length % 2 ? s[m] : (s[m - 1] + s[m]) / 2; };
const W = 980, H = 380, panelW = 400, panelH = 280, left = 60, top = 50;
const colours = { greedy: '#d9534f', cmaes: '#4e8fd9' };
let svg = `<svg xmlns="http://www.w3.org/2000/svg" width="${W}" height="${H}" font-family="sans-serif" font-size="12">\n`;
svg += `<rect width="${W}" height="${H}" fill="white"/>\n`;
svg += `<text x="${W / 2}" y="20" text-anchor="middle" font-size="14">Best objective (median of ${plotSeeds.length} seeds, log scale) against evaluations: greedy (§3.3) vs CMA-ES</text>\n`;
characters.forEach((character, ci) => {
  const x0 = left + ci * (panelW + 60);
  const series = methods.map((method) => {
    const rs = runs.filter((r) => r.character === character && r.method === method);
    return { method, points: rs[0].history.map((h, i) => [h.evaluations, median(rs.map((r) => r.history[i].best_objective))]) };
  });
  const all = series.flatMap((s) => s.points.map((p) => p[1])).filter((v) => v > 0);
  const lo = Math.log10(Math.min(...all)) - 0.05, hi = Math.log10(Math.max(...all)) + 0.05;
  const maxE = Math.max(...series.flatMap((s) => s.points.map((p) => p[0])));
  const px = (e) => x0 + (e / maxE) * panelW;
  const py = (v) => top + panelH - ((Math.log10(v) - lo) / (hi - lo)) * panelH;
  svg += `<rect x="${x0}" y="${top}" width="${panelW}" height="${panelH}" fill="none" stroke="#999"/>\n`;
  svg += `<text x="${x0 + panelW / 2}" y="${top - 8}" text-anchor="middle">${character}</text>\n`;
  const ticks = [10 ** lo, ...Array.from({ length: Math.floor(hi) - Math.ceil(lo) + 1 }, (_, i) => 10 ** (Math.ceil(lo) + i)), 10 ** hi];
  for (const v of ticks) {
    svg += `<line x1="${x0}" x2="${x0 + panelW}" y1="${py(v).toFixed(1)}" y2="${py(v).toFixed(1)}" stroke="#eee"/>`;
    svg += `<text x="${x0 - 6}" y="${(py(v) + 4).toFixed(1)}" text-anchor="end">${Number(v.toPrecision(3))}</text>\n`;
  }
  svg += `<text x="${x0 + panelW / 2}" y="${top + panelH + 30}" text-anchor="middle">evaluations</text>\n`;
  svg += `<text x="${x0}" y="${top + panelH + 15}" text-anchor="middle">0</text><text x="${x0 + panelW}" y="${top + panelH + 15}" text-anchor="middle">${maxE}</text>\n`;
  series.forEach((s, si) => {
    svg += `<polyline fill="none" stroke="${colours[s.method]}" stroke-width="2" points="${s.points.map(([e, v]) => `${px(e).toFixed(1)},${py(v).toFixed(1)}`).join(' ')}"/>\n`;
    svg += `<text x="${x0 + panelW - 10}" y="${top + 18 + 16 * si}" text-anchor="end" fill="${colours[s.method]}">${s.method}</text>\n`;
  });
});
svg += `<text x="${W / 2}" y="${H - 8}" text-anchor="middle" fill="#666">${machine.cpu}, ${machine.cores} cores; ${perGeneration} candidates/generation, ${episodeSeconds} s episodes; objective > 100 means the gait fell</text>\n`;
svg += '</svg>\n';
writeFileSync(path.join(results, 'optimizers.svg'), svg);
console.log(JSON.stringify({ speedup: doc.speedup, timing: doc.timing, best: runs.map((r) => ({ character: r.character, method: r.method, seed: r.seed, best_objective: r.best_objective })) }));
