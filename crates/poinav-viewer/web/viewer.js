// poinav viewer: the building (GLB from /api/model.glb) and the live robots (states over /ws).
//
// Server messages (JSON text):
//   {"type":"events","events":[...]}  recent POI events, sent once on connect
//   {"type":"state","storey":i,"step":N,"t":s,"paused":b,"robots":[{name,x,y,heading_deg,speed,mode,
//     brush:{on,angle_deg},roles:[...],rays:[{deg,d,hit,class}]}],"events":[...]}  every step
//   {"type":"error","message":"..."}  a refused message of ours
// Page messages: {"type":"key","robot":i,"key":"ArrowUp","down":true}, {"type":"brush","robot":i},
//   {"type":"pause","paused":b}, {"type":"reset"}, {"type":"storey","index":i}.
// The scene (/api/scene) lists every storey (`storeys`: elevation, bounds, robots with start
// poses, doors with passage rings and status, zones, `structure` outlines); `current` is the one
// simulated first. The page shows a storey cut by a horizontal section plane at a set height
// above its floor (everything above is clipped; cut walls get flat caps), so the robots, their
// rays and the doors' colours are visible from above; switching storey is the server's
// decision (every page follows the state's `storey`).
// Coordinates: plan (x, y) on the storey at elevation e is three.js (x, e + h, -y), as in the GLB.

import * as THREE from 'three';
import { GLTFLoader } from 'three/addons/loaders/GLTFLoader.js';
import { OrbitControls } from 'three/addons/controls/OrbitControls.js';
import { VRButton } from 'three/addons/webxr/VRButton.js';

const BACKGROUND = 0xf1f5f9;
const $ = (id) => document.getElementById(id);

// Colours of the POI view: doors by accessibility status, other elements by primary role.
const STATUS_COLOURS = {
  FULL_ACCESS: '#16a34a',
  RESTRICTED: '#f59e0b',
  BLOCKED: '#dc2626',
  PENDING_VALIDATION: '#94a3b8',
};
const ROLE_COLOURS = {
  'B-1': '#ef4444',
  'B-2': '#f97316',
  'A-2': '#22c55e',
  'C-1': '#a855f7',
  'C-2': '#d946ef',
  'A-3': '#0ea5e9',
  'A-1': '#64748b',
  Destination: '#eab308',
};
const ROLE_ORDER = ['B-1', 'B-2', 'A-2', 'C-1', 'C-2', 'A-3', 'Destination', 'A-1'];
const NO_ROLE = '#e2e8f0';
// Roles as a list, whether written `A-1;A-3` (IFC) or as an array (GLB extras).
const roleList = (v) => (Array.isArray(v) ? v : String(v ?? '').split(';').filter(Boolean));

const hook = {
  ready: false,
  errors: [],
  camera: 'perspective',
  scene: null,
  elements: 0,
  lastState: null,
  states: 0,
  storey: null,
  follow: false,
  cut_m: 1.5,
  xray: false,
  firstFrameMs: null,
  buildingMs: null,
  buildingFrameMs: null,
};
window.poinav = hook;
window.addEventListener('error', (e) => hook.errors.push(String(e.message)));

// ---------------------------------------------------------------- renderer, cameras, lights
const view = $('view');
const renderer = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
renderer.setPixelRatio(window.devicePixelRatio);
renderer.xr.enabled = true;
view.appendChild(renderer.domElement);
// The section plane: keeps what lies below elevation + cut (world y up); off in X-ray view.
const cutPlane = new THREE.Plane(new THREE.Vector3(0, -1, 0), 1.5);
const vrButton = VRButton.createButton(renderer);
vrButton.id = 'vr-button';
view.appendChild(vrButton);

// In VR the headset's floor is y = 0 at the user's feet: stand the user on the storey's floor,
// beside Robot1 (else at the centre of the view).
renderer.xr.addEventListener('sessionstart', () => {
  const pose = liveRobots[0]?.pose;
  const at = pose ? new THREE.Vector3(pose.x - 1.5, 0, -pose.y) : orbit.target.clone();
  scene.position.set(-at.x, -elevation, -at.z);
  applyCut();
});
renderer.xr.addEventListener('sessionend', () => { scene.position.set(0, 0, 0); applyCut(); });

const scene = new THREE.Scene();
scene.background = new THREE.Color(BACKGROUND);
scene.add(new THREE.HemisphereLight(0xffffff, 0x94a3b8, 2.2));
const sun = new THREE.DirectionalLight(0xffffff, 1.6);
sun.position.set(30, 60, 20);
scene.add(sun);

const perspective = new THREE.PerspectiveCamera(50, 1, 0.05, 5000);
const top = new THREE.OrthographicCamera(-10, 10, 10, -10, -1000, 1000);
top.up.set(0, 0, -1); // plan +y is up on screen
let camera = perspective;
const orbit = new OrbitControls(perspective, renderer.domElement);
const pan = new OrbitControls(top, renderer.domElement);
pan.enableRotate = false;
pan.enabled = false;
pan.screenSpacePanning = true;

function resize() {
  const w = view.clientWidth || 1;
  const h = view.clientHeight || 1;
  renderer.setSize(w, h);
  perspective.aspect = w / h;
  perspective.updateProjectionMatrix();
  fitTop();
}
window.addEventListener('resize', resize);

