// The `gaitlab` CLI's limits and its one option parser, natively and (where the file system
// allows) as WebAssembly under Node: gait files nested deep, endless or huge are refused at once;
// every subcommand has --help and takes only whole numbers for integer options and any 32-bit
// seed; `optimize` checks --out before searching and replaces the file whole (Ctrl-C included).
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { spawn, spawnSync } from 'node:child_process';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { fileURLToPath } from 'node:url';

const root = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '../..');
const native = path.join(root, 'build/native/gaitlab');
const tmp = fs.mkdtempSync(path.join(os.tmpdir(), 'gaitlab-cli-limits-'));

function run(args, cmd = native) {
  const r = spawnSync(cmd, cmd === native ? args : ['bench/wasm.mjs', ...args], { cwd: root, encoding: 'utf8', timeout: 60_000 });
  return { status: r.status, signal: r.signal, stdout: r.stdout, stderr: r.stderr };
}

test('gait files nested deep, endless or huge are refused with a message, natively and as WASM', () => {
  const deep = path.join(tmp, 'deep.json');
  fs.writeFileSync(deep, `{"format":${'['.repeat(100000)}${']'.repeat(100000)}}`);
  const huge = path.join(tmp, 'huge.json');
  fs.writeFileSync(huge, ' '.repeat(50 << 20));
  for (const cmd of [native, process.execPath]) {
    const d = run(['walk', '--params', deep, '--seconds', '0.1'], cmd);
    assert.equal(d.status, 2, d.stderr);
    assert.match(d.stderr, /nested deeper than 16 levels/);
    const h = run(['walk', '--params', huge, '--seconds', '0.1'], cmd);
    assert.equal(h.status, 2, h.stderr);
    assert.match(h.stderr, /longer than 262144 bytes/);
  }
  const zero = run(['walk', '--params', '/dev/zero', '--seconds', '0.1']);
  assert.equal(zero.status, 2, zero.stderr);
  assert.match(zero.stderr, /longer than 262144 bytes/);
});

test('every subcommand has --help, integers are integers, and seeds share one range', () => {
  for (const command of ['walk', 'bench', 'optimize', 'schema']) {
    const r = run([command, '--help']);
    assert.equal(r.status, 0, `${command} --help: ${r.stderr}`);
    assert.match(r.stdout, new RegExp(`^usage: gaitlab ${command}`));
  }
  // The optimiser's help lists every objective setting it accepts, each with its range.
  const help = run(['optimize', '--help']).stdout;
  for (const name of ['wd', 'wv', 'wa', 'wr', 'wt', 'wf', 'wk', 'ws', 'wp', 'wo', 'fallPenalty', 'seconds', 'warmup', 'starts', 'startImpulse',
    'startPhases', 'turnRate', 'turnBothWays', 'turnStraight', 'pushImpulse', 'pushEvery', 'pushDuration', 'pushAnyWay', 'ramp', 'stopFrom', 'boxHits', 'speedChanges']) {
    assert.match(help, new RegExp(`^  ${name} +\\S+ to \\S+`, 'm'), `optimize --help lists ${name}`);
  }
  for (const [args, name] of [
    [['walk', '--seed', '1.5'], 'walk'],
    [['optimize', '--out', path.join(tmp, 'x.json'), '--generations', '2.5'], 'optimize'],
    [['optimize', '--out', path.join(tmp, 'x.json'), '--seed', '7.25'], 'optimize'],
    [['optimize', '--out', path.join(tmp, 'x.json'), '--threads', '1.5'], 'optimize'],
    [['bench', '--steps', '10.5'], 'bench'],
  ]) {
    const r = run(args);
    assert.equal(r.status, 2, args.join(' '));
    assert.match(r.stderr, new RegExp(`^gaitlab ${name}: --\\w+: '[\\d.]+' is not a whole number`), r.stderr);
  }
  for (const command of ['walk', 'bench']) {
    const args = command === 'walk' ? ['walk', '--seconds', '0.05'] : ['bench', '--characters', '1', '--threads', '1', '--mode', 'serial', '--steps', '1', '--runs', '1'];
    assert.equal(run([...args, '--seed', '4294967295', '--json']).status, 0, command);
    assert.equal(run([...args, '--seed', '4294967296', '--json']).status, 2, command);
  }
});

