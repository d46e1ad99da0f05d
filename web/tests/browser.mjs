// SPDX-License-Identifier: MIT
// The page in headless Chromium (Debian's, through playwright-core), served
// from 127.0.0.1: real mouse and key events, the state the page prints
// against the WebAssembly module driven with the same input under node, the
// pixels of the screenshot, the editor's error messages against the native
// command's, bad URLs, and no console errors on any scene.
//
//   node tests/browser.mjs [--screenshot FILE]   (FILE: a PNG of the page, for the README)
import {spawnSync} from 'node:child_process';
import {mkdtempSync, readFileSync, writeFileSync} from 'node:fs';
import {tmpdir} from 'node:os';
import {join} from 'node:path';

import {serve} from '../tools/serve.mjs';
import {launch} from './chromium.mjs';
import {check, done, kNative, kRoot, kSite, loadCore} from './module.mjs';

const screenshotAt = process.argv.indexOf('--screenshot');
const screenshotFile = screenshotAt > 0 ? process.argv[screenshotAt + 1] : null;

const core = await loadCore();
const server = await serve(kSite);
const base = `http://127.0.0.1:${server.address().port}/`;
const browser = await launch();
const page = await browser.newPage({viewport: {width: 1000, height: 900}, deviceScaleFactor: 1,
                                    acceptDownloads: true});
const problems = [];
page.on('console', (m) => {
  if (m.type() === 'error' || m.type() === 'warning') problems.push(`${m.type()}: ${m.text()}`);
});
page.on('pageerror', (e) => problems.push(`page error: ${e.message}`));

async function open(path) {
  await page.goto(base + path);
  await page.waitForSelector('body[data-ready=true]', {timeout: 30000});
}
const hud = async (id) => (await page.textContent(`#hud-${id}`)).trim();
// Pauses the page's loop and starts the scene again at frame 0.
async function pausedAtStart() {
  await page.evaluate(() => {
    calderView.paused = true;
    calder.restart();
    calderView.paused = true;
  });
}
// The canvas's content box on the screen, and a point of the scene on it.
async function canvasBox() {
  return page.evaluate(() => {
    const c = document.getElementById('view');
    const r = c.getBoundingClientRect();
    return {left: r.left + c.clientLeft, top: r.top + c.clientTop, width: c.clientWidth};
  });
}
const onScreen = (box, x, y) => ({x: box.left + x, y: box.top + y});
async function frames(count) {
  for (let i = 0; i < count; ++i) await page.keyboard.press('.');
}

