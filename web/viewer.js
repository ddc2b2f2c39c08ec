// The saliency viewer of `meshsal view` pages: bundled with three.js by esbuild at build
// time (CMakeLists.txt) and inlined into the page, or written once beside a gallery's pages
// (meshsal-viewer.js, `batch --html`), so a page opens with no network. It reads the page's
// data (<script id="meshsal-data">: the mesh as GLB, quantised and meshopt-compressed; the
// best view's camera and numbers; the colour scale's ends, colours and percentiles), draws
// the model with orbit controls, colours it by S on the square-root scale (a live range),
// shows S under the cursor, the view's angles, lit edges on demand, and takes keys (b, w,
// s, p, r). document.body.dataset.status says how it went ("drawn" after the first frame,
// else "error: ..."), for the tests and for anyone puzzled by a blank page.
import * as THREE from 'three';
import { OrbitControls } from 'three/addons/controls/OrbitControls.js';
import { GLTFLoader } from 'three/addons/loaders/GLTFLoader.js';
import { MeshoptDecoder } from 'three/addons/libs/meshopt_decoder.module.js';

const errors = [];
function fail(message) {
  errors.push(String(message));
  document.body.dataset.status = 'error: ' + errors[0];
  const box = document.getElementById('error');
  if (box) {
    box.textContent = errors.join('\n');
    box.hidden = false;
  }
}
window.addEventListener('error', (e) => fail(e.message));
window.addEventListener('unhandledrejection', (e) => fail(e.reason));
const consoleError = console.error.bind(console);
console.error = (...args) => {
  fail(args.join(' '));
  consoleError(...args);
};

function base64Bytes(text) {
  const raw = atob(text);
  const bytes = new Uint8Array(raw.length);
  for (let i = 0; i < raw.length; ++i) bytes[i] = raw.charCodeAt(i);
  return bytes.buffer;
}

const $ = (id) => document.getElementById(id);
// A value as the panel shows it: 4 significant digits, no trailing zeros.
const fmt = (v) => (Number.isFinite(v) ? String(Number(v.toPrecision(4))) : String(v));
const deg = (r) => (r * 180 / Math.PI).toFixed(1);