let bounds = { min: [-10, -10], max: [10, 10] };
let elevation = 0;
function fitTop() {
  const w = view.clientWidth || 1;
  const h = view.clientHeight || 1;
  const cx = (bounds.min[0] + bounds.max[0]) / 2;
  const cy = (bounds.min[1] + bounds.max[1]) / 2;
  const half = Math.max((bounds.max[0] - bounds.min[0]) / 2, (bounds.max[1] - bounds.min[1]) / 2 * (w / h)) * 1.1 + 0.5;
  top.left = -half;
  top.right = half;
  top.top = half * h / w;
  top.bottom = -half * h / w;
  top.position.set(cx, elevation + 100, -cy);
  top.lookAt(cx, elevation, -cy);
  pan.target.set(cx, elevation, -cy);
  top.zoom = 1;
  top.updateProjectionMatrix();
  pan.update();
}

// The first view: the storey from above at an angle, all of it (and so its robots) in view.
function frameStorey() {
  const cx = (bounds.min[0] + bounds.max[0]) / 2;
  const cy = (bounds.min[1] + bounds.max[1]) / 2;
  const radius = Math.max(4, Math.hypot(bounds.max[0] - bounds.min[0], bounds.max[1] - bounds.min[1]) / 2);
  const distance = (radius / Math.sin((perspective.fov * Math.PI) / 360)) * 1.05;
  const target = new THREE.Vector3(cx, elevation, -cy);
  orbit.target.copy(target);
  perspective.position.copy(target).add(new THREE.Vector3(0.3, 0.85, 0.45).normalize().multiplyScalar(distance));
  perspective.near = Math.max(0.01, distance / 2000);
  perspective.far = distance * 50;
  perspective.updateProjectionMatrix();
  orbit.update();
}

let cutHeight = 1.5; // section height above the storey's floor, metres
let xray = false;
function applyCut() {
  cutPlane.constant = elevation + cutHeight + scene.position.y;
  renderer.clippingPlanes = xray ? [] : [cutPlane];
  capGroup.position.y = elevation + cutHeight - 0.01;
  capGroup.visible = !xray;
  // Elements wholly above the plane are not drawn at all: the plane would clip all of them,
  // but software WebGL would still pay for their vertices.
  const cutY = elevation + cutHeight;
  for (const [object, bottom] of elementBottoms) object.visible = xray || bottom < cutY;
  $('cut-value').textContent = `${cutHeight.toFixed(1)} m`;
  hook.cut_m = cutHeight;
  hook.xray = xray;
}

function setCamera(which) {
  camera = which === 'top' ? top : perspective;
  orbit.enabled = which !== 'top';
  pan.enabled = which === 'top';
  hook.camera = which;
  $('camera').textContent = which === 'top' ? 'Camera: top-down' : 'Camera: perspective';
}
$('camera').addEventListener('click', () => setCamera(hook.camera === 'top' ? 'perspective' : 'top'));

// ---------------------------------------------------------------- building
const elementMeshes = []; // meshes that a click can hit, each with .userData.element
const elementsById = new Map(); // GlobalId -> { object, meshes, originals }
let zoneGroup = new THREE.Group();
scene.add(zoneGroup);
let capGroup = new THREE.Group(); // flat caps where the section plane cuts walls and columns
scene.add(capGroup);
let doorGroup = new THREE.Group(); // door and doorway passages on the floor, coloured by status
scene.add(doorGroup);
const doorMeshes = new Map(); // door GlobalId -> mesh
const elementBottoms = []; // [element node, lowest y of its meshes in the scene's frame]
let poiView = false;

function elementColour(data) {
  if (data.AccessibilityStatus && /Door|Opening/.test(data.IfcClass || '')) {
    return STATUS_COLOURS[data.AccessibilityStatus] || NO_ROLE;
  }
  const roles = roleList(data.POI_PrimaryRoles).concat(roleList(data.POI_ConditionalRoles));
  for (const r of ROLE_ORDER) if (roles.includes(r)) return ROLE_COLOURS[r];
  return NO_ROLE;
}

// A see-through copy of a material, for the X-ray view.
const xrayMaterials = new WeakMap();
function xrayOf(material) {
  if (!xrayMaterials.has(material)) {
    const m = material.clone();
    m.transparent = true;
    m.opacity = 0.18;
    m.depthWrite = false;
    xrayMaterials.set(material, m);
  }
  return xrayMaterials.get(material);
}

function applyColours() {
  for (const { meshes, originals, object } of elementsById.values()) {
    const colour = elementColour(object.userData);
    meshes.forEach((m, i) => {
      let solid = originals[i];
      if (poiView) {
        if (!m.userData.poiMaterial) m.userData.poiMaterial = new THREE.MeshLambertMaterial();
        m.userData.poiMaterial.color.set(colour);
        solid = m.userData.poiMaterial;
      }
      m.material = xray ? xrayOf(solid) : solid;
    });
  }
  for (const [id, mesh] of doorMeshes) {
    const status = elementsById.get(id)?.object.userData.AccessibilityStatus ?? mesh.userData.status;
    mesh.material.color.set(STATUS_COLOURS[status] || NO_ROLE);
  }
  zoneGroup.visible = poiView;
  $('legend').hidden = !poiView;
}
$('poi-colours').addEventListener('change', (e) => { poiView = e.target.checked; applyColours(); });

