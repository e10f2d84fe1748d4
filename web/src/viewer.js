// The page of `sharpmesh view` / `sharpmesh render`: one mesh with flat
// shading, its sharp-feature polylines in a contrasting colour, optionally the
// input points and a colouring by distance to a reference. The data sits in
// the page (<script id="sharpmesh-data" type="application/json">), written by
// apps/sharpmesh/cmd_view.cpp; esbuild bundles this file with three.js so the
// page opens offline.
//
// For tests and `render`, the page reports its state on <body>:
// data-status="ready" after the first frame, data-errors = number of errors.
import * as THREE from 'three';
import { OrbitControls } from 'three/examples/jsm/controls/OrbitControls.js';
import { LineSegments2 } from 'three/examples/jsm/lines/LineSegments2.js';
import { LineSegmentsGeometry } from 'three/examples/jsm/lines/LineSegmentsGeometry.js';
import { LineMaterial } from 'three/examples/jsm/lines/LineMaterial.js';

const errors = [];
function recordError(message) {
  errors.push(String(message));
  document.body.dataset.errors = String(errors.length);
  document.body.dataset.lastError = String(message);
}
window.addEventListener('error', (e) => recordError(e.message));
window.addEventListener('unhandledrejection', (e) => recordError(e.reason));
const consoleError = console.error.bind(console);
console.error = (...args) => { recordError(args.join(' ')); consoleError(...args); };

function decode(base64, Type) {
  const bytes = Uint8Array.from(atob(base64), (c) => c.charCodeAt(0));
  return new Type(bytes.buffer);
}

function formatCount(n) { return Number(n).toLocaleString('en-US'); }
function formatLength(v) { return Number(v).toPrecision(3); }

// Camera directions of the named views (the camera looks from there at the centre; z is up).
const VIEWS = {
  iso: [1, -1.2, 0.9], front: [0, -1, 0], back: [0, 1, 0], left: [-1, 0, 0],
  right: [1, 0, 0], top: [0, 0, 1], bottom: [0, 0, -1],
};

// Colour ramp for distances: 0 = blue, max = red (through cyan, green, yellow).
function rampColor(t) {
  const stops = [[0.19, 0.31, 0.78], [0.18, 0.72, 0.86], [0.36, 0.78, 0.36], [0.98, 0.84, 0.2], [0.86, 0.18, 0.15]];
  const x = Math.min(Math.max(t, 0), 1) * (stops.length - 1);
  const i = Math.min(Math.floor(x), stops.length - 2);
  const f = x - i;
  return stops[i].map((a, k) => a + (stops[i + 1][k] - a) * f);
}

function buildMesh(data, scene) {
  const positions = decode(data.mesh.positions, Float32Array);
  const indices = decode(data.mesh.indices, Uint32Array);
  const indexed = new THREE.BufferGeometry();
  indexed.setAttribute('position', new THREE.BufferAttribute(positions, 3));
  indexed.setIndex(new THREE.BufferAttribute(indices, 1));
  let material;
  if (data.distance) {
    const d = decode(data.distance.values, Float32Array);
    const colors = new Float32Array(d.length * 3);
    for (let i = 0; i < d.length; ++i) colors.set(rampColor(d[i] / data.distance.scale), 3 * i);
    indexed.setAttribute('color', new THREE.BufferAttribute(colors, 3));
    material = new THREE.MeshLambertMaterial({ vertexColors: true, flatShading: true, side: THREE.DoubleSide });
  } else {
    material = new THREE.MeshStandardMaterial({ color: 0xcfd8e6, roughness: 0.7, metalness: 0.0, flatShading: true, side: THREE.DoubleSide });
  }
  // Keep the surface a little behind lines drawn on it (features, wireframe).
  material.polygonOffset = true;
  material.polygonOffsetFactor = 1;
  material.polygonOffsetUnits = 1;
  const geometry = indexed.toNonIndexed();
  geometry.computeVertexNormals();
  scene.add(new THREE.Mesh(geometry, material));
  const wire = new THREE.LineSegments(new THREE.WireframeGeometry(indexed),
    new THREE.LineBasicMaterial({ color: 0x1d2330, transparent: true, opacity: Math.min(0.2, 0.2 * Math.sqrt(20000 / data.mesh.facets)) }));
  wire.visible = data.wireframe;
  scene.add(wire);
  return wire;
}

function buildFeatures(data, scene, resolution) {
  const positions = decode(data.features.positions, Float32Array);
  if (positions.length === 0) return null;
  const geometry = new LineSegmentsGeometry();
  geometry.setPositions(positions);
  const material = new LineMaterial({ color: 0xe4572e, linewidth: 3.0, worldUnits: false });
  material.resolution.copy(resolution);
  const lines = new LineSegments2(geometry, material);
  scene.add(lines);
  return material;
}

function buildPoints(data, scene) {
  const geometry = new THREE.BufferGeometry();
  geometry.setAttribute('position', new THREE.BufferAttribute(decode(data.points.positions, Float32Array), 3));
  const points = new THREE.Points(geometry, new THREE.PointsMaterial({ color: 0x2f3b52, size: 2, sizeAttenuation: false }));
  scene.add(points);
  return points;
}

