// A gait as a filmstrip from the real renderer: the demo page in headless Chromium, one
// character of a type, paused and stepped a fixed number of 120 Hz steps between frames, seen
// from the side while the camera follows it. The frames are laid out in one row, each labelled
// with its simulated time, and saved as one PNG (the README's gait sequences).
//
//   node scripts/filmstrip.mjs --type biped [--frames 8] [--every 12] [--warmup 480]
//                              [--speed M_S] [--gait walk|trot|pace] [--out docs/images/biped-gait.png]
//                              [--patch '{"period": 0.6}']   (an edit of the gait, as the editors make)
//                              [--params FILE]   (a gait file, given to the page as a link carries one)
//                              [--throw]   (after the warm-up, a box thrown at it from the camera, as
//                                           the demo's shift-click throws one: a fall, and getting up)
//                              [--after STEPS]   (with --throw: steps run after the throw before the
//                                                 first frame, to film the getting up, not the blow)
//   node scripts/filmstrip.mjs --creature insect [...]   (a shipped creature, public/creatures/insect.json,
//                                                         alone in the scene: ?characters=0&creature=insect)
//
// Needs the WASM build (npm run build) and Chromium (CHROMIUM=/path overrides /usr/bin/chromium).
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { parseArgs } from 'node:util';
import { chromium } from 'playwright-core';
import { runnerImport } from 'vite';
import { startServer } from './serve.mjs';

const repoDir = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '..');

function usage(message) {
  console.error(`filmstrip: ${message}\nusage: node scripts/filmstrip.mjs --type biped|quadruped ` +
    '[--frames N] [--every STEPS] [--warmup STEPS] [--speed M_S] [--out FILE.png]');
  process.exit(2);
}

let args;
try {
  ({ values: args } = parseArgs({
    options: {
      type: { type: 'string' },
      creature: { type: 'string' },
      frames: { type: 'string', default: '8' },
      every: { type: 'string', default: '12' },
      warmup: { type: 'string', default: '480' },
      speed: { type: 'string' },
      gait: { type: 'string' },
      patch: { type: 'string' },
      params: { type: 'string' },
      out: { type: 'string' },
      throw: { type: 'boolean', default: false },
      after: { type: 'string', default: '0' },
    },
  }));
} catch (error) {
  usage(error.message);
}
if (args.creature !== undefined) {
  if (args.type !== undefined || args.gait || args.patch || args.params) usage('--creature takes none of --type, --gait, --patch, --params');
  if (!fs.existsSync(path.join(repoDir, 'public', 'creatures', `${args.creature}.json`))) usage(`--creature: no public/creatures/${args.creature}.json`);
} else if (args.type !== 'biped' && args.type !== 'quadruped') usage('--type must be biped or quadruped');
// A creature is seen and framed as the character its legs make it most like: a single pair (the
// bird) as the biped, more as the quadruped.
const creature = args.creature;
const creatureFrames = creature ? JSON.parse(fs.readFileSync(path.join(repoDir, 'public', 'creatures', `${creature}.json`), 'utf8')).legFrames.length : 0;
const view = creature ? (creatureFrames === 1 ? 'biped' : 'quadruped') : args.type;
const count = (name, min, max) => {
  const v = Number(args[name]);
  if (!Number.isInteger(v) || v < min || v > max) usage(`--${name} must be an integer in [${min}, ${max}]`);
  return v;
};
const frames = count('frames', 1, 24), every = count('every', 1, 1200), warmup = count('warmup', 0, 12000);
const after = count('after', 0, 12000);
if (after > 0 && !args.throw) usage('--after counts the steps after --throw');
const speed = args.speed === undefined ? null : Number(args.speed);
if (speed !== null && !(Number.isFinite(speed) && speed >= 0 && speed <= 5)) usage('--speed must be in [0, 5] m/s (the goal speeds the CLI takes)');
const out = path.resolve(args.out ?? path.join(repoDir, 'docs', 'images', `${creature ?? args.type}-gait.png`));

// A gait file reaches the page as a share link carries one, made by the page's own codec
// (web/src/share/link.ts, loaded through Vite): the page decodes it and the module judges it.
const webModule = async (file) =>
  (await runnerImport(path.join(repoDir, 'web', 'src', 'share', file), { configFile: false, logLevel: 'silent' })).module;
const gaitFile = args.params ? JSON.parse(fs.readFileSync(args.params, 'utf8')) : null;
const hash = gaitFile ? await (await webModule('link.ts')).encodeGaitHash(gaitFile) : '';
const sameParams = gaitFile ? (await webModule('gait-file.ts')).sameParams : null;

