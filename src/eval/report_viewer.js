// The report's image viewer: plain JavaScript, no network. It reads the JSON in
// #viewer-data: per method (the reference first) one tone-mapped PNG per frame, per method a
// FLIP map against the reference as an 8-bit grey PNG, the error views' opening scales and the
// frame rate to play at (viewer_frames.cpp).
(function () {
  'use strict';
  const data = JSON.parse(document.getElementById('viewer-data').textContent);
  const $ = (id) => document.getElementById(id);
  const canvas = $('v-canvas'), ctx = canvas.getContext('2d');
  const W = data.width, H = data.height;
  const buffer = document.createElement('canvas');
  buffer.width = W;
  buffer.height = H;
  const bctx = buffer.getContext('2d');
  const cache = new Map();
  // A starts on the first method that is not the noisy input, B on the reference.
  const firstDenoised = data.methods.findIndex((m, i) => i > 0 && m !== 'noisy');
  // Each error view opens at its own scale, from the data: at the frame the viewer opens on, the
  // 99th percentile of the best non-noisy method's error against the reference maps to full
  // brightness. A fixed scale (0.5) showed a good denoiser's error, a few hundredths, as black.
  // The scale slider still sets it, for the error view shown last.
  const scales = data.errorScale || {};
  const state = {frame: Math.max(0, data.frames.indexOf(data.shown)), a: firstDenoised > 0 ? firstDenoised : Math.min(1, data.methods.length - 1), b: 0, mode: 'a', ev: 0,
                 vmax: {abs: scales.abs || 0.5, rel: scales.rel || 0.5, flip: scales.flip || 0.5},
                 errorMode: 'abs', playing: false, zoom: 1, ox: 0, oy: 0, split: 0.5, fitted: true};
  const modes = {a: 'A', b: 'B', slider: 'slider', abs: 'absolute error',
                 rel: 'relative error', flip: 'FLIP error'};

  function decoded(kind, m, f) {
    const key = kind + ':' + m + ':' + f;
    if (cache.has(key)) return cache.get(key);
    const src = (kind === 'img' ? data.images : data.flip)[m][f];
    const p = new Promise((resolve, reject) => {
      if (!src) return resolve(null);
      const img = new Image();
      img.onload = () => {
        const c = document.createElement('canvas');
        c.width = W;
        c.height = H;
        const g = c.getContext('2d');
        g.drawImage(img, 0, 0, W, H);
        resolve(g.getImageData(0, 0, W, H).data);
      };
      img.onerror = () => reject(new Error('cannot decode ' + kind + ' of ' + data.methods[m]));
      img.src = src;
    });
    cache.set(key, p);
    return p;
  }

  // Display transform: the PNGs hold clamp(x^(1/2.2)); exposure scales the linear x by 2^EV.
  function exposureLut(ev) {
    const lut = new Uint8ClampedArray(256), k = Math.pow(2, ev);
    for (let v = 0; v < 256; ++v)
      lut[v] = Math.round(255 * Math.min(1, Math.pow(Math.pow(v / 255, 2.2) * k, 1 / 2.2)));
    return lut;
  }
  const linear = new Float32Array(256);
  for (let v = 0; v < 256; ++v) linear[v] = Math.pow(v / 255, 2.2);

  function magma(t) {
    const s = data.magma, x = Math.max(0, Math.min(1, t)) * (s.length - 1);
    const k = Math.min(s.length - 2, Math.floor(x)), f = x - k;
    return [0, 1, 2].map((c) => s[k][c] + f * (s[k + 1][c] - s[k][c]));
  }

  function drawBar() {
    const bar = $('v-bar'), g = bar.getContext('2d');
    const error = state.mode === 'abs' || state.mode === 'rel' || state.mode === 'flip';
    $('v-bar-box').style.visibility = error ? 'visible' : 'hidden';
    if (!error) return;
    for (let x = 0; x < bar.width; ++x) {
      const c = magma(x / (bar.width - 1));
      g.fillStyle = 'rgb(' + c.map(Math.round).join(',') + ')';
      g.fillRect(x, 0, 1, bar.height);
    }
    $('v-bar-lo').textContent = '0';
    const vmax = state.vmax[state.mode];
    $('v-bar-mid').textContent = (vmax / 2).toPrecision(2);
    $('v-bar-hi').textContent = vmax.toPrecision(2) + ' and above';
    $('v-bar-what').textContent = {abs: '|A - B| of displayed values, mean of RGB',
      rel: '|A - B| / (B + 0.01) of the decoded linear values (display range: clipped at 1), mean of RGB',
      flip: 'FLIP of A against the reference'}[state.mode];
  }

  async function compose() {
    const f = state.frame, mode = state.mode;
    const [a, b, fl] = await Promise.all([decoded('img', state.a, f), decoded('img', state.b, f),
      mode === 'flip' ? decoded('flip', state.a, f) : Promise.resolve(null)]);
    const out = bctx.createImageData(W, H), o = out.data;
    const lut = exposureLut(state.ev), inv = 1 / (state.vmax[mode] || 1);
    const splitX = Math.round(state.split * W);
    for (let i = 0, p = 0; p < W * H; ++p, i += 4) {
      let r, g, bl;
      if (mode === 'a' || mode === 'b' || mode === 'slider') {
        const src = mode === 'a' || (mode === 'slider' && p % W < splitX) ? a : b;
        r = lut[src[i]]; g = lut[src[i + 1]]; bl = lut[src[i + 2]];
      } else {
        let e = 0;
        if (mode === 'abs') {
          for (let c = 0; c < 3; ++c) e += Math.abs(a[i + c] - b[i + c]) / 255;
          e /= 3;
        } else if (mode === 'rel') {
          for (let c = 0; c < 3; ++c)
            e += Math.abs(linear[a[i + c]] - linear[b[i + c]]) / (linear[b[i + c]] + 0.01);
          e /= 3;
        } else {
          e = fl ? fl[i] / 255 : 0;
        }
        [r, g, bl] = magma(e * inv);
      }
      o[i] = r; o[i + 1] = g; o[i + 2] = bl; o[i + 3] = 255;
    }
    bctx.putImageData(out, 0, 0);
  }

  function fit() {
    const box = canvas.parentElement.clientWidth || W;
    const tall = Math.max(240, Math.floor(window.innerHeight * 0.7));
    state.zoom = Math.max(0.25, Math.min(8, Math.floor(Math.min(box / W, tall / H) * 4) / 4 || 1));
    state.ox = 0;
    state.oy = 0;
  }

  function present() {
    // The canvas is a viewport: at most the page's width and most of the window's height.
    const box = canvas.parentElement.clientWidth || W;
    canvas.width = Math.max(64, Math.min(box, Math.ceil(W * state.zoom)));
    canvas.height = Math.max(64, Math.min(Math.max(240, Math.floor(window.innerHeight * 0.8)),
                                          Math.ceil(H * state.zoom)));
    ctx.imageSmoothingEnabled = false;
    ctx.fillStyle = '#222';
    ctx.fillRect(0, 0, canvas.width, canvas.height);
    ctx.setTransform(state.zoom, 0, 0, state.zoom, -state.ox * state.zoom, -state.oy * state.zoom);
    ctx.drawImage(buffer, 0, 0);
    if (state.mode === 'slider') {
      ctx.strokeStyle = '#fff';
      ctx.lineWidth = 1 / state.zoom;
      ctx.beginPath();
      ctx.moveTo(state.split * W, 0);
      ctx.lineTo(state.split * W, H);
      ctx.stroke();
    }
    ctx.setTransform(1, 0, 0, 1, 0, 0);
  }

  let pending = Promise.resolve();
  function update() {
    const frameIndex = data.frames[state.frame];
    if (state.vmax[state.mode]) state.errorMode = state.mode;
    $('v-frame').value = state.frame;
    $('v-vmax').value = Math.log10(state.vmax[state.errorMode]);
    $('v-frame-label').textContent = 'frame ' + frameIndex +
        (data.every > 1 ? ' (every ' + data.every + ' frames embedded; all in viewer/)' : '') +
        (data.factor > 1 ? ' (embedded at 1/' + data.factor + ' size)' : '');
    $('v-a').value = state.a;
    $('v-b').value = state.b;
    $('v-mode').value = state.mode;
    $('v-ev-label').textContent = (state.ev >= 0 ? '+' : '') + state.ev.toFixed(1) + ' EV';
    $('v-zoom-label').textContent = (state.zoom * data.fullWidth / W).toFixed(2) + 'x';
    const shown = state.mode === 'b' ? state.b : state.a;
    $('v-full').href = data.full[shown][state.frame];
    $('v-full').textContent = 'full-size PNG of ' + data.methods[shown];
    $('v-caption').textContent = modes[state.mode] + ': A = ' + data.methods[state.a] +
        ', B = ' + data.methods[state.b] + ', frame ' + frameIndex;
    drawBar();
    pending = pending.then(compose).then(() => {
      present();
      window.bmfrViewer.ready = true;
      window.bmfrViewer.draws += 1;
    }).catch((e) => {
      $('v-caption').textContent = String(e);
      throw e;
    });
    return pending;
  }

  // Playback steps through the embedded frames, looping, at the sequence's frame rate: each
  // embedded frame stands for data.every frames. The next step waits for the last one's drawing,
  // so a slow machine plays slower rather than queueing frames; `run` ends a stopped loop.
  let run = 0;
  function setPlaying(on) {
    state.playing = on;
    run += 1;
    $('v-play').textContent = on ? 'pause' : 'play';
    if (on) step(run, performance.now());
  }
  function step(id, since) {
    const period = 1000 * data.every / (data.fps || 24);
    setTimeout(() => {
      if (id !== run) return;
      const started = performance.now();
      state.frame = (state.frame + 1) % data.frames.length;
      update().then(() => { if (id === run) step(id, started); }, () => setPlaying(false));
    }, Math.max(0, period - (performance.now() - since)));
  }

  function setup() {
    for (const id of ['v-a', 'v-b'])
      data.methods.forEach((name, i) => {
        const o = document.createElement('option');
        o.value = i;
        o.textContent = name;
        $(id).appendChild(o);
      });
    for (const [k, label] of Object.entries(modes)) {
      const o = document.createElement('option');
      o.value = k;
      o.textContent = label;
      $('v-mode').appendChild(o);
    }
    $('v-frame').max = data.frames.length - 1;
    // Taking the frame slider stops playback at the frame it is dragged to.
    $('v-frame').addEventListener('pointerdown', () => setPlaying(false));
    $('v-frame').addEventListener('input', (e) => {
      setPlaying(false);
      state.frame = +e.target.value;
      update();
    });
    $('v-play').addEventListener('click', () => setPlaying(!state.playing));
    // A button clicked with the mouse keeps no focus, so that space stays the play key; one
    // reached with Tab keeps its own space.
    for (const b of document.querySelectorAll('#viewer button'))
      b.addEventListener('mousedown', (e) => e.preventDefault());
    $('v-a').addEventListener('change', (e) => { state.a = +e.target.value; update(); });
    $('v-b').addEventListener('change', (e) => { state.b = +e.target.value; update(); });
    $('v-mode').addEventListener('change', (e) => { state.mode = e.target.value; update(); });
    $('v-ev').addEventListener('input', (e) => { state.ev = +e.target.value; update(); });
    $('v-vmax').addEventListener('input', (e) => {
      state.vmax[state.errorMode] = Math.pow(10, +e.target.value);
      update();
    });
    $('v-zoom-in').addEventListener('click', () => { state.zoom = Math.min(32, state.zoom * 2); update(); });
    $('v-zoom-out').addEventListener('click', () => { state.zoom = Math.max(0.25, state.zoom / 2); update(); });
    $('v-zoom-1').addEventListener('click', () => { state.zoom = W / data.fullWidth; state.ox = state.oy = 0; update(); });
    $('v-zoom-fit').addEventListener('click', () => { fit(); update(); });
    let drag = null;
    canvas.addEventListener('mousedown', (e) => { drag = {x: e.clientX, y: e.clientY, ox: state.ox, oy: state.oy}; });
    window.addEventListener('mouseup', () => { drag = null; });
    canvas.addEventListener('mousemove', (e) => {
      const rect = canvas.getBoundingClientRect();
      const ix = state.ox + (e.clientX - rect.left) / state.zoom, iy = state.oy + (e.clientY - rect.top) / state.zoom;
      if (drag && state.mode === 'slider' && e.shiftKey) {
        state.split = Math.max(0, Math.min(1, ix / W));
        update();
      } else if (drag) {
        state.ox = drag.ox - (e.clientX - drag.x) / state.zoom;
        state.oy = drag.oy - (e.clientY - drag.y) / state.zoom;
        present();
      }
      const px = Math.floor(ix * data.fullWidth / W), py = Math.floor(iy * data.fullHeight / H);
      $('v-pixel').textContent = px >= 0 && py >= 0 && px < data.fullWidth && py < data.fullHeight ? 'pixel ' + px + ', ' + py : '';
    });
    canvas.addEventListener('click', (e) => {
      if (state.mode !== 'slider') return;
      const rect = canvas.getBoundingClientRect();
      state.split = Math.max(0, Math.min(1, (state.ox + (e.clientX - rect.left) / state.zoom) / W));
      update();
    });
    canvas.addEventListener('wheel', (e) => {
      e.preventDefault();
      const rect = canvas.getBoundingClientRect();
      const ix = state.ox + (e.clientX - rect.left) / state.zoom, iy = state.oy + (e.clientY - rect.top) / state.zoom;
      state.zoom = Math.max(0.25, Math.min(32, state.zoom * (e.deltaY < 0 ? 1.25 : 0.8)));
      state.ox = ix - (e.clientX - rect.left) / state.zoom;
      state.oy = iy - (e.clientY - rect.top) / state.zoom;
      update();
    }, {passive: false});
    document.addEventListener('keydown', (e) => {
      // Selects and sliders keep their own arrow keys, selects and buttons their space; letters
      // work everywhere.
      const tag = e.target.tagName;
      if ((tag === 'SELECT' || tag === 'INPUT') && e.key.startsWith('Arrow')) return;
      if ((tag === 'SELECT' || tag === 'BUTTON') && e.key === ' ') return;
      if (e.key === ' ') {
        e.preventDefault();
        setPlaying(!state.playing);
        return;
      }
      const n = data.frames.length;
      const keys = {
        ArrowRight: () => { setPlaying(false); state.frame = (state.frame + 1) % n; },
        ArrowLeft: () => { setPlaying(false); state.frame = (state.frame + n - 1) % n; },
        f: () => { state.mode = state.mode === 'a' ? 'b' : 'a'; },
        a: () => { state.mode = 'a'; }, b: () => { state.mode = 'b'; },
        s: () => { state.mode = 'slider'; },
        e: () => { state.mode = state.mode === 'abs' ? 'rel' : state.mode === 'rel' ? 'flip' : 'abs'; },
        '+': () => { state.zoom = Math.min(32, state.zoom * 2); },
        '-': () => { state.zoom = Math.max(0.25, state.zoom / 2); },
      };
      if (!keys[e.key]) return;
      e.preventDefault();
      keys[e.key]();
      update();
    });
    fit();
  }

  window.bmfrViewer = {ready: false, draws: 0, state: state, update: update, setPlaying: setPlaying};
  setup();
  update();
})();