function overlay(data) {
  const rows = [];
  rows.push(`<b>${data.title}</b>`);
  rows.push(`${formatCount(data.mesh.facets)} facets, ${formatCount(data.mesh.vertices)} vertices`);
  if (data.features) rows.push(`<span class="feature">&#9644;</span> ${formatCount(data.features.polylines)} feature polylines, ${formatCount(data.features.segments)} segments`);
  if (data.points) rows.push(`${formatCount(data.points.count)} input points`);
  if (data.distance) {
    const s = data.distance;
    rows.push(`distance to ${s.reference}: mean ${formatLength(s.mean)}, max ${formatLength(s.max)} (${formatLength(100 * s.max / data.diagonal)}% of the diagonal)`);
    rows.push(`<span class="ramp"></span> 0 &ndash; ${formatLength(s.scale)}`);
  }
  const info = document.getElementById('info');
  info.innerHTML = rows.join('<br>');
  document.getElementById('help').textContent = 'drag: rotate · right-drag: pan · wheel: zoom · w: wireframe · p: points · 1-7: views' + (data.cameras ? ' · c/C: cameras' : '');
}

function main() {
  const data = JSON.parse(document.getElementById('sharpmesh-data').textContent);
  const canvas = document.getElementById('canvas');
  const renderer = new THREE.WebGLRenderer({ canvas, antialias: true, preserveDrawingBuffer: true });
  renderer.setPixelRatio(window.devicePixelRatio || 1);
  renderer.setSize(window.innerWidth, window.innerHeight);
  renderer.setClearColor(0xf5f6f8);
  const scene = new THREE.Scene();
  scene.add(new THREE.HemisphereLight(0xffffff, 0x707888, 1.0));
  const camera = new THREE.PerspectiveCamera(30, window.innerWidth / window.innerHeight, data.diagonal * 1e-3, data.diagonal * 100);
  camera.up.set(0, 0, 1);
  const key = new THREE.DirectionalLight(0xffffff, 2.2);
  camera.add(key);
  key.position.set(-0.6, 0.9, 0.5);
  scene.add(camera);

  const resolution = new THREE.Vector2(window.innerWidth, window.innerHeight);
  const wire = buildMesh(data, scene);
  const featureMaterial = data.features ? buildFeatures(data, scene, resolution) : null;
  const points = data.points ? buildPoints(data, scene) : null;
  overlay(data);

  const controls = new OrbitControls(camera, canvas);
  // The named views are given for z up; `data.up` turns them to the world's up.
  const worldUp = new THREE.Vector3(...data.up).normalize();
  const toWorld = new THREE.Quaternion().setFromUnitVectors(new THREE.Vector3(0, 0, 1), worldUp);
  function setView(name) {
    const dir = new THREE.Vector3(...(VIEWS[name] || VIEWS.iso)).normalize().applyQuaternion(toWorld);
    camera.fov = 30;
    camera.updateProjectionMatrix();
    const distance = 0.5 * data.diagonal / Math.tan(THREE.MathUtils.degToRad(camera.fov / 2)) * 0.92;
    camera.position.copy(dir.multiplyScalar(distance));
    if (name === 'top' || name === 'bottom') camera.up.set(0, 1, 0).applyQuaternion(toWorld); else camera.up.copy(worldUp);
    controls.target.set(0, 0, 0);
    camera.lookAt(0, 0, 0);
    controls.update();
  }
  // Looking through an input camera: its centre, direction, up and field of view.
  const cameras = data.cameras || [];
  let current = -1;
  function setCamera(i) {
    current = (i + cameras.length) % cameras.length;
    const c = cameras[current];
    camera.fov = c.fov;
    camera.updateProjectionMatrix();
    camera.position.set(...c.position);
    camera.up.set(...c.up);
    const forward = new THREE.Vector3(...c.forward);
    // Orbit about the point straight ahead at the depth of the mesh's centre.
    const depth = Math.max(-camera.position.dot(forward), 0.1 * data.diagonal);
    const target = camera.position.clone().addScaledVector(forward, depth);
    controls.target.copy(target);
    camera.lookAt(target);
    controls.update();
    const label = document.getElementById('camera-name');
    if (label) label.textContent = `camera: ${c.name}`;
  }
  if (cameras.length > 0) {
    const bar = document.createElement('div');
    bar.id = 'cameras';
    const label = document.createElement('div');
    label.id = 'camera-name';
    bar.appendChild(label);
    cameras.forEach((c, i) => {
      const button = document.createElement('button');
      button.textContent = c.name;
      button.addEventListener('click', () => { setCamera(i); render(); });
      bar.appendChild(button);
    });
    document.getElementById('info').appendChild(bar);
  }
  const hashView = new URLSearchParams(location.hash.slice(1)).get('view');
  if (data.camera >= 0 && !hashView) setCamera(data.camera); else setView(hashView || data.view);

  function render() {
    renderer.render(scene, camera);
  }
  controls.addEventListener('change', render);
  window.addEventListener('resize', () => {
    camera.aspect = window.innerWidth / window.innerHeight;
    camera.updateProjectionMatrix();
    renderer.setSize(window.innerWidth, window.innerHeight);
    resolution.set(window.innerWidth, window.innerHeight);
    if (featureMaterial) featureMaterial.resolution.copy(resolution);
    render();
  });
  const names = Object.keys(VIEWS);
  window.addEventListener('keydown', (e) => {
    if (e.key === 'w') wire.visible = !wire.visible;
    else if (e.key === 'p' && points) points.visible = !points.visible;
    else if (e.key >= '1' && e.key <= String(names.length)) setView(names[Number(e.key) - 1]);
    else if ((e.key === 'c' || e.key === 'C') && cameras.length > 0) setCamera(current + (e.key === 'c' ? 1 : -1));
    else return;
    render();
  });
  render();
  requestAnimationFrame(() => {
    render();
    document.body.dataset.status = 'ready';
  });
}

try {
  main();
} catch (e) {
  recordError(e && e.stack ? e.stack : e);
  document.body.dataset.status = 'failed';
}