test('optimize checks --out before the search and replaces a previous file whole', () => {
  const missing = run(['optimize', '--out', path.join(tmp, 'no-such-dir', 'x.json'), '--generations', '1']);
  assert.equal(missing.status, 1);
  assert.match(missing.stderr, /cannot be written .*nothing was searched/);
  assert.doesNotMatch(missing.stderr, /generation 1/);
  const dir = run(['optimize', '--out', tmp, '--generations', '1']);
  assert.equal(dir.status, 1);
  assert.match(dir.stderr, /is a directory; nothing was searched/);
  // A name that is not UTF-8 (it used to abort after the search, leaving an empty file).
  // (Node writes arguments as UTF-8: the shell passes the raw bytes.)
  const r = spawnSync('sh', ['-c', `"$0" optimize --out "$(printf '%s/\\377\\376.json' "$1")" --generations 1 --candidates 2 --seconds 0.5 --json`, native, tmp], { encoding: 'utf8' });
  assert.equal(r.status, 0, r.stderr);
  const odd = fs.readdirSync(tmp, { encoding: 'buffer' }).find((name) => name[0] === 0xff);
  assert.ok(odd, 'the file with the odd name was written');
  assert.match(fs.readFileSync(Buffer.concat([Buffer.from(`${tmp}/`), odd]), 'utf8'), /"format": "gaitlab-gait"/);
  assert.deepEqual(fs.readdirSync(tmp).filter((f) => f.includes('.tmp-')), []);
});

test('Ctrl-C during optimize writes the best so far whole, through a rename', async () => {
  const out = path.join(tmp, 'interrupted.json');
  fs.writeFileSync(out, 'PREVIOUS');
  const child = spawn(native, ['optimize', '--out', out, '--generations', '100000', '--candidates', '2', '--seconds', '0.5'], { cwd: root });
  let stderr = '';
  let interrupted = false;
  await new Promise((resolve) => {
    child.stderr.on('data', (chunk) => {
      stderr += chunk;
      if (!interrupted && stderr.includes('generation 2/')) {
        interrupted = true;
        child.kill('SIGINT');
      }
    });
    child.on('exit', resolve);
  });
  assert.match(stderr, /interrupted; writing the best so far/);
  const gait = JSON.parse(fs.readFileSync(out, 'utf8'));
  assert.equal(gait.format, 'gaitlab-gait');
  assert.equal(gait.meta.interrupted, true);
  assert.deepEqual(fs.readdirSync(tmp).filter((f) => f.includes('.tmp-')), []);
});

test('walk pushes: a duration past 0.3 s and an unknown direction are refused with the option named', () => {
  const long = run(['walk', '--seconds', '0.1', '--push-impulse', '10', '--push-duration', '0.5']);
  assert.equal(long.status, 2, long.stderr);
  assert.match(long.stderr, /--push-duration: 0\.5 is outside \[0\.0, 0\.3\]/);
  const way = run(['walk', '--seconds', '0.1', '--push-impulse', '10', '--push-direction', 'up']);
  assert.equal(way.status, 2, way.stderr);
  assert.match(way.stderr, /--push-direction: 'up' is not lateral, forward, backward or any/);
  const ok = run(['walk', '--seconds', '3', '--speed', '0', '--push-impulse', '10', '--push-every', '0.5',
    '--push-duration', '0.3', '--push-direction', 'any', '--json']);
  assert.equal(ok.status, 0, ok.stderr);
  const r = JSON.parse(ok.stdout);
  assert.equal(r.push_duration_s, 0.3);
  assert.ok(r.pushes_applied >= 2, `${r.pushes_applied} pushes in 1 s of 0.5 s spacing`);
});

test('walk schedules: a bad T:V or T:FILE entry is refused with the option and the entry named', () => {
  for (const [option, value, entry] of [
    ['--speed-schedule', '0:0,2:1,1:0', '1:0'],   // times not increasing
    ['--speed-schedule', '0:0,-1:1', '-1:1'],     // a negative time
    ['--speed-schedule', '0:0,2:fast', '2:fast'], // not a speed
    ['--speed-schedule', '0:0,2:9', '2:9'],       // faster than 5 m/s
    ['--speed-schedule', '0:0,2', '2'],           // no colon
    ['--gait-schedule', '1:', '1:'],              // no file
    ['--gait-schedule', `2:${path.join(root, 'public/presets/biped.json')},1:x.json`, '1:x.json'],
  ]) {
    const r = run(['walk', '--seconds', '0.1', option, value]);
    assert.equal(r.status, 2, `${option} ${value}: ${r.stderr}`);
    assert.ok(r.stderr.includes(`${option}: '${entry}' is not T:`), `${option} ${value}: ${r.stderr}`);
  }
  const ok = run(['walk', '--seconds', '2', '--speed-schedule', '0:0,1:0.5', '--json']);
  assert.equal(ok.status, 0, ok.stderr);
  assert.equal(JSON.parse(ok.stdout).goal_speed_m_s, 0.5);
});
