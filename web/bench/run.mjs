// SPDX-License-Identifier: MIT
// The web benchmark (not a test): in one headless Chromium run, side by side,
//  - example 2.9 with N = 100, 1,000, 3,000 bodies: the book's p5.js sketch
//    against calder's page (the book's exact sequential update, and the
//    n-body method the page picks): drawn frames/s and pair interactions/s;
//  - rain at 10^4 and 10^5 bodies: physics steps/s and drawn frames/s in the
//    page, and native `calder run` on one core of the same machine (a ratio);
//  - the module without WebAssembly SIMD (-msimd128), with it in calder::bulk's
//    kernels (the page's build) and in every kernel file, physics only;
//  - the page's size, gzipped.
// Prints a Markdown report (docs/PERFORMANCE.md, "In the browser").
//
//   node web/bench/run.mjs [--write docs/PERFORMANCE.md]
//     (scripts/web --bench; the SIMD rows need build-web-plain and
//     build-web-simd, which it builds)
import {spawnSync} from 'node:child_process';
import {existsSync, mkdtempSync, readFileSync, writeFileSync} from 'node:fs';
import {cpus, loadavg, tmpdir} from 'node:os';
import {dirname, join, resolve} from 'node:path';
import {fileURLToPath} from 'node:url';
import {gzipSync} from 'node:zlib';

import {launch} from '../tests/chromium.mjs';
import {kNative, kRoot, kSite, loadCore} from '../tests/module.mjs';
import {serve} from '../tools/serve.mjs';

const here = dirname(fileURLToPath(import.meta.url));
const plainSite = resolve(process.env.CALDER_WEB_PLAIN_SITE || join(kRoot, 'build-web-plain/web/site'));
const simdSite = resolve(process.env.CALDER_WEB_SIMD_SITE || join(kRoot, 'build-web-simd/web/site'));
const kMeasureMs = 3000;
// Every page load compiles the module again: V8 runs it with its baseline
// compiler (Liftoff) first and moves the hot functions to its optimising one
// (TurboFan) in the background, which takes seconds on a busy machine. The
// measurements start after that.
const kWarmMs = 2500;

const mounts = {'/': kSite, '/bench/': here, '/p5/': join(kRoot, 'web/node_modules/p5/lib')};
if (existsSync(plainSite) && existsSync(simdSite)) {
  mounts['/plain/'] = plainSite;
  mounts['/simd/'] = simdSite;
}
const server = await serve(mounts);
const base = `http://127.0.0.1:${server.address().port}`;
const browser = await launch();
const page = await browser.newPage({viewport: {width: 1000, height: 700}, deviceScaleFactor: 1});
const errors = [];
page.on('pageerror', (e) => errors.push(e.message));

const load0 = loadavg()[0];
const fmt = (v, digits = 1) => (v >= 1e5 ? v.toExponential(2) : v.toFixed(digits));

async function calderPage(path) {
  await page.goto(`${base}/${path}`);
  await page.waitForSelector('body[data-ready=true]', {timeout: 30000});
}
// Drawn frames/s and physics steps/s of the running page, over kMeasureMs.
async function pageRates() {
  await page.waitForTimeout(kWarmMs);
  const a = await page.evaluate(() => ({t: performance.now(), frame: calder.frame(), draws: calderView.draws}));
  await page.waitForTimeout(kMeasureMs);
  const b = await page.evaluate(() => ({t: performance.now(), frame: calder.frame(), draws: calderView.draws}));
  const seconds = (b.t - a.t) / 1000;
  return {fps: (b.draws - a.draws) / seconds, steps: (b.frame - a.frame) / seconds};
}
// Physics only, in the page: calder.step in a loop (nothing drawn meanwhile),
// the best of short windows (the machine is shared: the best window is the
// one least disturbed, like the best of the native runs below).
async function physicsRate(prefix, scene, options) {
  await page.goto(`${base}${prefix}/?n=${options.count ?? ''}#${scene}`);
  await page.waitForSelector('body[data-ready=true]', {timeout: 30000});
  return page.evaluate(([scene, options, ms, warmMs]) => {
    calderView.stop();
    calder.load(scene, options);
    let t0 = performance.now();
    while (performance.now() - t0 < warmMs) calder.step(1);
    let best = 0;
    const start = performance.now();
    while (performance.now() - start < ms) {
      t0 = performance.now();
      let steps = 0;
      while (steps < 2 || performance.now() - t0 < 250) {
        calder.step(1);
        steps += 1;
      }
      best = Math.max(best, steps / ((performance.now() - t0) / 1000));
    }
    return best;
  }, [scene, options, kMeasureMs, kWarmMs]);
}
// Native `calder run` of the same scene text on one thread: steps/s
// from the difference of two runs (frames and 1), which cancels the setup.
const core = await loadCore();
function nativeRate(scene, options, frames) {
  const sim = new core.Simulation(scene, options);
  const text = sim.toml();
  sim.delete();
  const dir = mkdtempSync(join(tmpdir(), 'calder-bench-'));
  const file = join(dir, `${scene}.toml`);
  writeFileSync(file, text);
  const time = (n) => {
    const t0 = process.hrtime.bigint();
    const run = spawnSync(kNative, ['run', file, '--frames', String(n)],
                          {encoding: 'utf8', env: {...process.env, OMP_NUM_THREADS: '1'}});
    if (run.status !== 0) throw new Error(run.stderr);
    return Number(process.hrtime.bigint() - t0) / 1e9;
  };
  const best = (n) => Math.min(time(n), time(n), time(n));
  return (frames - 1) / (best(frames) - best(1));
}

