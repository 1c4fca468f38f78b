// Where a system package is missing and cannot be installed (here: not root), set-up stops with a
// message naming what is missing and how to get it, not a stack trace.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { spawnSync } from 'node:child_process';
import { mkdtempSync, symlinkSync, existsSync, rmSync, chmodSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { fileURLToPath } from 'node:url';
import path from 'node:path';

const root = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '../..');
const isRoot = process.getuid?.() === 0;
const hasSetpriv = existsSync('/usr/bin/setpriv');

test('a non-root user without emcc and cmake is told what to install', { skip: !(isRoot && hasSetpriv) && 'needs root and setpriv to become another user' }, () => {
  // A PATH with the basic tools the script needs, but no emcc and no cmake.
  const bin = mkdtempSync(path.join(tmpdir(), 'gaitlab-path-'));
  chmodSync(bin, 0o755);
  for (const tool of ['bash', 'cat', 'cut', 'sha256sum', 'id', 'readlink', 'mkdir', 'grep', 'sed',
    'head', 'printf', 'dirname', 'g++', 'ninja', 'chromium', 'xz', 'curl', 'node']) {
    const found = ['/usr/bin', '/bin'].map((d) => path.join(d, tool)).find(existsSync);
    if (found) symlinkSync(found, path.join(bin, tool));
  }
  const r = spawnSync('/usr/bin/setpriv', ['--reuid=65534', '--regid=65534', '--clear-groups',
    path.join(bin, 'bash'), 'scripts/setup.sh', 'packages'], {
    cwd: root, encoding: 'utf8', timeout: 60_000, env: { PATH: bin, HOME: tmpdir() },
  });
  rmSync(bin, { recursive: true, force: true });
  assert.notEqual(r.status, 0);
  assert.match(r.stderr, /missing and cannot be installed automatically \(not root\)/);
  assert.match(r.stderr, /emscripten: emsdk/);
  assert.match(r.stderr, /cmake: https:\/\/cmake.org/);
  assert.match(r.stderr, /apt-get install .*cmake/);
  assert.doesNotMatch(r.stderr, /at \S+:\d+|Traceback|line \d+:/);
});
