// The peer benchmark in headless Chromium: opens the performance page's peer section
// (web/src/bench/peers.ts) with the grid in its URL through bench/browser.mjs's runner, and waits
// for `window.gaitlabBench.peers` to hold the finished run. The page's worker measures with the
// same code as Node (bench/peers/comparison.mjs).
import os from 'node:os';
import { runBenchPage } from '../browser.mjs';

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
export function runPeersInChromium(grid, { onProgress = () => {}, stallMs = 10 * 60_000 } = {}) {
  return runBenchPage(peersQuery(grid), {
    what: "the performance page's peer section",
    onProgress,
    stallMs,
    readStatus: () => {
      const p = window.gaitlabBench?.peers;
      return { state: p?.state, error: p?.error, status: p?.status ?? '' };
    },
    collect: async (page, browser) => {
      const run = await page.evaluate(() => window.gaitlabBench.peers.run);
      run.machine.browser = `Chromium ${browser.version()}`;
      run.machine.cpus = os.cpus()[0]?.model ?? 'unknown';
      run.machine.loadavg = os.loadavg();
      return run;
    },
  });
}