function legend() {
  const rows = Object.entries(STATUS_COLOURS).map(([k, c]) => `<div><span class="swatch" style="background:${c}"></span>door ${k}</div>`);
  for (const r of ROLE_ORDER) rows.push(`<div><span class="swatch" style="background:${ROLE_COLOURS[r]}"></span>${r}</div>`);
  $('legend').innerHTML = rows.join('');
}

function addZones(info) {
  scene.remove(zoneGroup);
  zoneGroup = new THREE.Group();
  zoneGroup.visible = poiView;
  for (const z of info.zones || []) {
    if (z.ring.length < 3) continue;
    const shape = new THREE.Shape(z.ring.map(([x, y]) => new THREE.Vector2(x, y)));
    const geometry = new THREE.ShapeGeometry(shape);
    geometry.rotateX(-Math.PI / 2); // plan (x, y) -> (x, 0, -y)
    const roles = z.roles || [];
    const role = ROLE_ORDER.find((r) => roles.includes(r));
    const material = new THREE.MeshBasicMaterial({
      color: role ? ROLE_COLOURS[role] : NO_ROLE, transparent: true, opacity: 0.35, depthWrite: false, side: THREE.DoubleSide,
    });
    const mesh = new THREE.Mesh(geometry, material);
    mesh.position.y = elevation + 0.02;
    mesh.userData.element = z.id;
    zoneGroup.add(mesh);
  }
  scene.add(zoneGroup);
}

function flat(ring, material, y) {
  const geometry = new THREE.ShapeGeometry(new THREE.Shape(ring.map(([x, yy]) => new THREE.Vector2(x, yy))));
  geometry.rotateX(-Math.PI / 2); // plan (x, y) -> (x, 0, -y)
  const mesh = new THREE.Mesh(geometry, material);
  mesh.position.y = y;
  return mesh;
}

// The storey's caps (walls and columns where the plane cuts them) and door passages.
function addOverlays(info) {
  for (const g of [capGroup, doorGroup]) {
    scene.remove(g);
    g.traverse((o) => { if (o.isMesh) { o.geometry.dispose(); o.material.dispose?.(); } });
  }
  capGroup = new THREE.Group();
  const cap = new THREE.MeshBasicMaterial({ color: 0x334155, side: THREE.DoubleSide });
  for (const { id, ring } of info.structure || []) {
    if (ring.length < 3) continue;
    const mesh = flat(ring, cap, 0);
    mesh.userData.element = id;
    capGroup.add(mesh);
  }
  doorGroup = new THREE.Group();
  doorMeshes.clear();
  for (const d of info.doors || []) {
    if (!d.ring || d.ring.length < 3) continue;
    const status = elementsById.get(d.id)?.object.userData.AccessibilityStatus ?? d.status;
    const material = new THREE.MeshBasicMaterial({ color: STATUS_COLOURS[status] || NO_ROLE, side: THREE.DoubleSide });
    const mesh = flat(d.ring, material, elevation + 0.03);
    mesh.userData.element = d.id;
    mesh.userData.status = d.status;
    doorGroup.add(mesh);
    doorMeshes.set(d.id, mesh);
  }
  scene.add(capGroup, doorGroup);
}

function megabytes(n) { return (n / 1e6).toFixed(1); }

async function loadBuilding(info) {
  const t0 = performance.now();
  let bytes = 0;
  const gltf = await new GLTFLoader().loadAsync('/api/model.glb', (e) => {
    bytes = e.loaded;
    $('progress').textContent = e.total
      ? `loading the building: ${megabytes(e.loaded)} of ${megabytes(e.total)} MB`
      : `loading the building: ${megabytes(e.loaded)} MB`;
  });
  $('progress').textContent = 'preparing the building…';
  scene.add(gltf.scene);
  gltf.scene.traverse((o) => {
    const d = o.userData || {};
    if (!d.GlobalId || d.IfcClass === 'IfcBuildingStorey') return;
    const meshes = [];
    o.traverse((m) => { if (m.isMesh) meshes.push(m); });
    meshes.forEach((m) => { m.userData.element = d.GlobalId; elementMeshes.push(m); });
    elementsById.set(d.GlobalId, { object: o, meshes, originals: meshes.map((m) => m.material) });
  });
  hook.elements = elementsById.size;
  for (const { object, meshes } of elementsById.values()) {
    if (!meshes.length) continue;
    const box = new THREE.Box3().setFromObject(object);
    elementBottoms.push([object, box.min.y - scene.position.y]);
  }
  applyCut();
  const box = new THREE.Box3().setFromObject(gltf.scene);
  if (!info.bounds && !box.isEmpty()) {
    bounds = { min: [box.min.x, -box.max.z], max: [box.max.x, -box.min.z] };
    fitTop();
    frameStorey();
  }
  hook.buildingMs = performance.now() - t0;
  $('progress').textContent = `building: ${elementsById.size} elements, ${megabytes(bytes)} MB, loaded in ${(hook.buildingMs / 1000).toFixed(1)} s`;
}

// ---------------------------------------------------------------- storeys
let storeyIndex = null;
let title = '';
function storeyOptions(info) {
  const storeys = info.storeys || [];
  $('storey').innerHTML = storeys.map((st, i) => {
    const label = `${esc(st.storey)} (${(+st.elevation_m).toFixed(2)} m)`;
    const off = st.robots && st.robots.length ? '' : ` disabled title="${esc(st.unplaced || 'no robots')}"`;
    return `<option value="${i}"${off}>${label}</option>`;
  }).join('');
  $('storey').disabled = storeys.length < 2;
}

