// End to end: the performance page (web/bench.html) in headless Chromium runs a tiny grid in its
// worker with the WASM thread pool, shows the device and the tables, offers the results as JSON
// (valid against bench/schema.json) and CSV, overlays an uploaded file, flags thread counts above
// the hardware's, and can be cancelled. The demo page links to it.
import assert from 'node:assert/strict';
import fs from 'node:fs';
import path from 'node:path';
import { after, before, describe, it } from 'node:test';
import { repoDir, resultsDir, startBrowser } from './browser.mjs';
import { validate } from '../../bench/lib/analysis.mjs';

const TIMEOUT = 180_000;

let session;
let server;
let context;

const tiny = 'legs=2,4&characters=1,2&threads=1,2&modes=serial,full&steps=8&runs=2';
const state = (page) => page.evaluate(() => window.gaitlabBench.state);

async function waitFor(page, states, timeout = TIMEOUT) {
  const end = Date.now() + timeout;
  for (;;) {
    const s = await state(page);
    if (states.includes(s)) return s;
    if (s === 'error') throw new Error(await page.evaluate(() => window.gaitlabBench.error));
    if (Date.now() > end) throw new Error(`the page stayed '${s}'`);
    await new Promise((r) => setTimeout(r, 250));
  }
}

describe('performance page', { timeout: TIMEOUT * 3 }, () => {
  before(async () => {
    session = await startBrowser({ viewport: { width: 1280, height: 900 } });
    ({ server, context } = session);
  });
  after(async () => {
    await session?.close();
  });

  it('runs a tiny grid and offers the results as JSON and CSV', { timeout: TIMEOUT }, async () => {
    const page = await context.newPage();
    const errors = [];
    page.on('pageerror', (e) => errors.push(e.message));
    await page.goto(`${server.url}bench.html?${tiny}&autorun=1`, { waitUntil: 'load' });
    assert.equal(await waitFor(page, ['done']), 'done');
    assert.deepEqual(errors, []);

    const device = await page.locator('.device').innerText();
    assert.match(device, /hardwareConcurrency\s+\d+/);
    assert.match(device, /crossOriginIsolated\s+true/);
    const doc = await page.evaluate(() => window.gaitlabBench.document);
    assert.deepEqual(validate(doc), []);
    assert.equal(doc.machine.runtime, 'wasm-browser');
    assert.equal(doc.points.length, 2 * 3 * 2, 'legs 2,4 x (serial, full 1T, full 2T) x characters 1, 2');
    assert.ok(await page.locator('.u-wrap canvas').count() >= 4, 'uPlot charts for both leg counts');
    assert.match(await page.locator('section').last().innerText(), /real-time capacity/);

    const [jsonDownload] = await Promise.all([page.waitForEvent('download'), page.getByRole('button', { name: 'Download JSON' }).click()]);
    const downloaded = JSON.parse(fs.readFileSync(await jsonDownload.path(), 'utf8'));
    assert.deepEqual(validate(downloaded), []);
    const [csvDownload] = await Promise.all([page.waitForEvent('download'), page.getByRole('button', { name: 'Download CSV' }).click()]);
    const csv = fs.readFileSync(await csvDownload.path(), 'utf8').trim().split('\n');
    assert.match(csv[2], /^legs,characters,threads,mode/);
    assert.equal(csv.length, 3 + doc.points.length);

    // Overlay the file just downloaded, as one would a native run.
    await page.locator('input[type=file]').setInputFiles(await jsonDownload.path());
    await page.getByText(/^Overlaid /).waitFor({ timeout: 10_000 });
    assert.deepEqual(errors, []);
    await page.close();
  });

  it('flags thread counts above the hardware and can cancel a run', { timeout: TIMEOUT }, async () => {
    const page = await context.newPage();
    await page.goto(`${server.url}bench.html?legs=4&characters=30,40,50&threads=5&modes=full&steps=400&runs=3`, { waitUntil: 'load' });
    const hw = await page.evaluate(() => navigator.hardwareConcurrency);
    if (hw < 5) assert.match(await page.locator('.warn').innerText(), /above this device/);
    await page.getByRole('button', { name: 'Run', exact: true }).click();
    await page.waitForFunction(() => window.gaitlabBench.state === 'running');
    await page.getByRole('button', { name: 'Cancel', exact: true }).click();
    assert.equal(await waitFor(page, ['cancelled', 'done']), 'cancelled');
    await page.close();
  });

  it('refuses a crowd larger than a simulation holds, before measuring anything', { timeout: TIMEOUT }, async () => {
    const page = await context.newPage();
    await page.goto(`${server.url}bench.html?legs=4&characters=1,911&threads=1&modes=serial&steps=8&runs=1&autorun=1`, { waitUntil: 'load' });
    await page.waitForFunction(() => window.gaitlabBench.state === 'error', null, { timeout: TIMEOUT });
    assert.match(await page.evaluate(() => window.gaitlabBench.error), /911 quadrupeds is more than a simulation holds \([1-8]\d\d\)/); // as many as the module's heap affords (README, "Limits")
    assert.equal(await page.evaluate(() => window.gaitlabBench.document?.points?.length ?? 0), 0, 'no point was measured');
    await page.close();
  });

  it('answers "how many can this device run?" with one button: both capacities shown large, beside the reference machines', { timeout: TIMEOUT }, async () => {
    const page = await context.newPage();
    const errors = [];
    page.on('pageerror', (e) => errors.push(e.message));
    // Each type's search cut to 6 s (the button's own limit is 50 s a type: under two minutes).
    await page.goto(`${server.url}bench.html?capacitySeconds=6`, { waitUntil: 'load' });
    assert.equal(await page.locator('details.advanced').getAttribute('open'), null, 'the experiment form waits under "advanced"');
    await page.getByRole('button', { name: 'How many can this device run?' }).click();
    await page.waitForFunction(() => ['done', 'error'].includes(window.gaitlabBench.capacity.state), null, { timeout: TIMEOUT });
    const capacity = await page.evaluate(() => window.gaitlabBench.capacity);
    assert.equal(capacity.state, 'done', await page.locator('.capacity').innerText());
    assert.ok(capacity.biped > 0 && capacity.quadruped > 0, JSON.stringify(capacity));
    assert.ok(capacity.seconds < 120, `answered in ${capacity.seconds.toFixed(0)} s`);
    assert.equal(await page.getByTestId('capacity-biped').innerText(), String(capacity.biped));
    assert.equal(await page.getByTestId('capacity-quadruped').innerText(), String(capacity.quadruped));
    const size = await page.getByTestId('capacity-biped').evaluate((e) => parseFloat(getComputedStyle(e).fontSize));
    assert.ok(size >= 32, `shown large (${size} px)`);
    assert.match(await page.locator('.capacity table').innerText(), /AMD EPYC.*551.*188/s);
    await page.screenshot({ path: path.join(resultsDir, 'capacity.png'), fullPage: false });
    assert.deepEqual(errors, []);
    await page.close();
  });

  it('is linked from the demo page', async () => {
    const html = fs.readFileSync(path.join(repoDir, 'web', 'index.html'), 'utf8');
    assert.match(html, /href="bench\.html"/);
    const response = await fetch(`${server.url}bench.html`);
    assert.equal(response.status, 200);
    assert.equal(response.headers.get('cross-origin-embedder-policy'), 'require-corp');
  });
});
