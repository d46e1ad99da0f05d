// SPDX-License-Identifier: MIT
// calder in the browser: the JavaScript API (docs/WEB.md).
//
//   await calder.ready;
//   calder.scenes();                          // [{name, description}, ...] from the engine
//   calder.load('example-2.7', {seed: 1});    // or scene text (TOML); throws Error on bad input
//   calder.step(600);                         // the scene's scripted input, as `calder run`
//   calder.step(1, {pressed: true, x: 320, y: 120});  // or live input, physics coordinates
//   calder.stateHash();                       // '6acf9870d534dba4', as `calder run` prints it
//   calder.bodies();                          // {count, x, y, vx, vy, mass, radius}: views
//   const view = calder.mount(canvas);        // draw and interact in the caller's <canvas>
//
// The body arrays are zero-copy views of the WebAssembly memory: good until
// the next call that can reallocate (load, step, reset, memory growth), so
// calder.bodies() and the view take fresh ones every time and never keep them.
(function (global) {
  'use strict';

  const script = document.currentScript;
  const base = new URL('.', script ? script.src : global.location.href);

  let core = null;
  let sim = null;
  let loaded = {source: null, options: {}};
  const listeners = new Set();

  // What the module throws is the C++ message (a string): make it an Error.
  function guard(f) {
    try {
      return f();
    } catch (e) {
      throw typeof e === 'string' ? new Error(e) : e;
    }
  }
  function need() {
    if (!core) throw new Error('calder: not ready yet (await calder.ready)');
    if (!sim) throw new Error('calder: no scene loaded (calder.load)');
    return sim;
  }

  const ready = new Promise((resolve, reject) => {
    const tag = document.createElement('script');
    tag.src = new URL('calder-core.js', base).href;
    tag.onload = () =>
      global
        .createCalderCore({locateFile: (file) => new URL(file, base).href})
        .then((module) => {
          core = module;
          resolve(api);
        }, reject);
    tag.onerror = () => reject(new Error('calder: could not load calder-core.js'));
    document.head.appendChild(tag);
  });

  // "A-B" or "A" (or [A, B]) frame ranges, as `calder run --mouse-pressed` takes them.
  function frameRanges(value) {
    const list = Array.isArray(value) && !Array.isArray(value[0]) && typeof value[0] !== 'string'
      ? [value] : [].concat(value);
    return list.map((item) => {
      if (Array.isArray(item)) return item.map(Number);
      const m = /^\s*(\d+)\s*(?:-\s*(\d+))?\s*$/.exec(String(item));
      if (!m) throw new Error(`mousePressed: expected A-B or A (frames), got '${item}'`);
      return [Number(m[1]), Number(m[2] ?? m[1])];
    });
  }

  const api = {
    ready,
    // The built-in scenes, in the book's order, from the engine.
    scenes() {
      if (!core) throw new Error('calder: not ready yet (await calder.ready)');
      return core.scenes();
    },
    // The instruction sets of the module's kernels: {bulk, nbody}.
    kernels() {
      if (!core) throw new Error('calder: not ready yet (await calder.ready)');
      return core.kernels();
    },
    // Starts a scene: a built-in name or scene text. options: seed (0..2^32-1),
    // count (bodies of the scenes made to scale), name (the file named in
    // error messages), mousePressed ('100-160' or [[100, 160], ...]), mouse
    // ([x, y]). On error it throws, and the scene that ran before keeps running.
    // A snapshot's bytes (an ArrayBuffer or a Uint8Array, from snapshot() or
    // `calder run --save`) go on from the frame where it was saved.
    load(source, options = {}) {
      if (!core) throw new Error('calder: not ready yet (await calder.ready)');
      const passed = {...options};
      if (source instanceof ArrayBuffer) source = new Uint8Array(source);
      if (source instanceof Uint8Array) {
        passed.snapshot = source;
        source = '';
      }
      if (passed.mousePressed !== undefined) passed.mousePressed = frameRanges(passed.mousePressed);
      const next = guard(() => new core.Simulation(String(source), passed));
      if (sim) sim.delete();
      sim = next;
      loaded = {source: passed.snapshot ?? String(source), options: {...options}};
      for (const f of listeners) f('load');
      return api.info();
    },
    // Starts the loaded scene again from its first frame.
    restart() {
      need();
      return api.load(loaded.source, loaded.options);
    },
    // n frames: with the scene's scripted input (as `calder run`), or with
    // input = {pressed, x, y} (physics coordinates) for every one of them.
    step(n = 1, input = undefined) {
      const s = need();
      const count = Math.floor(Number(n));
      if (!(count >= 0)) throw new Error(`step: expected a number of frames >= 0, got '${n}'`);
      if (input === undefined || input === null) {
        guard(() => s.step(count));
      } else {
        guard(() => s.stepInput(count, !!input.pressed, Number(input.x) || 0, Number(input.y) || 0));
      }
      for (const f of listeners) f('step');
      return s.frame();
    },
    // The book's reset(): new bodies from the scene's generator.
    resetBodies() {
      guard(() => need().resetBodies());
      for (const f of listeners) f('step');
    },
    stateHash: () => need().stateHash(),
    frame: () => need().frame(),
    // {kinetic, potential (NaN where the fields have none), total, exact,
    // error}: the HUD's energy, bounded per call (calder::displayed_energy);
    // exact false where the potential is a sampled estimate; error the
    // relative energy error since the start, NaN where it isn't measured.
    energy: () => need().energy(),
    // Fresh zero-copy views of the bodies' arrays (Float64Array).
    bodies() {
      const s = need();
      return {
        count: s.bodyCount(),
        x: s.view('x'),
        y: s.view('y'),
        vx: s.view('vx'),
        vy: s.view('vy'),
        mass: s.view('mass'),
        radius: s.view('radius'),
      };
    },
    // Each field's force on each body, field-major: [k * 2n + i] is fx, [k * 2n + n + i] fy.
    forces: () => guard(() => need().forces()),
    // Canvas, origin, the look of `calder render`, the fields and their bindings.
    info: () => need().describe(),
    // The running scene as scene text.
    toml: () => guard(() => need().toml()),
    // A snapshot of the run (docs/SNAPSHOTS.md): load(bytes) goes on from it bit for bit.
    snapshot: () => guard(() => need().snapshot()),
    // What was loaded last: {source, options}.
    loaded: () => ({source: loaded.source, options: {...loaded.options}}),
    onChange(f) {
      listeners.add(f);
      return () => listeners.delete(f);
    },
    // Draws the running scene in the caller's <canvas> and gives it the book's
    // mouse interactions; see CalderView in view.js.
    mount(canvas, options = {}) {
      return new global.CalderView(api, canvas, options);
    },
  };

  global.calder = api;
})(window);
