// rbla browser viewer: blocks, collapse mechanism (exact rigid motion), interface states.
import * as THREE from 'three';
import { OrbitControls } from 'three/examples/jsm/controls/OrbitControls.js';
import {
  STATE_COLORS, STATE_ORDER, triangulatePolygon, polyhedronMassProps, resultBlockMap, headline,
  fmt, norm, interfacePolygon,
} from '../../exchange/lib/rbla-geometry.mjs';

const ROLE_COLORS = { free: '#d8c3a0', fixed: '#6b6b6b', moving_support: '#2ca02c' };
const $ = (id) => document.getElementById(id);

// ---- test hook ------------------------------------------------------------------------------------
const hook = {
  ready: false,
  error: null,
  blockCount: 0,
  interfaceCount: 0,
  crackedCount: 0,
  stateCounts: {},
  title: '',
  headline: '',
  verdict: '',
  amplitude: 0,
  maxAmplitude: 0,
  frames: 0,
  setAmplitude: (s) => setAmplitude(s, true),
  load: (model, result) => show(model, result),
};
window.rblaViewer = hook;

// ---- three.js scene -------------------------------------------------------------------------------
const canvas = $('view');
const renderer = new THREE.WebGLRenderer({ canvas, antialias: true, preserveDrawingBuffer: true });
renderer.setPixelRatio(Math.min(window.devicePixelRatio || 1, 2));
const scene = new THREE.Scene();
scene.background = new THREE.Color('#f4f4f2');
const camera = new THREE.PerspectiveCamera(35, 1, 0.01, 1e6);
const controls = new OrbitControls(camera, canvas);
scene.add(new THREE.HemisphereLight(0xffffff, 0x8a8a8a, 2.2));
const sun = new THREE.DirectionalLight(0xffffff, 1.4);
scene.add(sun);
let root = new THREE.Group();
scene.add(root);
let movers = []; // { object, g:Vector3, u:Vector3, w:Vector3 }
let animating = false;
let animT0 = 0;

function resize() {
  const w = canvas.clientWidth, h = canvas.clientHeight;
  if (canvas.width !== Math.floor(w * renderer.getPixelRatio()) || canvas.height !== Math.floor(h * renderer.getPixelRatio())) {
    renderer.setSize(w, h, false);
    camera.aspect = w / Math.max(h, 1);
    camera.updateProjectionMatrix();
  }
}

function render() {
  resize();
  renderer.render(scene, camera);
  hook.frames++;
}

function loop(t) {
  if (animating) {
    const period = 3000;
    const phase = ((t - animT0) % period) / period;
    setAmplitude(hook.maxAmplitude * 0.5 * (1 - Math.cos(2 * Math.PI * phase)), false);
  }
  controls.update();
  render();
  requestAnimationFrame(loop);
}
requestAnimationFrame(loop);

// ---- geometry -------------------------------------------------------------------------------------
function blockGeometry(vertices, faces, g) {
  const pos = [];
  for (const f of faces) {
    const pts = f.map((i) => vertices[i]);
    for (const tri of triangulatePolygon(pts)) for (const k of tri) { const p = pts[k]; pos.push(p[0] - g[0], p[1] - g[1], p[2] - g[2]); }
  }
  const geo = new THREE.BufferGeometry();
  geo.setAttribute('position', new THREE.Float32BufferAttribute(pos, 3));
  geo.computeVertexNormals();
  return geo;
}

function edgesGeometry(vertices, faces, g) {
  const seen = new Set();
  const pos = [];
  for (const f of faces) for (let k = 0; k < f.length; k++) {
    const a = f[k], b = f[(k + 1) % f.length];
    const key = a < b ? `${a},${b}` : `${b},${a}`;
    if (seen.has(key)) continue;
    seen.add(key);
    for (const i of [a, b]) pos.push(vertices[i][0] - g[0], vertices[i][1] - g[1], vertices[i][2] - g[2]);
  }
  const geo = new THREE.BufferGeometry();
  geo.setAttribute('position', new THREE.Float32BufferAttribute(pos, 3));
  return geo;
}

function polygonGeometry(pts, g) {
  const pos = [];
  for (const tri of triangulatePolygon(pts)) for (const k of tri) { const p = pts[k]; pos.push(p[0] - g[0], p[1] - g[1], p[2] - g[2]); }
  const geo = new THREE.BufferGeometry();
  geo.setAttribute('position', new THREE.Float32BufferAttribute(pos, 3));
  return geo;
}

const gravityUp = { '-z': [0, 0, 1], '+z': [0, 0, -1], '-y': [0, 1, 0], '+y': [0, -1, 0], '-x': [1, 0, 0], '+x': [-1, 0, 0] };

function clear() {
  scene.remove(root);
  root.traverse((o) => { o.geometry?.dispose?.(); o.material?.dispose?.(); });
  root = new THREE.Group();
  scene.add(root);
  movers = [];
}