try {
  // --- example 2.7: drag the attractor with the mouse ---
  await open('?seed=1#example-2.7');
  check((await page.textContent('#description')).startsWith('example-2.7'), 'the URL chose example-2.7');
  await pausedAtStart();
  const box = await canvasBox();
  check(box.width === 640, `the canvas is 640 CSS pixels wide (got ${box.width})`);
  const from = {x: 320, y: 120};  // the attractor's centre
  const to = {x: 470, y: 80};
  let p = onScreen(box, from.x, from.y);
  await page.mouse.move(p.x, p.y);
  await page.mouse.down();
  await frames(1);  // the press grabs it
  p = onScreen(box, to.x, to.y);
  await page.mouse.move(p.x, p.y, {steps: 5});
  await frames(2);  // dragged
  await page.mouse.up();
  await frames(3);  // released
  const state = await page.evaluate(() => ({
    hash: calder.stateHash(),
    frame: calder.frame(),
    attractor: calder.info().fields[0],
  }));
  check(state.frame === 6, `six frames stepped with the . key (frame ${state.frame})`);
  check(state.attractor.x === to.x && state.attractor.y === to.y,
        `the attractor followed the mouse to (${state.attractor.x}, ${state.attractor.y})`);
  // The same input, given to the module under node.
  const sim = new core.Simulation('example-2.7', {seed: 1});
  sim.stepInput(1, true, from.x, from.y);
  sim.stepInput(2, true, to.x, to.y);
  sim.stepInput(3, false, to.x, to.y);
  check(state.hash === sim.stateHash(), `the page's state hash ${state.hash} is the module's`);
  sim.delete();
  await page.waitForFunction((h) => document.getElementById('hud-hash').textContent === h,
                             state.hash, {timeout: 5000});
  check((await hud('frame')) === '6' && (await hud('bodies')) === '10',
        'the HUD prints frame 6, 10 bodies and the state hash');
  // The screenshot: the attractor (fill(175, 200) over white: 192; stroke 4 px black,
  // diameter 40) is drawn where it was dragged to.
  const png = await page.locator('#view').screenshot();
  const pixels = await page.evaluate(async (bytes) => {
    const image = new Image();
    image.src = URL.createObjectURL(new Blob([new Uint8Array(bytes)], {type: 'image/png'}));
    await image.decode();
    const c = document.createElement('canvas');
    c.width = image.width;
    c.height = image.height;
    const ctx = c.getContext('2d', {willReadFrequently: true});
    ctx.drawImage(image, 0, 0);
    const at = (x, y) => Array.from(ctx.getImageData(x + 1, y + 1, 1, 1).data);  // + the border
    return {width: image.width, centre: at(470, 80 + 10), ring: [at(490, 80), at(450, 80), at(470, 100), at(470, 60)],
            old: at(320, 120 - 10)};
  }, Array.from(png));
  const gray = (c) => (c[0] + c[1] + c[2]) / 3;
  check(Math.abs(gray(pixels.centre) - 192) <= 12, `attractor fill at its new place (${pixels.centre})`);
  check(pixels.ring.filter((c) => gray(c) < 60).length >= 3, `its black ring, radius 20 (${pixels.ring.map(gray)})`);

  // --- example 2.1: hold the mouse, the wind blows ---
  await page.evaluate(() => (location.hash = '#example-2.1'));
  await page.waitForFunction(() => calder.info().name === 'example-2.1');
  await pausedAtStart();
  p = onScreen(await canvasBox(), 200, 100);
  await page.mouse.move(p.x, p.y);
  await page.mouse.down();
  await frames(30);
  await page.mouse.up();
  await frames(10);
  const wind = await page.evaluate(() => ({hash: calder.stateHash(), vx: calder.bodies().vx[0]}));
  const windSim = new core.Simulation('example-2.1', {});
  windSim.stepInput(30, true, 200, 100);
  windSim.stepInput(10, false, 200, 100);
  check(Math.abs(wind.vx - 3) < 1e-9, `30 frames of wind 0.1 on mass 1: vx = ${wind.vx}`);
  check(wind.hash === windSim.stateHash(), `held mouse: the page's hash is the module's (${wind.hash})`);
  windSim.delete();

  // --- the editor: a bad key, the command's message, the scene keeps running ---
  await page.evaluate(() => (calderView.paused = false));
  await page.click('#editor');
  await page.keyboard.press('Control+Home');
  await page.keyboard.type('colour = "red"\n');
  await page.click('#apply');
  const errorText = (await page.textContent('#editor-error')).trim();
  const editorText = await page.inputValue('#editor');
  const fileName = (await page.textContent('#file-name')).trim();
  const dir = mkdtempSync(join(tmpdir(), 'calder-web-'));
  writeFileSync(join(dir, fileName), editorText);
  const nativeMessage = spawnSync(kNative, ['run', fileName], {cwd: dir, encoding: 'utf8'})
                          .stderr.trim().replace(/^calder: /, '');
  check(errorText === nativeMessage && /:1:1: unknown key 'colour'/.test(errorText),
        `the editor shows the command's message: "${errorText}"`);
  check(await page.isVisible('#editor-error'), 'the message is shown in place');
  const f1 = await page.evaluate(() => calder.frame());
  await page.waitForTimeout(300);
  const f2 = await page.evaluate(() => ({frame: calder.frame(), name: calder.info().name}));
  check(f2.frame > f1 && f2.name === 'example-2.1', 'the previous scene keeps running');
  // A good edit applies.
  await page.fill('#editor', editorText.replace('colour = "red"\n', '').replace(/^frames = \d+$/m, 'frames = 50'));
  await page.click('#apply');
  check(!(await page.isVisible('#editor-error')), 'a good edit applies and clears the message');

  // --- the HUD's energy: bounded (calder::displayed_energy), "~" past its pairs ---
  {
    const small = await page.evaluate(() => calder.energy());
    check(small.exact === true &&
              small.total === (Number.isNaN(small.potential) ? small.kinetic : small.kinetic + small.potential),
          `a small scene's energy is exact (${JSON.stringify(small)})`);
    await page.fill('#editor', 'frames = 100000\n[[bodies]]\ncount = 3000\nmass = 1\n' +
                    'x = { min = 0, max = 640 }\ny = { min = 0, max = 360 }\n' +
                    '[[fields]]\ntype = "mutual_attraction"\nmethod = "barnes_hut"\n');
    await page.click('#apply');
    const big = await page.evaluate(() => {
      const t0 = performance.now();
      const e = calder.energy();
      return {...e, ms: performance.now() - t0};
    });
    check(big.exact === false && Number.isFinite(big.potential) && big.total === big.kinetic + big.potential,
          `3000 bodies (4.5e6 pairs): a sampled estimate (${JSON.stringify(big)})`);
    await page.waitForFunction(() => document.getElementById('hud-energy').textContent.startsWith('~'),
                               null, {timeout: 5000}).catch(() => {});
    const shown = await hud('energy');
    check(shown.startsWith('~'), `the HUD shows the estimate with a leading ~ ("${shown}")`);
    check(await page.isHidden('#hud-error-box'), 'and no energy error beside an estimate');
  }

  // --- a scene file from disk, and the edited one saved ---
  const fromDisk = readFileSync(join(kRoot, 'scenes/exercise-2.9.toml'));
  await page.setInputFiles('#file', {name: 'boxes.toml', mimeType: 'text/plain', buffer: fromDisk});
  await page.waitForFunction(() => calder.info().name === 'exercise-2.9');
  check((await page.textContent('#file-name')).trim() === 'boxes.toml' &&
        (await page.inputValue('#editor')) === fromDisk.toString(),
        `a .toml loaded from disk runs (${(await page.textContent('#file-name')).trim()}, ${(await page.inputValue('#editor')).length} vs ${fromDisk.length})`);
  await page.fill('#editor', fromDisk.toString().replace(/^frames = .*$/m, 'frames = 77'));
  const [download] = await Promise.all([page.waitForEvent('download'), page.click('#save')]);
  const saved = readFileSync(await download.path(), 'utf8');
  check(download.suggestedFilename() === 'boxes.toml' && /^frames = 77$/m.test(saved),
        'save downloads the edited text under its name');

  // --- the window's keys ---
  await page.locator('#view').focus();
  const keysBefore = await page.evaluate(() => ({speed: calderView.speed, paused: calderView.paused}));
  await page.keyboard.press('+');
  await page.keyboard.press('+');
  await page.keyboard.press('-');
  await page.keyboard.press('t');
  const keysAfter = await page.evaluate(() => ({speed: calderView.speed, trails: calderView.trails}));
  check(keysAfter.speed === keysBefore.speed * 2 && keysAfter.trails === true, '+ + - doubles the speed, t turns trails on');
  await page.keyboard.press(' ');
  const paused = await page.evaluate(() => calderView.paused);
  await page.keyboard.press(' ');
  await page.waitForFunction(() => calder.frame() > 20);
  await page.keyboard.press('r');
  const afterR = await page.evaluate(() => calder.frame());
  check(paused !== keysBefore.paused && afterR < 10, `space pauses, r restarts (frame ${afterR})`);

  // --- bad URLs: a message, and a scene still runs ---
  await open('#example-9.9');
  check((await page.textContent('#message')).startsWith("unknown scene 'example-9.9'"),
        'an unknown scene in the URL: a message');
  await page.waitForFunction(() => calder.frame() > 5);
  check(await page.evaluate(() => calder.info().name === 'example-2.7'), 'and the default scene runs');
  await open('?seed=-1#example-2.5');
  check((await page.textContent('#message')).includes('seed: expected an integer from 0 to 4294967295'),
        'a seed out of range: a message');
  await page.evaluate(() => (location.hash = '#example-2.5'));

  // --- a snapshot downloaded, then dropped on the page: it goes on bit for bit ---
  await open('?seed=42#exercise-2.7');
  await pausedAtStart();
  await frames(30);
  const [snapshotDownload] = await Promise.all([page.waitForEvent('download'),
                                                page.click('#snapshot')]);
  const snapshotBytes = readFileSync(await snapshotDownload.path());
  check(snapshotDownload.suggestedFilename() === 'exercise-2.7-30.snap' &&
            snapshotBytes.subarray(0, 8).toString() === 'CALDSNAP',
        `the snapshot button downloads exercise-2.7-30.snap (${snapshotDownload.suggestedFilename()})`);
  const goneOn = await page.evaluate(() => {
    calder.step(20);
    return calder.stateHash();
  });
  await open('?seed=7#example-2.1');
  await page.evaluate((bytes) => {
    // As it loads (before the page's loop steps it): its frame, and 20 scripted frames on.
    const stop = calder.onChange((what) => {
      if (what !== 'load') return;
      stop();
      window.dropped = {frame: calder.frame(), hash: (calder.step(20), calder.stateHash())};
    });
    const transfer = new DataTransfer();
    transfer.items.add(new File([new Uint8Array(bytes)], 'dropped.snap'));
    document.body.dispatchEvent(new DragEvent('drop', {dataTransfer: transfer, bubbles: true}));
  }, [...snapshotBytes]);
  await page.waitForFunction(() => window.dropped !== undefined);
  const dropped = await page.evaluate(() => window.dropped);
  check(dropped.frame === 30 && dropped.hash === goneOn,
        `a dropped snapshot goes on from frame ${dropped.frame} with the bits of the page's own run`);
  check((await page.textContent('#description')).startsWith('exercise-2.7'),
        "the dropped snapshot's scene is shown");

  // --- in the browser too, the native numbers: every scene, seed 1 ---
  {
    const names = await page.evaluate(() => calder.scenes().map((s) => s.name));
    const webHashes = await page.evaluate((list) => {
      calderView.paused = true;
      return list.map((name) => {
        calder.load(name, {seed: 1});
        calder.step(calder.info().frames);
        return calder.stateHash();
      });
    }, names);
    const differ = [];
    names.forEach((name, k) => {
      const run = spawnSync(kNative, ['run', name, '--seed', '1'], {encoding: 'utf8'});
      const native = /^state hash\s+([0-9a-f]{16})$/m.exec(run.stdout)[1];
      if (webHashes[k] !== native) differ.push(`${name} (${webHashes[k]} vs ${native})`);
    });
    check(differ.length === 0, `in Chromium, every scene --seed 1 has native's hash` +
          `${differ.length ? ': ' + differ.join(', ') : ''}`);
  }

  // --- every scene, forces and velocities shown, without a console error ---
  await open('?seed=1#example-2.1');
  const names = await page.evaluate(() => calder.scenes().map((s) => s.name));
  for (const name of names) {
    await page.evaluate((n) => (location.hash = '#' + n), name);
    await page.waitForFunction((n) => calder.info().name === n, name);
    await page.waitForTimeout(150);
    await page.keyboard.press('f');
    await page.keyboard.press('v');
    await page.waitForTimeout(150);
    await page.keyboard.press('f');
    await page.keyboard.press('v');
  }
  await open('?n=100000#rain');
  await page.waitForTimeout(1500);
  check(await page.evaluate(() => calder.bodies().count === 100000 && calderView.stats.renderer === 'pixels'),
        'rain with 10^5 bodies, drawn per pixel');
  check(problems.length === 0, `no console errors or warnings on any scene${problems.length ? ': ' + problems.join('; ') : ''}`);

  if (screenshotFile) {
    await open('?seed=1#example-2.5');
    await page.keyboard.press('f');
    await page.keyboard.press('v');
    await page.waitForFunction(() => calder.frame() >= 75);
    await page.keyboard.press(' ');
    await page.screenshot({path: screenshotFile, clip: {x: 0, y: 0, width: 1000, height: 560}});
    console.log(`wrote ${screenshotFile}`);
  }
} finally {
  await browser.close();
  server.close();
}
done();
