// SPDX-License-Identifier: MIT
// The WebAssembly module against the native command and the golden hashes:
// for every built-in scene and seeds 0, 1 and 42, the state hash after the
// scene's default frames equals `calder run SCENE --seed S`'s and the one
// recorded in tests/golden/state_hashes.txt (calder's own sin, cos, atan2,
// log and pow make them the same bits); scripted mouse input as
// --mouse-pressed; and bad input gives the command's own messages, as thrown
// JavaScript errors.
import {execFileSync, spawnSync} from 'node:child_process';
import {mkdtempSync, readFileSync, writeFileSync} from 'node:fs';
import {tmpdir} from 'node:os';
import {join} from 'node:path';

import {check, done, kNative, kRoot, loadCore} from './module.mjs';

const core = await loadCore();

function nativeRun(args, cwd) {
  return spawnSync(kNative, ['run', ...args], {cwd, encoding: 'utf8'});
}
function nativeHash(args) {
  const run = nativeRun(args);
  const m = /^state hash\s+([0-9a-f]{16})$/m.exec(run.stdout);
  if (run.status !== 0 || !m) throw new Error(`calder run ${args.join(' ')}: ${run.stderr}`);
  return m[1];
}
function thrown(f) {
  try {
    f();
  } catch (e) {
    return e;
  }
  return null;
}
// What the module throws is the C++ message; calder.js makes it an Error.
const message = (e) => (typeof e === 'string' ? e : e && e.message);

// --- the scene list is the engine's ---
const names = core.scenes().map((s) => s.name);
const listed = execFileSync(kNative, ['list'], {encoding: 'utf8'})
  .trim()
  .split('\n')
  .map((line) => line.split(/\s+/)[0]);
check(JSON.stringify(names) === JSON.stringify(listed),
      `the module's ${names.length} scenes are calder list's, in order`);

// --- same numbers as native, and as the golden file ---
const golden = readFileSync(join(kRoot, 'tests/golden/state_hashes.txt'), 'utf8')
  .split('\n')
  .filter((line) => line && !line.startsWith('#'))
  .map((line) => line.split(' '));
check(JSON.stringify(golden.map(([name, seed]) => `${name} ${seed}`)) ===
        JSON.stringify(names.flatMap((name) => [0, 1, 42].map((seed) => `${name} ${seed}`))),
      `tests/golden/state_hashes.txt covers the ${names.length} scenes, seeds 0, 1 and 42`);
for (const [name, seed, frames, recorded] of golden) {
  const sim = new core.Simulation(name, {seed: Number(seed)});
  check(sim.frames() === Number(frames), `${name}: ${frames} default frames`);
  sim.step(Number(frames));
  const web = sim.stateHash();
  sim.delete();
  const native = nativeHash([name, '--seed', seed]);
  check(web === native && web === recorded,
        `${name} --seed ${seed}: ${web} (native ${native}, golden ${recorded})`);
}

// Scripted input, as the command takes it: the wind of example 2.1.
{
  const sim = new core.Simulation('example-2.1', {mousePressed: [[100, 160]]});
  sim.step(600);
  const native = nativeHash(['example-2.1', '--mouse-pressed', '100-160']);
  check(sim.stateHash() === native, `example-2.1 --mouse-pressed 100-160: ${sim.stateHash()}`);
  const still = new core.Simulation('example-2.1', {});
  still.step(600);
  check(still.stateHash() !== sim.stateHash(), 'the scripted wind changes the state');
  sim.delete();
  still.delete();
}

// Scene text runs like the file: the built-in scene's TOML, round trip.
{
  const builtin = new core.Simulation('example-2.7', {seed: 1});
  const text = builtin.toml();
  const fromText = new core.Simulation(text, {});
  builtin.step(600);
  fromText.step(600);
  check(fromText.stateHash() === builtin.stateHash() &&
        builtin.stateHash() === nativeHash(['example-2.7', '--seed', '1']),
        'example-2.7 as scene text gives the built-in scene\'s hash');
  builtin.delete();
  fromText.delete();
}

