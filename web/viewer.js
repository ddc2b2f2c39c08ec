// The saliency viewer of `meshsal view` pages: bundled with three.js by esbuild at build
// time (CMakeLists.txt) and inlined into every page, so a page opens with no network.
// It reads the page's data (<script id="meshsal-data">: the mesh as GLB, the best view's
// camera, the colour bar, the statistics), draws the model with orbit controls and a
// toggle between saliency, plain shading and wireframe. document.body.dataset.status
// says how it went ("drawn" after the first frame, else "error: ..."), for the tests and
// for anyone puzzled by a blank page.
import * as THREE from 'three';
import { OrbitControls } from 'three/addons/controls/OrbitControls.js';
import { GLTFLoader } from 'three/addons/loaders/GLTFLoader.js';

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

function start() {
  const data = JSON.parse(document.getElementById('meshsal-data').textContent);
  const host = document.getElementById('view');
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
  camera.position.set(...c.eye);
  camera.up.set(...c.up);
  camera.near = radius * 1e-3;
  camera.far = radius * 4;
  const scene = new THREE.Scene();
  scene.add(new THREE.HemisphereLight(0xffffff, 0x808080, 1.2));
  const light = new THREE.DirectionalLight(0xffffff, 1.6);
  light.position.set(0, 0, 1);
  camera.add(light);  // a headlight: lit from wherever the viewer looks
  scene.add(camera);
  const controls = new OrbitControls(camera, renderer.domElement);
  controls.target.set(...c.target);
  controls.update();

  function resize() {
    const w = host.clientWidth, h = host.clientHeight;
    const half = c.half_extent * 1.05, aspect = w / h;
    camera.left = -half * Math.max(aspect, 1);
    camera.right = half * Math.max(aspect, 1);
    camera.top = half / Math.min(aspect, 1);
    camera.bottom = -half / Math.min(aspect, 1);
    camera.updateProjectionMatrix();
    renderer.setSize(w, h);
  }
  window.addEventListener('resize', () => { resize(); draw(); });
  resize();

  const materials = {
    saliency: new THREE.MeshLambertMaterial({ vertexColors: true, side: THREE.DoubleSide }),
    plain: new THREE.MeshLambertMaterial({ color: 0xbebebe, side: THREE.DoubleSide }),
    wireframe: new THREE.MeshBasicMaterial({ color: 0x303030, wireframe: true }),
  };
  const meshes = [];
  let mode = 'saliency';
  function setMode(m) {
    mode = m;
    for (const mesh of meshes) mesh.material = materials[m];
    for (const b of document.querySelectorAll('#modes button')) b.classList.toggle('on', b.dataset.mode === m);
    draw();
  }
  for (const b of document.querySelectorAll('#modes button')) b.addEventListener('click', () => setMode(b.dataset.mode));

  let drawn = false;
  function draw() {
    renderer.render(scene, camera);
    if (!drawn && meshes.length) {
      drawn = true;
      if (!errors.length) document.body.dataset.status = 'drawn';
    }
  }
  controls.addEventListener('change', draw);

  new GLTFLoader().parse(base64Bytes(data.glb), '', (gltf) => {
    gltf.scene.traverse((o) => {
      if (o.isMesh) {
        o.geometry.computeVertexNormals();
        meshes.push(o);
      }
    });
    scene.add(gltf.scene);
    setMode(mode);
  }, (e) => fail('the model could not be read: ' + (e.message || e)));
}

if (document.readyState === 'loading') document.addEventListener('DOMContentLoaded', start);
else start();
