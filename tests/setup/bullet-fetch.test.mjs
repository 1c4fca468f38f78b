// scripts/setup.sh's Bullet step against a local mirror (file://): a good tarball is verified
// and unpacked; a corrupt or partial one is caught by the sha256, deleted and reported; a
// missing one is reported. Runs `scripts/setup.sh bullet` on a scratch folder.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { spawnSync } from 'node:child_process';
import { mkdtempSync, mkdirSync, writeFileSync, readFileSync, existsSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { fileURLToPath } from 'node:url';
import path from 'node:path';

const root = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '../..');
const name = 'bullet_3.24+dfsg.orig.tar.xz';
const real = path.join(root, 'third_party', name);  // kept by the set-up that ran before the tests

function mirrorWith(bytes) {
  const dir = mkdtempSync(path.join(tmpdir(), 'gaitlab-mirror-'));
  if (bytes) {
    mkdirSync(path.join(dir, 'pool/main/b/bullet'), { recursive: true });
    writeFileSync(path.join(dir, 'pool/main/b/bullet', name), bytes);
  }
  return dir;
}

function setup(mirror) {
  const thirdParty = mkdtempSync(path.join(tmpdir(), 'gaitlab-third-party-'));
  const r = spawnSync('bash', ['scripts/setup.sh', 'bullet'], {
    cwd: root, encoding: 'utf8', timeout: 120_000,
    env: { ...process.env, BULLET_MIRROR: `file://${mirror}`, GAITLAB_THIRD_PARTY: thirdParty },
  });
  return { ...r, thirdParty };
}

test('a corrupt download is detected by the checksum, deleted and reported', () => {
  const r = setup(mirrorWith(Buffer.from('this is not a tarball')));
  assert.notEqual(r.status, 0);
  assert.match(r.stderr, /checksum mismatch \(corrupt or partial download\), deleted it/);
  assert.equal(existsSync(path.join(r.thirdParty, name)), false, 'the bad file must be gone');
  assert.equal(existsSync(path.join(r.thirdParty, 'bullet3')), false);
  rmSync(r.thirdParty, { recursive: true, force: true });
});

test('a partial download is detected the same way', { skip: !existsSync(real) && 'no tarball' }, () => {
  const whole = readFileSync(real);
  const r = setup(mirrorWith(whole.subarray(0, whole.length >> 1)));
  assert.notEqual(r.status, 0);
  assert.match(r.stderr, /checksum mismatch/);
  assert.equal(existsSync(path.join(r.thirdParty, name)), false);
  rmSync(r.thirdParty, { recursive: true, force: true });
});

test('a missing file on the mirror is reported, not a stack trace', () => {
  const r = setup(mirrorWith(null));
  assert.notEqual(r.status, 0);
  assert.match(r.stderr, /download of .* failed/);
  rmSync(r.thirdParty, { recursive: true, force: true });
});

test('the right tarball is verified and unpacked, and a second run does nothing', { skip: !existsSync(real) && 'no tarball' }, () => {
  const r = setup(mirrorWith(readFileSync(real)));
  assert.equal(r.status, 0, r.stderr);
  assert.ok(existsSync(path.join(r.thirdParty, 'bullet3/src/btBulletDynamicsAll.cpp')));
  assert.ok(existsSync(path.join(r.thirdParty, 'bullet3/.verified')));
  const again = spawnSync('bash', ['scripts/setup.sh', 'bullet'], {
    cwd: root, encoding: 'utf8',
    env: { ...process.env, BULLET_MIRROR: 'file:///nonexistent', GAITLAB_THIRD_PARTY: r.thirdParty },
  });
  assert.equal(again.status, 0, again.stderr);
  assert.equal(again.stderr, '', 'nothing fetched or unpacked the second time');
  rmSync(r.thirdParty, { recursive: true, force: true });
});