const lines = [];
const out = (s = '') => {
  lines.push(s);
  console.log(s);
};
const results = {nbody: {}, rain: {}, simd: [], gzipKiB: 0};

// --- example 2.9: p5.js against the page ---
out('| example 2.9, N | p5.js fps | p5.js pairs/s | calder exact: fps | pairs/s | calder (method) fps | pairs/s | exact physics only, steps/s | native exact, steps/s |');
out('|---|---|---|---|---|---|---|---|---|');
for (const n of [100, 1000, 3000]) {
  await page.goto(`${base}/bench/p5-nbody.html?n=${n}`);
  await page.waitForFunction(() => window.benchFrames > 0, null, {timeout: 60000});
  await page.waitForTimeout(kWarmMs);
  const a = await page.evaluate(() => ({t: performance.now(), f: window.benchFrames}));
  await page.waitForTimeout(kMeasureMs);
  const b = await page.evaluate(() => ({t: performance.now(), f: window.benchFrames}));
  const p5fps = (b.f - a.f) / ((b.t - a.t) / 1000);
  const pairs = n * (n - 1);
  await calderPage(`?seed=0&n=${n}&method=exact#example-2.9`);
  const exact = await pageRates();
  await calderPage(`?seed=0&n=${n}#example-2.9`);
  const picked = await pageRates();
  const method = await page.evaluate(() => document.body.dataset.method);
  const physics = await physicsRate('', 'example-2.9', {seed: 0, count: n, method: 'exact'});
  const native = nativeRate('example-2.9', {seed: 0, count: n, method: 'exact'}, Math.max(20, Math.round(2e8 / pairs)));
  results.nbody[n] = {p5fps, exact, picked, method, physics, native};
  out(`| ${n} | ${fmt(p5fps)} | ${fmt(p5fps * pairs)} | ${fmt(exact.fps)} | ${fmt(exact.steps * pairs)} | ` +
      `${fmt(picked.fps)} (${method}) | ${fmt(picked.steps * pairs)} | ${fmt(physics)} | ${fmt(native)} (web/native ${fmt(native / physics, 2)}x time) |`);
}
out();

// --- rain: the page against native ---
out('| rain, bodies | page: drawn frames/s | page: steps/s | physics only in the page, steps/s | native, one thread, steps/s | wasm time / native time |');
out('|---|---|---|---|---|---|');
for (const n of [10000, 100000]) {
  await calderPage(`?seed=1&n=${n}#rain`);
  const rates = await pageRates();
  const physics = await physicsRate('', 'rain', {seed: 1, count: n});
  const native = nativeRate('rain', {seed: 1, count: n}, n >= 100000 ? 200 : 2000);
  results.rain[n] = {rates, physics, native};
  out(`| ${n} | ${fmt(rates.fps)} | ${fmt(rates.steps)} | ${fmt(physics)} | ${fmt(native)} | ${fmt(native / physics, 2)} |`);
}
out();

// --- WebAssembly SIMD ---
if (mounts['/simd/']) {
  out('| physics only, steps/s | no SIMD | SIMD in calder::bulk\'s kernels (the page) | SIMD in every kernel file | page / no SIMD | every kernel / page |');
  out('|---|---|---|---|---|---|');
  const cases = [
    ['rain, 10^4 bodies', 'rain', {seed: 1, count: 10000}],
    ['rain, 10^5 bodies', 'rain', {seed: 1, count: 100000}],
    ['example 2.9, 1,000 bodies, exact', 'example-2.9', {seed: 0, count: 1000, method: 'exact'}],
    ['example 2.9, 1,000 bodies, direct', 'example-2.9', {seed: 0, count: 1000, method: 'direct'}],
    ['example 2.9, 3,000 bodies, Barnes-Hut', 'example-2.9', {seed: 0, count: 3000, method: 'barnes_hut'}],
  ];
  for (const [label, scene, options] of cases) {
    const plain = await physicsRate('/plain', scene, options);
    const bulk = await physicsRate('', scene, options);
    const all = await physicsRate('/simd', scene, options);
    out(`| ${label} | ${fmt(plain)} | ${fmt(bulk)} | ${fmt(all)} | ${fmt(bulk / plain, 2)} | ${fmt(all / bulk, 2)} |`);
    results.simd.push({label, bulk: bulk / plain, all: all / bulk});
  }
  out();
}