function start() {
  const data = JSON.parse($('meshsal-data').textContent);
  const host = $('view');
  let renderer;
  try {
    renderer = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
  } catch (e) {
    fail('WebGL is not available in this browser: ' + e.message);
    return;
  }
  renderer.setPixelRatio(window.devicePixelRatio || 1);
  renderer.setClearColor(0xffffff, 1);
  host.appendChild(renderer.domElement);

  // The best view's orthographic camera (ViewCamera: eye, target, up, half_extent).
  const c = data.camera;
  const camera = new THREE.OrthographicCamera(-1, 1, 1, -1, 1e-3, 1e3);
  const radius = Math.hypot(c.eye[0] - c.target[0], c.eye[1] - c.target[1], c.eye[2] - c.target[2]);
  camera.near = radius * 1e-3;
  camera.far = radius * 4;
  const scene = new THREE.Scene();
  scene.add(new THREE.HemisphereLight(0xffffff, 0x808080, 1.2));
  const light = new THREE.DirectionalLight(0xffffff, 1.6);
  light.position.set(0, 0, 1);
  camera.add(light);  // a headlight: lit from wherever the viewer looks
  scene.add(camera);
  const controls = new OrbitControls(camera, renderer.domElement);

  // The first view, exactly: the same numbers through the same steps each time, so "best
  // view" gives back the first frame's pixels.
  function bestView() {
    camera.position.set(...c.eye);
    camera.up.set(...c.up);
    camera.zoom = 1;
    camera.updateProjectionMatrix();
    controls.target.set(...c.target);
    controls.update();
  }
  bestView();

  function resize() {
    const w = host.clientWidth, h = host.clientHeight;
    // A margin around the model: it fills 1/1.15 of the view's smaller side.
    const half = c.half_extent * 1.15, aspect = w / h;
    camera.left = -half * Math.max(aspect, 1);
    camera.right = half * Math.max(aspect, 1);
    camera.top = half / Math.min(aspect, 1);
    camera.bottom = -half / Math.min(aspect, 1);
    camera.updateProjectionMatrix();
    renderer.setSize(w, h);
  }
  window.addEventListener('resize', () => { resize(); ticks(); draw(); });
  resize();

  // The view's angles in the frame of the page's up axis (ViewFrame::axes), as
  // direction_angles gives them: the best view's from the search, this view's from the camera.
  $('best-azimuth').textContent = deg(c.theta);
  $('best-elevation').textContent = deg(c.phi);
  $('up-axis').textContent = c.up_axis;
  $('best-u').textContent = c.U === undefined ? '-' : fmt(c.U);
  $('best-fraction').textContent = c.visible_fraction === undefined ? '-' : (100 * c.visible_fraction).toFixed(1) + '%';
  const dir = new THREE.Vector3();
  function showAngles() {
    dir.subVectors(camera.position, controls.target).normalize();
    const local = c.axes.map((a) => a[0] * dir.x + a[1] * dir.y + a[2] * dir.z);
    const phi = Math.asin(Math.max(-1, Math.min(1, local[1])));
    const theta = local[0] === 0 && local[2] === 0 ? 0 : Math.atan2(local[0], local[2]);
    $('azimuth').textContent = deg(theta);
    $('elevation').textContent = deg(phi);
  }

  // The colour scale: v at t = sqrt((v - lo) / (hi - lo)) through the pictures' colours
  // (sRGB bytes, made linear for WebGL's lighting); percentiles from the mesh points' values.
  const scale = data.scale, Q = scale.quantiles;
  const lut = new Float32Array(scale.lut.length);
  for (let i = 0; i < lut.length; ++i) {
    const s = scale.lut[i] / 255;
    lut[i] = s <= 0.04045 ? s / 12.92 : Math.pow((s + 0.055) / 1.055, 2.4);
  }
  function valueAt(p) {  // the value at percentile p (0..100)
    if (!Q.length) return 0;
    const x = Math.max(0, Math.min(1, p / 100)) * (Q.length - 1), k = Math.floor(x);
    return k + 1 < Q.length ? Q[k] + (Q[k + 1] - Q[k]) * (x - k) : Q[k];
  }
  function percentileOf(v) {  // the percentage of mesh points at or below v
    if (!Q.length || v < Q[0]) return 0;
    let a = 0, b = Q.length - 1;
    if (v >= Q[b]) return 100;
    while (b - a > 1) {
      const m = (a + b) >> 1;
      if (Q[m] <= v) a = m; else b = m;
    }
    const f = Q[b] > Q[a] ? (v - Q[a]) / (Q[b] - Q[a]) : 0;
    return 100 * (a + f) / (Q.length - 1);
  }
  let lo = scale.lo, hi = scale.hi;

  const meshes = [];  // the model as loaded (indexed): coloured, picked
  let wires = null;   // the same triangles one by one, with barycentric edges (made on first use)
  let mode = 'saliency', edges = false;
  let drawn = false;
  function draw() {
    renderer.render(scene, camera);
    showAngles();
    if (!drawn && meshes.length) {
      drawn = true;
      if (!errors.length) document.body.dataset.status = 'drawn';
    }
  }
  controls.addEventListener('change', draw);

  function colour(mesh) {
    const g = mesh.geometry, s = g.attributes._saliency, n = g.attributes.position.count;
    let col = g.attributes.color;
    if (!col) {
      col = new THREE.BufferAttribute(new Float32Array(3 * n), 3);
      g.setAttribute('color', col);
    }
    const span = hi > lo ? hi - lo : 0, last = lut.length / 3 - 1;
    for (let i = 0; i < n; ++i) {
      const v = s ? s.getX(i) : 0;
      const t = span > 0 ? Math.sqrt(Math.min(1, Math.max(0, (v - lo) / span))) : (v > lo ? 1 : 0);
      const k = 3 * Math.round(t * last);
      col.array[3 * i] = lut[k], col.array[3 * i + 1] = lut[k + 1], col.array[3 * i + 2] = lut[k + 2];
    }
    col.needsUpdate = true;
  }
  function recolour() {
    for (const m of meshes) colour(m);
    if (wires) wires.forEach((w, i) => expand(meshes[i].geometry.attributes.color, w.geometry.attributes.color, meshes[i].geometry.index));
    $('range-lo-value').textContent = fmt(lo);
    $('range-hi-value').textContent = fmt(hi);
    ticks();
    draw();
  }
  function expand(from, to, index) {
    const a = from.array, b = to.array, s = from.itemSize;
    for (let i = 0; i < index.count; ++i) {
      const v = index.getX(i);
      for (let k = 0; k < s; ++k) b[s * i + k] = a[s * v + k];
    }
    to.needsUpdate = true;
  }

  // The bar's values: at t = 0, 1/4, ..., 1 (the square-root positions), a label dropped
  // where it would touch its neighbour, whatever the panel's width.
  function ticks() {
    const box = $('ticks');
    box.textContent = '';
    const spans = [0, 0.25, 0.5, 0.75, 1].map((t) => {
      const s = document.createElement('span');
      s.style.left = (100 * t) + '%';
      s.textContent = fmt(lo + (hi - lo) * t * t);
      box.appendChild(s);
      return s;
    });
    const gap = 6, last = spans[spans.length - 1].getBoundingClientRect();
    let right = spans[0].getBoundingClientRect().right;
    if (right + gap > last.left) { spans[spans.length - 1].remove(); return; }
    for (const s of spans.slice(1, -1)) {
      const r = s.getBoundingClientRect();
      if (r.left < right + gap || r.right + gap > last.left) s.remove();
      else right = r.right;
    }
  }

  const materials = {
    saliency: new THREE.MeshLambertMaterial({ vertexColors: true, side: THREE.DoubleSide }),
    plain: new THREE.MeshLambertMaterial({ color: 0xbebebe, side: THREE.DoubleSide }),
  };
  // The same, darkened along the triangles' edges before the lighting (so the edges are lit
  // as the surface is); where triangles are a few pixels wide the edges fade, not to hide
  // the shape under a mesh of lines.
  function withEdges(material) {
    const m = material.clone();
    m.onBeforeCompile = (sh) => {
      sh.vertexShader = 'attribute vec3 bary;\nvarying vec3 vBary;\n' +
        sh.vertexShader.replace('#include <begin_vertex>', '#include <begin_vertex>\n  vBary = bary;');
      sh.fragmentShader = 'varying vec3 vBary;\n' + sh.fragmentShader.replace('#include <color_fragment>',
        `#include <color_fragment>
  vec3 fw = max(fwidth(vBary), vec3(1e-6));
  vec3 near = 1.0 - smoothstep(0.5 * fw, 1.5 * fw, vBary);
  float edge = max(max(near.x, near.y), near.z);
  float dense = smoothstep(0.15, 0.6, max(max(fw.x, fw.y), fw.z));
  diffuseColor.rgb *= 1.0 - 0.6 * edge * (1.0 - 0.5 * dense);`);
    };
    m.customProgramCacheKey = () => 'meshsal-edges';
    return m;
  }
  const edgeMaterials = { saliency: withEdges(materials.saliency), plain: withEdges(materials.plain) };
  function makeWires() {
    wires = meshes.map((mesh) => {
      const g = mesh.geometry, index = g.index, n = index.count, w = new THREE.BufferGeometry();
      const pos = new Float32Array(3 * n), v = new THREE.Vector3();
      for (let i = 0; i < n; ++i) v.fromBufferAttribute(g.attributes.position, index.getX(i)).toArray(pos, 3 * i);
      w.setAttribute('position', new THREE.BufferAttribute(pos, 3));
      for (const name of ['normal', 'color']) {
        const a = new THREE.BufferAttribute(new Float32Array(3 * n), 3);
        expand(g.attributes[name], a, index);
        w.setAttribute(name, a);
      }
      const bary = new Uint8Array(3 * n);
      for (let i = 0; i < n; ++i) bary[3 * i + (i % 3)] = 255;
      w.setAttribute('bary', new THREE.BufferAttribute(bary, 3, true));
      const wm = new THREE.Mesh(w, edgeMaterials[mode]);
      wm.position.copy(mesh.position), wm.quaternion.copy(mesh.quaternion), wm.scale.copy(mesh.scale);
      mesh.parent.add(wm);
      return wm;
    });
  }
  function show() {
    if (edges && !wires) makeWires();
    for (const m of meshes) { m.material = materials[mode]; m.visible = !edges; }
    if (wires) for (const w of wires) { w.material = edgeMaterials[mode]; w.visible = edges; }
    for (const b of document.querySelectorAll('#modes button[data-mode]')) b.classList.toggle('on', b.dataset.mode === mode);
    $('wire').classList.toggle('on', edges);
    draw();
  }
  function setMode(m) { mode = m; show(); }
  function toggleEdges() { edges = !edges; show(); }
  for (const b of document.querySelectorAll('#modes button[data-mode]')) b.addEventListener('click', () => setMode(b.dataset.mode));
  $('wire').addEventListener('click', toggleEdges);
  $('best').addEventListener('click', () => { bestView(); draw(); });

  // The colour range: two sliders in percentiles of S over the mesh points.
  const sliderLo = $('range-lo'), sliderHi = $('range-hi');
  function setRange(pLo, pHi) {
    sliderLo.value = pLo, sliderHi.value = pHi;
    lo = valueAt(Math.min(pLo, pHi)), hi = valueAt(Math.max(pLo, pHi));
    if (!(hi > lo)) hi = lo + Math.abs(lo) * 1e-6 + 1e-12;
    recolour();
  }
  function resetRange() {
    lo = scale.lo, hi = scale.hi;
    sliderLo.value = percentileOf(lo), sliderHi.value = percentileOf(hi);
    recolour();
  }
  sliderLo.addEventListener('input', () => setRange(+sliderLo.value, +sliderHi.value));
  sliderHi.addEventListener('input', () => setRange(+sliderLo.value, +sliderHi.value));
  $('range-reset').addEventListener('click', resetRange);

  // S under the cursor: the mesh point (vertex) nearest the picked point of the surface.
  const raycaster = new THREE.Raycaster(), ndc = new THREE.Vector2(), p = new THREE.Vector3();
  const tip = $('tip');
  function pick(x, y) {  // x, y: CSS pixels in the view
    const w = host.clientWidth, h = host.clientHeight;
    ndc.set(2 * x / w - 1, 1 - 2 * y / h);
    raycaster.setFromCamera(ndc, camera);
    const hit = raycaster.intersectObjects(meshes, false)[0];
    if (!hit || !hit.face) {
      tip.hidden = true;
      return null;
    }
    const g = hit.object.geometry;
    let best = -1, bestD = Infinity;
    for (const v of [hit.face.a, hit.face.b, hit.face.c]) {
      p.fromBufferAttribute(g.attributes.position, v).applyMatrix4(hit.object.matrixWorld);
      const d = p.distanceToSquared(hit.point);
      if (d < bestD) bestD = d, best = v;
    }
    const s = g.attributes._saliency ? g.attributes._saliency.getX(best) : NaN;
    const text = 'S = ' + fmt(s) + ', percentile ' + percentileOf(s).toFixed(1);
    $('readout').textContent = 'S under the cursor: ' + fmt(s) + ' (percentile ' + percentileOf(s).toFixed(1) +
      ' of the mesh points)';
    $('readout').dataset.value = String(s);
    tip.textContent = text;
    tip.style.left = Math.min(x + 14, w - 180) + 'px';
    tip.style.top = Math.max(y - 28, 0) + 'px';
    tip.hidden = false;
    return s;
  }
  let pending = null;
  function pickSoon(e) {
    const r = host.getBoundingClientRect();
    const first = pending === null;
    pending = [e.clientX - r.left, e.clientY - r.top];
    if (first) requestAnimationFrame(() => { if (meshes.length) pick(...pending); pending = null; });
  }
  host.addEventListener('pointermove', (e) => { if (e.pointerType === 'mouse' && !e.buttons) pickSoon(e); });
  let down = null;
  host.addEventListener('pointerdown', (e) => { down = [e.clientX, e.clientY]; });
  host.addEventListener('pointerup', (e) => {  // a tap (no drag) shows S there too
    if (down && Math.hypot(e.clientX - down[0], e.clientY - down[1]) < 5) pickSoon(e);
    down = null;
  });
  host.addEventListener('pointerleave', () => { tip.hidden = true; });

  window.addEventListener('keydown', (e) => {
    if (e.ctrlKey || e.metaKey || e.altKey) return;
    const act = { b: () => { bestView(); draw(); }, w: toggleEdges, s: () => setMode('saliency'),
                  p: () => setMode('plain'), r: resetRange }[e.key.toLowerCase()];
    if (act) { act(); e.preventDefault(); }
  });

  // Test hook (tests/api/test_view_page_controls.cpp): page.html#test=STEP;STEP... runs the
  // steps after the first frame, as a user would, so that headless Chromium can check the
  // pixels and the DOM. Steps: range:LO,HI (percentiles), wireframe, plain, orbit (turn and
  // zoom the camera), best, hover:X,Y (fractions of the view). It only calls what the
  // buttons, sliders and pointer call; then body's data-test is "done".
  function testHook() {
    const m = /#test=([^&]*)/.exec(location.hash);
    if (!m) return;
    for (const step of decodeURIComponent(m[1]).split(';')) {
      const [name, args = ''] = step.split(':');
      const a = args.split(',').map(Number);
      if (name === 'range') setRange(a[0], a[1]);
      else if (name === 'wireframe') toggleEdges();
      else if (name === 'plain') setMode('plain');
      else if (name === 'orbit') {
        const off = camera.position.clone().sub(controls.target).applyAxisAngle(camera.up, 1.0);
        camera.position.copy(controls.target).add(off);
        camera.zoom = 1.7;
        camera.updateProjectionMatrix();
        controls.update();
      } else if (name === 'best') { bestView(); draw(); }
      else if (name === 'hover') pick(a[0] * host.clientWidth, a[1] * host.clientHeight);
      else fail('unknown test step ' + step);
    }
    document.body.dataset.test = 'done';
  }

  const loader = new GLTFLoader();
  loader.setMeshoptDecoder(MeshoptDecoder);
  loader.parse(base64Bytes(data.glb), '', (gltf) => {
    gltf.scene.traverse((o) => {
      if (o.isMesh) {
        o.geometry.computeVertexNormals();
        meshes.push(o);
      }
    });
    scene.add(gltf.scene);
    scene.updateMatrixWorld(true);
    sliderLo.value = percentileOf(lo), sliderHi.value = percentileOf(hi);
    for (const m of meshes) colour(m);
    $('range-lo-value').textContent = fmt(lo);
    $('range-hi-value').textContent = fmt(hi);
    ticks();
    show();
    testHook();
  }, (e) => fail('the model could not be read: ' + (e.message || e)));
}

if (document.readyState === 'loading') document.addEventListener('DOMContentLoaded', start);
else start();
