// The peer benchmark in headless Chromium: serves the front end with the dev server
// (scripts/serve.mjs: COOP/COEP, so the page is cross-origin isolated and has threads), opens the
// performance page's peer section (web/src/bench/peers.ts) with the grid in its URL, and waits for
// `window.gaitlabBench.peers` to hold the finished run. The page's worker measures with the same
// code as Node (bench/peers/comparison.mjs).
import os from 'node:os';
import { chromium } from 'playwright-core';
import { startServer } from '../../scripts/serve.mjs';
import { executablePath } from '../browser.mjs';

/** URL query of the page's peer section for a grid ({ legs, characters, threads, steps, rounds, settle }). */
export function peersQuery({ legs, characters, threads, steps, rounds, settle }) {
  return new URLSearchParams({
    peerLegs: legs.join(','), peerCharacters: characters.join(','), peerThreads: threads.join(','),
    peerSteps: String(steps), peerRounds: String(rounds), peerSettle: String(settle), peerAutorun: '1',
  }).toString();
}

/**
 * Runs the grid in the page; resolves to `{ machine, points }` (points as measurePoint gives them).
 * Gives up when the page's status has not changed for `stallMs` (it changes at every point).
 */
export async function runPeersInChromium(grid, { onProgress = () => {}, stallMs = 10 * 60_000 } = {}) {
  const server = await startServer({ port: 0, quiet: true });
  const browser = await chromium.launch({
    executablePath,
    headless: true,
    args: ['--disable-background-timer-throttling', '--disable-renderer-backgrounding', '--disable-backgrounding-occluded-windows'],
  });
  try {
    const page = await browser.newPage();
    const errors = [];
    page.on('pageerror', (e) => errors.push(e.message));
    await page.goto(`${server.url}bench.html?${peersQuery(grid)}`, { waitUntil: 'load' });
    let deadline = Date.now() + stallMs;
    let last = '';
    for (;;) {
      const s = await page.evaluate(() => {
        const p = window.gaitlabBench?.peers;
        return { state: p?.state, error: p?.error, status: p?.status ?? '' };
      });
      if (s.status !== last) {
        onProgress((last = s.status));
        deadline = Date.now() + stallMs;
      }
      if (s.state === 'done') break;
      if (s.state === 'error') throw new Error(`the performance page's peer section stopped: ${s.error}`);
      if (errors.length) throw new Error(`the performance page failed: ${errors.join('; ')}`);
      if (Date.now() > deadline) throw new Error(`the peer section made no progress for ${stallMs / 60_000} minutes (at: ${last || 'start'})`);
      await new Promise((r) => setTimeout(r, 500));
    }
    const run = await page.evaluate(() => window.gaitlabBench.peers.run);
    run.machine.browser = `Chromium ${browser.version()}`;
    run.machine.cpus = os.cpus()[0]?.model ?? 'unknown';
    run.machine.loadavg = os.loadavg();
    return run;
  } finally {
    await browser.close();
    await server.close();
  }
}
