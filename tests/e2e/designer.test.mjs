// End to end: the creature designer (control panel, "Design a creature"; web/src/ui/
// creature-designer.ts) in headless Chromium on a laptop's screen: a body designed through
// window.gaitlab.designer is spawned beside the crowd and walks; an impossible one is refused
// with the reason in the panel; one the module refuses is said there too. A designed body is
// taught to walk (the optimize panel searches a gait for that body, its learner walks it), the
// result is shared as a link, and opening the link puts that creature in the scene with that gait;
// a damaged creature link is refused with a message.
//
//   node --test tests/e2e/designer.test.mjs
//
// Needs build/wasm/gaitlab.{mjs,wasm,worker.js} (npm run build) and Chromium. Screenshots go to
// test-results/e2e/.
import assert from 'node:assert/strict';
import path from 'node:path';
import { after, afterEach, before, describe, it } from 'node:test';
import { openRecordedPage, PAGE_TIMEOUT, ready, resultsDir, startBrowser, stats } from './browser.mjs';

const TEST_TIMEOUT = 240_000;

/** @type {Awaited<ReturnType<typeof startBrowser>>} */
let browser;

/** Steps a page opened with ?paused=1 to `seconds` of simulated time and returns the characters reported then. */
async function stepTo(page, seconds) {
  const steps = Math.round((seconds - (await stats(page)).simTime) * 120);
  await page.evaluate((n) => window.gaitlab.step(n), steps);
  await page.waitForFunction((t) => Math.abs(window.gaitlab.stats().simTime - t) < 1e-6, seconds, { timeout: PAGE_TIMEOUT, polling: 100 });
  // The statistics report after the step carries the characters.
  await page.waitForTimeout(700);
  return page.evaluate(() => window.gaitlab.characters());
}

const statusText = (page) => page.getByTestId('designer-status').innerText();

