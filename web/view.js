// SPDX-License-Identifier: MIT
// CalderView: draws calder's running scene in a <canvas> the way `calder
// render` does (the look comes from the engine's book_style), and drives it
// with the mouse and the window's keys, as `calder window` does.
//
// Drawing: up to kPathBodies bodies, Canvas 2D paths (the book's circles,
// each its own fill and stroke up to kSingleBodies, one path above); more,
// discs stamped per pixel into an ImageData with 32-bit writes, which holds
// the frame rate where software-rasterised arcs don't (docs/PERFORMANCE.md).
(function (global) {
  'use strict';

  const kSingleBodies = 300;   // each body its own fill and stroke, as p5 draws them
  const kPathBodies = 500;     // above: per-pixel drawing
  const kVectorBodies = 2000;  // force and velocity arrows up to this many bodies
  const kPixelRadius = 3;      // per-pixel drawing of more than kSmallDiscs bodies: discs of at most this radius
  const kSmallDiscs = 30000;
  const kStepsPerSecond = 60;  // the sketches' frame rate

  const css = (c, alpha = 1) =>
    `rgba(${Math.round(c[0] * 255)},${Math.round(c[1] * 255)},${Math.round(c[2] * 255)},${c[3] * alpha})`;

  class CalderView {
    // options: hidpi (default true), keys (listen to the window's keys, default true),
    // autostart (default true).
    constructor(api, canvas, options = {}) {
      this.api = api;
      this.canvas = canvas;
      this.ctx = canvas.getContext('2d');
      this.hidpi = options.hidpi !== false;
      this.paused = false;
      this.speed = 1;
      this.showForces = false;
      this.showVelocity = false;
      this.trails = null;  // null: the scene's own
      this.renderer = 'auto';  // 'auto', 'canvas' or 'pixels'
      this.mouse = {x: 0, y: 0, down: false, pending: false};
      this.error = null;
      this.onError = options.onError || null;
      this.stats = {fps: 0, stepsPerSecond: 0, renderer: ''};
      this.stepBudget = 0;
      this.draws = 0;  // frames drawn so far
      this.fresh = true;
      this.times = [];
      this.stepTimes = [];
      this.discs = new Map();
      this.info = null;
      this.unsubscribe = api.onChange((what) => {
        if (what === 'load') this.sceneChanged();
      });
      this.listen(options.keys !== false);
      this.sceneChanged();
      if (options.autostart !== false) this.start();
    }

    sceneChanged() {
      try {
        this.info = this.api.info();
      } catch (e) {
        this.info = null;
        return;
      }
      this.error = null;
      this.fresh = true;
      this.resize();
    }

    resize() {
      if (!this.info) return;
      const dpr = this.hidpi ? global.devicePixelRatio || 1 : 1;
      this.dpr = dpr;
      this.canvas.width = Math.round(this.info.width * dpr);
      this.canvas.height = Math.round(this.info.height * dpr);
      this.canvas.style.width = `${this.info.width}px`;
      this.canvas.style.aspectRatio = `${this.info.width} / ${this.info.height}`;
      this.image = null;
      this.fresh = true;
    }

    // --- input ---
    toScene(event) {
      // The content box: the border is not the canvas.
      const c = this.canvas;
      const r = c.getBoundingClientRect();
      const sx = this.info.width / (c.clientWidth || 1);
      const sy = this.info.height / (c.clientHeight || 1);
      return {
        x: (event.clientX - r.left - c.clientLeft) * sx - this.info.originX,
        y: (event.clientY - r.top - c.clientTop) * sy - this.info.originY,
      };
    }

    listen(keys) {
      const c = this.canvas;
      this.handlers = {
        down: (e) => {
          if (e.button !== 0 || !this.info) return;
          Object.assign(this.mouse, this.toScene(e), {down: true, pending: true});
          e.preventDefault();
        },
        move: (e) => {
          if (this.info) Object.assign(this.mouse, this.toScene(e));
        },
        up: (e) => {
          if (e.button === 0) this.mouse.down = false;
        },
        key: (e) => this.key(e),
      };
      // Pointer events: the mouse, a pen or a finger alike.
      c.addEventListener('pointerdown', this.handlers.down);
      global.addEventListener('pointermove', this.handlers.move);
      global.addEventListener('pointerup', this.handlers.up);
      if (keys) global.addEventListener('keydown', this.handlers.key);
    }

    // The keys of `calder window`: space pause, . one frame, r restart,
    // f forces, t trails, + and - double and halve the speed (v: velocities).
    key(e) {
      const t = e.target;
      if (t && (t.tagName === 'TEXTAREA' || t.tagName === 'INPUT' || t.tagName === 'SELECT')) return;
      if (e.ctrlKey || e.metaKey || e.altKey) return;
      switch (e.key) {
        case ' ':
          this.paused = !this.paused;
          break;
        case '.':
          if (this.paused) this.stepFrames(1);
          break;
        case 'r':
          this.restart();
          break;
        case 'f':
          this.showForces = !this.showForces;
          break;
        case 'v':
          this.showVelocity = !this.showVelocity;
          break;
        case 't':
          this.trails = !(this.trails ?? (this.info && this.info.look.trails));
          this.fresh = true;
          break;
        case '+':
        case '=':
          this.speed = Math.min(this.speed * 2, 64);
          break;
        case '-':
          this.speed = Math.max(this.speed / 2, 1 / 16);
          break;
        default:
          return;
      }
      e.preventDefault();
      this.changed();
    }

    changed() {
      if (this.onChangeState) this.onChangeState(this);
    }

    restart() {
      try {
        this.api.restart();
        this.paused = false;
      } catch (e) {
        this.fail(e);
      }
    }

    fail(e) {
      this.error = e;
      this.paused = true;
      if (this.onError) this.onError(e);
      this.changed();
    }

    // --- the loop ---
    start() {
      if (this.running) return;
      this.running = true;
      const tick = (now) => {
        if (!this.running) return;
        this.frameAt(now);
        this.raf = global.requestAnimationFrame(tick);
      };
      this.raf = global.requestAnimationFrame(tick);
    }

    stop() {
      this.running = false;
      if (this.raf) global.cancelAnimationFrame(this.raf);
    }

    destroy() {
      this.stop();
      this.unsubscribe();
      this.canvas.removeEventListener('pointerdown', this.handlers.down);
      global.removeEventListener('pointermove', this.handlers.move);
      global.removeEventListener('pointerup', this.handlers.up);
      global.removeEventListener('keydown', this.handlers.key);
    }

    stepFrames(count) {
      if (!this.info || count <= 0) return;
      const input = {pressed: this.mouse.down || this.mouse.pending, x: this.mouse.x, y: this.mouse.y};
      try {
        if (this.mouse.pending) {
          // A click shorter than a frame still presses the mouse for one frame.
          this.api.step(1, input);
          input.pressed = this.mouse.down;
          count -= 1;
          this.mouse.pending = false;
        }
        if (count > 0) this.api.step(count, input);
      } catch (e) {
        this.fail(e);
      }
    }

    frameAt(now) {
      if (!this.info) return;
      const last = this.lastNow ?? now;
      this.lastNow = now;
      let steps = 0;
      if (!this.paused && !this.error) {
        // 60 frames of physics a second, times the speed; a machine that
        // can't keep up slows the scene down (as p5's draw() loop does)
        // rather than piling up steps.
        this.stepBudget += ((now - last) / 1000) * kStepsPerSecond * this.speed;
        if (this.times.length === 0) this.stepBudget = Math.max(this.stepBudget, 1);
        const most = Math.max(1, Math.ceil(this.speed));
        steps = Math.min(Math.floor(this.stepBudget), most);
        this.stepBudget = Math.min(this.stepBudget - steps, 1);
        this.stepFrames(steps);
      }
      this.draw();
      this.times.push(now);
      this.stepTimes.push([now, steps]);
      while (this.times.length > 0 && now - this.times[0] > 1000) this.times.shift();
      while (this.stepTimes.length > 0 && now - this.stepTimes[0][0] > 1000) this.stepTimes.shift();
      const span = this.times.length > 1 ? (now - this.times[0]) / 1000 : 0;
      this.stats.fps = span > 0 ? (this.times.length - 1) / span : 0;
      let stepped = 0;
      for (let i = 1; i < this.stepTimes.length; ++i) stepped += this.stepTimes[i][1];
      this.stats.stepsPerSecond = span > 0 ? stepped / span : 0;
      if (this.onFrame) this.onFrame(this);
    }

    // --- drawing ---
    draw() {
      if (!this.info) return;
      this.draws += 1;
      // Fields move (a dragged attractor, the fan at the mouse): describe them anew.
      const info = (this.info = this.api.info());
      const look = info.look;
      const ctx = this.ctx;
      const dpr = this.dpr;
      const b = this.api.bodies();  // fresh views: the last step may have moved the memory
      const trails = this.trails ?? look.trails;
      const pixels =
        this.renderer === 'pixels' || (this.renderer === 'auto' && b.count > kPathBodies);
      this.stats.renderer = pixels ? 'pixels' : 'canvas';
      ctx.setTransform(1, 0, 0, 1, 0, 0);
      if (pixels) {
        this.drawPixels(b, look, trails);
      } else {
        ctx.globalCompositeOperation = 'source-over';
        if (!trails || this.fresh) {
          ctx.fillStyle = css(look.background);
        } else {
          ctx.fillStyle = css(look.background, look.trailAlpha);
        }
        ctx.fillRect(0, 0, this.canvas.width, this.canvas.height);
      }
      this.fresh = false;
      ctx.setTransform(dpr, 0, 0, dpr, info.originX * dpr, info.originY * dpr);
      ctx.lineJoin = 'round';
      ctx.lineCap = 'round';
      if (pixels) {
        this.drawFields(info, look);  // over the bodies: few shapes, drawn as paths
      } else {
        this.drawFields(info, look);
        this.drawBodies(b, look);
      }
      if ((this.showForces || this.showVelocity) && b.count <= kVectorBodies) {
        this.drawVectors(info, look);
      }
      ctx.setTransform(dpr, 0, 0, dpr, 0, 0);
      if (this.showForces || this.showVelocity) this.drawLegend(info, look);
    }

    drawFields(info, look) {
      const ctx = this.ctx;
      for (const f of info.fields) {
        if (!f.visible || !f.enabled) continue;
        if (f.type === 'liquid') {
          ctx.fillStyle = css(look.liquidFill);
          ctx.fillRect(f.x, f.y, f.w, f.h);
        } else if (f.type === 'attractor') {
          ctx.beginPath();
          ctx.arc(f.x, f.y, (f.mass * look.attractorDiameterPerMass) / 2, 0, 2 * Math.PI);
          ctx.fillStyle = css(look.attractorFill);
          ctx.fill();
          ctx.lineWidth = look.attractorStrokeWeight;
          ctx.strokeStyle = css(look.attractorStroke);
          ctx.stroke();
        }
      }
    }

    drawBodies(b, look) {
      const ctx = this.ctx;
      const {x, y, radius, count} = b;
      ctx.fillStyle = css(look.bodyFill);
      ctx.strokeStyle = css(look.bodyStroke);
      ctx.lineWidth = look.bodyStrokeWeight;
      const shape = (i) => {
        const r = radius[i];
        if (r <= 0) {
          ctx.moveTo(x[i] + look.bodyStrokeWeight / 2, y[i]);
          ctx.arc(x[i], y[i], look.bodyStrokeWeight / 2, 0, 2 * Math.PI);
        } else if (look.squares) {
          ctx.rect(x[i] - r, y[i] - r, 2 * r, 2 * r);
        } else {
          ctx.moveTo(x[i] + r, y[i]);
          ctx.arc(x[i], y[i], r, 0, 2 * Math.PI);
        }
      };
      if (count <= kSingleBodies) {
        for (let i = 0; i < count; ++i) {
          ctx.beginPath();
          shape(i);
          if (radius[i] > 0) {
            ctx.fill();
            ctx.stroke();
          } else {
            ctx.fillStyle = css(look.bodyStroke);
            ctx.fill();
            ctx.fillStyle = css(look.bodyFill);
          }
        }
        return;
      }
      ctx.beginPath();
      for (let i = 0; i < count; ++i) shape(i);
      ctx.fill();
      ctx.stroke();
    }

    // A disc's pixels, inside first, then its rim (the stroke): offsets in
    // the image of the canvas's width, and dx, dy for the edges.
    disc(r) {
      const key = Math.max(1, Math.round(r * 2)) / 2;
      let d = this.discs.get(key);
      if (d && d.width === this.canvas.width) return d;
      const inside = [];
      const rim = [];
      const reach = Math.ceil(key);
      for (let dy = -reach; dy <= reach; ++dy) {
        for (let dx = -reach; dx <= reach; ++dx) {
          const dist = Math.hypot(dx, dy);
          if (dist > key) continue;
          (dist > key - 1.25 ? rim : inside).push([dx, dy]);
        }
      }
      const all = inside.concat(rim);
      const w = this.canvas.width;
      d = {
        width: w,
        reach,
        rimFrom: inside.length,
        offsets: Int32Array.from(all, ([dx, dy]) => dy * w + dx),
        dx: Int32Array.from(all, ([dx]) => dx),
        dy: Int32Array.from(all, ([, dy]) => dy),
      };
      this.discs.set(key, d);
      return d;
    }

    drawPixels(b, look, trails) {
      const w = this.canvas.width;
      const h = this.canvas.height;
      if (!this.image || this.image.width !== w || this.image.height !== h) {
        this.image = this.ctx.createImageData(w, h);
        this.pixels = new Uint32Array(this.image.data.buffer);
        this.fresh = true;
      }
      const px = this.pixels;
      const bytes = this.image.data;
      const bg = look.background.map((c) => Math.round(c * 255));
      const bgWord = (255 << 24) | (bg[2] << 16) | (bg[1] << 8) | bg[0];  // little-endian RGBA
      if (!trails || this.fresh) {
        px.fill(bgWord >>> 0);
      } else {
        const a = look.trailAlpha;
        for (let i = 0; i < bytes.length; i += 4) {
          bytes[i] += Math.round((bg[0] - bytes[i]) * a);
          bytes[i + 1] += Math.round((bg[1] - bytes[i + 1]) * a);
          bytes[i + 2] += Math.round((bg[2] - bytes[i + 2]) * a);
        }
      }
      // Solid 32-bit writes: the fill as it looks over the background (p5's
      // fill(127, 127) over white), the stroke at the rim. At these counts
      // bodies cover each other anyway; blending would cost 3x the time.
      const word = (c) =>
        ((255 << 24) | (Math.round(c[2] * 255) << 16) | (Math.round(c[1] * 255) << 8) |
         Math.round(c[0] * 255)) >>> 0;
      const fill = look.bodyFill;
      const over = (k) => fill[k] * fill[3] + look.background[k] * (1 - fill[3]);
      const fillWord = word([over(0), over(1), over(2)]);
      const strokeWord = word(look.bodyStroke);
      const dpr = this.dpr;
      const ox = this.info.originX;
      const oy = this.info.originY;
      const {x, y, radius, count} = b;
      const cap = count > kSmallDiscs ? kPixelRadius : Infinity;
      for (let i = 0; i < count; ++i) {
        const cx = Math.round((x[i] + ox) * dpr);
        const cy = Math.round((y[i] + oy) * dpr);
        const d = this.disc(Math.min(radius[i], cap) * dpr);
        if (cx < -d.reach || cy < -d.reach || cx >= w + d.reach || cy >= h + d.reach) continue;
        const inside = cx >= d.reach && cy >= d.reach && cx < w - d.reach && cy < h - d.reach;
        const centre = cy * w + cx;
        const offsets = d.offsets;
        const rimFrom = d.rimFrom;
        if (inside) {
          for (let k = 0; k < offsets.length; ++k) px[centre + offsets[k]] = k < rimFrom ? fillWord : strokeWord;
        } else {
          const dx = d.dx;
          const dy = d.dy;
          for (let k = 0; k < offsets.length; ++k) {
            const qx = cx + dx[k];
            const qy = cy + dy[k];
            if (qx >= 0 && qy >= 0 && qx < w && qy < h) px[qy * w + qx] = k < rimFrom ? fillWord : strokeWord;
          }
        }
      }
      this.ctx.putImageData(this.image, 0, 0);
    }

    arrow(x, y, dx, dy, width, maxLength) {
      const ctx = this.ctx;
      let length = Math.hypot(dx, dy);
      if (!(length > 0.5)) return;
      if (length > maxLength) {
        dx *= maxLength / length;
        dy *= maxLength / length;
        length = maxLength;
      }
      const head = Math.min(6, length / 3);
      const ux = dx / length;
      const uy = dy / length;
      ctx.lineWidth = width;
      ctx.beginPath();
      ctx.moveTo(x, y);
      ctx.lineTo(x + dx, y + dy);
      ctx.moveTo(x + dx - head * (ux - uy * 0.5), y + dy - head * (uy + ux * 0.5));
      ctx.lineTo(x + dx, y + dy);
      ctx.lineTo(x + dx - head * (ux + uy * 0.5), y + dy - head * (uy - ux * 0.5));
      ctx.stroke();
    }

    drawVectors(info, look) {
      const ctx = this.ctx;
      const maxLength = 4 * (info.width + info.height);
      const n = this.api.bodies().count;
      if (this.showForces) {
        const f = this.api.forces();
        const b = this.api.bodies();  // forces() may have grown the memory: fresh views
        const fields = info.fields.length;
        ctx.strokeStyle = css(look.netForceColor);
        for (let i = 0; i < n; ++i) {
          let fx = 0;
          let fy = 0;
          for (let k = 0; k < fields; ++k) {
            fx += f[2 * k * n + i];
            fy += f[2 * k * n + n + i];
          }
          this.arrow(b.x[i], b.y[i], fx * look.forceScale, fy * look.forceScale,
                     look.vectorWeight * 2, maxLength);
        }
        for (let k = 0; k < fields; ++k) {
          ctx.strokeStyle = css(look.fieldColors[k % look.fieldColors.length]);
          for (let i = 0; i < n; ++i) {
            this.arrow(b.x[i], b.y[i], f[2 * k * n + i] * look.forceScale,
                       f[2 * k * n + n + i] * look.forceScale, look.vectorWeight, maxLength);
          }
        }
      }
      if (this.showVelocity) {
        const b = this.api.bodies();
        ctx.strokeStyle = css(look.velocityColor);
        for (let i = 0; i < n; ++i) {
          this.arrow(b.x[i], b.y[i], b.vx[i] * look.velocityScale, b.vy[i] * look.velocityScale,
                     look.vectorWeight, maxLength);
        }
      }
    }

    // Which colour is which: the net force, each field, the velocity.
    legend() {
      const info = this.info;
      const look = info.look;
      const entries = [];
      if (this.showForces) {
        entries.push({label: 'net force', color: look.netForceColor});
        info.fields.forEach((f, k) =>
          entries.push({label: f.type, color: look.fieldColors[k % look.fieldColors.length]}));
      }
      if (this.showVelocity) entries.push({label: 'velocity', color: look.velocityColor});
      return entries;
    }

    drawLegend() {
      const ctx = this.ctx;
      const entries = this.legend();
      ctx.font = '11px sans-serif';
      ctx.textBaseline = 'middle';
      let width = 0;
      for (const e of entries) width = Math.max(width, ctx.measureText(e.label).width);
      ctx.fillStyle = 'rgba(255,255,255,0.8)';
      ctx.fillRect(6, 6, width + 32, entries.length * 15 + 6);
      entries.forEach((e, row) => {
        const y = 16 + row * 15;
        ctx.fillStyle = css(e.color);
        ctx.fillRect(12, y - 5, 12, 10);
        ctx.fillStyle = 'rgb(40,40,40)';
        ctx.fillText(e.label, 30, y);
      });
    }
  }

  global.CalderView = CalderView;
})(window);
