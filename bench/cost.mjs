#!/usr/bin/env node
// The controller's cost and the crowd's real-time capacity, measured against an earlier build:
// the locomotion skills (speed keys, standing, gaits chosen by speed, getting up) were allowed to
// make the controller at most 25 % dearer per character per step, and to take at most 10 % off
// the crowd's real-time capacity. This measures both, native, against any earlier commit.
//
//   node bench/cost.mjs [--base REF] [--rounds 7] [--steps 800] [--controller-crowd 100]
//                       [--instruction-crowd 10] [--instruction-steps 600]
//                       [--crowd 2:600,4:250] [--threads 2]
//
// REF (default 8242d90, the last commit before speed keys: one tuned point per gait) is built
// natively from `git archive` into build/cost-base/<commit>/ with this checkout's Bullet
// (third_party/, scripts/setup.sh), the `gaitlab` target only; a second run reuses it. Each
// binary runs with its own shipped presets, as a user of that commit would have had them.
//
// A shared 2-core machine varies by 15 % between runs minutes apart, so the two builds run in
// turns (`gaitlab bench`, one point per call, the order alternating each round) and every figure
// is the median over rounds of the ratio within a round, with its range:
//   - controller: µs per character per step, serial (one thread, the thesis's controller loop),
//     a crowd of --controller-crowd walking at each kind's cruise speed;
//   - controller instructions: the same, counted by valgrind's callgrind (Controller::update and
//     everything it calls, over --instruction-crowd characters for --instruction-steps steps):
//     the count is the same on every run of a binary, whatever else the machine does, so it shows
//     a change of a few per cent that wall-clock rounds on a shared machine cannot (skipped, and
//     said so, where valgrind is missing);
//   - capacity: the whole step (controller and physics) of a crowd near the real-time limit,
//     full mode on --threads threads. A crowd's step grows about linearly with its size there
//     (the crowd benchmark's capacity table), so the capacity ratio is the step-time ratio
//     inverted, and each build's capacity is estimated as N · 8.33 ms / its step at N.
//
// Writes bench/results/cost.{json,md} and prints the table; progress goes to stderr. With 15
// rounds it takes about 25 minutes on the 2-core reference machine (the callgrind part about 5).
import { execFileSync } from 'node:child_process';
import { existsSync, mkdirSync, rmSync, writeFileSync } from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { STEP_BUDGET_MS, legsName } from './lib/analysis.mjs';

const root = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '..');
const args = process.argv.slice(2);
const flag = (name, fallback) => {
  const i = args.indexOf(name);
  return i >= 0 && i + 1 < args.length ? args[i + 1] : fallback;
};
const positive = (name, fallback) => {
  const v = Number(flag(name, fallback));
  if (!Number.isInteger(v) || v < 1) {
    console.error(`bench/cost.mjs: ${name} must be a whole number of at least 1 (got ${flag(name, fallback)})`);
    process.exit(2);
  }
  return v;
};

const BASE_REF = flag('--base', '8242d90');
const ROUNDS = positive('--rounds', '7');
const STEPS = positive('--steps', '800');
const CONTROLLER_CROWD = positive('--controller-crowd', '100');
const THREADS = positive('--threads', '2');
const INSTRUCTION_CROWD = positive('--instruction-crowd', '10');
const INSTRUCTION_STEPS = positive('--instruction-steps', '600');
// Crowds near the real-time limit of 2 threads on the 2-core reference machine (the crowd
// benchmark's capacity table: about 620 bipeds and 250 quadrupeds natively).
const CROWDS = flag('--crowd', '2:600,4:250').split(',').map((pair) => {
  const [legs, n] = pair.split(':').map(Number);
  if (![2, 4].includes(legs) || !Number.isInteger(n) || n < 1) {
    console.error(`bench/cost.mjs: --crowd takes LEGS:N pairs with LEGS 2 or 4 (got ${pair})`);
    process.exit(2);
  }
  return { legs, n };
});

const git = (...a) => execFileSync('git', ['-C', root, ...a], { encoding: 'utf8' }).trim();
const say = (s) => process.stderr.write(`bench/cost: ${s}\n`);

