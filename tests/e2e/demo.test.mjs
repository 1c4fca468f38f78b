// End to end: the demo page in headless Chromium, served by scripts/serve.mjs on a free port,
// simulating the real WASM module in its worker and drawing it with WebGL (SwiftShader).
//
//   node --test tests/e2e
//
// Needs build/wasm/gaitlab.{mjs,wasm,worker.js} (npm run build) and Chromium (CHROMIUM=/path
// overrides /usr/bin/chromium). Screenshots go to test-results/e2e/.
import assert from 'node:assert/strict';
import fs from 'node:fs';
import http from 'node:http';
import path from 'node:path';
import { after, afterEach, before, describe, it } from 'node:test';
import { chromium } from 'playwright-core';
import { isDeepStrictEqual } from 'node:util';
import { openRecordedPage, PAGE_TIMEOUT, ready, repoDir, resultsDir, startBrowser, stats } from './browser.mjs';

const executablePath = process.env.CHROMIUM || '/usr/bin/chromium';

const TEST_TIMEOUT = 240_000;

/** @type {Awaited<ReturnType<typeof startBrowser>>} */
let browser;
/** @type {Awaited<ReturnType<typeof startBrowser>>['server']} */
let server;
/** @type {import('playwright-core').BrowserContext} */
let context;

const openPage = (url) => openRecordedPage(context, url);

/** Waits for the worker's next report (4 a second) so characters() is current. */
async function freshCharacters(page) {
  const before = await page.evaluate(() => window.gaitlab.stats().simTime);
  await page.waitForFunction((t) => window.gaitlab.stats().simTime !== t, before, { timeout: PAGE_TIMEOUT, polling: 100 });
  await page.waitForTimeout(600);
  return page.evaluate(() => window.gaitlab.characters());
}

/** Steps a page that was opened with ?paused=1 and waits until its report shows the steps. */
async function stepTo(page, steps) {
  const target = steps / 120;
  await page.evaluate((n) => window.gaitlab.step(n), steps);
  await page.waitForFunction((t) => Math.abs(window.gaitlab.stats().simTime - t) < 1e-6, target, { timeout: PAGE_TIMEOUT, polling: 100 });
  // The statistics report after the step carries the characters.
  await page.waitForTimeout(700);
  return page.evaluate(() => window.gaitlab.characters());
}

const dist = (a, b) => Math.hypot(a[0] - b[0], a[1] - b[1], a[2] - b[2]);

/** Skips a test that needs the parameter schema when this build of the module has none. */
async function needsSchema(t, page) {
  if ((await stats(page)).gaits) return false;
  t.skip('this build of the WASM module has no parameter schema yet (gl_schema_json)');
  await page.close();
  return true;
}


/** Distinct colours (4 bits per channel) in a PNG, decoded by the browser itself. */
async function distinctColours(page, png) {
  return page.evaluate(async (base64) => {
    const bitmap = await createImageBitmap(await (await fetch(`data:image/png;base64,${base64}`)).blob());
    const canvas = new OffscreenCanvas(bitmap.width, bitmap.height);
    const ctx = canvas.getContext('2d');
    ctx.drawImage(bitmap, 0, 0);
    const { data } = ctx.getImageData(0, 0, bitmap.width, bitmap.height);
    const colours = new Set();
    for (let i = 0; i < data.length; i += 4) colours.add(((data[i] >> 4) << 8) | ((data[i + 1] >> 4) << 4) | (data[i + 2] >> 4));
    return colours.size;
  }, png.toString('base64'));
}

/**
 * The built page (build/web, `npm run build`) served as a static host without COOP/COEP would
 * serve it: plain files, right content types, no isolation headers. `serviceWorker`, if given,
 * rewrites the script the browser installs as the service worker (its requests carry
 * `Service-Worker: script`; the page's own <script> of the same file is served as it is), to try
 * the page against a worker that installs slowly or does not isolate.
 */
function startStaticHost(root, { serviceWorker } = {}) {
  const types = { '.html': 'text/html', '.js': 'text/javascript', '.mjs': 'text/javascript', '.css': 'text/css', '.wasm': 'application/wasm', '.json': 'application/json', '.svg': 'image/svg+xml' };
  const host = http.createServer((request, response) => {
    const url = new URL(request.url ?? '/', 'http://host');
    const file = path.join(root, decodeURIComponent(url.pathname).replace(/\/$/, '/index.html'));
    if (!file.startsWith(root) || !fs.existsSync(file) || !fs.statSync(file).isFile()) {
      response.writeHead(404).end();
      return;
    }
    response.writeHead(200, { 'Content-Type': types[path.extname(file)] ?? 'application/octet-stream' });
    if (serviceWorker && request.headers['service-worker'] === 'script') {
      response.end(serviceWorker(fs.readFileSync(file, 'utf8')));
      return;
    }
    fs.createReadStream(file).pipe(response);
  });
  return new Promise((resolve) => {
    host.listen(0, '127.0.0.1', () => {
      const { port } = /** @type {import('node:net').AddressInfo} */ (host.address());
      resolve({ port, url: `http://127.0.0.1:${port}/`, close: () => new Promise((done) => host.close(done)) });
    });
  });
}

