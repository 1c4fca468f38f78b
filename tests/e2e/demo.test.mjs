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
import os from 'node:os';
import path from 'node:path';
import { after, before, describe, it } from 'node:test';
import { fileURLToPath } from 'node:url';
import { chromium } from 'playwright-core';
import { startServer } from '../../scripts/serve.mjs';

const repoDir = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '../..');
const resultsDir = path.join(repoDir, 'test-results', 'e2e');
const executablePath = process.env.CHROMIUM || '/usr/bin/chromium';

// This machine is slow (2 shared cores, software WebGL): be generous.
const PAGE_TIMEOUT = 120_000;
const TEST_TIMEOUT = 240_000;

/** @type {Awaited<ReturnType<typeof startServer>>} */
let server;
/** @type {import('playwright-core').BrowserContext} */
let context;
let profileDir = '';

/** Opens a page and records its uncaught errors and console errors. */
async function openPage(url) {
  const page = await context.newPage();
  const problems = [];
  page.on('pageerror', (error) => problems.push(`page error: ${error.message}`));
  page.on('console', (message) => {
    if (message.type() === 'error') problems.push(`console error: ${message.text()}`);
  });
  page.on('requestfailed', (request) => problems.push(`request failed: ${request.url()} (${request.failure()?.errorText})`));
  await page.goto(url, { waitUntil: 'load', timeout: PAGE_TIMEOUT });
  return { page, problems };
}

const stats = (page) => page.evaluate(() => window.gaitlab.stats());

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

/** A proxy in front of the dev server that drops the cross-origin isolation headers. */
function startStrippingProxy(target) {
  const proxy = http.createServer((request, response) => {
    const upstream = http.request(
      new URL(request.url ?? '/', target),
      { method: request.method, headers: { ...request.headers, host: new URL(target).host } },
      (answer) => {
        const headers = { ...answer.headers };
        delete headers['cross-origin-opener-policy'];
        delete headers['cross-origin-embedder-policy'];
        response.writeHead(answer.statusCode ?? 502, headers);
        answer.pipe(response);
      },
    );
    upstream.on('error', () => response.destroy());
    request.pipe(upstream);
  });
  return new Promise((resolve) => {
    proxy.listen(0, '127.0.0.1', () => {
      const { port } = /** @type {import('node:net').AddressInfo} */ (proxy.address());
      resolve({ url: `http://127.0.0.1:${port}/`, close: () => new Promise((done) => proxy.close(done)) });
    });
  });
}