function show(model, result) {
  clear();
  const res = result || { blocks: [], interfaces: [] };
  const rb = resultBlockMap(res);
  const centroids = new Map();
  const box = new THREE.Box3();
  const edgeMat = new THREE.LineBasicMaterial({ color: 0x3a3a3a, transparent: true, opacity: 0.55 });
  const ghostMat = new THREE.LineBasicMaterial({ color: 0x777777, transparent: true, opacity: 0.22 });
  const mats = {};
  const matFor = (hex) => (mats[hex] ||= new THREE.MeshLambertMaterial({ color: hex, polygonOffset: true, polygonOffsetFactor: 1, polygonOffsetUnits: 1 }));
  let blockCount = 0;
  const holders = new Map();
  for (const b of model.blocks) {
    const role = b.role || 'free';
    const { centroid: g } = polyhedronMassProps(b.vertices, b.faces);
    centroids.set(b.id, g);
    for (const v of b.vertices) box.expandByPoint(new THREE.Vector3(v[0], v[1], v[2]));
    const r = rb.get(b.id);
    const holder = new THREE.Group();
    holder.position.set(g[0], g[1], g[2]);
    holder.userData.blockId = b.id;
    const hex = r?.falling ? '#e377c2' : ROLE_COLORS[role] || ROLE_COLORS.free;
    const mesh = new THREE.Mesh(blockGeometry(b.vertices, b.faces, g), matFor(hex));
    mesh.userData.block = true;
    holder.add(mesh);
    holder.add(new THREE.LineSegments(edgesGeometry(b.vertices, b.faces, g), edgeMat));
    root.add(holder);
    holders.set(b.id, holder);
    blockCount++;
    const moving = r && (norm(r.translation || [0, 0, 0]) > 0 || norm(r.rotation || [0, 0, 0]) > 0);
    if (moving) {
      // ghost of the original position
      const ghost = new THREE.LineSegments(edgesGeometry(b.vertices, b.faces, g), ghostMat);
      ghost.position.set(g[0], g[1], g[2]);
      root.add(ghost);
      movers.push({ object: holder, g: new THREE.Vector3(...g), u: new THREE.Vector3(...(r.translation || [0, 0, 0])), w: new THREE.Vector3(...(r.rotation || [0, 0, 0])) });
    }
  }
  // interfaces, attached to blocks[1] (the block the interface force acts on)
  const counts = Object.fromEntries(STATE_ORDER.map((k) => [k, 0]));
  let cracked = 0;
  const ifMats = {};
  for (const iface of res.interfaces || []) {
    const st = STATE_ORDER.includes(iface.state) ? iface.state : 'closed';
    counts[st]++;
    if (iface.cracked) cracked++;
    const pts = interfacePolygon(iface);
    const holder = holders.get(iface.blocks?.[1]) || holders.get(iface.blocks?.[0]);
    if (!holder || pts.length < 2) continue;
    const g = centroids.get(holder.userData.blockId);
    ifMats[st] ||= new THREE.MeshBasicMaterial({
      color: STATE_COLORS[st], side: THREE.DoubleSide, transparent: st === 'closed', opacity: st === 'closed' ? 0.35 : 1,
      polygonOffset: true, polygonOffsetFactor: -2, polygonOffsetUnits: -4, depthWrite: st !== 'closed',
    });
    if (pts.length >= 3) {
      const m = new THREE.Mesh(polygonGeometry(pts, g), ifMats[st]);
      m.renderOrder = 1;
      holder.add(m);
    } else {
      const geo = new THREE.BufferGeometry();
      geo.setAttribute('position', new THREE.Float32BufferAttribute(pts.flatMap((p) => [p[0] - g[0], p[1] - g[1], p[2] - g[2]]), 3));
      holder.add(new THREE.Line(geo, new THREE.LineBasicMaterial({ color: STATE_COLORS[st] })));
    }
  }
  if (Array.isArray(res.cracked_interfaces) && res.cracked_interfaces.length > cracked) cracked = res.cracked_interfaces.length;

  // camera: look along the planar axis (or y) with gravity pointing down
  const up = gravityUp[model.gravity || '-z'];
  camera.up.set(...up);
  const center = box.getCenter(new THREE.Vector3());
  const size = box.getSize(new THREE.Vector3()).length() || 1;
  const axis = res.analysis?.planar_axis || 'y';
  const viewDir = { x: new THREE.Vector3(1, 0, 0), y: new THREE.Vector3(0, -1, 0), z: new THREE.Vector3(0, 0, 1) }[axis].clone();
  if (Math.abs(viewDir.dot(new THREE.Vector3(...up))) > 0.9) viewDir.set(0, -1, 0);
  const side = new THREE.Vector3().crossVectors(new THREE.Vector3(...up), viewDir).normalize();
  const dir = viewDir.clone().multiplyScalar(1).add(side.multiplyScalar(0.35)).add(new THREE.Vector3(...up).multiplyScalar(0.25)).normalize();
  const dist = size / (2 * Math.tan((camera.fov * Math.PI) / 360)) * 0.95;
  camera.position.copy(center.clone().add(dir.multiplyScalar(dist)));
  camera.near = size / 1000; camera.far = size * 100;
  camera.updateProjectionMatrix();
  controls.target.copy(center);
  sun.position.copy(center.clone().add(new THREE.Vector3(size, -size * 1.5, size * 2)));
  controls.update();

  // text panel
  const h = headline(res);
  const modelTitle = model.title || res.model?.title || 'rbla model';
  hook.blockCount = blockCount;
  hook.interfaceCount = (res.interfaces || []).length;
  hook.crackedCount = cracked;
  hook.stateCounts = counts;
  hook.headline = h.text;
  hook.verdict = res.verdict || '';
  hook.title = `rbla \u2014 ${h.text} \u2014 ${modelTitle}`;
  document.title = hook.title;
  $('headline').textContent = h.text;
  $('model-title').textContent = modelTitle;
  $('verdict').textContent = res.verdict || 'no result loaded';
  $('verdict').className = `verdict status-${res.status || 'none'}`;
  $('note').textContent = res.mechanism?.scale_note ? `velocities: ${res.mechanism.scale_note}` : '';
  const legend = $('legend');
  legend.innerHTML = '';
  for (const st of STATE_ORDER) {
    const li = document.createElement('li');
    li.innerHTML = `<span class="sw" style="background:${STATE_COLORS[st]}"></span>${st.replace('_', ' + ')} <span class="n">${counts[st]}</span>`;
    legend.appendChild(li);
  }
  for (const [role, hex] of Object.entries(ROLE_COLORS)) {
    const li = document.createElement('li');
    li.innerHTML = `<span class="sw block" style="background:${hex}"></span>${role.replace('_', ' ')} block`;
    legend.appendChild(li);
  }
  const s0 = res.mechanism?.displacement_scale ?? 0;
  hook.maxAmplitude = movers.length ? 2 * s0 : 0;
  const slider = $('amplitude');
  slider.max = String(hook.maxAmplitude || 1);
  slider.step = 'any';
  slider.disabled = movers.length === 0;
  $('play').disabled = movers.length === 0;
  setAmplitude(s0, true);
  setSeeThrough($('xray').checked);
  hook.ready = true;
}

