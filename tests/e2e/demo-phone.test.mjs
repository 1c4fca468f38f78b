// End to end: the demo page on a phone, in Chromium's mobile emulation (390×844 CSS pixels,
// touch events): the scene keeps most of the screen (the panel a drawer, the heads-up one line)
// and the crowd its height,
// a tap throws, a tap on a character selects it and the editors open as a bottom sheet with the
// character kept in view above it; one finger orbits, two fingers pinch to zoom.
//
//   node --test tests/e2e/demo-phone.test.mjs
import assert from 'node:assert/strict';
import path from 'node:path';
import { after, afterEach, before, describe, it } from 'node:test';
import { openRecordedPage, PAGE_TIMEOUT, resultsDir, startBrowser, stats } from './browser.mjs';

const TEST_TIMEOUT = 240_000;
let browser;

/** Share of the screen where the canvas is what a finger would touch (sampled on a 20 px grid). */
const sceneShare = (page) =>
  page.evaluate(() => {
    const canvas = document.querySelector('#scene');
    let seen = 0;
    let all = 0;
    for (let y = 5; y < innerHeight; y += 20) {
      for (let x = 5; x < innerWidth; x += 20) {
        all++;
        if (document.elementFromPoint(x, y) === canvas) seen++;
      }
    }
    return seen / all;
  });

/** A touch gesture through the DevTools protocol: `tracks` is one list of points per finger. */
async function gesture(page, tracks) {
  const cdp = await page.context().newCDPSession(page);
  const points = (i) => tracks.map((t, id) => ({ x: t[i][0], y: t[i][1], id }));
  await cdp.send('Input.dispatchTouchEvent', { type: 'touchStart', touchPoints: points(0) });
  for (let i = 1; i < tracks[0].length; i++) {
    await cdp.send('Input.dispatchTouchEvent', { type: 'touchMove', touchPoints: points(i) });
    await page.waitForTimeout(16);
  }
  await cdp.send('Input.dispatchTouchEvent', { type: 'touchEnd', touchPoints: [] });
  await cdp.detach();
}

const cameraOf = (page) => page.evaluate(() => window.gaitlab.camera());