describe('demo page', { timeout: TEST_TIMEOUT * 3 }, () => {
  before(async () => {
    for (const file of ['gaitlab.mjs', 'gaitlab.wasm', 'gaitlab.worker.js']) {
      assert.ok(fs.existsSync(path.join(repoDir, 'build', 'wasm', file)), `build/wasm/${file} exists (run npm run build)`);
    }
    fs.mkdirSync(resultsDir, { recursive: true });
    server = await startServer({ port: 0, quiet: true });
    profileDir = fs.mkdtempSync(path.join(os.tmpdir(), 'gaitlab-chromium-'));
    context = await chromium.launchPersistentContext(profileDir, {
      executablePath,
      headless: true,
      viewport: { width: 1024, height: 640 },
      args: [
        '--no-sandbox',
        '--disable-gpu',
        '--enable-unsafe-swiftshader', // WebGL in software, without a GPU
        '--disable-quic',
        '--no-first-run',
        '--disable-background-networking',
        '--disable-component-update',
        '--disable-sync',
      ],
    });
  });

  after(async () => {
    await context?.close();
    await server?.close();
    if (profileDir) fs.rmSync(profileDir, { recursive: true, force: true });
  });

  it('simulates and draws the demo scene', { timeout: TEST_TIMEOUT }, async () => {
    const { page, problems } = await openPage(server.url);

    assert.equal(await page.evaluate(() => window.crossOriginIsolated), true, 'the page is cross-origin isolated');
    await page.waitForFunction(() => window.gaitlab?.stats().ready || window.gaitlab?.stats().error, null, {
      timeout: PAGE_TIMEOUT,
      polling: 250,
    });
    const first = await stats(page);
    assert.equal(first.error, null, 'no problem is shown on the page');
    assert.equal(first.crossOriginIsolated, true);
    assert.ok(first.bodies > 0, `bodies are drawn (${first.bodies})`);
    assert.ok(first.threads >= 1, `the simulation has threads (${first.threads})`);

    // Simulated time advances: in real time on a desktop, slower on a loaded 2-core machine
    // rendering in software, so the bounds only rule out standing still and running ahead.
    await page.waitForTimeout(4000);
    const later = await stats(page);
    const advanced = later.simTime - first.simTime;
    assert.ok(advanced > 0.5, `simulated time advanced by ${advanced.toFixed(2)} s in 4 s of wall time`);
    assert.ok(later.realtimeFactor > 0.1 && later.realtimeFactor < 1.5, `real-time factor ${later.realtimeFactor.toFixed(2)}`);
    console.log(`demo: ${later.bodies} bodies, ${later.threads} threads, ${later.fps.toFixed(1)} FPS, real-time factor ${later.realtimeFactor.toFixed(2)}`);
    assert.ok(later.fps > 0, `frames are drawn (${later.fps.toFixed(1)} FPS)`);

    const png = await page.screenshot({ path: path.join(resultsDir, 'demo.png') });
    const colours = await distinctColours(page, png);
    assert.ok(colours >= 8, `the canvas is not blank (${colours} distinct colours)`);

    // Pause stops simulated time; resume restarts it.
    await page.getByRole('button', { name: 'Pause' }).click();
    await page.waitForFunction(() => window.gaitlab.stats().paused, null, { timeout: PAGE_TIMEOUT });
    await page.getByRole('button', { name: 'Resume' }).waitFor({ timeout: PAGE_TIMEOUT });
    await page.waitForTimeout(1000); // the worker's last frame reaches the screen
    const pausedAt = (await stats(page)).simTime;
    await page.waitForTimeout(1500);
    assert.equal((await stats(page)).simTime, pausedAt, 'simulated time stands still while paused');
    await page.getByRole('button', { name: 'Resume' }).click();
    await page.waitForFunction((t) => window.gaitlab.stats().simTime > t + 0.2, pausedAt, { timeout: PAGE_TIMEOUT });

    // Reset builds a new scene from the start: simulated time goes back to (nearly) 0.
    const beforeReset = (await stats(page)).simTime;
    await page.getByRole('button', { name: 'Reset' }).click();
    await page.waitForFunction((t) => window.gaitlab.stats().simTime < t, beforeReset, { timeout: PAGE_TIMEOUT });
    assert.ok((await stats(page)).bodies > 0, 'the new scene is drawn');

    assert.deepEqual(problems, [], 'no page errors');
    await page.close();
  });

  it('explains itself instead of a blank page when served without isolation headers', { timeout: TEST_TIMEOUT }, async () => {
    const proxy = await startStrippingProxy(server.url);
    try {
      const { page, problems } = await openPage(proxy.url);
      assert.equal(await page.evaluate(() => window.crossOriginIsolated), false);
      const notice = page.getByRole('alert');
      await notice.waitFor({ state: 'visible', timeout: PAGE_TIMEOUT });
      const text = await notice.innerText();
      assert.match(text, /Cross-Origin-Opener-Policy/);
      assert.match(text, /npm start/);
      const hook = await stats(page);
      assert.equal(hook.crossOriginIsolated, false);
      assert.equal(hook.ready, false);
      await page.screenshot({ path: path.join(resultsDir, 'not-isolated.png') });
      assert.deepEqual(problems, [], 'no page errors');
      await page.close();
    } finally {
      await proxy.close();
    }
  });
});
