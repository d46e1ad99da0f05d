// SPDX-License-Identifier: MIT
// Snapshots in the WebAssembly module: for every built-in scene and seeds 0,
// 1 and 42, N frames, snapshot, load, M more frames give the hash of N + M
// frames straight; a snapshot saved by the native command (`calder run
// --save`) loads in the module at the same state, and one saved by the module
// goes on in the native command; a corrupted one is refused with one line.
import {spawnSync} from 'node:child_process';
import {mkdtempSync, readFileSync, writeFileSync} from 'node:fs';
import {tmpdir} from 'node:os';
import {join} from 'node:path';

import {check, done, kNative, loadCore} from './module.mjs';

const core = await loadCore();
const work = mkdtempSync(join(tmpdir(), 'calder-snapshot-'));
const kN = 40;
const kM = 30;

function nativeRun(args) {
  const run = spawnSync(kNative, ['run', ...args], {encoding: 'utf8'});
  const m = /^state hash\s+([0-9a-f]{16})$/m.exec(run.stdout);
  if (run.status !== 0 || !m) throw new Error(`calder run ${args.join(' ')}: ${run.stderr}`);
  return m[1];
}

for (const {name} of core.scenes()) {
  for (const seed of [0, 1, 42]) {
    const straight = new core.Simulation(name, {seed});
    straight.step(kN + kM);
    const first = new core.Simulation(name, {seed});
    first.step(kN);
    const bytes = first.snapshot();
    const resumed = new core.Simulation('', {snapshot: bytes});
    check(resumed.frame() === kN, `${name} --seed ${seed}: loaded at frame ${kN}`);
    resumed.step(kM);
    check(resumed.stateHash() === straight.stateHash(),
          `${name} --seed ${seed}: ${kN} frames, snapshot, ${kM} more = ${kN + kM} straight`);

    // Across: native saves, the module loads; the module saves, native goes on.
    const nativeFile = join(work, `${name}-${seed}-native.snap`);
    const atSave = nativeRun([name, '--seed', String(seed), '--frames', String(kN),
                              '--save', nativeFile]);
    const fromNative = new core.Simulation('', {snapshot: new Uint8Array(readFileSync(nativeFile))});
    check(fromNative.stateHash() === atSave,
          `${name} --seed ${seed}: native's snapshot loads at native's state`);
    const webFile = join(work, `${name}-${seed}-web.snap`);
    writeFileSync(webFile, bytes);
    const nativeOn = nativeRun([webFile, '--frames', String(kN + kM)]);
    fromNative.step(kM);
    check(fromNative.stateHash() === nativeRun([name, '--seed', String(seed), '--frames',
                                                String(kN + kM)]),
          `${name} --seed ${seed}: native's snapshot goes on in the module as natively`);
    check(nativeOn === straight.stateHash(),
          `${name} --seed ${seed}: the module's snapshot goes on natively as in the module`);
    for (const s of [straight, first, resumed, fromNative]) s.delete();
  }
}

// A flipped byte: one line naming the snapshot and the section.
{
  const sim = new core.Simulation('example-2.1', {});
  const bytes = sim.snapshot();
  bytes[bytes.length - 12] ^= 0x40;
  let message = null;
  try {
    new core.Simulation('', {snapshot: bytes, name: 'dropped.snap'});
  } catch (e) {
    message = typeof e === 'string' ? e : e && e.message;
  }
  check(message !== null && message.startsWith('dropped.snap: ') && message.includes('checksum') &&
            !message.includes('\n'),
        `a corrupted snapshot is refused: ${message}`);
  sim.delete();
}

done();
