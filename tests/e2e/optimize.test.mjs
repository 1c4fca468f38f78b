// End to end: the demo page's optimize panel in headless Chromium, with the real WASM
// module: a search runs in its own worker while the crowd keeps running, the chart gets a point
// per generation, the learner walks the best so far, Stop keeps the best, Apply gives it to the
// characters (undo takes it back), Share makes a link that reproduces it, and bad input is
// refused with a message naming the field.
//
//   node --test tests/e2e/optimize.test.mjs
//
// Needs build/wasm (npm run build) and Chromium (CHROMIUM=/path overrides /usr/bin/chromium).
// Nothing here depends on objective values: the presets are being retuned.
import assert from 'node:assert/strict';
import path from 'node:path';
import { after, afterEach, before, describe, it } from 'node:test';
import { openRecordedPage, PAGE_TIMEOUT, resultsDir, startBrowser } from './browser.mjs';

const RUN_TIMEOUT = 300_000;
const TEST_TIMEOUT = 600_000;

let browser;
let server;
let context;

/** A recorded page (browser.mjs) once the demo has drawn its first frame without a problem. */
async function openPage(url) {
  const { page, problems } = await openRecordedPage(context, url);
  await page.waitForFunction(() => window.gaitlab?.stats().ready || window.gaitlab?.stats().error, null, { timeout: PAGE_TIMEOUT, polling: 250 });
  assert.equal((await page.evaluate(() => window.gaitlab.stats())).error, null, 'no problem is shown on the page');
  return { page, problems };
}

/** Skips when this build of the module has no parameter schema or no optimiser settings. */
async function needsOptimizer(t, page) {
  const ok = await page.evaluate(() => {
    try {
      window.gaitlab.optimizeStatus();
      return true;
    } catch {
      return false;
    }
  });
  if (ok) return false;
  t.skip('this build of the WASM module has no optimiser settings (gl_opt_settings_json) or no parameter schema');
  await page.close();
  return true;
}

const status = (page) => page.evaluate(() => window.gaitlab.optimizeStatus());

/** Waits until the search is over and returns its status. */
async function finished(page) {
  await page.waitForFunction(() => !['loading', 'running'].includes(window.gaitlab.optimizeStatus().state), null, { timeout: RUN_TIMEOUT, polling: 250 });
  return status(page);
}

/** Character `id`'s gait once it has `params` (gait commands apply at the next fixed step). */
async function waitForGait(page, id, params, what) {
  const deadline = Date.now() + PAGE_TIMEOUT;
  let last = null;
  while (Date.now() < deadline) {
    last = await page.evaluate((i) => window.gaitlab.getGait(i).then((g) => g.params, (e) => String(e)), id);
    try {
      assert.deepEqual(last, params);
      return;
    } catch {
      await page.waitForTimeout(250);
    }
  }
  assert.deepEqual(last, params, what);
}

function assertHistory(s, what) {
  assert.equal(s.history.length, s.generation, `${what}: one history entry per generation`);
  s.history.forEach((h, i) => {
    assert.equal(h.generation, i + 1, what);
    assert.ok(Number.isFinite(h.best), `${what}: generation ${i + 1}'s best is a number (${h.best})`);
    assert.ok(h.seconds > 0, `${what}: generation ${i + 1} took time`);
    if (i > 0) assert.ok(h.best <= s.history[i - 1].best, `${what}: the best never gets worse (${s.history.map((x) => x.best).join(', ')})`);
  });
  assert.equal(s.best, s.history[s.history.length - 1].best, what);
  assert.equal(s.chartPoints, s.generation, `${what}: the chart has a point per generation`);
  assert.ok(s.result, `${what}: there is a result`);
  // The result's objective is the best reported (the optimiser's own record of it).
  assert.equal(s.result.meta.objective, s.best, what);
}

