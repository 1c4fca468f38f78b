// Runs the benchmark as WebAssembly in headless Chromium: serves the front end with the dev server
// (scripts/serve.mjs: COOP/COEP headers, so the page is cross-origin isolated and has threads),
// opens the performance page (web/bench.html) with the grid in its URL, and waits for the page's
// `window.gaitlabBench` hook to hold the finished document.
import { chromium } from 'playwright-core';
import { startServer } from '../scripts/serve.mjs';

/** Chromium to drive: $CHROMIUM or Debian's. */
export const executablePath = process.env.CHROMIUM || '/usr/bin/chromium';

/** URL query of the page for a grid, in the CLI's terms. */
export function benchQuery({ legs, characters, threads, modes, steps, runs, frames }) {
  const q = new URLSearchParams({
    legs: legs.join(','), characters: characters.join(','), threads: threads.join(','),
    modes: modes.join(','), steps: String(steps), runs: String(runs), frames: frames ? '1' : '0', autorun: '1',
  });
  return q.toString();
}

/**
 * Runs `grid` in the page and resolves to its document (bench/schema.json). `onProgress(text)`
 * receives the page's status line as it changes. Gives up when the status line has not changed for
 * `stallMs` (it changes at every point of the grid; the thesis's full grid runs for many hours, so
 * there is no limit on the whole).
 */
export async function runInChromium(grid, { onProgress = () => {}, stallMs = 15 * 60_000 } = {}) {
  const server = await startServer({ port: 0, quiet: true });
  const browser = await chromium.launch({
    executablePath,
    headless: true,
    // Headless Chromium lowers the priority of pages it considers hidden; the benchmark is the
    // foreground work here.
    args: ['--disable-background-timer-throttling', '--disable-renderer-backgrounding', '--disable-backgrounding-occluded-windows'],
  });
  try {
    const page = await browser.newPage();
    const errors = [];
    page.on('pageerror', (e) => errors.push(e.message));
    await page.goto(`${server.url}bench.html?${benchQuery(grid)}`, { waitUntil: 'load' });
    let deadline = Date.now() + stallMs;
    let last = '';
    for (;;) {
      const s = await page.evaluate(() => ({
        state: window.gaitlabBench?.state,
        error: window.gaitlabBench?.error,
        status: document.querySelector('progress')?.nextElementSibling?.textContent ?? '',
      }));
      if (s.status !== last) {
        onProgress((last = s.status));
        deadline = Date.now() + stallMs;
      }
      if (s.state === 'done') break;
      if (s.state === 'error' || s.state === 'cancelled') throw new Error(`the performance page stopped: ${s.error ?? s.state}`);
      if (errors.length) throw new Error(`the performance page failed: ${errors.join('; ')}`);
      if (Date.now() > deadline) throw new Error(`the performance page made no progress for ${stallMs / 60_000} minutes (at: ${last || 'start'})`);
      await new Promise((r) => setTimeout(r, 500));
    }
    const doc = await page.evaluate(() => window.gaitlabBench.document);
    doc.machine.runtime_version = doc.machine.runtime_version ?? (await browser.version());
    return doc;
  } finally {
    await browser.close();
    await server.close();
  }
}
