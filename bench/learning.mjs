#!/usr/bin/env node
// The learning benchmark: how many new bodies learn to walk in the browser. Larsson (2015, §7.5)
// ends with creatures a player designs and then sees come to life "without too much failure and
// within the strict time scopes of a game"; this measures that, in headless Chromium, through the
// demo page's own designer and optimize panel (window.gaitlab), nothing typed in.
//
// For each body: the shipped insect, spider and dragon as the designer reads them (new bodies of
// each kind: the designer's settings, not the tuned files), then random bodies within the
// designer's limits (creature/design.ts, randomDesign: seeds 1, 2, ...):
//   1. the designer builds it (its checks pass by construction) and its creature file is read;
//   2. its first gait, the one derived from the body, walks 30 s at 0.4 m/s: `gaitlab walk
//      --creature` as WebAssembly (bench/wasm.mjs), the page's module and so its arithmetic. The
//      native build walks it too, as a second reading: its maths library rounds some functions
//      differently in the last bit, so after half a second its walk is another walk of the same
//      gait (docs/parallel.md), and a gait that walks there as well is not on the edge of a fall;
//   3. "Teach it to walk": the optimize panel searches a gait for that body in its worker with all
//      of the device's threads, from the derived gait, with its teaching settings (episodes and
//      goal speed: optimize-panel.ts, TEACHING; --seconds overrides the episodes), for --budget
//      seconds of wall clock, and is stopped there, keeping the best of the generations finished;
//   4. the best gait found walks 30 s at 0.4 m/s.
// A body has learnt to walk if the gait it has after the search (or before it) walks those 30 s
// without falling in the page's arithmetic.
//
//   node bench/learning.mjs [--random 20] [--budget 180] [--shipped insect,spider,dragon]
//        [--candidates 10] [--seconds S] [--out bench/results/learning]
//
// Writes OUT.json and OUT.md. Needs the built page (npm run build) and Chromium.
import { execFileSync } from 'node:child_process';
import { mkdirSync, mkdtempSync, writeFileSync } from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { startServer } from '../scripts/serve.mjs';
import { launchChromium } from './browser.mjs';

const root = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '..');
const args = Object.fromEntries(process.argv.slice(2).reduce((pairs, a, i, all) =>
  (a.startsWith('--') ? [...pairs, [a.slice(2), all[i + 1]]] : pairs), []));
const inputs = {
  random: Number(args.random ?? 20),
  budget: Number(args.budget ?? 180),
  shipped: (args.shipped ?? 'insect,spider,dragon').split(',').filter((s) => s !== ''),
  candidates: Number(args.candidates ?? 10),
  // Episode length: the teaching settings' unless given (then read back from the search's options).
  seconds: args.seconds === undefined ? null : Number(args.seconds),
  // The walking criteria's slow speed: what the judgement walks at, and the teaching goal.
  speed: 0.4,
  judgeSeconds: 30,
};
const out = path.resolve(root, args.out ?? 'bench/results/learning');
const native = path.join(root, 'build/native/gaitlab');
const wasm = [process.execPath, path.join(root, 'bench/wasm.mjs')];
const tmp = mkdtempSync(path.join(os.tmpdir(), 'gaitlab-learning-'));

/**
 * 30 s at the criteria's slow speed with `gait` (a gait file, or null for the body's own first
 * gait): as the page computes it (WebAssembly), and natively.
 */
function judge(creature, gait, name) {
  const body = path.join(tmp, `${name}.json`);
  writeFileSync(body, JSON.stringify(creature));
  const params = [];
  if (gait) {
    params.push('--params', path.join(tmp, `${name}-gait.json`));
    writeFileSync(params[1], JSON.stringify(gait));
  }
  const walk = ([command, ...first]) => {
    const r = JSON.parse(execFileSync(command, [...first, 'walk', '--json', '--creature', body, ...params,
      '--seconds', String(inputs.judgeSeconds), '--speed', String(inputs.speed)], { encoding: 'utf8' }));
    return { fell: r.fell, fall_time_s: r.fall_time_s, mean_speed_m_s: r.mean_speed_m_s, heading_drift_deg: r.heading_drift_deg };
  };
  return { ...walk(wasm), native: walk([native]) };
}

