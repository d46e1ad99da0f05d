// SPDX-License-Identifier: MIT
// The page: the scene menu and the URL (#example-2.7?seed=1&n=10000 or
// ?seed=1#example-2.7), the HUD, the controls and the scene editor, around
// calder.js (the engine) and view.js (drawing and the mouse).
(function () {
  'use strict';

  const $ = (id) => document.getElementById(id);
  const kDefaultScene = 'example-2.7';
  // The scenes made to scale, and the sizes offered (the first is the scene's own size).
  const kSizes = {
    'rain': [1000, 10000, 30000, 100000],
    'exercise-2.16': [100, 300, 1000, 3000],
    'example-2.9': [10, 100, 1000, 3000],
  };

  // The n-body method "auto" picks: the book's exact sum while it holds 60
  // frames per second, then all pairs vectorised, then Barnes-Hut
  // (docs/PERFORMANCE.md, "In the browser").
  const kNBodyScenes = ['example-2.9', 'exercise-2.16'];
  function autoMethod(count) {
    if (count === null || count <= 300) return null;
    return count <= 600 ? 'direct' : 'barnes_hut';
  }

  let view = null;
  let fileName = 'scene.toml';
  let current = {scene: null, seed: null, count: null, method: null};

  function showMessage(text) {
    const box = $('message');
    box.textContent = text || '';
    box.hidden = !text;
  }

  // #scene, then ?seed= and ?n= from either the query or the hash's own query.
  function fromUrl() {
    const hash = decodeURIComponent(location.hash.replace(/^#/, ''));
    const [scene, hashQuery] = hash.split('?');
    const params = new URLSearchParams(location.search);
    for (const [k, v] of new URLSearchParams(hashQuery || '')) params.set(k, v);
    return {scene: scene || kDefaultScene, seed: params.get('seed'), count: params.get('n'),
            method: params.get('method')};
  }

  function toUrl(want) {
    const params = new URLSearchParams();
    if (want.seed !== null && want.seed !== '') params.set('seed', want.seed);
    if (want.count !== null && want.count !== '') params.set('n', want.count);
    if (want.method && want.method !== 'auto') params.set('method', want.method);
    const query = params.toString();
    history.replaceState(null, '', `${location.pathname}${query ? '?' + query : ''}#${want.scene}`);
  }

  // Loads a built-in scene; on bad input the message is shown and the scene
  // that ran before keeps running.
  function start(want) {
    const options = {};
    if (want.seed !== null && want.seed !== '') options.seed = /^\d+$/.test(want.seed) ? Number(want.seed) : want.seed;
    if (want.count !== null && want.count !== '') {
      if (!kSizes[want.scene]) {
        showMessage(`n: the scene '${want.scene}' is not made to scale (those that are: ${Object.keys(kSizes).join(', ')})`);
        return false;
      }
      options.count = Number(want.count);
    }
    const method = want.method && want.method !== 'auto' ? want.method
                   : autoMethod(options.count ?? null);
    if (method) options.method = method;
    try {
      calder.load(want.scene, options);
    } catch (e) {
      showMessage(e.message);
      syncControls();
      return false;
    }
    showMessage('');
    current = {...want};
    document.body.dataset.method = method || 'exact';
    fileName = `${want.scene}.toml`;
    afterLoad();
    return true;
  }

  function afterLoad() {
    const info = calder.info();
    $('description').textContent = `${info.name}: ${info.description}`;
    $('editor').value = calder.toml();
    $('file-name').textContent = fileName;
    $('editor-error').hidden = true;
    if (view) view.paused = false;
    syncControls();
  }

  function syncControls() {
    if (current.scene && $('scene').value !== current.scene) $('scene').value = current.scene;
    $('seed').value = current.seed ?? '';
    const sizes = kSizes[current.scene];
    $('size-label').hidden = !sizes;
    const size = $('size');
    size.textContent = '';
    if (sizes) {
      for (const n of sizes) size.add(new Option(n.toLocaleString('en'), String(n)));
      const count = current.count ?? String(sizes[0]);
      if (!sizes.includes(Number(count))) size.add(new Option(Number(count).toLocaleString('en'), count));
      size.value = count;
    }
    $('method-label').hidden = !kNBodyScenes.includes(current.scene);
    $('method').value = current.method || 'auto';
    if (!view) return;
    $('pause').textContent = view.paused ? 'run' : 'pause';
    $('forces').checked = view.showForces;
    $('velocity').checked = view.showVelocity;
    $('trails').checked = view.trails ?? (view.info ? view.info.look.trails : false);
    $('speed').textContent = `speed ${view.speed >= 1 ? view.speed : '1/' + 1 / view.speed}x`;
    $('renderer').value = view.renderer;
  }

  function formatNumber(v) {
    if (!Number.isFinite(v)) return String(v);
    return Math.abs(v) >= 1e5 || (Math.abs(v) < 1e-3 && v !== 0) ? v.toExponential(4) : v.toFixed(4);
  }

  let hudAt = 0;
  function hud(v, force) {
    const now = performance.now();
    if (!force && now - hudAt < 250) return;
    hudAt = now;
    try {
      $('hud-frame').textContent = String(calder.frame());
      $('hud-bodies').textContent = String(calder.bodies().count);
      const energy = calder.energy();  // bounded: a sampled estimate past its pairs
      $('hud-energy').textContent = (energy.exact ? '' : '~') + formatNumber(energy.total);
      $('hud-error-box').hidden = !Number.isFinite(energy.error);
      $('hud-error').textContent = formatNumber(energy.error);
      $('hud-hash').textContent = calder.stateHash();
    } catch (e) {
      return;
    }
    $('hud-fps').textContent = v.stats.fps.toFixed(1);
    $('hud-steps').textContent = v.stats.stepsPerSecond.toFixed(0);
    $('hud-renderer').textContent = v.stats.renderer;
  }

  function applyEditor() {
    const box = $('editor-error');
    try {
      calder.load($('editor').value, {name: fileName});
    } catch (e) {
      box.textContent = e.message;
      box.hidden = false;
      return;
    }
    box.hidden = true;
    showMessage('');
    const info = calder.info();
    $('description').textContent = `${info.name}: ${info.description}`;
    if (view) view.paused = false;
    syncControls();
  }

  function wire() {
    $('scene').addEventListener('change', () => {
      const want = {scene: $('scene').value, seed: current.seed, count: null, method: null};
      if (start(want)) toUrl(want);
    });
    $('seed').addEventListener('change', () => {
      const want = {...current, seed: $('seed').value.trim()};
      if (start(want)) toUrl(want);
    });
    $('size').addEventListener('change', () => {
      const want = {...current, count: $('size').value};
      if (start(want)) toUrl(want);
    });
    $('method').addEventListener('change', () => {
      const want = {...current, method: $('method').value};
      if (start(want)) toUrl(want);
    });
    window.addEventListener('hashchange', () => {
      const want = fromUrl();
      if (start(want)) toUrl(want);
    });
    $('renderer').addEventListener('change', () => {
      view.renderer = $('renderer').value;
      view.fresh = true;
    });
    $('pause').addEventListener('click', () => {
      view.paused = !view.paused;
      syncControls();
    });
    $('next').addEventListener('click', () => {
      view.paused = true;
      view.stepFrames(1);
      syncControls();
    });
    $('restart').addEventListener('click', () => view.restart());
    $('forces').addEventListener('change', () => (view.showForces = $('forces').checked));
    $('velocity').addEventListener('change', () => (view.showVelocity = $('velocity').checked));
    $('trails').addEventListener('change', () => {
      view.trails = $('trails').checked;
      view.fresh = true;
    });
    $('apply').addEventListener('click', applyEditor);
    $('editor').addEventListener('keydown', (e) => {
      if (e.key === 'Enter' && (e.ctrlKey || e.metaKey)) applyEditor();
    });
    $('file').addEventListener('change', async () => {
      const file = $('file').files[0];
      if (!file) return;
      fileName = file.name;
      $('file-name').textContent = fileName;
      $('editor').value = await file.text();
      $('file').value = '';
      applyEditor();
    });
    $('save').addEventListener('click', () => download($('editor').value, fileName, 'application/toml'));
    // A snapshot (docs/SNAPSHOTS.md) downloads; one dropped on the page goes on from its frame.
    $('snapshot').addEventListener('click', () => {
      const name = `${fileName.replace(/\.toml$/, '')}-${calder.frame()}.snap`;
      download(calder.snapshot(), name, 'application/octet-stream');
    });
    document.addEventListener('dragover', (e) => e.preventDefault());
    document.addEventListener('drop', async (e) => {
      e.preventDefault();
      const file = e.dataTransfer && e.dataTransfer.files[0];
      if (file) openDropped(file);
    });
  }

  function download(data, name, type) {
    const link = document.createElement('a');
    link.href = URL.createObjectURL(new Blob([data], {type}));
    link.download = name;
    link.click();
    setTimeout(() => URL.revokeObjectURL(link.href), 1000);
  }

  // A dropped snapshot runs on from where it was saved; a scene file goes to the editor.
  async function openDropped(file) {
    const bytes = new Uint8Array(await file.arrayBuffer());
    if (new TextDecoder().decode(bytes.subarray(0, 8)) !== 'CALDSNAP') {
      fileName = file.name;
      $('file-name').textContent = fileName;
      $('editor').value = new TextDecoder().decode(bytes);
      applyEditor();
      return;
    }
    try {
      calder.load(bytes, {name: file.name});
    } catch (err) {
      showMessage(err.message);
      return;
    }
    showMessage('');
    fileName = `${calder.info().name}.toml`;
    afterLoad();
  }

  async function main() {
    try {
      await calder.ready;
    } catch (e) {
      showMessage(`calder could not start: ${e.message || e}`);
      return;
    }
    const menu = $('scene');
    for (const s of calder.scenes()) menu.add(new Option(`${s.name}: ${s.description}`, s.name));
    wire();
    const want = fromUrl();
    if (!start(want)) {
      // Never a blank page: the message stays, and the default scene runs.
      const message = $('message').textContent;
      start({scene: kDefaultScene, seed: null, count: null, method: null});
      showMessage(message);
    }
    view = calder.mount($('view'), {
      onError: (e) => showMessage(`${e.message} (paused; r restarts)`),
    });
    view.onFrame = (v) => hud(v, false);
    view.onChangeState = () => {
      syncControls();
      hud(view, true);
    };
    syncControls();
    window.calderView = view;  // for automation: the page's CalderView
    document.body.dataset.ready = 'true';
  }

  main();
})();