const qTmp = new THREE.Quaternion();
const vTmp = new THREE.Vector3();
function setAmplitude(s, stopAnimation) {
  s = Math.max(0, Number(s) || 0);
  if (stopAnimation) { animating = false; $('play').textContent = 'Animate'; }
  hook.amplitude = s;
  // exact rigid motion p -> g + R(s w)(p - g) + s u: the holder's local frame is centred on g
  for (const m of movers) {
    const th = m.w.length() * s;
    if (th > 0) qTmp.setFromAxisAngle(vTmp.copy(m.w).normalize(), th); else qTmp.identity();
    m.object.quaternion.copy(qTmp);
    m.object.position.copy(m.g).addScaledVector(m.u, s);
  }
  const slider = $('amplitude');
  if (stopAnimation || document.activeElement !== slider) slider.value = String(s);
  $('amp-value').textContent = fmt(s);
  render();
}

// ---- UI -------------------------------------------------------------------------------------------
$('amplitude').addEventListener('input', (e) => setAmplitude(e.target.value, true));
$('xray').addEventListener('change', (e) => setSeeThrough(e.target.checked));
function setSeeThrough(on) {
  hook.seeThrough = on;
  root.traverse((o) => {
    if (o.isMesh && o.userData.block) { o.material.transparent = on; o.material.opacity = on ? 0.3 : 1; o.material.depthWrite = !on; o.material.needsUpdate = true; }
  });
  render();
}
hook.setSeeThrough = setSeeThrough;
$('play').addEventListener('click', () => {
  animating = !animating;
  animT0 = performance.now();
  $('play').textContent = animating ? 'Stop' : 'Animate';
});

let pending = { model: null, result: null };
async function readJsonFile(input) {
  const f = input.files?.[0];
  return f ? JSON.parse(await f.text()) : null;
}
for (const which of ['model', 'result']) {
  $(`${which}-file`).addEventListener('change', async (e) => {
    try {
      pending[which] = await readJsonFile(e.target);
      if (pending.model) show(pending.model, pending.result);
    } catch (err) { fail(err); }
  });
}

function fail(err) {
  hook.error = String(err && err.message ? err.message : err);
  $('verdict').textContent = `error: ${hook.error}`;
  $('verdict').className = 'verdict status-error';
}

async function fromUrl() {
  const q = new URLSearchParams(location.search);
  const mu = q.get('model');
  if (!mu) { $('verdict').textContent = 'Open a model JSON and its result JSON.'; hook.ready = true; return; }
  try {
    const get = async (u) => { const r = await fetch(u); if (!r.ok) throw new Error(`${u}: HTTP ${r.status}`); return r.json(); };
    const [model, result] = await Promise.all([get(mu), q.get('result') ? get(q.get('result')) : Promise.resolve(null)]);
    pending = { model, result };
    show(model, result);
    if (q.get('amplitude') !== null) setAmplitude(Number(q.get('amplitude')), true);
    if (q.get('animate') === '1') $('play').click();
  } catch (err) { fail(err); hook.ready = true; }
}
fromUrl();