const server = await startServer({ port: 0, quiet: true });
const browser = await launchChromium({ webgl: true });
const bodies = [];
let machine = null;
const started = new Date().toISOString();
try {
  const page = await browser.newPage({ viewport: { width: 1024, height: 640 } });
  const errors = [];
  page.on('pageerror', (e) => errors.push(e.message));
  // No crowd: the search has the cores, as a player teaching one creature would give it.
  await page.goto(`${server.url}?characters=0`, { waitUntil: 'load' });
  await page.waitForFunction(() => window.gaitlab?.stats().ready, null, { timeout: 120_000 });
  machine = await page.evaluate(() => ({ userAgent: navigator.userAgent, hardwareConcurrency: navigator.hardwareConcurrency }));
  const plan = [...inputs.shipped.map((name) => ({ name, shipped: name })), ...Array.from({ length: inputs.random }, (_, k) => ({ name: `random-${k + 1}`, seed: k + 1 }))];
  for (const item of plan) {
    if (item.shipped) await page.evaluate((name) => window.gaitlab.designer.preset(name), item.shipped);
    else await page.evaluate((seed) => window.gaitlab.designer.randomize(seed), item.seed);
    const creature = await page.evaluate(() => window.gaitlab.designer.json());
    if (!creature) throw new Error(`${item.name}: the designer refused it: ${await page.evaluate(() => window.gaitlab.designer.error())}`);
    const design = await page.evaluate(() => window.gaitlab.designer.values());
    const before = judge(creature, null, item.name);
    let search = null;
    let after = before;
    if (inputs.budget > 0) {
      await page.evaluate((form) => { window.__run = window.gaitlab.designer.teach(form); }, {
        generations: 1_000_000, candidates: inputs.candidates, ...(inputs.seconds === null ? {} : { seconds: inputs.seconds }),
        speeds: String(inputs.speed), seed: 1, start: 'preset', threads: machine.hardwareConcurrency,
      });
      const t0 = Date.now();
      await page.waitForFunction(() => window.gaitlab.optimizeStatus().state === 'running', null, { timeout: 120_000, polling: 200 });
      const loadSeconds = (Date.now() - t0) / 1000;
      await page.waitForTimeout(inputs.budget * 1000);
      await page.evaluate(() => window.gaitlab.stopOptimize());
      const status = await page.evaluate(() => window.__run);
      search = {
        state: status.state,
        generations: status.generation,
        evaluations: status.evaluations,
        best_objective: status.best,
        start_objective: status.history[0]?.best ?? null,
        seconds_per_generation: status.secondsPerGeneration,
        episode_seconds: status.options?.settings.seconds ?? null,
        goal_speeds: status.options?.speeds ?? null,
        load_seconds: loadSeconds,
      };
      if (status.result) after = judge(creature, status.result, `${item.name}-learnt`);
    }
    const body = {
      name: item.name,
      ...(item.seed !== undefined ? { seed: item.seed } : {}),
      legs: 2 * creature.legFrames.length,
      design,
      derived_gait: before,
      search,
      learnt_gait: after,
      walks: !after.fell,
    };
    bodies.push(body);
    process.stderr.write(`${item.name}: ${body.legs} legs, derived gait ${before.fell ? `falls at ${before.fall_time_s.toFixed(1)} s` : 'walks'}` +
      (search ? `; after ${search.generations} generations ${after.fell ? `falls at ${after.fall_time_s.toFixed(1)} s` : 'walks'}` : '') + '\n');
  }
  if (errors.length) throw new Error(errors.join('; '));
} finally {
  await browser.close();
  await server.close();
}

const randomBodies = bodies.filter((b) => b.seed !== undefined);
const result = {
  benchmark: 'learning',
  started,
  inputs,
  machine: { ...machine, cpus: os.cpus().length, cpu: os.cpus()[0]?.model, load_average: os.loadavg() },
  bodies,
  summary: {
    shipped_kinds_walk: bodies.filter((b) => b.seed === undefined).map((b) => ({ name: b.name, walks: b.walks })),
    random_bodies: randomBodies.length,
    random_walk_before_search: randomBodies.filter((b) => !b.derived_gait.fell).length,
    random_walk_after_search: randomBodies.filter((b) => b.walks).length,
    random_walk_after_search_native: randomBodies.filter((b) => !b.learnt_gait.native.fell).length,
    random_three_segment_legs: randomBodies.filter((b) => b.design.tarsusLength > 0).length,
  },
};
mkdirSync(path.dirname(out), { recursive: true });
writeFileSync(`${out}.json`, `${JSON.stringify(result, null, 2)}\n`);
/** The episode lengths the searches used, as read back from their options. */
function episodes(list) {
  const lengths = [...new Set(list.map((b) => b.search?.episode_seconds).filter((x) => x != null))];
  return lengths.length ? lengths.map((x) => `${x.toFixed(2)} s`).join(' / ') : '–';
}
const walked = (j) => (j.fell ? `falls at ${j.fall_time_s.toFixed(1)} s` : `walks, ${j.mean_speed_m_s.toFixed(2)} m/s`);
const row = (b) => `| ${b.name} | ${b.legs}${b.design.tarsusLength > 0 ? ' (3 segments)' : ''} | ${walked(b.derived_gait)} | ` +
  `${b.search ? `${b.search.generations} (${b.search.seconds_per_generation?.toFixed(2) ?? '–'} s each)` : '–'} | ` +
  `${b.search ? `${b.search.start_objective?.toPrecision(4) ?? '–'} → ${b.search.best_objective?.toPrecision(4) ?? '–'}` : '–'} | ` +
  `${walked(b.learnt_gait)} | ${walked(b.learnt_gait.native)} |`;
writeFileSync(`${out}.md`, [
  `# The learning benchmark`,
  ``,
  `${started}, ${result.machine.cpus} × ${result.machine.cpu}, ${machine?.userAgent ?? ''}; budget ${inputs.budget} s of search per body,`,
  `${inputs.candidates} candidates per generation, ${episodes(bodies)} episodes at ${inputs.speed} m/s; judged by 30 s at ${inputs.speed} m/s`,
  `as the page computes it (WebAssembly, bench/wasm.mjs), and natively as a second reading (another rounding of the same walk).`,
  ``,
  `Random bodies that walk 30 s: ${result.summary.random_walk_before_search} of ${randomBodies.length} with their derived gait, ` +
    `${result.summary.random_walk_after_search} of ${randomBodies.length} after the search ` +
    `(natively ${result.summary.random_walk_after_search_native} of ${randomBodies.length}); ` +
    `${result.summary.random_three_segment_legs} of them have legs of three segments.`,
  ``,
  `| body | legs | derived gait, 30 s | generations in the budget | best objective | learnt gait, 30 s | natively |`,
  `|---|---|---|---|---|---|---|`,
  ...bodies.map(row),
  ``,
].join('\n'));
process.stdout.write(`${JSON.stringify(result.summary)}\n`);