// The base build: sources from git archive, Bullet from this checkout, the CLI target only.
function buildBase(ref) {
  let commit;
  try {
    commit = git('rev-parse', '--verify', `${ref}^{commit}`);
  } catch {
    console.error(`bench/cost.mjs: --base ${ref} is not a commit of this repository`);
    process.exit(2);
  }
  const dir = path.join(root, 'build/cost-base', commit.slice(0, 12));
  const src = path.join(dir, 'src'), out = path.join(dir, 'native');
  const bullet = path.join(root, 'third_party/bullet3');
  if (!existsSync(path.join(bullet, 'src/btBulletDynamicsAll.cpp'))) {
    console.error('bench/cost.mjs: no Bullet in third_party/bullet3: run scripts/setup.sh (npm test does)');
    process.exit(2);
  }
  if (!existsSync(path.join(src, 'native/CMakeLists.txt'))) {
    say(`unpacking ${commit.slice(0, 12)} into ${path.relative(root, src)}`);
    mkdirSync(src, { recursive: true });
    execFileSync('bash', ['-c', `git -C "${root}" archive ${commit} | tar -x -C "${src}"`]);
  }
  if (!existsSync(path.join(out, 'build.ninja'))) {
    execFileSync('cmake', ['-S', path.join(src, 'native'), '-B', out, '-G', 'Ninja', '-DCMAKE_BUILD_TYPE=Release',
      `-DBULLET_ROOT=${bullet}`], { stdio: ['ignore', 'ignore', 'inherit'] });
  }
  say(`building ${commit.slice(0, 12)} natively (the gaitlab target; minutes the first time)`);
  execFileSync('ninja', ['-C', out, 'gaitlab'], { stdio: ['ignore', 'ignore', 'inherit'] });
  return { name: 'base', commit, cli: path.join(out, 'gaitlab') };
}

const current = { name: 'now', commit: git('rev-parse', 'HEAD'), cli: path.join(root, 'build/native/gaitlab') };
if (!existsSync(current.cli)) {
  console.error('bench/cost.mjs: build/native/gaitlab is missing: run npm run build');
  process.exit(2);
}
const base = buildBase(BASE_REF);
const dirty = git('status', '--porcelain', '--untracked-files=no') !== '';

// One point of the thesis's experiment; returns it as `gaitlab bench --json` reports it.
function point(build, { legs, characters, mode, threads }) {
  const out = execFileSync(build.cli, ['bench', '--legs', String(legs), '--characters', String(characters),
    '--threads', String(threads), '--mode', mode, '--steps', String(STEPS), '--runs', '1', '--json'],
  { encoding: 'utf8', stdio: ['ignore', 'pipe', 'ignore'], maxBuffer: 1 << 28 });
  return JSON.parse(out).points[0];
}

const median = (a) => {
  const s = [...a].sort((x, y) => x - y);
  return s.length % 2 ? s[s.length >> 1] : (s[s.length / 2 - 1] + s[s.length / 2]) / 2;
};
const summary = (a) => ({ median: median(a), min: Math.min(...a), max: Math.max(...a), n: a.length });

// Both builds measure the same point in turns, the order alternating by round.
function inTurns(what, read) {
  const rows = [];
  for (let round = 0; round < ROUNDS; ++round) {
    say(`${what.characters} ${legsName(what.legs)}s, ${what.mode} ${what.threads}T: round ${round + 1}/${ROUNDS}`);
    const order = round % 2 ? [current, base] : [base, current];
    const got = {};
    for (const b of order) got[b.name] = read(point(b, what));
    rows.push(got);
  }
  return rows;
}