describe('the creature designer', { timeout: TEST_TIMEOUT * 3 }, () => {
  before(async () => {
    browser = await startBrowser({ viewport: { width: 1280, height: 800 } });
  });
  afterEach(() => browser?.closePages());
  after(() => browser?.close());

  it('spawns a six-legged body designed through the hook beside the crowd, which walks; refuses an impossible one with its reason', { timeout: TEST_TIMEOUT }, async () => {
    const { page, problems } = await openRecordedPage(browser.context, `${browser.server.url}?threads=1&paused=1&characters=2`);
    await ready(page);
    await page.waitForFunction(() => window.gaitlab.characters().length === 2, null, { timeout: PAGE_TIMEOUT, polling: 100 });
    const crowd = await page.evaluate(() => window.gaitlab.characters());
    // Nothing is spawned until the designer is used.
    assert.equal(await page.evaluate(() => window.gaitlab.designer.preview()), null);

    // Six legs, shorter thighs than the insect's.
    await page.evaluate(() => window.gaitlab.designer.set({ pairs: 3, upperLength: 0.2, lowerLength: 0.22 }));
    assert.equal(await page.evaluate(() => window.gaitlab.designer.error()), null);
    const file = await page.evaluate(() => window.gaitlab.designer.json());
    assert.equal(file.legFrames.length, 3);
    assert.deepEqual(file.legFrames.map((f) => f.legs.upper.length), [0.2, 0.2, 0.2]);
    await page.waitForFunction(() => window.gaitlab.designer.preview() !== null, null, { timeout: PAGE_TIMEOUT, polling: 100 });
    const id = await page.evaluate(() => window.gaitlab.designer.preview());
    const start = (await page.evaluate(() => window.gaitlab.characters())).find((c) => c.id === id);
    assert.equal(start.legs, 6, 'the preview has six legs');
    assert.ok(start.position[0] > Math.max(...crowd.map((c) => c.position[0])), 'it stands beside (right of) the crowd');
    assert.match(await statusText(page), new RegExp(`6 legs, [\\d.]+ kg: #${id} walks beside the crowd`));

    // 10 s of simulated time: it walks more than a metre and does not fall.
    const moved = (await stepTo(page, 10)).find((c) => c.id === id);
    assert.ok(moved, 'the preview is still there after 10 s (it was not started over)');
    assert.equal(moved.fallen, false, 'it has not fallen');
    const walked = Math.hypot(moved.position[0] - start.position[0], moved.position[2] - start.position[2]);
    assert.ok(walked > 1, `it walked ${walked.toFixed(2)} m in 10 s`);
    // The folder open, as a user sees it.
    await page.getByText('Design a creature', { exact: true }).click();
    await page.getByRole('button', { name: 'Look at it' }).click();
    await page.waitForFunction((preview) => window.gaitlab.stats().selected === preview, id, { timeout: PAGE_TIMEOUT, polling: 100 });
    await page.waitForTimeout(3000); // the camera comes round to it
    await page.screenshot({ path: path.join(resultsDir, 'designer.png') });

    // Frames closer than a foot's sweep and length: refused before anything is sent, with the
    // reason in the panel; the last body that could be built keeps walking.
    await page.evaluate(() => window.gaitlab.designer.set({ frameSpacing: 0.12 }));
    const error = await page.evaluate(() => window.gaitlab.designer.error());
    assert.match(error, /the legs of neighbouring leg frames would collide/);
    assert.equal(await page.evaluate(() => window.gaitlab.designer.json()), null, 'no file for an impossible body');
    await page.waitForFunction(() => /neighbouring leg frames would collide/.test(document.querySelector('[data-testid=designer-status]')?.textContent ?? ''), null, {
      timeout: PAGE_TIMEOUT,
      polling: 100,
    });
    assert.match(await statusText(page), /^Not built:/);
    await page.waitForTimeout(1000); // past the controls' pause: nothing is sent
    assert.equal(await page.evaluate(() => window.gaitlab.designer.preview()), id, 'the walking preview stays');
    await page.screenshot({ path: path.join(resultsDir, 'designer-refused.png') });

    // Back to a possible body: it replaces the preview.
    await page.evaluate(() => window.gaitlab.designer.set({ frameSpacing: 0.4 }));
    await page.waitForFunction((old) => ![null, old].includes(window.gaitlab.designer.preview()), id, { timeout: PAGE_TIMEOUT, polling: 100 });
    const characters = await page.evaluate(() => window.gaitlab.characters());
    assert.equal(characters.length, 3, 'the crowd and one preview: the old one was removed');

    // Legs of three segments: the preview is rebuilt with a tarsus below every lower leg, and
    // walks on them.
    const two = await page.evaluate(() => window.gaitlab.designer.preview());
    await page.evaluate(() => window.gaitlab.designer.set({ upperLength: 0.18, lowerLength: 0.18, tarsusLength: 0.1 }));
    const three = await page.evaluate(() => window.gaitlab.designer.json());
    assert.deepEqual(three.legFrames.map((f) => f.legs.tarsus?.length), [0.1, 0.1, 0.1]);
    await page.waitForFunction((old) => ![null, old].includes(window.gaitlab.designer.preview()), two, { timeout: PAGE_TIMEOUT, polling: 100 });
    const tarsal = await page.evaluate(() => window.gaitlab.designer.preview());
    const owned = await page.evaluate((preview) => window.gaitlab.bodies().filter((b) => b.owner === preview).length, tarsal);
    const segments = three.legFrames.length + three.spine.reduce((n, section) => n + section.links, 0) + 6 * 4;
    assert.equal(owned, segments, 'its leg frames, its spine links, and six legs of four bodies each');
    const from = (await page.evaluate(() => window.gaitlab.characters())).find((c) => c.id === tarsal);
    const later = (await stepTo(page, (await stats(page)).simTime + 8)).find((c) => c.id === tarsal);
    assert.equal(later?.fallen, false, 'it walks on legs of three segments without falling');
    const distance = Math.hypot(later.position[0] - from.position[0], later.position[2] - from.position[2]);
    assert.ok(distance > 1, `it walked ${distance.toFixed(2)} m in 8 s`);
    assert.deepEqual(problems, []);
  });

  it('changes a body by dragging the handles of its drawing, and the preview follows', { timeout: TEST_TIMEOUT }, async () => {
    const { page, problems } = await openRecordedPage(browser.context, `${browser.server.url}?threads=1&characters=1`);
    await ready(page);
    await page.getByText('Design a creature').click();
    await page.evaluate(() => window.gaitlab.designer.preset('insect'));
    await page.waitForFunction(() => window.gaitlab.designer.preview() !== null, null, { timeout: PAGE_TIMEOUT, polling: 100 });
    const first = await page.evaluate(() => window.gaitlab.designer.preview());
    const before = await page.evaluate(() => window.gaitlab.designer.values());
    const drag = async (name, dx, dy) => {
      const at = await page.evaluate((n) => window.gaitlab.designer.handle(n), name);
      assert.ok(at, `the ${name} handle is drawn`);
      await page.mouse.move(at.x, at.y);
      await page.mouse.down();
      await page.mouse.move(at.x + dx, at.y + dy, { steps: 6 });
      // The handle stays under the pointer (on the circle through it, for a leg's joint).
      const moved = await page.evaluate((n) => window.gaitlab.designer.handle(n), name);
      await page.mouse.up();
      return moved;
    };
    // The knee dragged down: a longer upper leg, the other settings as they were.
    const knee = await drag('knee', 0, 12);
    const longer = await page.evaluate(() => window.gaitlab.designer.values());
    assert.ok(longer.upperLength > before.upperLength, `upper leg ${before.upperLength} → ${longer.upperLength} m`);
    assert.deepEqual({ ...longer, upperLength: before.upperLength }, before);
    assert.ok(knee.y > (await page.evaluate(() => window.gaitlab.designer.handle('knee'))).y - 40, 'the drawing did not jump');
    // The last leg frame dragged back: a longer body.
    await drag('frame', -20, 0);
    const stretched = await page.evaluate(() => window.gaitlab.designer.values());
    assert.ok(stretched.frameSpacing > before.frameSpacing, `body length ${before.frameSpacing} → ${stretched.frameSpacing} m`);
    // The preview is the dragged body.
    await page.waitForFunction((old) => ![null, old].includes(window.gaitlab.designer.preview()), first, { timeout: PAGE_TIMEOUT, polling: 100 });
    const file = await page.evaluate(() => window.gaitlab.designer.json());
    assert.equal(file.legFrames[0].legs.upper.length, longer.upperLength);
    assert.ok(Math.abs(file.legFrames[0].z - file.legFrames[1].z - stretched.frameSpacing) < 1e-6);
    await page.screenshot({ path: path.join(resultsDir, 'designer-dragged.png') });
    assert.deepEqual(problems, []);
  });

  it('teaches a designed body to walk, shares it, and the link puts that creature in the scene with the gait it learnt', { timeout: TEST_TIMEOUT }, async () => {
    const { page, problems } = await openRecordedPage(browser.context, `${browser.server.url}?threads=2&characters=2`);
    await ready(page);
    await page.evaluate(() => window.gaitlab.designer.set({ pairs: 3, upperLength: 0.2, lowerLength: 0.22 }));
    await page.waitForFunction(() => window.gaitlab.designer.preview() !== null, null, { timeout: PAGE_TIMEOUT, polling: 100 });
    const body = await page.evaluate(() => window.gaitlab.designer.json());

    // A short search, for the test's time: two generations of three candidates, 2 s episodes.
    const status = await page.evaluate(() =>
      window.gaitlab.designer.teach({ generations: 2, candidates: 3, seconds: 2, speeds: '0.4', seed: 1, threads: 1, start: 'preset' }));
    assert.equal(status.state, 'done', status.message);
    assert.equal(status.body, body.name, 'the search learnt for the designed body');
    assert.equal(status.options.character, 'hexapod');
    assert.equal(status.history.length, 2);
    assert.equal(status.result.character, 'hexapod');
    assert.equal(status.result.meta.creature, body.name);
    assert.match(await page.getByTestId('optimize-body').innerText(), /Learning for .* \(hexapod, its own body\)/);
    // The learner walks the best so far with the designed body: six legs, its thighs 0.2 m.
    await page.waitForFunction(() => window.gaitlab.learner() !== null, null, { timeout: PAGE_TIMEOUT, polling: 100 });
    const learner = await page.evaluate(() => window.gaitlab.characters().find((c) => c.id === window.gaitlab.learner()));
    assert.equal(learner.legs, 6);
    assert.equal(learner.type, 'hexapod');

    const url = await page.evaluate(() => window.gaitlab.optimizeShareUrl());
    assert.match(url, /#creature=1\.\d+\.[A-Za-z0-9_-]+&gait=1\.\d+\.[A-Za-z0-9_-]+$/);
    await page.screenshot({ path: path.join(resultsDir, 'designer-taught.png') });

    const shared = await openRecordedPage(browser.context, url);
    await ready(shared.page);
    await shared.page.getByRole('status').getByText(/Shared hexapod loaded from the link/).waitFor({ timeout: PAGE_TIMEOUT });
    await shared.page.waitForFunction(() => window.gaitlab.characters().some((c) => c.legs === 6), null, { timeout: PAGE_TIMEOUT, polling: 100 });
    const creature = (await shared.page.evaluate(() => window.gaitlab.characters())).find((c) => c.legs === 6);
    assert.equal(creature.type, 'hexapod');
    const gait = await shared.page.evaluate((id) => window.gaitlab.getGait(id), creature.id);
    assert.deepEqual(gait.params, status.result.params, 'the link reproduces the learnt gait exactly');
    // Its body is the designed one: as many bodies as the design's file has segments.
    const owned = await shared.page.evaluate((id) => window.gaitlab.bodies().filter((b) => b.owner === id).length, creature.id);
    const segments = body.legFrames.length + body.spine.reduce((n, section) => n + section.links, 0) + 6 * 3;
    assert.equal(owned, segments, 'its leg frames, its spine links, and six legs of three bodies each');
    assert.deepEqual(shared.problems, [], 'no page errors on the shared page');

    // A creature link damaged in transit: refused with a message, the page runs without it.
    const damaged = url.replace(/(#creature=1\.\d+\.)(.)/, (_m, head, c) => head + (c === 'A' ? 'B' : 'A'));
    const bad = await openRecordedPage(browser.context, damaged);
    await ready(bad.page);
    const refusal = bad.page.getByRole('status').getByText(/The creature link was refused: /);
    await refusal.waitFor({ timeout: PAGE_TIMEOUT });
    assert.match(await refusal.innerText(), /the link data is damaged|not a JSON creature/);
    assert.equal((await bad.page.evaluate(() => window.gaitlab.characters())).filter((c) => c.legs === 6).length, 0);
    assert.deepEqual(problems, []);
  });

  it('says in the panel when the module refuses the body (here: the page is full)', { timeout: TEST_TIMEOUT }, async () => {
    const { page } = await openRecordedPage(browser.context, `${browser.server.url}?threads=1&paused=1&characters=256`);
    await ready(page);
    await page.waitForFunction(() => window.gaitlab.characters().length === 256, null, { timeout: PAGE_TIMEOUT, polling: 250 });
    await page.evaluate(() => window.gaitlab.designer.preset('spider'));
    await page.waitForFunction(() => window.gaitlab.designer.error() !== null, null, { timeout: PAGE_TIMEOUT, polling: 100 });
    assert.match(await page.evaluate(() => window.gaitlab.designer.error()), /the module refused the body: the crowd is at its limit/);
    assert.equal(await page.evaluate(() => window.gaitlab.designer.json()), null);
    assert.match(await statusText(page), /the module refused the body/);
    assert.equal(await page.evaluate(() => window.gaitlab.designer.values().pairs), 4, 'the spider\'s settings were loaded');
  });
});