// --- size ---
const files = ['calder-core.wasm', 'calder-core.js', 'calder.js', 'view.js', 'page.js', 'index.html', 'style.css'];
let raw = 0;
let gz = 0;
for (const f of files) {
  const bytes = readFileSync(join(kSite, f));
  raw += bytes.length;
  gz += gzipSync(bytes, {level: 9}).length;
}
results.gzipKiB = gz / 1024;
out(`The page's files (${files.join(', ')}): ${(raw / 1024).toFixed(0)} KiB, ` +
    `${(gz / 1024).toFixed(0)} KiB gzipped.`);
out();
out(`Chromium ${browser.version()} headless (software rendering), ${cpus().length} cores ` +
    `(${cpus()[0].model}); load average ${load0.toFixed(1)} at the start, ` +
    `${loadavg()[0].toFixed(1)} at the end.`);
if (errors.length) out(`page errors: ${errors.join('; ')}`);
out();

// --- the targets, from the figures above ---
const verdict = (ok) => (ok ? 'met' : 'not met');
const r5 = results.rain[100000];
const n1000 = results.nbody[1000];
out(`- rain with 10^5 bodies drawn at 30 frames/s or more: ${fmt(r5.rates.fps)} frames/s, ${verdict(r5.rates.fps >= 30)}.`);
out(`- example 2.9 with 1,000 bodies at 60 frames/s (the page's method, ${n1000.method}): ` +
    `${fmt(n1000.picked.fps)} frames/s, ${verdict(n1000.picked.fps >= 57)}; p5.js: ${fmt(n1000.p5fps)}.`);
for (const [label, r] of [['rain, 10^4', results.rain[10000]], ['rain, 10^5', r5],
                          ['example 2.9 exact, 1,000', n1000]]) {
  out(`- WebAssembly physics within 1.5x of native single-threaded time, ${label}: ` +
      `${fmt(r.native / r.physics, 2)}x, ${verdict(r.native / r.physics <= 1.5)}.`);
}
out(`- the page's files at most 500 KB gzipped: ${fmt(results.gzipKiB * 1.024, 0)} KB, ${verdict(results.gzipKiB * 1.024 <= 500)}.`);
if (results.simd.length) {
  const wins = (key) => results.simd.filter((s) => s[key] > 1.05).map((s) => s.label);
  const list = (labels) => (labels.length ? labels.join('; ') : 'none of the cases');
  out(`- SIMD in calder::bulk's kernels (the page's build) faster by more than 5% than no SIMD for ${list(wins('bulk'))}.`);
  out(`- SIMD in the n-body kernels too faster by more than 5% than the page's build for ${list(wins('all'))}.`);
}

// --write FILE: this report as the section "In the browser" of FILE (the last one).
const writeAt = process.argv.indexOf('--write');
if (writeAt > 0) {
  const file = resolve(process.argv[writeAt + 1]);
  const before = existsSync(file) ? readFileSync(file, 'utf8') : '';
  const at = before.indexOf('\n## In the browser\n');
  const head = (at >= 0 ? before.slice(0, at) : before).replace(/\n*$/, '\n');
  // What follows the section (the next "## " heading on) stays as it is.
  const next = at >= 0 ? before.indexOf('\n## ', at + 1) : -1;
  const tail = next >= 0 ? `\n${before.slice(next + 1)}` : '';
  const section = [
    '## In the browser',
    '',
    'calder\'s page (docs/WEB.md) in headless Chromium, side by side in one run with the',
    'book\'s example 2.9 written as a p5.js sketch (`web/bench/p5-nbody.js`, p5.js from npm)',
    'and with native `calder run` of the same scene text on one thread of the same machine.',
    'Frames/s are the page\'s drawn frames (the browser caps them at 60); pairs/s are',
    'N(N-1) per physics step (for Barnes-Hut, the pairs it stands for); "physics only"',
    'steps the module in a loop inside the page, nothing drawn. The machine is shared:',
    'compare figures within one run only (its load average is printed below the tables).',
    'Written by `scripts/web --bench` (`node web/bench/run.mjs --write',
    'docs/PERFORMANCE.md`), which replaces this section; `scripts/performance` keeps it.',
    'In the SIMD table, the example 2.9 rows of "page / no SIMD" run the same code (the',
    'page gives SIMD to calder::bulk\'s kernels only): their distance from 1 is this run\'s noise.',
    '',
    ...lines,
  ].join('\n');
  writeFileSync(file, `${head}\n${section}\n${tail}`);
  console.log(`wrote ${file}`);
}

await browser.close();
server.close();