// Instructions of Controller::update and its callees per character per step, by callgrind
// (inclusive cost), over the same serial run as above but smaller (about a minute per binary).
function hasValgrind() {
  try {
    execFileSync('valgrind', ['--version'], { stdio: 'ignore' });
    execFileSync('sh', ['-c', 'command -v callgrind_annotate'], { stdio: 'ignore' });  // its --version exits 255
    return true;
  } catch {
    return false;
  }
}
function controllerInstructions(build, legs) {
  const out = path.join(os.tmpdir(), `gaitlab-cost-${process.pid}-${build.name}-${legs}.callgrind`);
  execFileSync('valgrind', ['--tool=callgrind', `--callgrind-out-file=${out}`, build.cli, 'bench', '--legs', String(legs),
    '--characters', String(INSTRUCTION_CROWD), '--threads', '1', '--mode', 'serial',
    '--steps', String(INSTRUCTION_STEPS), '--runs', '1'], { stdio: 'ignore' });
  const text = execFileSync('callgrind_annotate', ['--inclusive=yes', out], { encoding: 'utf8', maxBuffer: 1 << 28 });
  rmSync(out, { force: true });
  // "  66,666,763 ( 4.76%)  ???:gaitlab::gait::Controller::update(double, ...) [clone ...]"
  const line = text.split('\n').find((l) => /gaitlab::gait::Controller::update\(double/.test(l));
  if (!line) throw new Error(`${build.cli}: callgrind saw no Controller::update`);
  return Number(line.trim().split(/\s+/)[0].replace(/,/g, '')) / (INSTRUCTION_CROWD * INSTRUCTION_STEPS);
}

const measured = [];
if (hasValgrind()) {
  for (const legs of [2, 4]) {
    say(`${INSTRUCTION_CROWD} ${legsName(legs)}s under callgrind, ${INSTRUCTION_STEPS} steps`);
    const counts = { base: controllerInstructions(base, legs), now: controllerInstructions(current, legs) };
    measured.push({ kind: 'instructions', legs, characters: INSTRUCTION_CROWD, steps: INSTRUCTION_STEPS,
      unit: 'instructions per character per step', ...counts, ratio: summary([counts.now / counts.base]) });
  }
} else {
  say('no valgrind: the controller\'s instruction counts are not measured');
}
for (const legs of [2, 4]) {
  const what = { legs, characters: CONTROLLER_CROWD, mode: 'serial', threads: 1 };
  const rows = inTurns(what, (p) => p.controller_us_per_character);
  measured.push({ kind: 'controller', ...what, unit: 'µs per character per step', rows,
    base: summary(rows.map((r) => r.base)), now: summary(rows.map((r) => r.now)),
    ratio: summary(rows.map((r) => r.now / r.base)) });
}
for (const { legs, n } of CROWDS) {
  const what = { legs, characters: n, mode: 'full', threads: THREADS };
  const rows = inTurns(what, (p) => p.step_ms.mean);
  const capacity = (ms) => Math.floor((n * STEP_BUDGET_MS) / ms);
  measured.push({ kind: 'capacity', ...what, unit: 'ms per whole step', rows,
    base: summary(rows.map((r) => r.base)), now: summary(rows.map((r) => r.now)),
    // capacity now / capacity before = step before / step now
    ratio: summary(rows.map((r) => r.base / r.now)),
    capacity: { base: capacity(median(rows.map((r) => r.base))), now: capacity(median(rows.map((r) => r.now))) } });
}

// ---- results ---------------------------------------------------------------------------------
const cpu = os.cpus()[0]?.model ?? 'unknown CPU';
const f = (x, d = 2) => x.toFixed(d);
const range = (s, d = 2) => `${f(s.median, d)} (${f(s.min, d)}–${f(s.max, d)})`;
const LIMITS = { controller: 1.25, capacity: 0.9 };
const verdict = (m) => (m.kind === 'capacity' ? m.ratio.median >= LIMITS.capacity : m.ratio.median <= LIMITS.controller);
const row = (m) => {
  const met = verdict(m) ? 'yes' : '**no**';
  if (m.kind === 'instructions') {
    return `| controller instructions per character per step, ${legsName(m.legs)} (callgrind, ${m.characters} for ${m.steps} steps) | ${Math.round(m.base)} | ${Math.round(m.now)} | ${f(m.ratio.median, 3)} | ≤ ${LIMITS.controller} | ${met} |`;
  }
  if (m.kind === 'controller') {
    return `| controller µs per character per step, ${legsName(m.legs)}, serial, ${m.characters} | ${range(m.base)} | ${range(m.now)} | ${range(m.ratio)} | ≤ ${LIMITS.controller} | ${met} |`;
  }
  return `| real-time capacity at 120 Hz, ${legsName(m.legs)}s, full, ${m.threads} threads (whole step at ${m.characters}, ms) | ${m.capacity.base} (${range(m.base)}) | ${m.capacity.now} (${range(m.now)}) | ${range(m.ratio)} | ≥ ${LIMITS.capacity} | ${met} |`;
};

const doc = {
  schema: 'gaitlab-cost/1', date: new Date().toISOString(),
  machine: { cpu, cores: os.cpus().length, load_average: os.loadavg()[0] },
  base: { ref: BASE_REF, commit: base.commit }, now: { commit: current.commit, uncommitted_changes: dirty },
  rounds: ROUNDS, steps: STEPS, limits: LIMITS, measured,
};
const md = [
  `# The controller's cost against ${base.commit.slice(0, 7)} (${cpu}, ${os.cpus().length} cores)`, '',
  `Measured ${doc.date.slice(0, 10)} at ${current.commit.slice(0, 7)}${dirty ? ' with uncommitted changes' : ''} by`,
  `\`node bench/cost.mjs --base ${BASE_REF}\`: each build with its own shipped presets, ${ROUNDS} rounds of`,
  `${STEPS} steps in turns; medians over rounds, the range in brackets.`, '',
  '| what | base | now | now / base | allowed | met |',
  '|---|---|---|---|---|---|',
  ...measured.map(row),
  '',
  'Capacity is N · 8.33 ms / the median whole step at N, and its ratio is the whole step\'s ratio inverted, round by round.',
];
mkdirSync(path.join(root, 'bench/results'), { recursive: true });
writeFileSync(path.join(root, 'bench/results/cost.json'), `${JSON.stringify(doc, null, 2)}\n`);
writeFileSync(path.join(root, 'bench/results/cost.md'), `${md.join('\n')}\n`);
console.log(md.join('\n'));
