// End to end: the performance page's peer section (web/src/bench/peers.ts) in headless Chromium
// loads gaitlab's module and both builds of the jolt-physics package in its worker and times a
// small point of the reference scene with every engine: each reports a time per step, and its
// ragdolls still stand where they were built. No timing is judged: that is the benchmark's
// business (bench/peers.mjs --browser).
import assert from 'node:assert/strict';
import { after, before, describe, it } from 'node:test';
import { startBrowser } from './browser.mjs';

const TIMEOUT = 120_000;

let session;
let server;
let context;

describe('performance page: beside Jolt Physics', { timeout: TIMEOUT }, () => {
  before(async () => {
    session = await startBrowser({ viewport: { width: 1280, height: 900 } });
    ({ server, context } = session);
  });
  after(async () => {
    await session?.close();
  });

  it('times 20 quadrupeds with gaitlab and both Jolt builds on 1 thread, and gaitlab and Jolt\'s multithreaded build on 2', { timeout: TIMEOUT }, async () => {
    const page = await context.newPage();
    const errors = [];
    page.on('pageerror', (e) => errors.push(e.message));
    await page.goto(`${server.url}bench.html?peerLegs=4&peerCharacters=20&peerThreads=1,2&peerSteps=8&peerRounds=1&peerSettle=2&peerAutorun=1`, { waitUntil: 'load' });
    await page.waitForFunction(() => ['done', 'error'].includes(window.gaitlabBench.peers.state), null, { timeout: TIMEOUT });
    const peers = await page.evaluate(() => window.gaitlabBench.peers);
    assert.equal(peers.state, 'done', peers.error ?? '');
    assert.deepEqual(errors, []);
    assert.equal(peers.run.machine.cross_origin_isolated, true);
    const key = (p) => `${p.engine} ${p.threads}`;
    assert.deepEqual(peers.run.points.map(key).sort(), ['gaitlab 1', 'gaitlab 2', 'jolt 1', 'jolt-mt 1', 'jolt-mt 2']);
    for (const p of peers.run.points) {
      assert.equal(p.skipped, undefined, key(p));
      assert.equal(p.characters, 20);
      assert.ok(p.ms_per_step > 0 && Number.isFinite(p.ms_per_step), `${key(p)}: ${p.ms_per_step} ms`);
      // The quadruped's root is built 0.525 m up (native/src/body/morphology.cpp); a few steps on
      // it is still there in every engine: both built the same standing ragdoll.
      assert.ok(Math.abs(p.root_height_m - 0.525) < 0.02, `${key(p)}: root at ${p.root_height_m}`);
    }
    // The table shows both thread counts, each with gaitlab's and Jolt's times.
    const rows = await page.locator('section.peers table tr').allInnerTexts();
    assert.equal(rows.length, 3, rows.join('\n'));
    assert.match(rows[1], /quadrupeds\s+20\s+1\s+[\d.]+ \([\d.]+–[\d.]+\)\s+[\d.]+ \([\d.]+–[\d.]+\)\s+[\d.]+ \([\d.]+–[\d.]+\)\s+[\d.]+/);
    assert.match(rows[2], /quadrupeds\s+20\s+2\s+[\d.]+ \([\d.]+–[\d.]+\)\s+[\d.]+ \([\d.]+–[\d.]+\)\s+—\s+[\d.]+/);
    await page.close();
  });
});