function releaseKeys() {
  for (const code of held) send({ type: 'key', robot: KEYS[code][0], key: KEYS[code][1], down: false });
  held.clear();
}

// Shows storey `i`: its floor level, cut, caps, doors, zones and robots, and a camera on it.
function showStorey(i) {
  const st = hook.scene.storeys?.[i] ?? hook.scene;
  storeyIndex = i;
  hook.storey = i;
  elevation = st.elevation_m || 0;
  if (st.bounds) bounds = st.bounds;
  zones = st.zones || [];
  addZones(st);
  addOverlays(st);
  releaseKeys();
  for (const r of liveRobots) { scene.remove(r.group); r.rays.forEach((l) => scene.remove(l)); }
  liveRobots = (st.robots || []).map((spec, k) => makeRobot(spec, k));
  liveRobots.forEach((r) => {
    if (r.spec.start) placeRobot(r, { x: r.spec.start[0], y: r.spec.start[1], heading_deg: r.spec.heading_deg || 0, rays: [] });
  });
  if (playing) setLiveVisible(false);
  $('brushes').innerHTML = liveRobots.map((r, k) => `<button id="brush-${k}">${esc(r.spec.name)} brush</button>`).join('');
  liveRobots.forEach((r, k) => $(`brush-${k}`).addEventListener('click', () => send({ type: 'brush', robot: k })));
  $('storey').value = String(i);
  $('title').textContent = `${title} · ${st.storey}`;
  applyCut();
  applyColours();
  fitTop();
  frameStorey();
}

$('storey').addEventListener('change', (e) => send({ type: 'storey', index: Number(e.target.value) }));
$('cut').addEventListener('input', (e) => { cutHeight = Number(e.target.value); applyCut(); });
$('xray').addEventListener('change', (e) => { xray = e.target.checked; applyCut(); applyColours(); });

let follow = false;
function setFollow(on) {
  follow = on;
  hook.follow = on;
  $('follow').textContent = `Follow Robot1: ${on ? 'on' : 'off'}`;
}
$('follow').addEventListener('click', () => setFollow(!follow));

// Follow mode: both cameras keep Robot1 in the middle of the view.
function followRobot() {
  const r = (playing ? playRobots : liveRobots)[0];
  if (!follow || !r?.pose) return;
  const p = new THREE.Vector3(r.pose.x, elevation, -r.pose.y);
  const delta = p.clone().sub(orbit.target);
  if (delta.lengthSq() > 1e-8) {
    orbit.target.add(delta);
    perspective.position.add(delta);
    orbit.update();
  }
  pan.target.copy(p);
  top.position.set(p.x, elevation + 100, p.z);
  top.lookAt(p);
  pan.update();
}

// ---------------------------------------------------------------- click to inspect
const raycaster = new THREE.Raycaster();
let downAt = null;
let selected = null;
renderer.domElement.addEventListener('pointerdown', (e) => { downAt = [e.clientX, e.clientY]; });
renderer.domElement.addEventListener('pointerup', (e) => {
  if (!downAt || Math.hypot(e.clientX - downAt[0], e.clientY - downAt[1]) > 4) return;
  const r = renderer.domElement.getBoundingClientRect();
  const ndc = new THREE.Vector2(((e.clientX - r.left) / r.width) * 2 - 1, -((e.clientY - r.top) / r.height) * 2 + 1);
  raycaster.setFromCamera(ndc, camera);
  const targets = [...elementMeshes, ...(capGroup.visible ? capGroup.children : []), ...(zoneGroup.visible ? zoneGroup.children : [])];
  const hit = raycaster.intersectObjects(targets, false).find((h) => h.object.visible && belowCut(h.point));
  inspect(hit ? hit.object.userData.element : null);
});

// True for a point the section plane keeps (everything in X-ray view).
function belowCut(p) {
  return xray || cutPlane.distanceToPoint(p) >= -1e-6;
}