// Large worlds step through calder::bulk's tile kernels (with WebAssembly
// SIMD in the default build), as natively: the book arithmetic gives the
// plain loops' bits, so the same hash as native `calder run` of the same text.
{
  const kernels = core.kernels();
  const expected = process.env.CALDER_WEB_MOVERS_KERNELS || 'wasm-simd128';
  check(kernels.bulk === expected, `the bulk kernels are ${kernels.bulk} (expected ${expected})`);
  const sim = new core.Simulation('rain', {seed: 1, count: 20000});
  const text = sim.toml();
  sim.step(300);
  const file = join(mkdtempSync(join(tmpdir(), 'calder-web-rain-')), 'rain.toml');
  writeFileSync(file, text);
  const native = nativeHash([file, '--frames', '300']);
  check(sim.stateHash() === native, `rain, 20,000 bodies, 300 frames (the kernels): ${sim.stateHash()} (native ${native})`);
  // The fast arithmetics run through the same kernels (without them the
  // module would throw); their last bits are the instruction set's (fused
  // multiply-adds, estimates), so they are checked against the book's numbers.
  for (const arithmetic of ['float64', 'float32']) {
    const fast = new core.Simulation(text.replace('arithmetic = "book"', `arithmetic = "${arithmetic}"`), {});
    fast.step(300);
    // float32 rounds the state to float: a drop near the floor may bounce a
    // step earlier or later, so the 99.9th percentile is checked there.
    const book = sim.view('y');
    const gaps = Array.from(fast.view('y'), (y, i) => Math.abs(y - book[i])).sort((a, b) => a - b);
    const [quantile, tolerance] = arithmetic === 'float64' ? [1, 1e-9] : [0.999, 1e-3];
    const gap = gaps[Math.min(gaps.length - 1, Math.floor(gaps.length * quantile))];
    check(gaps.length === book.length && gap < tolerance,
          `rain with arithmetic ${arithmetic}: y within ${tolerance} px of book after 300 frames ` +
          `(${quantile === 1 ? 'every body' : `${quantile * 100}% of the bodies`}: ${gap.toExponential(1)})`);
    fast.delete();
  }
  sim.delete();
}

// --- bad input: the command's messages ---
const dir = mkdtempSync(join(tmpdir(), 'calder-web-'));
const badTexts = {
  'typo.toml': 'name = "typo"\n\n[[bodies]]\ncount = 3\nmas = 2\n',
  'syntax.toml': 'name = "broken"\n[canvas\nwidth = 640\n',
  'range.toml': 'name = "r"\n[[bodies]]\ncount = 2\nmass = -1\n',
  'field.toml': 'name = "f"\n[[bodies]]\ncount = 1\nmass = 1\nx = 1\ny = 1\n[[fields]]\ntype = "gravty"\n',
};
for (const [file, text] of Object.entries(badTexts)) {
  writeFileSync(join(dir, file), text);
  const run = nativeRun([file], dir);
  const nativeMessage = run.stderr.trim().replace(/^calder: /, '');
  const e = thrown(() => new core.Simulation(text, {name: file}));
  check(run.status !== 0 && e !== null && message(e) === nativeMessage,
        `${file}: "${message(e)}" is the command's message`);
}
{
  const e = thrown(() => new core.Simulation(badTexts['typo.toml'], {name: 'typo.toml'}));
  check(/^typo\.toml:5:1: .*did you mean 'mass'/.test(message(e)), 'line:col and "did you mean"');
}
for (const seed of [-1, 4294967296, 1.5, 'abc']) {
  const e = thrown(() => new core.Simulation('example-2.7', {seed}));
  const run = nativeRun(['example-2.7', '--seed', String(seed)]);
  const expected = run.stderr.trim().replace(/^calder: --seed: /, 'seed: ');
  check(e !== null && message(e) === expected, `seed ${seed}: "${message(e)}"`);
}
{
  const e = thrown(() => new core.Simulation('example-2.77', {}));
  check(e !== null &&
        /^unknown scene 'example-2.77' \(did you mean 'example-2.7'\?\): not a built-in scene \(example-2.1, /.test(message(e)),
        `unknown scene: "${message(e).slice(0, 60)}..."`);
}

// --- views: zero-copy, and re-taken after the memory grows ---
{
  const small = new core.Simulation('example-2.7', {seed: 1});
  const x = small.view('x');
  check(x.length === 10 && x.buffer === core.HEAPF64.buffer, 'a view is a window on the module memory');
  const before = core.HEAPF64.buffer.byteLength;
  const big = new core.Simulation('rain', {count: 200000});
  const grew = core.HEAPF64.buffer.byteLength > before;
  check(grew && x.length === 0, 'a view taken before the memory grew is detached (never read stale)');
  const fresh = small.view('x');
  check(fresh.length === 10 && fresh.every(Number.isFinite), 'a fresh view reads the bodies');
  big.step(2);
  check(big.view('y').length === 200000 && big.bodyCount() === 200000, 'rain at 2 x 10^5 bodies');
  small.delete();
  big.delete();
}

// --- the HUD's energy error: what the native summary reports ---
{
  const sim = new core.Simulation('pythagorean', {});
  sim.step(100);
  const e = sim.energy();
  const run = nativeRun(['pythagorean', '--frames', '100']);
  const m = /^energy error\s+(\S+) \(relative, since frame 0\)$/m.exec(run.stdout);
  const native = m ? Number(m[1]) : NaN;
  check(e.exact && Number.isFinite(e.error) && e.error < 1e-9 && Math.abs(e.error - native) <= 1e-15,
        `pythagorean, 100 frames: the HUD's energy error ${e.error} (native summary ${native})`);
  sim.delete();
  const windy = new core.Simulation('example-2.1', {});
  windy.step(10);
  check(Number.isNaN(windy.energy().error), "example-2.1's wind changes the energy: no error shown");
  windy.delete();
}

done();
