#!/usr/bin/env node
// Times the demo page's optimize panel in headless Chromium: how long a generation takes in the
// optimizer worker (its own module instance, web/src/optimize/optimizer.worker.ts), how long the
// worker takes to load, and what the running crowd keeps of real time meanwhile. These are the
// figures behind running the search outside the sim worker. Nothing is typed in: every figure
// comes from the page's window.gaitlab hook.
//
//   node bench/optimize-panel.mjs [--character biped] [--method greedy] [--candidates 10]
//        [--seconds 6.66667] [--generations 4] [--threads 1,2] [--characters 24]
//
// Writes bench/results/optimize-panel.json.
import { mkdirSync, writeFileSync } from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { startServer } from '../scripts/serve.mjs';
import { launchChromium } from './browser.mjs';

const root = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '..');
const args = Object.fromEntries(process.argv.slice(2).reduce((pairs, a, i, all) =>
  (a.startsWith('--') ? [...pairs, [a.slice(2), all[i + 1]]] : pairs), []));
const inputs = {
  character: args.character ?? 'biped',
  method: args.method ?? 'greedy',
  candidates: Number(args.candidates ?? 10),
  // The module's default episode: the thesis's 800 fixed steps at 120 Hz.
  seconds: Number(args.seconds ?? 800 / 120),
  generations: Number(args.generations ?? 4),
  threads: (args.threads ?? '1,2').split(',').map(Number),
  crowd: Number(args.characters ?? 24),
  seed: Number(args.seed ?? 1),
};

const mean = (xs) => (xs.length ? xs.reduce((a, b) => a + b, 0) / xs.length : null);
const median = (xs) => {
  if (!xs.length) return null;
  const s = [...xs].sort((a, b) => a - b);
  return s.length % 2 ? s[(s.length - 1) / 2] : (s[s.length / 2 - 1] + s[s.length / 2]) / 2;
};

/** Samples the crowd's real-time factor and frame rate every 500 ms while `until()` is false. */
async function sampleCrowd(page, until) {
  const samples = [];
  const t0 = await page.evaluate(() => window.gaitlab.stats().simTime);
  const w0 = Date.now();
  while (!(await until())) {
    await page.waitForTimeout(500);
    const s = await page.evaluate(() => window.gaitlab.stats());
    samples.push({ rtf: s.realtimeFactor, fps: s.fps });
  }
  const t1 = await page.evaluate(() => window.gaitlab.stats().simTime);
  return {
    // Simulated seconds per wall-clock second over the whole window (not smoothed).
    realtime_factor: (t1 - t0) / ((Date.now() - w0) / 1000),
    fps_mean: mean(samples.map((s) => s.fps)),
  };
}

const server = await startServer({ port: 0, quiet: true });
const browser = await launchChromium({ webgl: true });
const browserVersion = browser.version();
const loadAtStart = os.loadavg();
const runs = [];
let machine = null;
try {
  for (const threads of inputs.threads) {
    const page = await browser.newPage({ viewport: { width: 1024, height: 640 } });
    const errors = [];
    page.on('pageerror', (e) => errors.push(e.message));
    await page.goto(`${server.url}?characters=${inputs.crowd}`, { waitUntil: 'load' });
    await page.waitForFunction(() => window.gaitlab?.stats().ready, null, { timeout: 120_000 });
    machine ??= await page.evaluate(() => ({ userAgent: navigator.userAgent, hardwareConcurrency: navigator.hardwareConcurrency }));
    await page.waitForTimeout(3000);
    // The crowd alone first, for comparison: 6 s.
    const start = Date.now();
    const alone = await sampleCrowd(page, async () => Date.now() - start > 6000);
    const crowdThreads = (await page.evaluate(() => window.gaitlab.stats())).threads;
    await page.evaluate((form) => { window.__run = window.gaitlab.optimize(form); }, {
      character: inputs.character, method: inputs.method, candidates: inputs.candidates, seconds: inputs.seconds,
      generations: inputs.generations, threads, seed: inputs.seed,
    });
    const during = await sampleCrowd(page, () => page.evaluate(() => !['loading', 'running'].includes(window.gaitlab.optimizeStatus().state)));
    const status = await page.evaluate(() => window.__run);
    if (status.state !== 'done') throw new Error(`the search ended ${status.state}: ${status.message}`);
    if (errors.length) throw new Error(errors.join('; '));
    const seconds = status.history.map((h) => h.seconds);
    const run = {
      threads,
      crowd_threads: crowdThreads,
      load_seconds: status.loadSeconds,
      seconds_per_generation: seconds,
      mean_seconds_per_generation: mean(seconds),
      median_seconds_per_generation: median(seconds),
      best_objective: status.best,
      crowd_alone: alone,
      crowd_during_search: during,
    };
    console.error(`threads ${threads}: ${run.mean_seconds_per_generation.toFixed(2)} s per generation ` +
      `(${seconds.map((s) => s.toFixed(2)).join(', ')}), load ${run.load_seconds.toFixed(2)} s; crowd real-time factor ` +
      `${alone.realtime_factor.toFixed(2)} alone, ${during.realtime_factor.toFixed(2)} during the search`);
    runs.push(run);
    await page.close();
  }
} finally {
  await browser.close();
  await server.close();
}

const doc = {
  benchmark: 'optimize panel in Chromium',
  date: new Date().toISOString(),
  machine: { ...machine, browser: browserVersion, cpu: os.cpus()[0]?.model ?? 'unknown', cores: os.cpus().length,
    // Timings mean little on a machine busy with other work: say how busy it was.
    load_average_at_start: loadAtStart, load_average_at_end: os.loadavg() },
  inputs,
  runs,
};
mkdirSync(path.join(root, 'bench/results'), { recursive: true });
writeFileSync(path.join(root, 'bench/results/optimize-panel.json'), `${JSON.stringify(doc, null, 2)}\n`);
console.log(JSON.stringify(doc, null, 2));