describe('the demo on a phone', { timeout: TEST_TIMEOUT * 2 }, () => {
  before(async () => {
    browser = await startBrowser({ viewport: { width: 390, height: 844 }, isMobile: true, hasTouch: true, deviceScaleFactor: 2 });
  });
  afterEach(() => browser?.closePages());
  after(() => browser?.close());

  it('keeps the scene on most of the screen; taps throw and select, one finger orbits, two pinch', { timeout: TEST_TIMEOUT }, async () => {
    const { page, problems } = await openRecordedPage(browser.context, `${browser.server.url}?characters=6&paused=1`);
    await page.waitForFunction(() => window.gaitlab?.stats().ready || window.gaitlab?.stats().error, null, { timeout: PAGE_TIMEOUT, polling: 250 });
    assert.equal((await stats(page)).error, null);
    await page.waitForTimeout(2500); // the camera settles on the crowd
    // The layout: the panel folded into a drawer, the heads-up line one line.
    assert.equal(await page.locator('.lil-gui.lil-root').evaluate((e) => e.classList.contains('lil-closed')), true, 'the panel starts folded');
    const hud = await page.getByTestId('hud').boundingBox();
    assert.ok(hud.height <= 26, `the heads-up line is one line (${hud.height} px)`);
    const share = await sceneShare(page);
    assert.ok(share >= 0.6, `the scene has ${(share * 100).toFixed(0)} % of the screen`);
    // The crowd uses the screen's height, not only a band across its middle: on a tall screen the
    // first view looks down steeply (render/stage.ts, frame). At the usual low view the six
    // characters spread over 10 % of the height, at the steep one over 21 %.
    const spread = await page.evaluate(() => {
      const ys = window.gaitlab.characters().map((c) => window.gaitlab.screenPosition(c.id)).filter(Boolean).map((p) => p.y);
      return (Math.max(...ys) - Math.min(...ys)) / innerHeight;
    });
    assert.ok(spread >= 0.15, `the crowd spreads over ${(spread * 100).toFixed(0)} % of the screen's height`);
    await page.screenshot({ path: path.join(resultsDir, 'phone.png') });

    // A tap on the ground, away from the characters: a box is thrown.
    const ground = await page.evaluate(() => {
      const canvas = document.querySelector('#scene');
      const marks = window.gaitlab.characters().map((c) => window.gaitlab.screenPosition(c.id));
      for (let y = innerHeight - 120; y > 200; y -= 30) {
        for (let x = 30; x < innerWidth - 30; x += 30) {
          if (document.elementFromPoint(x, y) === canvas && marks.every((p) => !p || Math.hypot(p.x - x, p.y - y) > 60)) return { x, y };
        }
      }
      return null;
    });
    assert.ok(ground, 'some ground is visible');
    const bodies = (await stats(page)).bodies;
    await page.touchscreen.tap(ground.x, ground.y);
    await page.waitForFunction((n) => window.gaitlab.stats().bodies === n + 1, bodies, { timeout: PAGE_TIMEOUT });

    // A tap on a character: it is selected, the editors open as a bottom sheet, and the
    // camera keeps the character in view above the sheet.
    const p = await page.evaluate(() => window.gaitlab.screenPosition(0));
    await page.touchscreen.tap(p.x, p.y);
    await page.waitForFunction(() => window.gaitlab.stats().selected === 0, null, { timeout: PAGE_TIMEOUT });
    await page.waitForTimeout(2500);
    const sheet = await page.locator('details.editors').boundingBox();
    assert.ok(sheet.y + sheet.height >= 843 && sheet.width >= 380, `the editors are a bottom sheet (${JSON.stringify(sheet)})`);
    assert.ok(sheet.height <= 0.4 * 844, `the sheet leaves the scene most of the screen (${sheet.height} px)`);
    const seen = await page.evaluate(() => window.gaitlab.screenPosition(0));
    assert.ok(seen.y > 0 && seen.y < sheet.y && seen.x > 0 && seen.x < 390, `the selected character is above the sheet (${seen.x.toFixed(0)}, ${seen.y.toFixed(0)})`);
    await page.screenshot({ path: path.join(resultsDir, 'phone-selected.png') });

    // One finger drags: the camera orbits (its direction changes, its distance does not). The
    // camera moves in the page's next frames, which a loaded machine draws a second or more
    // apart: wait for the change, not for a fixed time.
    await page.keyboard.press('Escape');
    await page.waitForFunction(() => window.gaitlab.stats().selected === null, null, { timeout: PAGE_TIMEOUT });
    const before0 = await cameraOf(page);
    await gesture(page, [Array.from({ length: 12 }, (_, i) => [110 + i * 14, 300])]);
    await page
      .waitForFunction((a) => Math.abs(window.gaitlab.camera().azimuth - a) > 0.1, before0.azimuth, { timeout: PAGE_TIMEOUT, polling: 100 })
      .catch(() => {});
    await page.waitForTimeout(1500); // the orbit's damping settles
    const orbited = await cameraOf(page);
    assert.ok(Math.abs(orbited.azimuth - before0.azimuth) > 0.1, `orbit: azimuth ${before0.azimuth.toFixed(2)} → ${orbited.azimuth.toFixed(2)}`);
    // Two fingers apart: zoom in (the camera comes closer to what it looks at), even with one
    // finger landing on a character (a finger on a character used to take the gesture from the
    // camera, and the pinch zoomed only when both fingers missed the crowd).
    const finger = await page.evaluate(() => {
      const canvas = document.querySelector('#scene');
      const onScreen = window.gaitlab.characters().map((c) => ({ id: c.id, p: window.gaitlab.screenPosition(c.id) }))
        .filter(({ id, p }) => p && p.x > 80 && p.x < innerWidth - 80 && p.y > 120 && p.y < innerHeight - 120 &&
          document.elementFromPoint(p.x, p.y) === canvas && window.gaitlab.ownerAt(p.x, p.y) === id);
      onScreen.sort((a, b) => Math.abs(a.p.x - innerWidth / 2) - Math.abs(b.p.x - innerWidth / 2));
      return onScreen[0]?.p ?? null;
    });
    assert.ok(finger, 'a character in view to put a finger on');
    const side = finger.x > 195 ? -1 : 1; // the other finger towards the middle of the screen
    await gesture(page, [
      Array.from({ length: 10 }, (_, i) => [finger.x - side * i * 6, finger.y]),
      Array.from({ length: 10 }, (_, i) => [finger.x + side * (40 + i * 6), finger.y]),
    ]);
    await page
      .waitForFunction((d) => window.gaitlab.camera().distance < 0.9 * d, orbited.distance, { timeout: PAGE_TIMEOUT, polling: 100 })
      .catch(() => {});
    const zoomed = await cameraOf(page);
    assert.ok(zoomed.distance < 0.9 * orbited.distance, `pinch: distance ${orbited.distance.toFixed(1)} → ${zoomed.distance.toFixed(1)} m`);
    assert.equal((await stats(page)).selected, null, 'a pinch is not a tap: nothing selected');
    assert.deepEqual(problems, [], 'no page errors');
  });
});
