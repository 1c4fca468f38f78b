// Shared by the end-to-end tests: the dev server on a free port and one headless Chromium
// (software WebGL) with a throw-away profile, and pages that record their own errors.
// Not a test file itself (node --test picks *.test.mjs).
import assert from 'node:assert/strict';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { chromium } from 'playwright-core';
import { startServer } from '../../scripts/serve.mjs';

export const repoDir = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '../..');
export const resultsDir = path.join(repoDir, 'test-results', 'e2e');
// This machine is slow (2 shared cores, software WebGL): be generous.
export const PAGE_TIMEOUT = 120_000;

/**
 * Checks the WASM build is there, starts the dev server and Chromium (with `viewport` and any
 * other context options, such as a phone's isMobile and hasTouch). Resolves to
 * `{ server, context, closePages(), close() }`.
 */
export async function startBrowser({ viewport, ...contextOptions }) {
  for (const file of ['gaitlab.mjs', 'gaitlab.wasm', 'gaitlab.worker.js']) {
    assert.ok(fs.existsSync(path.join(repoDir, 'build', 'wasm', file)), `build/wasm/${file} exists (run npm run build)`);
  }
  fs.mkdirSync(resultsDir, { recursive: true });
  const server = await startServer({ port: 0, quiet: true });
  const profileDir = fs.mkdtempSync(path.join(os.tmpdir(), 'gaitlab-chromium-'));
  const context = await chromium.launchPersistentContext(profileDir, {
    executablePath: process.env.CHROMIUM || '/usr/bin/chromium',
    headless: true,
    viewport,
    // e.g. a phone: isMobile, hasTouch, deviceScaleFactor.
    ...contextOptions,
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
  // Every action and wait on every page (a click, a fill, a locator's wait) gets the same
  // generous bound rather than Playwright's 30 s: a click on a button of a page that renders at
  // 2 frames a second, beside a search and the rest of the suite on the same 2 cores, timed out
  // at 30 s once, and passed alone.
  context.setDefaultTimeout(PAGE_TIMEOUT);
  return {
    server,
    context,
    // A test that failed half-way leaves its page open, simulating and rendering on this small
    // machine's cores while the next test runs: close every page between tests.
    closePages: async () => {
      for (const page of context.pages()) await page.close().catch(() => {});
    },
    close: async () => {
      await context.close();
      await server.close();
      fs.rmSync(profileDir, { recursive: true, force: true });
    },
  };
}

/** Opens `url` in a new page that records its uncaught errors, console errors and failed requests. */
export async function openRecordedPage(context, url) {
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

/** The page's statistics (window.gaitlab.stats()). */
export const stats = (page) => page.evaluate(() => window.gaitlab.stats());

/** Waits until the page has drawn a simulated frame (or shows a problem), and checks it is fine. */
export async function ready(page) {
  await page.waitForFunction(() => window.gaitlab?.stats().ready || window.gaitlab?.stats().error, null, {
    timeout: PAGE_TIMEOUT,
    polling: 250,
  });
  const s = await stats(page);
  assert.equal(s.error, null, 'no problem is shown on the page');
  return s;
}