const server = await startServer({ port: 0, quiet: true });
const profile = fs.mkdtempSync(path.join(os.tmpdir(), 'gaitlab-filmstrip-'));
const context = await chromium.launchPersistentContext(profile, {
  executablePath: process.env.CHROMIUM || '/usr/bin/chromium',
  headless: true,
  viewport: { width: 900, height: 640 },
  args: ['--no-sandbox', '--disable-gpu', '--enable-unsafe-swiftshader', '--no-first-run'],
});
try {
  const page = await context.newPage();
  page.on('pageerror', (error) => console.error(`page error: ${error.message}`));
  // The mixed crowd alternates biped, quadruped, …: one character for a biped, two for a
  // quadruped (the other then walks beside it, a grid place away).
  const crowd = creature ? 0 : args.type === 'biped' ? 1 : 2;
  await page.goto(`${server.url}?characters=${crowd}&paused=1&threads=1${creature ? `&creature=${creature}` : ''}${hash}`, { waitUntil: 'load' });
  await page.waitForFunction(() => window.gaitlab?.stats().ready || window.gaitlab?.stats().error, null,
    { timeout: 120_000, polling: 250 });
  const error = await page.evaluate(() => window.gaitlab.stats().error);
  if (error) throw new Error(`the page shows a problem: ${error}`);

  let simSteps = 0;
  const stepBy = async (n) => {
    if (n === 0) return;
    simSteps += n;
    await page.evaluate((k) => window.gaitlab.step(k), n);
    await page.waitForFunction((t) => Math.abs(window.gaitlab.stats().simTime - t) < 1e-6, simSteps / 120,
      { timeout: 120_000, polling: 50 });
    await page.waitForTimeout(400); // the next animation frames draw the newest state
  };
  await stepBy(1);
  if (creature) {  // the page fetches its file, then spawns it
    await page.waitForFunction(() => window.gaitlab.characters().length > 0, null, { timeout: 30_000, polling: 100 });
  }
  const characters = await page.evaluate(() => window.gaitlab.characters());
  const subject = creature ? characters[0] : characters.find((c) => c.type === args.type);
  if (!subject) throw new Error(`no ${creature ?? args.type} in the scene`);
  if (gaitFile) {
    // The page applies a linked gait once the simulation has it; a refused link keeps the presets.
    const carried = async () => sameParams(await page.evaluate((id) => window.gaitlab.getGait(id), subject.id), gaitFile);
    let ok = false;
    for (let tries = 0; tries < 40 && !(ok = await carried()); ++tries) await page.waitForTimeout(250);
    if (!ok) throw new Error(`the page did not take ${args.params} (its link was refused, or it is for another character)`);
  }
  if (speed !== null) await page.evaluate(([id, v]) => window.gaitlab.setGoal(id, { speed: v, turn: 0 }), [subject.id, speed]);
  if (args.gait) {
    // The quadruped's gait menu of the demo (walk, trot or pace: whole tuned gaits).
    if (args.type !== 'quadruped') usage('--gait is for the quadruped');
    await page.locator('.lil-controller', { hasText: 'quadruped gait' }).locator('select').selectOption(args.gait);
    await page.waitForTimeout(1000);
  }
  await page.evaluate((id) => window.gaitlab.select(id), subject.id);
  if (args.patch) {
    let patch;
    try {
      patch = JSON.parse(args.patch);
    } catch (error) {
      usage(`--patch is not JSON: ${error.message}`);
    }
    const refused = await page.evaluate((p) => window.gaitlab.editGait(p), patch);
    if (refused) usage(`--patch refused: ${refused}`);
  }
  // Only the scene: the panels and the heads-up line would cover the character.
  await page.addStyleTag({ content: 'body > :not(canvas) { visibility: hidden !important; }' });
  await stepBy(warmup);
  // The camera is put beside the character before every frame, seen from its left side (+x,
  // characters walk along +z), at a distance it keeps (the demo's follow key eases after the
  // character, and at 2.5 m/s lagged it out of the frame).
  const side = view === 'biped' ? [6.5, 0.7, 0] : creature === 'dragon' ? [5.6, 0.35, 0] : [4.2, 0.35, 0];
  const lookAt = async () => {
    const here = (await page.evaluate(() => window.gaitlab.characters())).find((c) => c.id === subject.id);
    const to = [here.position[0], here.position[1], here.position[2]];
    const from = to.map((v, i) => v + side[i]);
    await page.evaluate(([a, b]) => window.gaitlab.view(a, b), [from, to]);
  };

  if (args.throw) {
    await lookAt();
    await page.waitForTimeout(300);
    await page.evaluate((id) => {
      const c = window.gaitlab.characters().find((x) => x.id === id);
      window.gaitlab.throwBox([c.position[0], c.position[1], c.position[2]]);
    }, subject.id);
    if (after > 0) await stepBy(after);
  }
  const [w, h] = view === 'biped' ? [260, 380] : [400, 300];  // one frame, px
  const shots = [];
  for (let f = 0; f < frames; ++f) {
    if (f > 0) await stepBy(every);
    await lookAt();
    await page.waitForTimeout(300); // the next animation frames draw the new view
    const at = await page.evaluate((id) => window.gaitlab.screenPosition(id), subject.id);
    if (!at) throw new Error('the character is not on screen');
    // The character's screen position is its root leg frame's: the biped's trunk, the quadruped's
    // front leg frame, whose body trails behind it (to the right, seen from its left side).
    const clip = { x: Math.max(0, at.x - w * (view === 'biped' ? 0.5 : 0.28)), y: Math.max(0, at.y - h * 0.32), width: w, height: h };
    shots.push({ png: (await page.screenshot({ clip })).toString('base64'), t: simSteps / 120 });
    process.stderr.write(`frame ${f + 1}/${frames} at ${(simSteps / 120).toFixed(3)} s\n`);
  }

  // One row of frames, labelled, drawn by the browser itself.
  const sheet = await context.newPage();
  await sheet.setViewportSize({ width: w * frames, height: h + 30 });
  await sheet.setContent(`<body style="margin:0;display:flex;font:13px system-ui;background:#fff">${shots
    .map((s) => `<figure style="margin:0;width:${w}px"><img src="data:image/png;base64,${s.png}" style="display:block">` +
      `<figcaption style="text-align:center;padding:4px">t = ${s.t.toFixed(2)} s</figcaption></figure>`)
    .join('')}</body>`);
  fs.mkdirSync(path.dirname(out), { recursive: true });
  await sheet.screenshot({ path: out, fullPage: true });
  console.log(`filmstrip: ${path.relative(repoDir, out)} (${frames} frames, ${every} steps apart, from ${(warmup / 120).toFixed(2)} s)`);
} finally {
  await context.close();
  await server.close();
  fs.rmSync(profile, { recursive: true, force: true });
}
