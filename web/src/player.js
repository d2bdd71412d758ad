// The 3D player of seqmassage's report.html: the input frames (left) and the corrected frames
// (right) in one WebGL canvas, two viewports of one camera (so orbit, pan and zoom are linked),
// a frame slider with the failed and repaired frames marked, play/pause at the sequence's frame
// rate, and three shadings: a checker on the template's texture coordinates (fixed to the
// template's surface, so swimming shows as squares sliding), the shear per triangle (eq. 8) on
// one colour scale for both sides, and wireframe. Bundled with three.js by esbuild into one
// script (web/package.json); report_page.js calls window.SeqmassagePlayer.create.
import {
  AmbientLight, BufferAttribute, BufferGeometry, Color, DataTexture, DirectionalLight,
  DoubleSide, Mesh, MeshBasicMaterial, MeshLambertMaterial, NearestFilter, PerspectiveCamera,
  RepeatWrapping, RGBAFormat, Scene, SRGBColorSpace, Vector3, WebGLRenderer,
} from 'three';
import { OrbitControls } from 'three/addons/controls/OrbitControls.js';

// Viridis at 9 stops: one perceptual scale, low shear dark blue, high shear yellow.
const VIRIDIS = [
  [68, 1, 84], [71, 44, 122], [59, 81, 139], [44, 113, 142], [33, 144, 141],
  [39, 173, 129], [92, 200, 99], [170, 220, 50], [253, 231, 37],
];
function viridis(t) {
  const x = Math.min(Math.max(t, 0), 1) * (VIRIDIS.length - 1);
  const i = Math.min(Math.floor(x), VIRIDIS.length - 2), f = x - i;
  return VIRIDIS[i].map((a, k) => (a + (VIRIDIS[i + 1][k] - a) * f) / 255);
}

function el(tag, cls, text) {
  const e = document.createElement(tag);
  if (cls) e.className = cls;
  if (text !== undefined) e.textContent = text;
  return e;
}

function checkerTexture(cells) {
  const px = Math.max(8, Math.floor(256 / cells)), size = px * cells;
  const data = new Uint8Array(size * size * 4);
  for (let y = 0; y < size; y++)
    for (let x = 0; x < size; x++) {
      const light = ((Math.floor(x / px) + Math.floor(y / px)) & 1) === 0;
      const o = (y * size + x) * 4;
      data.set(light ? [235, 235, 235, 255] : [45, 50, 70, 255], o);
    }
  const t = new DataTexture(data, size, size, RGBAFormat);
  t.wrapS = t.wrapT = RepeatWrapping;
  t.magFilter = NearestFilter;
  t.colorSpace = SRGBColorSpace;
  t.needsUpdate = true;
  return t;
}