describe('optimize panel', { timeout: TEST_TIMEOUT * 3 }, () => {
  before(async () => {
    browser = await startBrowser({ viewport: { width: 1280, height: 760 } });
    ({ server, context } = browser);
  });

  afterEach(() => browser?.closePages());

  after(() => browser?.close());

  it('refuses bad input, runs a search beside the running crowd, stops keeping the best, applies and shares it', { timeout: TEST_TIMEOUT }, async (t) => {
    const { page, problems } = await openPage(`${server.url}?characters=2`);
    if (await needsOptimizer(t, page)) return;
    const crowd = await page.evaluate(() => window.gaitlab.characters());
    const biped = crowd.find((c) => c.type === 'biped');
    const quadruped = crowd.find((c) => c.type === 'quadruped');
    await page.getByText('Optimize: learning to walk').click();
    const panel = page.getByTestId('optimize-panel');
    const message = page.getByTestId('optimize-message');

    // ---- bad input: a message naming each field; nothing starts ----
    await panel.getByLabel('generations').fill('0');
    await panel.getByLabel('candidates').fill('1');
    await panel.getByLabel('seed').fill('abc');
    await panel.getByRole('button', { name: 'Start' }).click();
    await message.getByText(/generations: 0 is below the minimum, 1/).waitFor({ timeout: PAGE_TIMEOUT });
    const refused = await message.innerText();
    assert.match(refused, /candidates: 1 is below the minimum, 2/);
    assert.match(refused, /seed: 'abc' is not a number/);
    assert.equal(await panel.getByLabel('generations').getAttribute('aria-invalid'), 'true');
    assert.equal((await status(page)).state, 'idle', 'nothing started');
    const hookRefusal = await page.evaluate(() => window.gaitlab.optimize({ generations: 3, candidates: 3, seed: 1, speeds: '1, fast' }).then(() => null, (e) => e.message));
    assert.match(hookRefusal, /speeds: 'fast' is not a number/);
    const noSelection = await page.evaluate(() => window.gaitlab.optimize({ speeds: '1', start: 'selected' }).then(() => null, (e) => e.message));
    assert.match(noSelection, /no character is selected/);
    assert.equal((await status(page)).state, 'idle');

    // ---- a tiny search, typed into the form and started with the button ----
    await panel.getByLabel('start from').selectOption('preset');
    for (const [label, value] of [['generations', '3'], ['candidates', '3'], ['seed', '2'], ['threads', '1'], ['episode (s)', '1']]) {
      await panel.getByLabel(label, { exact: true }).fill(value);
    }
    await panel.getByRole('button', { name: 'Start' }).click();
    // A search this small can end between two polls: wait for it to have left 'idle'.
    await page.waitForFunction(() => window.gaitlab.optimizeStatus().state !== 'idle', null, { timeout: PAGE_TIMEOUT, polling: 50 });
    // The state and the button are read in one task of the page: a search this small can end
    // between two separate reads, and then the Stop button is rightly disabled.
    const early = await panel.evaluate((el) => {
      const stop = [...el.querySelectorAll('button')].find((b) => b.textContent.trim() === 'Stop');
      return { state: window.gaitlab.optimizeStatus().state, stopEnabled: Boolean(stop && !stop.disabled) };
    });
    if (early.state === 'running') assert.equal(early.stopEnabled, true, 'Stop is enabled while the search runs');
    const done = await finished(page);
    assert.equal(done.state, 'done', done.message);
    assert.equal(done.generation, 3);
    assert.equal(done.evaluations, 9, '3 generations of 3 candidates');
    assertHistory(done, 'tiny search');
    assert.equal(done.result.character, 'biped');
    assert.equal(done.result.meta.seed, 2);
    assert.equal(done.result.meta.candidates, 3);
    assert.equal(done.result.meta.objective_settings.seconds, 1);
    assert.match(await page.getByTestId('optimize-progress').innerText(), /done: generation 3 of 3 · 9 evaluations · .* per generation/);
    console.log(`optimize: ${done.history.map((h) => h.seconds.toFixed(2)).join(', ')} s per generation (3 candidates, 1 s episodes, 1 thread); module loaded in ${done.loadSeconds.toFixed(2)} s`);

    // The learner walks the result, apart from the crowd.
    await page.waitForFunction(() => window.gaitlab.learner() !== null, null, { timeout: PAGE_TIMEOUT });
    const learner = await page.evaluate(async () => {
      for (let attempt = 0; attempt < 40; attempt++) {
        const id = window.gaitlab.learner();
        try {
          const gait = await window.gaitlab.getGait(id);
          const c = window.gaitlab.characters().find((x) => x.id === id);
          if (c) return { id, type: c.type, x: c.position[0], params: gait.params };
        } catch {
          // It started over under a new id between the two calls: ask again.
        }
        await new Promise((r) => setTimeout(r, 250));
      }
      return null;
    });
    assert.ok(learner, 'the learner is in the scene');
    assert.equal(learner.type, 'biped');
    assert.deepEqual(learner.params, done.result.params, 'the learner walks the best gait');
    assert.ok(crowd.every((c) => learner.x < c.position[0] - 3), `the learner stands apart (x ${learner.x.toFixed(1)})`);

    // ---- a long search, stopped midway with the button: the best so far is kept ----
    // It runs long enough to show that the crowd keeps running beside it: wait for a simulated
    // second of the crowd (however slow this machine is) and two generations, then check that
    // the search is still running. (The tiny search above can end before a second is simulated.)
    const simStart = await page.evaluate(() => window.gaitlab.stats().simTime);
    await page.evaluate(() => { window.__run = window.gaitlab.optimize({ generations: 1000, candidates: 3, seconds: 1, seed: 5 }); });
    await page.waitForFunction((t0) => window.gaitlab.optimizeStatus().generation >= 2 && window.gaitlab.stats().simTime >= t0 + 1, simStart, { timeout: RUN_TIMEOUT, polling: 100 });
    const running = await status(page);
    assert.equal(running.state, 'running', 'the search is still running after the crowd simulated a second beside it');
    assert.ok(running.secondsLeft > 0, `a time left is estimated (${running.secondsLeft})`);
    assert.match(await page.getByTestId('optimize-progress').innerText(), /running: generation \d+ of 1000 · .* left/);
    await page.screenshot({ path: path.join(resultsDir, 'optimize-panel.png') });
    await panel.getByRole('button', { name: 'Stop' }).click();
    const stopped = await page.evaluate(() => window.__run);
    assert.equal(stopped.state, 'stopped');
    assert.ok(stopped.generation >= 2 && stopped.generation < 1000, `stopped after ${stopped.generation} generations`);
    assertHistory(stopped, 'stopped search');
    assert.equal(stopped.result.meta.interrupted, true);
    assert.equal(stopped.result.meta.generations, stopped.generation);
    await page.waitForTimeout(2000);
    const later = await status(page);
    assert.equal(later.generation, stopped.generation, 'no generation finishes after Stop');
    assert.deepEqual(later.result, stopped.result, 'the best so far is kept');
    const result = stopped.result;

    // ---- Apply to every biped: through the gait editors, so undo takes it back ----
    const original = (await page.evaluate((id) => window.gaitlab.getGait(id), biped.id)).params;
    await panel.getByLabel('apply to').selectOption('all');
    await panel.getByRole('button', { name: 'Apply', exact: true }).click();
    await message.getByText('Applied to every biped').waitFor({ timeout: PAGE_TIMEOUT });
    await waitForGait(page, biped.id, result.params, 'every biped walks the result');
    assert.match(await page.locator('.editors-heading').innerText(), /Gait of every biped/);
    await page.getByRole('button', { name: 'Undo' }).click();
    await waitForGait(page, biped.id, original, 'undo takes the result back');

    // ---- Apply to the selected character: refused for none or another type, then given ----
    await page.evaluate(() => window.gaitlab.select(null));
    const none = await page.evaluate(() => window.gaitlab.applyOptimizeResult('selected').then(() => null, (e) => e.message));
    assert.match(none, /Not applied: no character is selected/);
    await page.evaluate((id) => window.gaitlab.select(id), quadruped.id);
    const otherType = await page.evaluate(() => window.gaitlab.applyOptimizeResult('selected').then(() => null, (e) => e.message));
    assert.match(otherType, /the selected character is a quadruped; the result is a biped's gait/);
    await page.evaluate((id) => window.gaitlab.select(id), biped.id);
    await panel.getByLabel('apply to').selectOption('selected');
    await panel.getByRole('button', { name: 'Apply', exact: true }).click();
    await message.getByText(`Applied to biped #${biped.id}`).waitFor({ timeout: PAGE_TIMEOUT });
    await waitForGait(page, biped.id, result.params, 'the selected biped walks the result');

    // ---- Share: a link that runs every biped with the result ----
    await panel.getByRole('button', { name: 'Share result' }).click();
    await message.getByText(/Link (copied|ready)/).waitFor({ timeout: PAGE_TIMEOUT });
    const url = await panel.getByLabel('result link').inputValue();
    assert.match(url, /#gait=1\.\d+\.[A-Za-z0-9_-]+$/);
    assert.equal(url, await page.evaluate(() => window.gaitlab.optimizeShareUrl()));
    // The gait editors show the applied result, and share it with the same link: one transfer
    // module for both (web/src/ui/gait-transfer.ts).
    assert.deepEqual((await page.evaluate(() => window.gaitlab.editorGait())).params, result.params, 'the editors show the result');
    assert.equal(await page.evaluate((id) => window.gaitlab.shareUrl(id), biped.id), url, 'the editors share the same link');
    const shared = await openPage(url);
    await shared.page.getByRole('status').getByText(/gait loaded from the link/).waitFor({ timeout: PAGE_TIMEOUT });
    const sharedBiped = (await shared.page.evaluate(() => window.gaitlab.characters())).find((c) => c.type === 'biped');
    await waitForGait(shared.page, sharedBiped.id, result.params, 'the link reproduces the result exactly');
    assert.deepEqual(shared.problems, [], 'no page errors on the shared page');
    await shared.page.close();

    assert.equal((await page.evaluate(() => window.gaitlab.stats())).error, null);
    assert.deepEqual(problems, [], 'no page errors');
    await page.close();
  });

  it('searches a quadruped with CMA-ES from the selected character\'s gait', { timeout: TEST_TIMEOUT }, async (t) => {
    const { page, problems } = await openPage(`${server.url}?characters=2`);
    if (await needsOptimizer(t, page)) return;
    const quadruped = (await page.evaluate(() => window.gaitlab.characters())).find((c) => c.type === 'quadruped');
    await page.evaluate((id) => window.gaitlab.select(id), quadruped.id);
    await page.waitForFunction((id) => window.gaitlab.stats().selected === id, quadruped.id, { timeout: PAGE_TIMEOUT });
    const s = await page.evaluate(() => window.gaitlab.optimize({
      character: 'quadruped', method: 'cmaes', start: 'selected', generations: 2, candidates: 3, seconds: 0.5, warmup: 0, seed: 9, threads: 2,
    }));
    assert.equal(s.state, 'done', s.message);
    assert.equal(s.evaluations, 6);
    assertHistory(s, 'CMA-ES');
    assert.equal(s.result.character, 'quadruped');
    assert.equal(s.result.meta.method, 'cmaes');
    assert.equal(s.result.meta.start, `quadruped #${quadruped.id}`);
    assert.deepEqual(problems, [], 'no page errors');
    await page.close();
  });
});
