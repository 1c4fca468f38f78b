// Runs the benchmark as WebAssembly in headless Chromium: serves the front end with the dev server
// (scripts/serve.mjs: COOP/COEP headers, so the page is cross-origin isolated and has threads),
// opens the performance page (web/bench.html) with the grid in its URL, and waits for the page's
// `window.gaitlabBench` hook to hold the finished document. The peer benchmark
// (bench/peers/browser.mjs) drives its section of the same page with runBenchPage too.
import { chromium } from 'playwright-core';
import { startServer } from '../scripts/serve.mjs';

/** Chromium to drive: $CHROMIUM or Debian's. */
export const executablePath = process.env.CHROMIUM || '/usr/bin/chromium';

/** Headless Chromium lowers the priority of pages it considers hidden; a benchmark is the foreground work here. */
const FOREGROUND = ['--disable-background-timer-throttling', '--disable-renderer-backgrounding', '--disable-backgrounding-occluded-windows'];
/** The demo page draws with WebGL: in software (SwiftShader), with no GPU and no sandbox on a server. */
const WEBGL = ['--no-sandbox', '--disable-gpu', '--enable-unsafe-swiftshader'];

/** Headless Chromium for a benchmark; `webgl` for pages that draw (the demo page). */
export function launchChromium({ webgl = false } = {}) {
  return chromium.launch({ executablePath, headless: true, args: [...(webgl ? WEBGL : []), ...FOREGROUND] });
}

/** URL query of the page for a grid, in the CLI's terms. */
export function benchQuery({ legs, characters, threads, modes, steps, runs, frames }) {
  const q = new URLSearchParams({
    legs: legs.join(','), characters: characters.join(','), threads: threads.join(','),
    modes: modes.join(','), steps: String(steps), runs: String(runs), frames: frames ? '1' : '0', autorun: '1',
  });
  return q.toString();
}

/**
 * Opens the performance page with `query` in headless Chromium, served by the dev server, and
 * polls it until it is done. `readStatus()` runs in the page and returns `{ state, error, status }`:
 * state 'done' ends the wait, 'error' or 'cancelled' fails it; `status` is the progress line,
 * passed to `onProgress` as it changes. Gives up when the status has not changed for `stallMs` (it
 * changes at every point of a grid; the thesis's full grid runs for many hours, so there is no
 * limit on the whole). Resolves to `collect(page, browser)`, run before the browser closes.
 * `what` names the page or section in errors.
 */
export async function runBenchPage(query, { readStatus, collect, onProgress = () => {}, stallMs, what }) {
  const server = await startServer({ port: 0, quiet: true });
  const browser = await launchChromium();
  try {
    const page = await browser.newPage();
    const errors = [];
    page.on('pageerror', (e) => errors.push(e.message));
    await page.goto(`${server.url}bench.html?${query}`, { waitUntil: 'load' });
    let deadline = Date.now() + stallMs;
    let last = '';
    for (;;) {
      const s = await page.evaluate(readStatus);
      if (s.status !== last) {
        onProgress((last = s.status));
        deadline = Date.now() + stallMs;
      }
      if (s.state === 'done') break;
      if (s.state === 'error' || s.state === 'cancelled') throw new Error(`${what} stopped: ${s.error ?? s.state}`);
      if (errors.length) throw new Error(`${what} failed: ${errors.join('; ')}`);
      if (Date.now() > deadline) throw new Error(`${what} made no progress for ${stallMs / 60_000} minutes (at: ${last || 'start'})`);
      await new Promise((r) => setTimeout(r, 500));
    }
    return await collect(page, browser);
  } finally {
    await browser.close();
    await server.close();
  }
}

/**
 * Runs `grid` in the page and resolves to its document (bench/schema.json). `onProgress(text)`
 * receives the page's status line as it changes; `stallMs` as runBenchPage.
 */
export function runInChromium(grid, { onProgress = () => {}, stallMs = 15 * 60_000 } = {}) {
  return runBenchPage(benchQuery(grid), {
    what: 'the performance page',
    onProgress,
    stallMs,
    readStatus: () => ({
      state: window.gaitlabBench?.state,
      error: window.gaitlabBench?.error,
      status: document.querySelector('progress')?.nextElementSibling?.textContent ?? '',
    }),
    collect: async (page, browser) => {
      const doc = await page.evaluate(() => window.gaitlabBench.document);
      doc.machine.runtime_version = doc.machine.runtime_version ?? (await browser.version());
      return doc;
    },
  });
}