function esc(s) {
  return String(s ?? '').replace(/[&<>"']/g, (c) => ({ '&': '&amp;', '<': '&lt;', '>': '&gt;', '"': '&quot;', "'": '&#39;' }[c]));
}

function highlight(id, on) {
  const el = elementsById.get(id);
  if (!el) return;
  for (const m of el.meshes) {
    if (m.material.emissive) m.material = m.material.clone();
    if (m.material.emissive) m.material.emissive.set(on ? 0x1d4ed8 : 0x000000);
  }
}

async function inspect(id) {
  if (selected) highlight(selected, false);
  selected = id;
  hook.selected = id;
  if (!id) {
    $('inspect-body').innerHTML = '<span class="muted">Nothing there.</span>';
    return;
  }
  highlight(id, true);
  const el = elementsById.get(id);
  const local = el ? el.object.userData : {};
  let info = null;
  try {
    const r = await fetch(`/api/element/${encodeURIComponent(id)}`);
    if (r.ok) info = await r.json();
  } catch (err) { hook.errors.push(String(err)); }
  const rows = [['GlobalId', id], ['Class', info?.Class ?? local.IfcClass], ['Name', info?.Name ?? ''], ['Storey', info?.Storey ?? local.Storey ?? '']];
  const poi = { ...(info?.POI || {}) };
  for (const k of ['POI_Category', 'POI_Type', 'POI_PrimaryRoles', 'POI_ConditionalRoles', 'AccessibilityStatus']) {
    if (local[k] !== undefined) poi[k] = /Roles$/.test(k) ? roleList(local[k]).join(';') : local[k]; // live values (sensor findings) win
  }
  for (const [k, v] of Object.entries(poi)) rows.push([k, v]);
  let html = `<table>${rows.map(([k, v]) => `<tr><th>${esc(k)}</th><td>${esc(v)}</td></tr>`).join('')}</table>`;
  for (const [set, props] of Object.entries(info?.PropertySets || {})) {
    html += `<details><summary>${esc(set)}</summary><table>${Object.entries(props).map(([k, v]) => `<tr><th>${esc(k)}</th><td>${esc(v)}</td></tr>`).join('')}</table></details>`;
  }
  $('inspect-body').innerHTML = html;
  hook.inspected = { id, rows: Object.fromEntries(rows) };
}

// ---------------------------------------------------------------- robots
const BODY_COLOURS = ['#ea580c', '#4f46e5', '#0d9488', '#be123c'];
const BODY_HEIGHT = 0.3;

function makeRobot(spec, index) {
  const group = new THREE.Group();
  const length = spec.length_m || 0.6;
  const width = spec.width_m || 0.5;
  const body = new THREE.Mesh(new THREE.BoxGeometry(length, BODY_HEIGHT, width), new THREE.MeshLambertMaterial({ color: BODY_COLOURS[index % BODY_COLOURS.length] }));
  body.position.y = BODY_HEIGHT / 2 + 0.02;
  group.add(body);
  const nose = new THREE.Mesh(new THREE.ConeGeometry(width * 0.25, length * 0.3, 12), new THREE.MeshLambertMaterial({ color: 0xffffff }));
  nose.rotation.z = -Math.PI / 2;
  nose.position.set(length * 0.35, BODY_HEIGHT + 0.05, 0);
  group.add(nose);
  // The brush: a disc with two bars under the front, rotating while on.
  const brush = new THREE.Group();
  const disc = new THREE.Mesh(new THREE.CylinderGeometry(width * 0.3, width * 0.3, 0.02, 24), new THREE.MeshLambertMaterial({ color: 0x94a3b8 }));
  brush.add(disc);
  for (const a of [0, Math.PI / 2]) {
    const bar = new THREE.Mesh(new THREE.BoxGeometry(width * 0.62, 0.03, 0.04), new THREE.MeshLambertMaterial({ color: 0x1e293b }));
    bar.rotation.y = a;
    bar.position.y = 0.02;
    brush.add(bar);
  }
  brush.position.set(length * 0.5, 0.03, 0);
  group.add(brush);
  const rays = [];
  for (let k = 0; k < 5; k++) {
    const g = new THREE.BufferGeometry().setAttribute('position', new THREE.Float32BufferAttribute([0, 0, 0, 1, 0, 0], 3));
    const line = new THREE.Line(g, new THREE.LineBasicMaterial({ color: spec.ray_clear || '#22c55e' }));
    scene.add(line);
    rays.push(line);
  }
  scene.add(group);
  return { spec, group, brush, disc, rays, clear: new THREE.Color(spec.ray_clear || '#22c55e'), hitColour: new THREE.Color(spec.ray_hit || '#ef4444'), pose: null };
}

function placeRobot(r, s) {
  const y = elevation;
  r.group.position.set(s.x, y, -s.y);
  r.group.rotation.y = (s.heading_deg * Math.PI) / 180;
  r.brush.rotation.y = ((s.brush?.angle_deg || 0) * Math.PI) / 180;
  r.disc.material.color.set(s.brush?.on ? 0xfacc15 : 0x94a3b8);
  const rayHeight = y + BODY_HEIGHT * 0.6;
  (s.rays || []).forEach((ray, k) => {
    const line = r.rays[k];
    if (!line) return;
    const a = ((s.heading_deg + ray.deg) * Math.PI) / 180;
    const p = line.geometry.attributes.position;
    p.setXYZ(0, s.x, rayHeight, -s.y);
    p.setXYZ(1, s.x + Math.cos(a) * ray.d, rayHeight, -(s.y + Math.sin(a) * ray.d));
    p.needsUpdate = true;
    line.geometry.computeBoundingSphere();
    line.material.color.copy(ray.hit ? r.hitColour : r.clear);
  });
  r.pose = s;
}

function robotReport(r) {
  const s = r.pose;
  if (!s) return null;
  return {
    name: r.spec.name,
    x: s.x,
    y: s.y,
    heading_deg: s.heading_deg,
    speed: s.speed,
    brush_on: !!s.brush?.on,
    rays: r.rays.map((line, k) => ({ deg: s.rays?.[k]?.deg, d: s.rays?.[k]?.d, hit: s.rays?.[k]?.hit ?? null, colour: `#${line.material.color.getHexString()}` })),
  };
}

let liveRobots = [];
let playRobots = [];

// ---------------------------------------------------------------- events panel
const EVENT_LIMIT = 300;
let zones = [];
function zoneAt(x, y) {
  return zones.find((z) => {
    let c = false;
    const ring = z.ring;
    for (let i = 0, j = ring.length - 1; i < ring.length; j = i++) {
      const [xi, yi] = ring[i];
      const [xj, yj] = ring[j];
      if ((yi > y) !== (yj > y) && x < xi + ((y - yi) / (yj - yi)) * (xj - xi)) c = !c;
    }
    return c;
  });
}

function describe(e) {
  const what = e.name ? `${e.name} (${e.element || e.door})` : (e.element || e.door);
  switch (e.kind) {
    case 'role-added': return `${what}: ${e.role} added`;
    case 'role-removed': return `${what}: ${e.role} removed`;
    case 'status-changed': return `${what}: status ${e.from} → ${e.to}`;
    case 'clearance': return `${what}: clearance ${(+e.estimate_m).toFixed(3)} m (needs ${(+e.required_m).toFixed(2)} m) → ${e.status}`;
    case 'robot-role': {
      if (!e.on) return `${e.role} ended`;
      const pose = liveRobots.find((r) => r.spec.name === e.robot)?.pose;
      const zone = pose ? zoneAt(pose.x, pose.y) : null;
      const protocol = zone?.protocol ? ` — ${zone.protocol}${zone.protocol === 'SPEED_REDUCTION' ? ': speed reduced' : ''}` : '';
      return `${e.role} active: ${e.other ?? 'robot'} at ${(+e.distance_m).toFixed(2)} m${protocol}`;
    }
    case 'contact': return `contact with ${e.class} ${e.with}`;
    case 'zone-entered': return `entered ${e.name || e.zone}`;
    case 'arrived': return `arrived in ${e.name || e.zone}`;
    case 'brush': return `brush ${e.on ? 'on' : 'off'}`;
    default: return null;
  }
}

function addEvents(events) {
  const list = $('events');
  for (const e of events) {
    if (e.kind === 'key') continue;
    if (e.kind === 'status-changed' && elementsById.has(e.element)) {
      elementsById.get(e.element).object.userData.AccessibilityStatus = e.to;
      applyColours();
    }
    if ((e.kind === 'role-added' || e.kind === 'role-removed') && elementsById.has(e.element)) {
      const d = elementsById.get(e.element).object.userData;
      const roles = new Set(roleList(d.POI_ConditionalRoles));
      if (e.kind === 'role-added') roles.add(e.role); else roles.delete(e.role);
      d.POI_ConditionalRoles = [...roles];
      if (poiView) applyColours();
    }
    const text = describe(e);
    if (!text) continue;
    const li = document.createElement('li');
    li.textContent = `${(+e.t).toFixed(2)} s ${e.robot}: ${text}`;
    li.dataset.kind = e.kind;
    list.prepend(li);
    while (list.children.length > EVENT_LIMIT) list.lastChild.remove();
  }
  hook.events = list.children.length;
}

// ---------------------------------------------------------------- robots table
function robotsTable(robots) {
  $('robots').innerHTML = '<tr><th></th><th>x, y (m)</th><th>m/s</th><th>roles</th></tr>' + robots.filter((r) => r.pose).map((r) => {
    const s = r.pose;
    return `<tr><td>${esc(r.spec.name)}</td><td>${s.x.toFixed(2)}, ${s.y.toFixed(2)}</td><td>${(+s.speed || 0).toFixed(2)}</td><td>${esc((s.roles || []).join(' '))}</td></tr>`;
  }).join('');
}

// ---------------------------------------------------------------- WebSocket
let socket = null;
let playing = null; // playback state when a trace is loaded and shown
function connect() {
  socket = new WebSocket(`${location.protocol === 'https:' ? 'wss' : 'ws'}://${location.host}/ws`);
  socket.onopen = () => { $('status').textContent = 'live'; $('status').classList.remove('error'); };
  socket.onclose = () => { $('status').textContent = 'disconnected; retrying…'; $('status').classList.add('error'); setTimeout(connect, 2000); };
  socket.onmessage = (m) => {
    const msg = JSON.parse(m.data);
    if (msg.type === 'events') addEvents(msg.events);
    else if (msg.type === 'error') { $('status').textContent = `server: ${msg.message}`; $('status').classList.add('error'); }
    else if (msg.type === 'state') {
      hook.states += 1;
      hook.lastState = msg;
      if (msg.storey !== undefined && msg.storey !== storeyIndex) showStorey(msg.storey);
      msg.robots.forEach((s, i) => { if (liveRobots[i]) placeRobot(liveRobots[i], s); });
      if (msg.events.length) addEvents(msg.events);
      if (!playing) {
        robotsTable(liveRobots);
        $('status').textContent = `live · t = ${msg.t.toFixed(1)} s${msg.paused ? ' · paused' : ''}`;
      }
    }
  };
}

function send(m) {
  if (socket && socket.readyState === WebSocket.OPEN) socket.send(JSON.stringify(m));
}

const KEYS = {
  ArrowUp: [0, 'ArrowUp'], ArrowDown: [0, 'ArrowDown'], ArrowLeft: [0, 'ArrowLeft'], ArrowRight: [0, 'ArrowRight'],
  KeyW: [1, 'w'], KeyA: [1, 'a'], KeyS: [1, 's'], KeyD: [1, 'd'],
};
const held = new Set();
function typing(e) { return e.target instanceof HTMLInputElement && e.target.type !== 'checkbox' && e.target.type !== 'range'; }
window.addEventListener('keydown', (e) => {
  if (typing(e)) return;
  if (e.code === 'KeyC' && !e.repeat) { setCamera(hook.camera === 'top' ? 'perspective' : 'top'); return; }
  if (e.code === 'KeyF' && !e.repeat) { setFollow(!follow); return; }
  const k = KEYS[e.code];
  if (!k) return;
  e.preventDefault();
  if (e.repeat || held.has(e.code) || k[0] >= liveRobots.length) return;
  held.add(e.code);
  send({ type: 'key', robot: k[0], key: k[1], down: true });
});
window.addEventListener('keyup', (e) => {
  const k = KEYS[e.code];
  if (!k || !held.has(e.code)) return;
  held.delete(e.code);
  send({ type: 'key', robot: k[0], key: k[1], down: false });
});
window.addEventListener('blur', releaseKeys);
let paused = false;
$('pause').addEventListener('click', () => { paused = !paused; send({ type: 'pause', paused }); $('pause').textContent = paused ? 'Resume' : 'Pause'; });
$('reset').addEventListener('click', () => send({ type: 'reset' }));

// ---------------------------------------------------------------- playback of trace.jsonl
function parseTrace(text) {
  const byStep = new Map();
  const names = [];
  let line = 0;
  for (const raw of text.split('\n')) {
    line += 1;
    if (!raw.trim()) continue;
    let r;
    try { r = JSON.parse(raw); } catch { throw new Error(`line ${line}: not JSON`); }
    if (typeof r.step !== 'number' || typeof r.robot !== 'string' || typeof r.x !== 'number') throw new Error(`line ${line}: not a poinav trace record`);
    if (!names.includes(r.robot)) names.push(r.robot);
    if (!byStep.has(r.step)) byStep.set(r.step, { step: r.step, t: r.t, robots: {}, events: [] });
    const f = byStep.get(r.step);
    f.robots[r.robot] = r;
    for (const e of r.events || []) f.events.push({ robot: r.robot, t: r.t, ...e });
  }
  const frames = [...byStep.values()].sort((a, b) => a.step - b.step);
  if (!frames.length) throw new Error('the trace is empty');
  return { names, frames };
}

function showFrame(i) {
  const p = playing;
  p.index = Math.max(0, Math.min(i, p.frames.length - 1));
  const f = p.frames[p.index];
  p.names.forEach((n, k) => { if (f.robots[n]) placeRobot(playRobots[k], f.robots[n]); });
  $('slider').value = String(p.index);
  const end = p.frames[p.frames.length - 1].t;
  $('ptime').textContent = `t = ${f.t.toFixed(2)} s of ${end.toFixed(2)} s`;
  robotsTable(playRobots);
  if (p.index === p.frames.length - 1) { p.playing = false; p.ended = true; $('play').textContent = 'Play'; }
}

function setLiveVisible(v) {
  for (const r of liveRobots) { r.group.visible = v; r.rays.forEach((l) => { l.visible = v; }); }
  for (const r of playRobots) { r.group.visible = !v; r.rays.forEach((l) => { l.visible = !v; }); }
}

$('trace-file').addEventListener('change', async (e) => {
  const file = e.target.files[0];
  if (!file) return;
  try {
    const trace = parseTrace(await file.text());
    for (const r of playRobots) { scene.remove(r.group); r.rays.forEach((l) => scene.remove(l)); }
    playRobots = trace.names.map((n, k) => {
      const live = hook.scene.robots.find((s) => s.name === n);
      return makeRobot(live || { name: n, ray_clear: '#22c55e', ray_hit: ['#ef4444', '#3b82f6'][k] || '#f59e0b' }, k);
    });
    playing = { ...trace, index: 0, playing: false, ended: false, clock: 0, file: file.name };
    $('slider').max = String(trace.frames.length - 1);
    for (const id of ['slider', 'play', 'live']) $(id).disabled = false;
    setLiveVisible(false);
    showFrame(0);
    $('status').textContent = `playback of ${file.name}`;
  } catch (err) {
    $('ptime').textContent = `${file.name}: ${err.message}`;
  }
});
$('play').addEventListener('click', () => {
  const p = playing;
  if (!p) return;
  if (p.ended) { p.ended = false; showFrame(0); }
  p.playing = !p.playing;
  p.clock = p.frames[p.index].t;
  $('play').textContent = p.playing ? 'Pause' : 'Play';
});
$('slider').addEventListener('input', (e) => {
  if (!playing) return;
  playing.playing = false;
  playing.ended = false;
  $('play').textContent = 'Play';
  showFrame(Number(e.target.value));
});
$('live').addEventListener('click', () => {
  if (!playing) return;
  playing = null;
  for (const id of ['slider', 'play', 'live']) $(id).disabled = true;
  setLiveVisible(true);
  $('ptime').textContent = 'Live.';
});

function advancePlayback(dt) {
  const p = playing;
  if (!p || !p.playing) return;
  p.clock += dt;
  let i = p.index;
  while (i + 1 < p.frames.length && p.frames[i + 1].t <= p.clock) {
    i += 1;
    if (p.frames[i].events.length) addEvents(p.frames[i].events);
  }
  if (i !== p.index) showFrame(i);
}

hook.playback = () => playing && {
  file: playing.file, frames: playing.frames.length, index: playing.index, t: playing.frames[playing.index].t,
  end: playing.frames[playing.frames.length - 1].t, playing: playing.playing, ended: playing.ended,
};
hook.robots = () => (playing ? playRobots : liveRobots).map(robotReport);
// Page coordinates of a visible element of a class (top centre, not hidden behind another).
hook.screenPoint = (classPrefix) => {
  const rect = renderer.domElement.getBoundingClientRect();
  for (const [id, el] of elementsById) {
    if (!(el.object.userData.IfcClass || '').startsWith(classPrefix)) continue;
    const box = new THREE.Box3().setFromObject(el.object);
    const p = box.getCenter(new THREE.Vector3());
    p.y = xray ? box.max.y : Math.min(box.max.y, cutPlane.constant - 0.01);
    const ndc = p.clone().project(camera);
    if (Math.abs(ndc.x) > 0.9 || Math.abs(ndc.y) > 0.9) continue;
    raycaster.setFromCamera(new THREE.Vector2(ndc.x, ndc.y), camera);
    const targets = [...elementMeshes, ...(capGroup.visible ? capGroup.children : [])];
    const hit = raycaster.intersectObjects(targets, false).find((h) => belowCut(h.point));
    if (!hit || hit.object.userData.element !== id) continue;
    return { id, x: rect.left + ((ndc.x + 1) / 2) * rect.width, y: rect.top + ((1 - ndc.y) / 2) * rect.height };
  }
  return null;
};
// The displayed colour and status of the element named `name`.
hook.elementColour = (name) => {
  const wanted = name.replace(/\s/g, '_');
  for (const [id, el] of elementsById) {
    if (el.object.name !== wanted && el.object.name !== name) continue;
    return { id, status: el.object.userData.AccessibilityStatus ?? null, colour: `#${el.meshes[0].material.color.getHexString()}` };
  }
  return null;
};
// Pixels of the view (full resolution) within `tol` (sum of |dr|+|dg|+|db|) of each colour.
hook.countColours = (colours, tol = 30) => {
  const src = renderer.domElement;
  const c = document.createElement('canvas');
  c.width = src.width;
  c.height = src.height;
  const g = c.getContext('2d');
  g.drawImage(src, 0, 0);
  const px = g.getImageData(0, 0, c.width, c.height).data;
  const want = colours.map((s) => { const v = parseInt(s.slice(1), 16); return [(v >> 16) & 255, (v >> 8) & 255, v & 255]; });
  const counts = want.map(() => 0);
  for (let i = 0; i < px.length; i += 4) {
    want.forEach(([r, gg, b], k) => { if (Math.abs(px[i] - r) + Math.abs(px[i + 1] - gg) + Math.abs(px[i + 2] - b) <= tol) counts[k] += 1; });
  }
  return counts;
};
// The door passages drawn on the storey: id, status and colour.
hook.doors = () => [...doorMeshes].map(([id, m]) => ({ id, status: elementsById.get(id)?.object.userData.AccessibilityStatus ?? m.userData.status, colour: `#${m.material.color.getHexString()}` }));
hook.cutAt = () => cutPlane.constant;
hook.showTop = () => { setCamera('top'); fitTop(); };
hook.cameraMatrix = () => camera.projectionMatrix.elements.concat(camera.matrixWorld.elements);
// The view as a 160 x 120 RGBA thumbnail (what a screenshot shows, small).
hook.thumbnail = () => {
  const c = document.createElement('canvas');
  c.width = 160;
  c.height = 120;
  const g = c.getContext('2d');
  g.drawImage(renderer.domElement, 0, 0, c.width, c.height);
  return Array.from(g.getImageData(0, 0, c.width, c.height).data);
};
// Share of the view whose colour differs from the background.
hook.coverage = () => {
  const px = hook.thumbnail();
  const bg = [(BACKGROUND >> 16) & 255, (BACKGROUND >> 8) & 255, BACKGROUND & 255];
  let differ = 0;
  for (let i = 0; i < px.length; i += 4) {
    if (Math.abs(px[i] - bg[0]) + Math.abs(px[i + 1] - bg[1]) + Math.abs(px[i + 2] - bg[2]) > 24) differ += 1;
  }
  return differ / (px.length / 4);
};

// ---------------------------------------------------------------- start
const clock = new THREE.Timer();
function frame(time) {
  clock.update(time);
  advancePlayback(Math.min(clock.getDelta(), 0.1));
  followRobot();
  renderer.render(scene, camera);
  hook.frames = (hook.frames || 0) + 1;
  if (hook.firstFrameMs === null) hook.firstFrameMs = performance.now();
  if (hook.buildingFrameMs === null && hook.buildingMs !== null) hook.buildingFrameMs = performance.now();
}

async function start() {
  legend();
  $('progress').textContent = 'loading the scene…';
  const info = await (await fetch('/api/scene')).json();
  hook.scene = info;
  title = info.title;
  $('title').title = info.source;
  storeyOptions(info);
  resize();
  // The storey, its robots and their rays are drawn before the building arrives.
  showStorey(info.current ?? 0);
  connect();
  renderer.setAnimationLoop(frame);
  await loadBuilding(info);
  applyColours();
  hook.ready = true;
}
start().catch((err) => {
  hook.errors.push(String(err));
  $('progress').textContent = `failed: ${err.message}`;
  $('progress').classList.add('error');
});