function create(section, opts) {
  const P = opts.player, n = P.vertices, m = P.triangles, K = P.frames.length;
  const tri = new Uint32Array(opts.blocks('tri'));
  const uv = new Float32Array(opts.blocks('uv'));
  const lo = P.box.slice(0, 3), ext = [0, 1, 2].map((k) => P.box[3 + k] - P.box[k]);
  const lut = new Float32Array(256 * 3);
  for (let c = 0; c < 256; c++) lut.set(viridis(c / 255), c * 3);

  // --- DOM.
  const view = el('div', 'player-view');
  const canvas = el('canvas');
  view.appendChild(canvas);
  view.appendChild(el('span', 'label', 'input (before)'));
  const right = el('span', 'label', 'corrected (after)');
  right.style.left = '50%';
  view.appendChild(right);
  const controlsBar = el('div', 'player-controls');
  const play = el('button', 'play', 'Play');
  play.type = 'button';
  const sliderWrap = el('div', 'slider-wrap');
  const slider = el('input');
  slider.type = 'range';
  slider.min = '0';
  slider.max = String(K - 1);
  slider.step = '1';
  slider.value = '0';
  slider.setAttribute('aria-label', 'frame');
  const marks = el('div', 'slider-marks');
  Object.keys(opts.marks).forEach((k) => {
    const s = el('span', opts.marks[k]);
    s.title = opts.marks[k];
    s.style.left = (K > 1 ? (Number(k) / (K - 1)) * 100 : 0) + '%';
    marks.appendChild(s);
  });
  sliderWrap.appendChild(slider);
  sliderWrap.appendChild(marks);
  const label = el('span', 'frame-label');
  const mode = el('select', 'mode');
  mode.setAttribute('aria-label', 'shading');
  [['checker', 'checker (' + (P.uv === 'input' ? "template's texture coordinates" : 'automatic charts on the template') + ')'],
   ['shear', P.colour === 'radius ratio' ? 'radius ratio per triangle' : 'shear per triangle (eq. 8)'],
   ['wireframe', 'wireframe']].forEach(([v, t]) => {
    const o = el('option', null, t);
    o.value = v;
    mode.appendChild(o);
  });
  const legend = el('span', 'legend');
  const bar = el('canvas');
  bar.width = 200;
  bar.height = 12;
  const g = bar.getContext('2d');
  for (let x = 0; x < 200; x++) {
    const c = viridis(x / 199).map((v) => Math.round(v * 255));
    g.fillStyle = 'rgb(' + c.join(',') + ')';
    g.fillRect(x, 0, 1, 12);
  }
  const ratio = P.colour === 'radius ratio';
  legend.appendChild(el('span', null, ratio ? 'radius ratio 0 (degenerate)' : 'shear 0'));
  legend.appendChild(bar);
  legend.appendChild(el('span', null, ratio ? '1 (equilateral)' : '\u2265 ' + Number(P.shear_scale.toPrecision(3)) +
    ' (the largest p95 of the input; degenerate triangles at the top)'));
  legend.hidden = true;
  controlsBar.append(play, sliderWrap, label, mode, legend);
  section.append(view, controlsBar);

  // --- Scene: one geometry per side, not indexed (corners carry the texture coordinates and
  // the triangles' flat colours).
  const renderer = new WebGLRenderer({ canvas, antialias: true, preserveDrawingBuffer: true });
  renderer.setPixelRatio(Math.min(window.devicePixelRatio || 1, 2));
  renderer.setScissorTest(true);
  const texture = checkerTexture(P.checker_cells || 8);
  const materials = {
    checker: new MeshLambertMaterial({ map: texture, side: DoubleSide }),
    shear: new MeshLambertMaterial({ vertexColors: true, side: DoubleSide }),
    wireframe: new MeshBasicMaterial({ color: 0xd0d6e0, wireframe: true }),
  };
  const sides = ['i', 'o'].map((tag) => {
    const geometry = new BufferGeometry();
    geometry.setAttribute('position', new BufferAttribute(new Float32Array(m * 9), 3));
    geometry.setAttribute('uv', new BufferAttribute(uv, 2));
    geometry.setAttribute('color', new BufferAttribute(new Float32Array(m * 9), 3));
    const mesh = new Mesh(geometry, materials.checker);
    const scene = new Scene();
    scene.background = new Color(0x20242c);
    scene.add(mesh, new AmbientLight(0xffffff, 1.2));
    const light = new DirectionalLight(0xffffff, 2.0);
    scene.add(light);
    return { tag, geometry, mesh, scene, light };
  });

  const center = new Vector3(lo[0] + ext[0] / 2, lo[1] + ext[1] / 2, lo[2] + ext[2] / 2);
  const radius = Math.max(1e-9, 0.5 * Math.hypot(ext[0], ext[1], ext[2]));
  const camera = new PerspectiveCamera(35, 1, radius / 100, radius * 100);
  camera.position.copy(center).add(new Vector3(0.35, 0.25, 1).normalize().multiplyScalar(radius * 2.4));
  const controls = new OrbitControls(camera, canvas);
  controls.target.copy(center);
  controls.update();

  // --- Frames, decoded when shown (a few cached).
  const cache = new Map();
  function frameData(k) {
    if (cache.has(k)) return cache.get(k);
    const d = ['i', 'o'].map((t) => ({
      q: new Uint16Array(opts.blocks(t + k)),
      s: new Uint8Array(opts.blocks('s' + t + k)),
    }));
    if (cache.size > 8) cache.delete(cache.keys().next().value);
    cache.set(k, d);
    return d;
  }
  let current = -1, dirty = true;
  function setFrame(k) {
    k = Math.min(Math.max(Math.round(k), 0), K - 1);
    if (k === current) return;
    current = k;
    const d = frameData(k);
    sides.forEach((side, s) => {
      const pos = side.geometry.attributes.position.array, col = side.geometry.attributes.color.array;
      const q = d[s].q, codes = d[s].s;
      for (let t = 0; t < m; t++) {
        const c = codes[t] * 3;
        for (let j = 0; j < 3; j++) {
          const v = tri[t * 3 + j], o = t * 9 + j * 3;
          for (let a = 0; a < 3; a++) {
            pos[o + a] = lo[a] + (q[v * 3 + a] / 65535) * ext[a];
            col[o + a] = lut[c + a];
          }
        }
      }
      side.geometry.attributes.position.needsUpdate = true;
      side.geometry.attributes.color.needsUpdate = true;
      side.geometry.computeVertexNormals();
    });
    slider.value = String(k);
    const mark = opts.marks[k] ? ' [' + opts.marks[k] + ']' : '';
    label.textContent = 'frame ' + P.frames[k] + ' (' + opts.names[k] + ')' + mark +
      ', ' + (k + 1) + ' of ' + K;
    dirty = true;
    if (opts.onFrame) opts.onFrame(P.frames[k]);
  }
  function setMode(name) {
    sides.forEach((s) => { s.mesh.material = materials[name] || materials.checker; });
    legend.hidden = name !== 'shear';
    mode.value = name;
    dirty = true;
  }

  function render() {
    const w = canvas.clientWidth, h = canvas.clientHeight;
    if (canvas.width !== Math.floor(w * renderer.getPixelRatio()) || canvas.height !== Math.floor(h * renderer.getPixelRatio()))
      renderer.setSize(w, h, false);
    camera.aspect = w / 2 / Math.max(h, 1);
    camera.updateProjectionMatrix();
    sides.forEach((side, s) => {
      side.light.position.copy(camera.position);
      renderer.setViewport(s * w / 2, 0, w / 2, h);
      renderer.setScissor(s * w / 2, 0, w / 2, h);
      renderer.render(side.scene, camera);
    });
    dirty = false;
  }

  let playing = false, last = 0, clock = 0;
  function tick(now) {
    if (playing) {
      clock += Math.min((now - last) / 1000, 0.25);
      // The kept frames may be spaced: each step lasts its frames' time at the sequence's rate.
      const step = K > 1 ? (P.frames[Math.min(current + 1, K - 1)] - P.frames[current]) / opts.fps : 1;
      if (clock >= step) {
        clock -= step;
        setFrame(current + 1 >= K ? 0 : current + 1);
      }
    }
    last = now;
    if (dirty) render();
    requestAnimationFrame(tick);
  }
  controls.addEventListener('change', () => { dirty = true; });
  window.addEventListener('resize', () => { dirty = true; });
  slider.addEventListener('input', () => setFrame(Number(slider.value)));
  mode.addEventListener('change', () => setMode(mode.value));
  function setPlaying(on) {
    playing = on && K > 1;
    play.textContent = playing ? 'Pause' : 'Play';
    clock = 0;
  }
  play.addEventListener('click', () => setPlaying(!playing));
  slider.addEventListener('pointerdown', () => setPlaying(false));
  setFrame(0);
  setMode('checker');
  render();
  // Playing from the start: the checker slides on the left and holds still on the right.
  setPlaying(true);
  requestAnimationFrame(tick);
  return { setFrame, setMode, setPlaying, render, frames: K, canvas };
}

window.SeqmassagePlayer = { create };