describe('demo page', { timeout: TEST_TIMEOUT * 14 }, () => {
  before(async () => {
    browser = await startBrowser({ viewport: { width: 1024, height: 640 } });
    ({ server, context } = browser);
  });

  afterEach(() => browser?.closePages());

  after(() => browser?.close());

  it('runs a mixed crowd, draws it in a constant number of draw calls, pauses, steps and resets', { timeout: TEST_TIMEOUT }, async () => {
    const { page, problems } = await openPage(server.url);
    assert.equal(await page.evaluate(() => window.crossOriginIsolated), true, 'the page is cross-origin isolated');
    const first = await ready(page);
    assert.equal(first.crossOriginIsolated, true);
    assert.equal(first.isolation, 'headers');
    assert.ok(first.threads >= 1, `the simulation has threads (${first.threads})`);
    const crowd = await freshCharacters(page);
    assert.equal(crowd.length, 24, 'a crowd of 24 by default');
    assert.equal(crowd.filter((c) => c.type === 'biped').length, 12, 'a dozen bipeds');
    assert.equal(crowd.filter((c) => c.type === 'quadruped').length, 12, 'a dozen quadrupeds');

    // Simulated time advances: in real time on a desktop, slower on a loaded 2-core machine
    // rendering in software, so the bounds only rule out standing still and running ahead.
    await page.waitForTimeout(4000);
    const later = await stats(page);
    const advanced = later.simTime - first.simTime;
    assert.ok(advanced > 0.5, `simulated time advanced by ${advanced.toFixed(2)} s in 4 s of wall time`);
    assert.ok(later.realtimeFactor > 0.1 && later.realtimeFactor < 1.5, `real-time factor ${later.realtimeFactor.toFixed(2)}`);
    assert.ok(later.fps > 0, `frames are drawn (${later.fps.toFixed(1)} FPS)`);
    assert.ok(later.drawCalls > 0, `draw calls are counted (${later.drawCalls})`);
    console.log(`demo: ${later.characters} characters, ${later.bodies} bodies, ${later.threads} threads, ${later.fps.toFixed(1)} FPS, ` +
      `real-time factor ${later.realtimeFactor.toFixed(2)}, ${later.drawCalls} draw calls`);
    const hud = await page.getByTestId('hud').innerText();
    assert.match(hud, /FPS · .* · 24 characters.* · \d+ threads? · (multi-threaded|serial) .* · \d+ draw calls/);
    // The wording follows the thread count: one thread is serial, not "multi-threaded".
    assert.match(hud, later.threads > 1 ? /\d+ threads · multi-threaded/ : /1 thread · serial/);

    const png = await page.screenshot({ path: path.join(resultsDir, 'demo.png') });
    const colours = await distinctColours(page, png);
    assert.ok(colours >= 8, `the canvas is not blank (${colours} distinct colours)`);

    // More characters, same draw calls: everything is one instanced mesh.
    await page.getByRole('button', { name: 'Add characters' }).click();
    await page.getByRole('button', { name: 'Add characters' }).click();
    await page.waitForFunction(() => window.gaitlab.stats().characters === 26, null, { timeout: PAGE_TIMEOUT });
    await page.waitForTimeout(500);
    assert.equal((await stats(page)).drawCalls, later.drawCalls, 'draw calls do not grow with the number of characters');

    // Pause stops simulated time; single steps advance it by 1/120 s; resume restarts it.
    await page.getByRole('button', { name: 'Pause' }).click();
    await page.waitForFunction(() => window.gaitlab.stats().paused, null, { timeout: PAGE_TIMEOUT });
    await page.getByRole('button', { name: 'Resume' }).waitFor({ timeout: PAGE_TIMEOUT });
    await page.waitForTimeout(1000); // the worker's last frame reaches the screen
    const pausedAt = (await stats(page)).simTime;
    await page.waitForTimeout(1000);
    assert.equal((await stats(page)).simTime, pausedAt, 'simulated time stands still while paused');
    await page.getByRole('button', { name: 'Step' }).click();
    await page.waitForFunction((t) => window.gaitlab.stats().simTime > t, pausedAt, { timeout: PAGE_TIMEOUT });
    assert.ok(Math.abs((await stats(page)).simTime - pausedAt - 1 / 120) < 1e-9, 'one step is 1/120 s');
    await page.getByRole('button', { name: 'Resume' }).click();
    await page.waitForFunction((t) => window.gaitlab.stats().simTime > t + 0.2, pausedAt, { timeout: PAGE_TIMEOUT });

    // Reset builds a new scene from the start: simulated time goes back to (nearly) 0.
    const beforeReset = (await stats(page)).simTime;
    await page.getByRole('button', { name: 'Reset', exact: true }).click();
    await page.waitForFunction((t) => window.gaitlab.stats().simTime < t, beforeReset, { timeout: PAGE_TIMEOUT });
    assert.ok((await stats(page)).bodies > 0, 'the new scene is drawn');

    assert.deepEqual(problems, [], 'no page errors');
    await page.close();
  });

  // The demo's first promise: the default crowd (bipeds at 1.0 m/s, quadrupeds at 0.4 m/s, the
  // speeds their presets are benchmarked at) walks.
  it('the crowd walks: every character advances and none has fallen after 10 s', { timeout: TEST_TIMEOUT }, async () => {
    const { page, problems } = await openPage(server.url);
    await ready(page);
    const start = await freshCharacters(page);
    // Ten simulated seconds from the first sample (under load the page may be seconds into the
    // walk by then: a fixed end time left a quadruped at 0.4 m/s short of 2 m).
    const t0 = (await stats(page)).simTime;
    await page.waitForFunction((t) => window.gaitlab.stats().simTime >= t + 10, t0, { timeout: PAGE_TIMEOUT, polling: 500 });
    const end = await freshCharacters(page);
    const fallen = end.filter((c) => c.fallen).map((c) => `${c.type} #${c.id}`);
    const stuck = end
      .filter((c) => {
        const s = start.find((x) => x.id === c.id);
        return Math.hypot(c.position[0] - s.position[0], c.position[2] - s.position[2]) < 2;
      })
      .map((c) => `${c.type} #${c.id}`);
    assert.deepEqual(fallen, [], `characters fallen after 10 s: ${fallen.length} of ${end.length}`);
    assert.deepEqual(stuck, [], 'every character walked at least 2 m in 10 s');
    assert.deepEqual(problems, [], 'no page errors');
    await page.close();
  });

  it('the quadrupeds switch from trot to walk, to pace and back in mid-stride, and keep walking', { timeout: TEST_TIMEOUT }, async (t) => {
    const { page, problems } = await openPage(`${server.url}?characters=4`);
    await ready(page);
    if (await needsSchema(t, page)) return;
    const quadrupeds = (await page.evaluate(() => window.gaitlab.characters())).filter((c) => c.type === 'quadruped').map((c) => c.id);
    assert.equal(quadrupeds.length, 2);
    const walk = await page.evaluate(async () => (await fetch('presets/quadruped-walk.json')).json());
    const pace = await page.evaluate(async () => (await fetch('presets/quadruped-pace.json')).json());
    const gaitSelect = page.locator('.lil-controller', { hasText: 'quadruped gait' }).locator('select');
    const simTime = async () => (await stats(page)).simTime;

    // A gait reaches the simulation through the worker: wait for it (frames come seconds apart
    // under load), then compare exactly.
    const gaitReaches = async (id, params, what) => {
      const deadline = Date.now() + PAGE_TIMEOUT;
      let now;
      do {
        now = (await page.evaluate((i) => window.gaitlab.getGait(i), id)).params;
        if (isDeepStrictEqual(now, params)) return;
        await page.waitForTimeout(250);
      } while (Date.now() < deadline);
      assert.deepEqual(now, params, what);
    };
    await gaitSelect.selectOption('walk');
    for (const id of quadrupeds) await gaitReaches(id, walk.params, `quadruped #${id} walks with the walk preset`);
    const switched = await simTime();
    await page.waitForFunction((t0) => window.gaitlab.stats().simTime >= t0 + 5, switched, { timeout: PAGE_TIMEOUT, polling: 250 });
    await gaitSelect.selectOption('pace');
    for (const id of quadrupeds) await gaitReaches(id, pace.params, `quadruped #${id} paces`);
    const paced = await simTime();
    await page.waitForFunction((t0) => window.gaitlab.stats().simTime >= t0 + 5, paced, { timeout: PAGE_TIMEOUT, polling: 250 });
    await gaitSelect.selectOption('trot');
    const trot = await page.evaluate(() => window.gaitlab.presetGait('quadruped'));
    for (const id of quadrupeds) await gaitReaches(id, trot.params, `quadruped #${id} trots again`);
    const back = await simTime();
    await page.waitForFunction((t0) => window.gaitlab.stats().simTime >= t0 + 5, back, { timeout: PAGE_TIMEOUT, polling: 250 });
    const fallen = (await freshCharacters(page)).filter((c) => c.fallen).map((c) => `${c.type} #${c.id}`);
    assert.deepEqual(fallen, [], 'nobody fell over the three switches');
    assert.deepEqual(problems, [], 'no page errors');
    await page.close();
  });

  it('creatures by name: an insect and a spider from their files walk beside the crowd; a bad creature is refused with a message', { timeout: TEST_TIMEOUT }, async () => {
    const { page: crowdOnly } = await openPage(`${server.url}?threads=1&paused=1&characters=2`);
    const before = await ready(crowdOnly);
    await crowdOnly.close();
    const { page, problems } = await openPage(`${server.url}?threads=1&paused=1&characters=2&creature=insect,spider`);
    await ready(page);
    // The page fetches the files, then spawns them: 2 crowd characters and 2 creatures.
    await page.waitForFunction(() => window.gaitlab.characters().length === 4, null, { timeout: PAGE_TIMEOUT, polling: 100 });
    const start = await page.evaluate(() => window.gaitlab.characters());
    const moved = await stepTo(page, 1200);  // 10 s
    // Their bodies are drawn: the insect's 23 and the spider's 31 beside the crowd's scene.
    assert.equal((await stats(page)).bodies - before.bodies, 23 + 31);
    for (const c of start.slice(2)) {
      const now = moved.find((m) => m.id === c.id);
      assert.equal(now.fallen, false, `creature ${c.id} has not fallen`);
      assert.ok(now.position[2] - c.position[2] > 3, `creature ${c.id} walked ${(now.position[2] - c.position[2]).toFixed(2)} m forward in 10 s`);
    }
    await page.screenshot({ path: path.join(resultsDir, 'creatures.png') });
    assert.deepEqual(moved.map((c) => c.legs), [2, 4, 6, 8]);
    // A creature file the module refuses is said on the page, with the field named.
    const insect = fs.readFileSync(path.join(repoDir, 'public/creatures/insect.json'), 'utf8');
    await page.evaluate((json) => window.gaitlab.spawnCreature(json.replace('"mass": 8', '"mass": -8'), 10, 0, 0.4), insect);
    await page.waitForFunction(() => /legFrames\[0\]\.mass: -8(\.0)? is outside/.test(document.body.innerText), null, { timeout: PAGE_TIMEOUT, polling: 100 });
    await page.waitForTimeout(700);  // a report after the refusal
    assert.equal((await page.evaluate(() => window.gaitlab.characters())).length, 4, 'nothing was spawned from the refused file');
    assert.deepEqual(problems, []);
    // Alone, a creature walks the gait derived from its body, which the gait editors (showing
    // every quadruped's gait) neither read nor edit.
    const { page: alone } = await openPage(`${server.url}?threads=1&characters=0&creature=insect`);
    await ready(alone);
    await alone.waitForFunction(() => window.gaitlab.characters().length === 1, null, { timeout: PAGE_TIMEOUT, polling: 100 });
    await alone.waitForTimeout(1500);
    assert.doesNotMatch(await alone.evaluate(() => document.body.innerText), /Could not read the gait/);
  });

  it('a thrown box hits a character and changes its motion; the crowd keeps running', { timeout: TEST_TIMEOUT }, async () => {
    // The same run from step 0 twice (the simulation is deterministic and Reset rebuilds the
    // scene from the same seed), the second time with a box thrown at a character.
    const { page, problems } = await openPage(`${server.url}?characters=4&paused=1`);
    const s = await ready(page);
    assert.equal(s.paused, true);
    const quiet = await stepTo(page, 150);
    assert.equal(quiet.length, 4);

    await page.getByRole('button', { name: 'Reset', exact: true }).click();
    await page.waitForFunction(() => window.gaitlab.stats().simTime === 0, null, { timeout: PAGE_TIMEOUT });
    await page.waitForTimeout(700);
    const start = await page.evaluate(() => window.gaitlab.characters());
    const bodies = (await stats(page)).bodies;
    await page.evaluate((p) => window.gaitlab.throwBox([p[0], p[1] + 0.2, p[2]]), start[0].position);
    await page.waitForFunction((n) => window.gaitlab.stats().bodies === n + 1, bodies, { timeout: PAGE_TIMEOUT });
    const hit = await stepTo(page, 150);

    const moved = dist(hit[0].position, quiet[0].position);
    assert.ok(moved > 0.05, `the character hit moved differently (by ${moved.toFixed(3)} m)`);
    const untouched = hit.filter((c, i) => dist(c.position, quiet[i].position) === 0);
    assert.ok(untouched.length >= 1, 'characters the box missed moved exactly as without it (determinism)');
    await page.screenshot({ path: path.join(resultsDir, 'box-thrown.png') });
    // The crowd keeps running.
    await page.evaluate(() => window.gaitlab.resume());
    await page.waitForFunction(() => window.gaitlab.stats().simTime > 1.8, null, { timeout: PAGE_TIMEOUT });
    assert.equal((await stats(page)).error, null);
    assert.deepEqual(problems, [], 'no page errors');
    await page.close();
  });

  it('switches the ground to slope and bumps: drawn from the physics samples, characters re-placed standing on it', { timeout: TEST_TIMEOUT }, async () => {
    const { page, problems } = await openPage(`${server.url}?characters=6&paused=1`);
    await ready(page);
    await page.waitForFunction(() => window.gaitlab.stats().drawnTerrain === 'flat', null, { timeout: PAGE_TIMEOUT });
    await page.waitForTimeout(700);
    const onFlat = await page.evaluate(() => window.gaitlab.characters());
    assert.equal(onFlat.length, 6);
    // How high each root stands above the ground under it, on flat ground.
    const heightAbove = (chars) => page.evaluate((cs) => cs.map((c) => c.position[1] - window.gaitlab.groundHeight(c.position[0], c.position[2])), chars);
    const standing = await heightAbove(onFlat);

    const check = async (kind) => {
      await page.waitForFunction((k) => window.gaitlab.stats().terrain === k && window.gaitlab.stats().drawnTerrain === k, kind, { timeout: PAGE_TIMEOUT });
      await page.waitForTimeout(700); // the report after the change carries the re-placed characters
      const now = await page.evaluate(() => window.gaitlab.characters());
      assert.deepEqual(now.map((c) => c.id), onFlat.map((c) => c.id), `${kind}: the same characters`);
      const above = await heightAbove(now);
      now.forEach((c, i) => {
        // Re-placed where they stood, standing on the new ground: a biped's feet are close
        // together, a quadruped's hind feet may hang over ground that falls away (5° over 0.9 m).
        assert.ok(Math.hypot(c.position[0] - onFlat[i].position[0], c.position[2] - onFlat[i].position[2]) < 0.3, `${kind}: ${c.type} #${c.id} stays where it was`);
        const tolerance = c.type === 'biped' ? 0.03 : 0.1;
        assert.ok(Math.abs(above[i] - standing[i]) < tolerance,
          `${kind}: ${c.type} #${c.id} stands ${above[i].toFixed(3)} m above the drawn ground (${standing[i].toFixed(3)} m on flat)`);
      });
      // Half a second later the bipeds are still up on it.
      const t0 = (await stats(page)).simTime;
      await page.evaluate(() => window.gaitlab.step(60));
      await page.waitForFunction((t) => Math.abs(window.gaitlab.stats().simTime - t - 0.5) < 1e-6, t0, { timeout: PAGE_TIMEOUT, polling: 100 });
      await page.waitForTimeout(700);
      const later = await page.evaluate(() => window.gaitlab.characters());
      for (const c of later.filter((x) => x.type === 'biped')) assert.equal(c.fallen, false, `${kind}: biped #${c.id} is up after 0.5 s`);
      return later;
    };

    // Through the control panel: the slope. Its ridges and valleys are those of the physics.
    await page.locator('.lil-controller', { hasText: 'terrain' }).locator('select').selectOption('slope');
    await check('slope');
    const ground = (x, z) => page.evaluate(([a, b]) => window.gaitlab.groundHeight(a, b), [x, z]);
    assert.ok(Math.abs(await ground(3, 0)) < 1e-6, 'the slope passes through the origin');
    assert.ok(Math.abs((await ground(3, 2.5)) - 2.5 * Math.tan((5 * Math.PI) / 180)) < 1e-5, 'a ridge at z = 2.5 m, 5° up from the origin');
    assert.ok(Math.abs((await ground(3, -2.5)) + 2.5 * Math.tan((5 * Math.PI) / 180)) < 1e-5, 'a valley at z = -2.5 m');
    await page.screenshot({ path: path.join(resultsDir, 'terrain-slope.png') });

    // Through the test hook: the bumps.
    await page.evaluate(() => window.gaitlab.setTerrain('bumps'));
    await check('bumps');
    const samples = await page.evaluate(() => {
      const out = [];
      for (let x = -3; x <= 3; x += 0.0625) out.push(window.gaitlab.groundHeight(x, 0)); // along a row of the lattice
      return out;
    });
    const range = Math.max(...samples) - Math.min(...samples);
    assert.ok(range > 0.015 && range <= 0.0301, `bumps of 2-3 cm along a line (${(range * 100).toFixed(1)} cm)`);
    await page.screenshot({ path: path.join(resultsDir, 'terrain-bumps.png') });

    // The page still runs on the new ground, and flat ground comes back.
    await page.evaluate(() => window.gaitlab.resume());
    const t0 = (await stats(page)).simTime;
    await page.waitForFunction((t) => window.gaitlab.stats().simTime > t + 0.5, t0, { timeout: PAGE_TIMEOUT });
    await page.evaluate(() => window.gaitlab.setTerrain('flat'));
    await page.waitForFunction(() => window.gaitlab.stats().terrain === 'flat' && window.gaitlab.stats().drawnTerrain === 'flat', null, { timeout: PAGE_TIMEOUT });
    assert.equal(await ground(3, 2.5), 0, 'flat again');
    const s = await stats(page);
    assert.equal(s.error, null);
    assert.ok(s.fps > 0, 'frames are drawn');
    assert.deepEqual(problems, [], 'no page errors');
    await page.close();
  });

  it('clicks select characters and throw boxes; dragging a body pulls it', { timeout: TEST_TIMEOUT }, async () => {
    const { page, problems } = await openPage(`${server.url}?characters=4&paused=1`);
    await ready(page);
    await page.waitForTimeout(500); // the first frame is framed by the camera
    const at = (id) => page.evaluate((i) => window.gaitlab.screenPosition(i), id);

    // Steering goals reach one character or all of them.
    await page.evaluate(() => window.gaitlab.setGoal('all', { speed: 0.6, turn: 0 }));
    await page.evaluate(() => window.gaitlab.setGoal(3, { speed: 1.4, turn: -0.3 }));
    await page.waitForFunction(() => window.gaitlab.characters().find((c) => c.id === 3)?.goal.speed === 1.4, null, { timeout: PAGE_TIMEOUT });
    const goals = Object.fromEntries((await page.evaluate(() => window.gaitlab.characters())).map((c) => [c.id, c.goal]));
    assert.deepEqual(goals, { 0: { speed: 0.6, turn: 0 }, 1: { speed: 0.6, turn: 0 }, 2: { speed: 0.6, turn: 0 }, 3: { speed: 1.4, turn: -0.3 } });

    // Slow motion is the worker's clock's business: the page reports it.
    await page.locator('.lil-controller', { hasText: 'slow motion' }).locator('select').selectOption({ label: '0.25×' });
    await page.waitForFunction(() => window.gaitlab.stats().timeScale === 0.25, null, { timeout: PAGE_TIMEOUT });

    // Click a character: it is selected.
    const p1 = await at(1);
    await page.mouse.click(p1.x, p1.y);
    await page.waitForFunction(() => window.gaitlab.stats().selected === 1, null, { timeout: PAGE_TIMEOUT });
    assert.match(await page.getByTestId('hud').innerText(), /selected: quadruped #1/);
    // Keys steer the selected character: W is 0.1 m/s faster, A turns 5°/s more to the left.
    await page.keyboard.press('w');
    await page.keyboard.press('a');
    await page.waitForFunction(() => window.gaitlab.characters().find((c) => c.id === 1)?.goal.turn > 0, null, { timeout: PAGE_TIMEOUT });
    const steered = (await page.evaluate(() => window.gaitlab.characters())).find((c) => c.id === 1).goal;
    assert.ok(Math.abs(steered.speed - 0.7) < 1e-9 && Math.abs(steered.turn - (5 * Math.PI) / 180) < 1e-9, JSON.stringify(steered));
    assert.equal((await page.evaluate(() => window.gaitlab.characters())).find((c) => c.id === 0).goal.speed, 0.6, 'the others keep theirs');

    // Click the ground where nothing else is (no panel over the canvas, no character near): a box flies.
    const ground = await page.evaluate(() => {
      const canvas = document.querySelector('#scene');
      const characters = window.gaitlab.characters().map((c) => window.gaitlab.screenPosition(c.id));
      for (let y = 620; y > 300; y -= 40) {
        for (let x = 20; x < 1000; x += 40) {
          if (document.elementFromPoint(x, y) !== canvas) continue;
          if (characters.every((p) => !p || Math.hypot(p.x - x, p.y - y) > 120)) return { x, y };
        }
      }
      return null;
    });
    assert.ok(ground, 'some ground is visible');
    const bodies = (await stats(page)).bodies;
    await page.mouse.click(ground.x, ground.y);
    await page.waitForFunction((n) => window.gaitlab.stats().bodies === n + 1, bodies, { timeout: PAGE_TIMEOUT });

    // Deselect (Esc), which folds the gait editors away from the view.
    await page.keyboard.press('Escape');
    await page.waitForFunction(() => window.gaitlab.stats().selected === null, null, { timeout: PAGE_TIMEOUT });

    // Drag the biped #0's pelvis upwards and hold it while the simulation steps: it stays up,
    // while biped #2, untouched and not walking yet, sinks (or, walking, stays at its height).
    const p0 = await at(0);
    await page.mouse.move(p0.x, p0.y);
    await page.mouse.down();
    for (let k = 1; k <= 6; k++) await page.mouse.move(p0.x, p0.y - 25 * k);
    const after = await stepTo(page, 90);
    await page.screenshot({ path: path.join(resultsDir, 'drag.png') });
    await page.mouse.up();
    assert.equal((await stats(page)).selected, null, 'a drag does not select');
    const y0 = after.find((c) => c.id === 0).position[1];
    const y2 = after.find((c) => c.id === 2).position[1];
    assert.ok(y0 > y2 + 0.2, `the dragged biped was pulled up (${y0.toFixed(2)} m against ${y2.toFixed(2)} m)`);
    assert.deepEqual(problems, [], 'no page errors');
    await page.close();
  });

  it('dragging a curve knot changes the running gait; a share link reproduces it; export then import gives it back', { timeout: TEST_TIMEOUT }, async (t) => {
    const { page, problems } = await openPage(`${server.url}?characters=2`);
    await ready(page);
    if (await needsSchema(t, page)) return;
    await page.evaluate(() => window.gaitlab.select(0));
    const canvas = page.locator('.curve-editor canvas').first();
    await canvas.waitFor({ timeout: PAGE_TIMEOUT });
    const name = await page.locator('.curve-editor').first().getAttribute('data-param');
    const before = await page.evaluate(() => window.gaitlab.getGait(0));
    // Press at knot 2 (φ = 1/3) and drag it to the top of the editor: the schema's maximum.
    const box = await canvas.boundingBox();
    const x = box.x + box.width * ((8 + (324 * 1) / 3) / 340);
    await page.mouse.move(x, box.y + box.height / 2);
    await page.mouse.down();
    await page.mouse.move(x, box.y + 2, { steps: 5 });
    await page.mouse.up();
    await page.waitForTimeout(1000);
    const after = await page.evaluate(() => window.gaitlab.getGait(0));
    assert.notDeepEqual(after.params[name], before.params[name], `${name} changed in the running simulation`);
    assert.deepEqual(after.params[name].filter((_, k) => k !== 1), before.params[name].filter((_, k) => k !== 1), 'only knot 2 moved');
    // Undo puts the knot back in the running simulation; redo moves it again.
    await page.getByRole('button', { name: 'Undo' }).click();
    await page.waitForTimeout(800);
    assert.deepEqual((await page.evaluate(() => window.gaitlab.getGait(0))).params[name], before.params[name], 'undo');
    await page.getByRole('button', { name: 'Redo' }).click();
    await page.waitForTimeout(800);
    assert.deepEqual((await page.evaluate(() => window.gaitlab.getGait(0))).params[name], after.params[name], 'redo');
    await page.locator('.editors').screenshot({ path: path.join(resultsDir, 'editors.png') });
    await page.screenshot({ path: path.join(resultsDir, 'demo-editing.png') });

    // Share: a new page opened with the link runs every biped with exactly these parameters.
    const url = await page.evaluate(() => window.gaitlab.shareUrl(0));
    assert.match(url, /#gait=1\.\d+\.[A-Za-z0-9_-]+$/);
    const shared = await openPage(url);
    await shared.page.getByRole('status').getByText(/gait loaded from the link/).waitFor({ timeout: PAGE_TIMEOUT });
    await ready(shared.page);
    const bipedId = (await shared.page.evaluate(() => window.gaitlab.characters())).find((c) => c.type === 'biped').id;
    const received = await shared.page.evaluate((id) => window.gaitlab.getGait(id), bipedId);
    assert.deepEqual(received.params, after.params, 'the link reproduces the parameters exactly');
    // A biped added now walks with the shared gait too, not with the preset.
    await shared.page.getByRole('button', { name: 'Add characters' }).click();
    await shared.page.waitForFunction(() => window.gaitlab.characters().length === 3, null, { timeout: PAGE_TIMEOUT });
    const added = Math.max(...(await shared.page.evaluate(() => window.gaitlab.characters())).map((c) => c.id));
    assert.deepEqual((await shared.page.evaluate((id) => window.gaitlab.getGait(id), added)).params, after.params, 'added biped');
    assert.deepEqual(shared.problems, [], 'no page errors on the shared page');
    await shared.page.close();

    // Export, reset to the preset, import: the exported parameters are back.
    const [download] = await Promise.all([page.waitForEvent('download'), page.getByRole('button', { name: 'Export JSON' }).click()]);
    const file = path.join(resultsDir, 'exported-gait.json');
    await download.saveAs(file);
    const exported = JSON.parse(fs.readFileSync(file, 'utf8'));
    assert.equal(exported.format, 'gaitlab-gait');
    assert.deepEqual(exported.params, after.params);
    await page.getByRole('button', { name: 'Reset to preset' }).click();
    await page.waitForTimeout(1000);
    assert.notDeepEqual((await page.evaluate(() => window.gaitlab.getGait(0))).params[name], after.params[name], 'reset to preset');
    const [chooser] = await Promise.all([page.waitForEvent('filechooser'), page.getByRole('button', { name: 'Import JSON' }).click()]);
    await chooser.setFiles(file);
    await page.waitForTimeout(1000);
    assert.deepEqual((await page.evaluate(() => window.gaitlab.getGait(0))).params, after.params, 'import gives the exported gait back');
    // A file the module refuses is not imported, and the page shows the module's reason, field named.
    const bad = path.join(resultsDir, 'refused-gait.json');
    fs.writeFileSync(bad, JSON.stringify({ ...exported, params: { ...exported.params, period: 99 } }));
    const [badChooser] = await Promise.all([page.waitForEvent('filechooser'), page.getByRole('button', { name: 'Import JSON' }).click()]);
    await badChooser.setFiles(bad);
    const refusal = page.getByRole('status').locator('.message-problem', { hasText: 'refused-gait.json was not imported' });
    await refusal.waitFor({ timeout: PAGE_TIMEOUT });
    assert.match(await refusal.innerText(), /period: 99(\.0)? is outside \[/);
    assert.deepEqual((await page.evaluate(() => window.gaitlab.getGait(0))).params, after.params, 'a refused file changes nothing');
    // A file of schema version 1 is migrated by the module, not refused.
    const old = path.join(resultsDir, 'version-1-gait.json');
    const { 'gains.swingTargetRate': _, ...v1params } = exported.params;
    const { speed: _speed, keys: _keys, ...unkeyed } = exported; // speed keys came with schema 4
    fs.writeFileSync(old, JSON.stringify({ ...unkeyed, version: 1, params: { ...v1params, 'legFrame.supportGain': 800 } }));
    const [oldChooser] = await Promise.all([page.waitForEvent('filechooser'), page.getByRole('button', { name: 'Import JSON' }).click()]);
    await oldChooser.setFiles(old);
    await page.getByRole('status').getByText('Imported version-1-gait.json.').waitFor({ timeout: PAGE_TIMEOUT });
    await page.waitForTimeout(500);
    assert.deepEqual((await page.evaluate(() => window.gaitlab.getGait(0))).params, { ...after.params, 'gains.swingTargetRate': 0 }, 'a version-1 file is migrated');
    assert.deepEqual(problems, [], 'no page errors');
    await page.close();
  });

  it('an edit the simulation refuses is taken back in the editors, with a message naming the command and the parameter', { timeout: TEST_TIMEOUT }, async (t) => {
    const { page, problems } = await openPage(`${server.url}?characters=2`);
    await ready(page);
    if (await needsSchema(t, page)) return;
    await page.evaluate(() => window.gaitlab.select(0));
    await page.locator('.curve-editor canvas').first().waitFor({ timeout: PAGE_TIMEOUT });
    await page.waitForFunction(() => window.gaitlab.editorGait() !== null, null, { timeout: PAGE_TIMEOUT });
    const name = await page.locator('.curve-editor').first().getAttribute('data-param');
    const before = await page.evaluate(() => window.gaitlab.getGait(0));
    const knot = page.getByLabel(`${name} knot 2`, { exact: false });
    const shown = await knot.inputValue();
    // An accepted edit reaches the simulation as a patch of that one parameter.
    const moved = before.params[name][1] === 0 ? 0.01 : before.params[name][1] / 2;
    const accepted = await page.evaluate(([n, v]) => window.gaitlab.editGait({ [n]: window.gaitlab.editorGait().params[n].map((x, k) => (k === 1 ? v : x)) }), [name, moved]);
    assert.equal(accepted, null);
    const edited = await page.evaluate(() => window.gaitlab.getGait(0));
    assert.equal(edited.params[name][1], moved, 'the edit reached the simulation');
    assert.deepEqual({ ...edited.params, [name]: before.params[name] }, before.params, 'and nothing else changed');
    // A value beyond the schema's bounds, as an editor out of step with the schema would send it:
    // refused by the module, naming the command and the parameter; the editors show the gait the
    // simulation has, and the page says why.
    const refusal = await page.evaluate((n) => window.gaitlab.editGait({ period: 99, [n]: [0, 0, 0, 0] }), name);
    assert.match(refusal, /patchParams/);
    assert.match(refusal, /period: 99(\.0)? is outside \[/);
    const [running, editor] = await page.evaluate(() => Promise.all([window.gaitlab.getGait(0), window.gaitlab.editorGait()]));
    assert.deepEqual(running.params, edited.params, 'nothing of the refused edit reached the simulation');
    assert.deepEqual(editor.params, running.params, 'the editors show what the simulation has');
    assert.equal(await knot.inputValue(), String(Number(moved.toPrecision(5))), 'the curve editor was reverted');
    assert.notEqual(await knot.inputValue(), '0');
    assert.notEqual(shown, await knot.inputValue());
    const message = page.getByRole('status').locator('.message-problem').last();
    await message.waitFor({ timeout: PAGE_TIMEOUT });
    assert.match(await message.innerText(), /patchParams.*period/s);
    // Undo takes the accepted edit back, through the same path.
    await page.getByRole('button', { name: 'Undo' }).click();
    await page.waitForTimeout(800);
    assert.deepEqual((await page.evaluate(() => window.gaitlab.getGait(0))).params, before.params, 'undo');
    assert.deepEqual(problems, [], 'no page errors');
    await page.close();
  });

  it('refuses each kind of bad link with its message and runs with the presets', { timeout: TEST_TIMEOUT }, async (t) => {
    const { page } = await openPage(`${server.url}?characters=2`);
    await ready(page);
    if (await needsSchema(t, page)) return;
    // Links made in the page with its own codec (Vite serves the TypeScript module).
    const links = await page.evaluate(async () => {
      const link = await import('/src/share/link.ts');
      const gait = await window.gaitlab.getGait(0);
      const good = (await link.encodeGaitHash(gait)).slice(1);
      const scalar = Object.keys(gait.params).find((k) => typeof gait.params[k] === 'number');
      const outOfBounds = (await link.encodeGaitHash({ ...gait, params: { ...gait.params, [scalar]: 1e9 } })).slice(1);
      // Well-formed JSON that is not a gait: the module names the field.
      const malformed = (await link.encodeGaitHash({ ...gait, params: [1, 2] })).slice(1);
      // JSON cannot say Infinity, but 1e999 reads as Infinity: build that link by hand.
      const json = JSON.stringify({ ...gait, params: { ...gait.params, [scalar]: 12345.5 } }).replace('12345.5', '1e999');
      const text = new TextEncoder().encode(json);
      const packed = new Uint8Array(await new Response(new Blob([text]).stream().pipeThrough(new CompressionStream('deflate-raw'))).arrayBuffer());
      const bytes = new Uint8Array(4 + packed.length);
      new DataView(bytes.buffer).setUint32(0, link.crc32(text));
      bytes.set(packed, 4);
      const data = link.toBase64Url(bytes);
      const dataStart = good.lastIndexOf('.') + 1;
      const flip = dataStart + 10;
      return {
        truncated: good.slice(0, good.length - 7),
        corrupt: good.slice(0, flip) + (good[flip] === 'A' ? 'B' : 'A') + good.slice(flip + 1),
        tooLong: `gait=1.${link.MAX_LINK_CHARS + 1000}.${'A'.repeat(link.MAX_LINK_CHARS + 1000)}`,
        unknownVersion: good.replace(/^gait=1\./, 'gait=7.'),
        outOfBounds,
        malformed,
        notFinite: `gait=1.${data.length}.${data}`,
        scalar,
      };
    });
    await page.close();
    // The gait inside a link is the module's to judge: its refusals name the field ("FIELD: WHAT").
    const { scalar } = links;
    delete links.scalar;
    const expected = {
      truncated: /truncated/,
      corrupt: /damaged|not a JSON gait/,
      tooLong: /at most \d+ are accepted/,
      unknownVersion: /format version 7/,
      outOfBounds: new RegExp(`: ${scalar}: 1000000000(\\.0)? is outside \\[`),
      malformed: /: params: expected an object, got an array of 2/,
      notFinite: /number overflow parsing '1e999'/,
    };
    // The first kind on a fresh page (a link opened in a new tab), the others by changing the
    // hash of that page (a link pasted into the address bar of an open page).
    const kinds = Object.keys(links);
    const { page: bad, problems } = await openPage(`${server.url}?characters=2#${links[kinds[0]]}`);
    await ready(bad);
    for (const [n, kind] of kinds.entries()) {
      if (n > 0) await bad.evaluate((hash) => (location.hash = hash), links[kind]);
      const message = bad.getByRole('status').locator('.message-problem').nth(n);
      await message.waitFor({ timeout: PAGE_TIMEOUT });
      const text = await message.innerText();
      assert.match(text, /The gait link was refused/, kind);
      assert.match(text, expected[kind], `${kind}: ${text}`);
      assert.match(text, /Running with the presets/);
      if (kind === 'corrupt') await bad.screenshot({ path: path.join(resultsDir, 'bad-link.png') });
    }
    // The page still runs, with the presets.
    const t0 = (await stats(bad)).simTime;
    await bad.waitForFunction((t) => window.gaitlab.stats().simTime > t + 0.2, t0, { timeout: PAGE_TIMEOUT });
    const [running, preset] = await bad.evaluate(() => Promise.all([window.gaitlab.getGait(0), window.gaitlab.presetGait('biped')]));
    assert.deepEqual(running.params, preset.params, 'biped #0 runs with the preset');
    assert.deepEqual(problems, [], 'no page errors');
    await bad.close();
  });

  it('runs the built page from a static host without isolation headers, through the service worker, and says so', { timeout: TEST_TIMEOUT }, async () => {
    const webDir = path.join(repoDir, 'build', 'web');
    assert.ok(fs.existsSync(path.join(webDir, 'index.html')), 'build/web/index.html exists (npm run build)');
    const host = await startStaticHost(webDir);
    try {
      const { page, problems } = await openPage(`${host.url}?characters=2`);
      // The first load installs coi-serviceworker and reloads itself once.
      await page.waitForFunction(() => window.crossOriginIsolated === true, null, { timeout: PAGE_TIMEOUT, polling: 250 });
      const s = await ready(page);
      assert.equal(s.isolation, 'service worker');
      assert.match(await page.getByTestId('hud').innerText(), /isolated by service worker/);
      const t0 = s.simTime;
      await page.waitForFunction((t) => window.gaitlab.stats().simTime > t + 0.2, t0, { timeout: PAGE_TIMEOUT });
      await page.screenshot({ path: path.join(resultsDir, 'service-worker.png') });
      // Requests cut short by the reload are not errors.
      assert.deepEqual(problems.filter((p) => !p.includes('net::ERR_ABORTED')), [], 'no page errors');
      await page.close();
    } finally {
      await host.close();
    }
  });

  it('reaches isolation on a static host when the service worker installs slower than the page reloads', { timeout: TEST_TIMEOUT }, async () => {
    // coi-serviceworker reloads the page as soon as its worker starts installing. A worker still
    // installing when the reloaded page registers again (a busy machine; here 3 s, forced) once
    // left that page controlled but never isolated: it waited until its error message.
    const slowInstall = (source) => 'self.addEventListener("install", (e) => e.waitUntil(new Promise((r) => setTimeout(r, 3000))));\n' + source;
    const host = await startStaticHost(path.join(repoDir, 'build', 'web'), { serviceWorker: slowInstall });
    try {
      const { page, problems } = await openPage(`${host.url}?characters=2`);
      await page.waitForFunction(() => window.crossOriginIsolated === true, null, { timeout: PAGE_TIMEOUT, polling: 250 });
      const s = await ready(page);
      assert.equal(s.isolation, 'service worker');
      assert.deepEqual(problems.filter((p) => !p.includes('net::ERR_ABORTED')), [], 'no page errors');
    } finally {
      await host.close();
    }
  });

  it('reloads once, not for ever, and explains itself when the service worker does not isolate the page', { timeout: TEST_TIMEOUT }, async () => {
    // A worker that takes the page over but adds no headers (not coi-serviceworker's own).
    const inert = () => 'self.addEventListener("install", () => self.skipWaiting());\n' +
      'self.addEventListener("activate", (e) => e.waitUntil(self.clients.claim()));\n';
    const host = await startStaticHost(path.join(repoDir, 'build', 'web'), { serviceWorker: inert });
    try {
      const page = await context.newPage();
      let loads = 0;
      page.on('framenavigated', (frame) => { if (frame === page.mainFrame()) loads++; });
      await page.goto(`${host.url}?characters=2`, { waitUntil: 'load', timeout: PAGE_TIMEOUT });
      const notice = page.getByRole('alert');
      await notice.waitFor({ state: 'visible', timeout: PAGE_TIMEOUT });
      assert.match(await notice.innerText(), /service worker/);
      const settled = loads;
      // The first load, coi-serviceworker's reload, then the page's own (isolation.ts): one when
      // the worker takes it over, if it was not controlled yet, and one, once, of a controlled page.
      assert.ok(settled >= 2 && settled <= 4, `loaded ${settled} times`);
      await page.waitForTimeout(6000);
      assert.equal(loads, settled, 'no further reloads');
      assert.equal(await page.evaluate(() => window.crossOriginIsolated), false);
    } finally {
      await host.close();
    }
  });

  it('explains itself instead of a blank page when neither headers nor a service worker isolate it', { timeout: TEST_TIMEOUT }, async () => {
    const host = await startStaticHost(path.join(repoDir, 'build', 'web'));
    // A plain-http host by name: not a secure context, so no service worker may be installed
    // (a static site on http://, as opposed to localhost or https).
    const browser = await chromium.launch({
      executablePath,
      headless: true,
      args: ['--no-sandbox', '--disable-gpu', '--enable-unsafe-swiftshader', '--host-resolver-rules=MAP gaitlab.test 127.0.0.1'],
    });
    try {
      const page = await browser.newPage({ viewport: { width: 1024, height: 640 } });
      const problems = [];
      page.on('pageerror', (error) => problems.push(`page error: ${error.message}`));
      await page.goto(`http://gaitlab.test:${host.port}/`, { waitUntil: 'load', timeout: PAGE_TIMEOUT });
      assert.equal(await page.evaluate(() => window.isSecureContext), false);
      assert.equal(await page.evaluate(() => window.crossOriginIsolated), false);
      const notice = page.getByRole('alert');
      await notice.waitFor({ state: 'visible', timeout: PAGE_TIMEOUT });
      const text = await notice.innerText();
      assert.match(text, /Cross-Origin-Opener-Policy/);
      assert.match(text, /service worker/);
      assert.match(text, /npm start/);
      const hook = await stats(page);
      assert.equal(hook.crossOriginIsolated, false);
      assert.equal(hook.ready, false);
      await page.screenshot({ path: path.join(resultsDir, 'not-isolated.png') });
      assert.deepEqual(problems, [], 'no page errors');
    } finally {
      await browser.close();
      await host.close();
    }
  });
});
