// The cost benchmark (bench/cost.mjs) refuses what it cannot measure before it builds or runs
// anything: a bad count, a crowd of a kind it does not have, a base that is not a commit. The
// measuring itself is the benchmark's business (bench/results/cost.md), not a test's.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { spawnSync } from 'node:child_process';
import fs from 'node:fs';
import path from 'node:path';
import { fileURLToPath } from 'node:url';

const root = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '../..');
const results = path.join(root, 'bench/results/cost.md');

const cost = (...args) => spawnSync(process.execPath, ['bench/cost.mjs', ...args], { cwd: root, encoding: 'utf8', timeout: 60_000 });

test('bench/cost.mjs refuses bad arguments by name, exit 2, writing nothing', () => {
  const before = fs.existsSync(results) ? fs.readFileSync(results, 'utf8') : null;
  for (const [args, named] of [
    [['--rounds', '0'], /--rounds must be a whole number of at least 1 \(got 0\)/],
    [['--steps', '1.5'], /--steps must be a whole number/],
    [['--crowd', '3:100'], /--crowd takes LEGS:N pairs with LEGS 2 or 4 \(got 3:100\)/],
    [['--crowd', '2:0'], /--crowd takes LEGS:N pairs/],
    [['--base', 'no-such-commit-anywhere'], /--base no-such-commit-anywhere is not a commit of this repository/],
  ]) {
    const r = cost(...args);
    assert.equal(r.status, 2, `${args.join(' ')}: ${r.stderr}`);
    assert.match(r.stderr, named, args.join(' '));
  }
  assert.equal(fs.existsSync(results) ? fs.readFileSync(results, 'utf8') : null, before);
});
