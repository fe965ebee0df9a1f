// poinav viewer: the building (one GLB per storey, listed in the scene's `model`, the simulated
// storey's first) and the live robots (states over /ws).
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
// Frames are drawn only when something changed (a robot moved, the camera, the cut, colours):
// software WebGL has no time to spare. The building is a few merged meshes (building.js).

import * as THREE from 'three';
import { GLTFLoader } from 'three/addons/loaders/GLTFLoader.js';
import { OrbitControls } from 'three/addons/controls/OrbitControls.js';
import { VRButton } from 'three/addons/webxr/VRButton.js';
import { Building, firstAtLeast } from './building.js';

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
  storeyMs: null,
  storeyFrameMs: null,
  frames: 0,
  stillDraws: 0, // times the still picture was drawn
  motion: { frames: 0, ms: 0 }, // frames drawn while robots moved, and for how long they moved
  parts: [], // indices (in the scene's `model`) of the building's parts loaded, in order
};
window.poinav = hook;
window.addEventListener('error', (e) => hook.errors.push(String(e.message)));

// ---------------------------------------------------------------- renderer, cameras, lights
const view = $('view');
// Software WebGL (SwiftShader, llvmpipe) pays for every sample: no antialiasing there.
function softwareGl() {
  const gl = document.createElement('canvas').getContext('webgl2');
  const info = gl?.getExtension('WEBGL_debug_renderer_info');
  const name = info ? gl.getParameter(info.UNMASKED_RENDERER_WEBGL) : gl?.getParameter(gl.RENDERER);
  gl?.getExtension('WEBGL_lose_context')?.loseContext();
  return /swiftshader|llvmpipe|softpipe|software/i.test(String(name ?? ''));
}
hook.software = softwareGl();
const renderer = new THREE.WebGLRenderer({ antialias: !hook.software, preserveDrawingBuffer: true });
renderer.setPixelRatio(hook.software ? 1 : window.devicePixelRatio);
renderer.localClippingEnabled = true;
renderer.xr.enabled = true;
view.appendChild(renderer.domElement);
// The section plane: the building keeps what lies below elevation + cut (world y up); in
// X-ray view what lies above it is drawn too, translucent (`abovePlane` keeps that part).
const cutPlane = new THREE.Plane(new THREE.Vector3(0, -1, 0), 1.5);
const abovePlane = new THREE.Plane(new THREE.Vector3(0, 1, 0), -1.5);
const building = new Building(cutPlane, abovePlane);
let dirty = true; // a frame is due
let stale = true; // ... and the still picture (below) must be drawn again
// Anything but the robots changed (camera, cut, colours, building, overlays).
function redraw() { dirty = true; stale = true; }
// Only robots or their rays moved.
function moved() { dirty = true; }
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
scene.add(building.group);
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
orbit.addEventListener('change', redraw);
pan.addEventListener('change', redraw);

function resize() {
  const w = view.clientWidth || 1;
  const h = view.clientHeight || 1;
  renderer.setSize(w, h);
  perspective.aspect = w / h;
  perspective.updateProjectionMatrix();
  fitTop();
  redraw();
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
  abovePlane.constant = -cutPlane.constant;
  capGroup.position.y = elevation + cutHeight - 0.01;
  // Elements wholly above the plane are not drawn at all (unless in X-ray view): the plane
  // would clip all of them, but software WebGL would still pay for their vertices.
  building.setCut(elevation + cutHeight, xray);
  redraw();
  $('cut-value').textContent = `${cutHeight.toFixed(1)} m`;
  hook.cut_m = cutHeight;
  hook.xray = xray;
}

function setCamera(which) {
  camera = which === 'top' ? top : perspective;
  orbit.enabled = which !== 'top';
  pan.enabled = which === 'top';
  hook.camera = which;
  redraw();
  $('camera').textContent = which === 'top' ? 'Camera: top-down' : 'Camera: perspective';
}
$('camera').addEventListener('click', () => setCamera(hook.camera === 'top' ? 'perspective' : 'top'));

// ---------------------------------------------------------------- building
const elementsById = building.elements; // GlobalId -> element (building.js)
let zoneGroup = new THREE.Group();
scene.add(zoneGroup);
let capGroup = new THREE.Group(); // flat caps where the section plane cuts walls and columns
scene.add(capGroup);
let doorGroup = new THREE.Group(); // door and doorway passages on the floor, coloured by status
scene.add(doorGroup);
let caps = null; // the caps as one flat batch (flatBatch)
let doors = null; // the door passages as one flat batch
let poiView = false;

function elementColour(data) {
  if (data.AccessibilityStatus && /Door|Opening/.test(data.IfcClass || '')) {
    return STATUS_COLOURS[data.AccessibilityStatus] || NO_ROLE;
  }
  const roles = roleList(data.POI_PrimaryRoles).concat(roleList(data.POI_ConditionalRoles));
  for (const r of ROLE_ORDER) if (roles.includes(r)) return ROLE_COLOURS[r];
  return NO_ROLE;
}

const poiColour = new THREE.Color();
function applyColours() {
  for (const el of elementsById.values()) {
    building.setColour(el.id, poiView ? poiColour.set(elementColour(el.data)) : null);
  }
  building.flush();
  if (doors) {
    for (const [id, item] of doors.items) {
      const status = elementsById.get(id)?.data.AccessibilityStatus ?? item.status;
      doors.setColour(id, STATUS_COLOURS[status] || NO_ROLE);
    }
  }
  zoneGroup.visible = poiView;
  $('legend').hidden = !poiView;
  redraw();
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

// Flat outlines (plan rings) as one mesh with a colour per outline: `items` [{ id, ring,
// colour, ... }]. Returns { mesh, items: id -> item, idAt(faceIndex), setColour(id, css) }.
function flatBatch(items, name) {
  const position = [];
  const colour = [];
  const index = [];
  const ends = [];
  const ids = [];
  const byId = new Map();
  const c = new THREE.Color();
  for (const item of items) {
    let contour = item.ring.map(([x, y]) => new THREE.Vector2(x, y));
    if (THREE.ShapeUtils.isClockWise(contour)) contour = contour.reverse();
    const triangles = THREE.ShapeUtils.triangulateShape(contour, []);
    if (!triangles.length) continue;
    const v0 = position.length / 3;
    c.set(item.colour);
    for (const p of contour) { position.push(p.x, 0, -p.y); colour.push(c.r, c.g, c.b); } // plan (x, y) -> (x, 0, -y)
    for (const t of triangles) index.push(v0 + t[0], v0 + t[1], v0 + t[2]);
    ends.push(index.length);
    ids.push(item.id);
    const list = byId.get(item.id) ?? [];
    list.push([v0, v0 + contour.length]);
    byId.set(item.id, list);
    item.shown = item.colour;
  }
  const geometry = new THREE.BufferGeometry();
  geometry.setAttribute('position', new THREE.Float32BufferAttribute(position, 3));
  const colours = new THREE.Float32BufferAttribute(colour, 3);
  geometry.setAttribute('color', colours);
  geometry.setIndex(index);
  const mesh = new THREE.Mesh(geometry, new THREE.MeshBasicMaterial({ vertexColors: true, side: THREE.DoubleSide }));
  mesh.name = name;
  const itemsById = new Map(items.map((i) => [i.id, i]));
  return {
    mesh,
    items: itemsById,
    idAt: (face) => ids[firstAtLeast(ends, 3 * face + 1)],
    setColour(id, css) {
      const item = itemsById.get(id);
      if (!item || item.shown === css) return;
      item.shown = css;
      c.set(css);
      for (const [a, b] of byId.get(id) ?? []) for (let v = a; v < b; v += 1) colours.setXYZ(v, c.r, c.g, c.b);
      colours.needsUpdate = true;
    },
  };
}

// The storey's caps (walls and columns where the plane cuts them) and door passages.
function addOverlays(info) {
  for (const g of [capGroup, doorGroup]) {
    scene.remove(g);
    g.traverse((o) => { if (o.isMesh) { o.geometry.dispose(); o.material.dispose?.(); } });
  }
  capGroup = new THREE.Group();
  const rings = (info.structure || []).filter((r) => r.ring.length >= 3);
  caps = flatBatch(rings.map(({ id, ring }) => ({ id, ring, colour: '#334155' })), 'caps');
  capGroup.add(caps.mesh);
  doorGroup = new THREE.Group();
  const passages = (info.doors || []).filter((d) => d.ring && d.ring.length >= 3).map((d) => {
    const status = elementsById.get(d.id)?.data.AccessibilityStatus ?? d.status;
    return { id: d.id, ring: d.ring, status: d.status, colour: STATUS_COLOURS[status] || NO_ROLE };
  });
  doors = flatBatch(passages, 'doors');
  doors.mesh.position.y = elevation + 0.03;
  doorGroup.add(doors.mesh);
  scene.add(capGroup, doorGroup);
  redraw();
}

function megabytes(n) { return (n / 1e6).toFixed(1); }

// The building's parts (one GLB per storey): the simulated storey's first, then the elements
// without a storey, then the other storeys nearest first. Each part is drawn once merged.
function partOrder(info, current) {
  const parts = (info.model || []).map((p, k) => ({ ...p, k }));
  const elev = info.storeys?.[current]?.elevation_m ?? 0;
  const rank = (p) => (p.storey === current ? -2 : p.storey === null ? -1 : Math.abs(p.elevation_m - elev));
  return parts.sort((a, b) => rank(a) - rank(b) || a.k - b.k);
}

async function loadBuilding(info) {
  const t0 = performance.now();
  const parts = partOrder(info, storeyIndex ?? info.current ?? 0);
  const total = parts.reduce((n, p) => n + p.bytes, 0);
  let done = 0;
  const loader = new GLTFLoader();
  for (const [n, part] of parts.entries()) {
    const what = parts.length > 1 ? `${part.name} (${n + 1} of ${parts.length})` : 'the building';
    const gltf = await loader.loadAsync(part.url, (e) => {
      $('progress').textContent = `loading ${what}: ${megabytes(done + e.loaded)} of ${megabytes(total)} MB`;
    });
    done += part.bytes;
    building.addPart(gltf.scene, part.k);
    hook.parts.push(part.k);
    hook.elements = elementsById.size;
    // The simulated storey's part is drawn at once, the others together when the last has
    // arrived: drawing the whole view again after each would take longer than loading them.
    if (n === 0 || n === parts.length - 1) {
      applyColours();
      applyCut();
    }
    if (n === 0) hook.storeyMs = performance.now() - t0;
  }
  const box = new THREE.Box3();
  for (const b of building.batches) box.union(b.mesh.geometry.boundingBox);
  if (!info.bounds && !box.isEmpty()) {
    bounds = { min: [box.min.x, -box.max.z], max: [box.max.x, -box.min.z] };
    fitTop();
    frameStorey();
  }
  hook.buildingMs = performance.now() - t0;
  $('progress').textContent = `building: ${elementsById.size} elements, ${megabytes(total)} MB in ${parts.length} parts, loaded in ${(hook.buildingMs / 1000).toFixed(1)} s`;
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
  for (const r of liveRobots) removeRobot(r);
  lastPoses = null;
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
  redraw();
}

$('storey').addEventListener('change', (e) => send({ type: 'storey', index: Number(e.target.value) }));
$('cut').addEventListener('input', (e) => { cutHeight = Number(e.target.value); applyCut(); });
$('xray').addEventListener('change', (e) => { xray = e.target.checked; applyCut(); applyColours(); });

let follow = false;
function setFollow(on) {
  follow = on;
  hook.follow = on;
  $('follow').textContent = `Follow Robot1: ${on ? 'on' : 'off'}`;
  redraw();
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
    redraw();
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
  const hit = pickAt(ndc, true);
  inspect(hit ? hit.id : null);
});

// What the view shows at `ndc`: the nearest element (below the cut unless X-ray), cap or
// (when `zones`) zone, as { id, point, distance }, or null.
const sceneInverse = new THREE.Matrix4();
function pickAt(ndc, zones) {
  raycaster.setFromCamera(ndc, camera);
  scene.updateMatrixWorld();
  sceneInverse.copy(scene.matrixWorld).invert();
  const ray = raycaster.ray.clone().applyMatrix4(sceneInverse);
  let best = building.pick(ray, (p) => belowCut(p.clone().applyMatrix4(scene.matrixWorld)));
  if (best) best.distance = best.point.clone().applyMatrix4(scene.matrixWorld).distanceTo(raycaster.ray.origin);
  const flats = [...(caps && capGroup.visible ? [caps.mesh] : []), ...(zones && zoneGroup.visible ? zoneGroup.children : [])];
  const hit = raycaster.intersectObjects(flats, false)[0];
  if (hit && (!best || hit.distance < best.distance)) {
    best = { id: hit.object === caps?.mesh ? caps.idAt(hit.faceIndex) : hit.object.userData.element, point: hit.point, distance: hit.distance };
  }
  return best;
}

// True for a point the section plane keeps (everything in X-ray view).
function belowCut(p) {
  return xray || cutPlane.distanceToPoint(p) >= -1e-6;
}

function esc(s) {
  return String(s ?? '').replace(/[&<>"']/g, (c) => ({ '&': '&amp;', '<': '&lt;', '>': '&gt;', '"': '&quot;', "'": '&#39;' }[c]));
}

function highlight(id, on) {
  building.setColour(id, undefined, on);
  building.flush();
  redraw();
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
  const local = el ? el.data : {};
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
const RAYS = 5; // rays drawn per robot

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
  // The rays: one set of line segments, updated in place, coloured per ray.
  const g = new THREE.BufferGeometry();
  g.setAttribute('position', new THREE.BufferAttribute(new Float32Array(RAYS * 6), 3).setUsage(THREE.DynamicDrawUsage));
  g.setAttribute('color', new THREE.BufferAttribute(new Float32Array(RAYS * 6), 3).setUsage(THREE.DynamicDrawUsage));
  g.setDrawRange(0, 0);
  const lines = new THREE.LineSegments(g, new THREE.LineBasicMaterial({ vertexColors: true }));
  lines.frustumCulled = false;
  scene.add(lines, group);
  const clear = new THREE.Color(spec.ray_clear || '#22c55e');
  return { spec, group, brush, disc, lines, rayColours: [], clear, hitColour: new THREE.Color(spec.ray_hit || '#ef4444'), pose: null };
}

function removeRobot(r) {
  scene.remove(r.group, r.lines);
  r.lines.geometry.dispose();
}

function placeRobot(r, s) {
  const y = elevation;
  r.group.position.set(s.x, y, -s.y);
  r.group.rotation.y = (s.heading_deg * Math.PI) / 180;
  r.brush.rotation.y = ((s.brush?.angle_deg || 0) * Math.PI) / 180;
  r.disc.material.color.set(s.brush?.on ? 0xfacc15 : 0x94a3b8);
  const rayHeight = y + BODY_HEIGHT * 0.6;
  const rays = (s.rays || []).slice(0, RAYS);
  const p = r.lines.geometry.attributes.position;
  const c = r.lines.geometry.attributes.color;
  rays.forEach((ray, k) => {
    const a = ((s.heading_deg + ray.deg) * Math.PI) / 180;
    p.setXYZ(2 * k, s.x, rayHeight, -s.y);
    p.setXYZ(2 * k + 1, s.x + Math.cos(a) * ray.d, rayHeight, -(s.y + Math.sin(a) * ray.d));
    const colour = ray.hit ? r.hitColour : r.clear;
    c.setXYZ(2 * k, colour.r, colour.g, colour.b);
    c.setXYZ(2 * k + 1, colour.r, colour.g, colour.b);
    r.rayColours[k] = colour;
  });
  p.needsUpdate = true;
  c.needsUpdate = true;
  r.lines.geometry.setDrawRange(0, 2 * rays.length);
  r.pose = s;
  moved();
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
    rays: Array.from({ length: RAYS }, (_, k) => ({ deg: s.rays?.[k]?.deg, d: s.rays?.[k]?.d, hit: s.rays?.[k]?.hit ?? null, colour: `#${(r.rayColours[k] ?? r.clear).getHexString()}` })),
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
      elementsById.get(e.element).data.AccessibilityStatus = e.to;
      applyColours();
    }
    if ((e.kind === 'role-added' || e.kind === 'role-removed') && elementsById.has(e.element)) {
      const d = elementsById.get(e.element).data;
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
let lastPoses = null; // the robots of the last state, as JSON
let movedAt = -Infinity; // when robots last moved
let panelAt = -Infinity; // when the robots table was last written
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
      // Robots standing still need no new frame.
      const poses = JSON.stringify(msg.robots);
      if (poses !== lastPoses) {
        const now = performance.now();
        if (lastPoses !== null && now - movedAt < 250) hook.motion.ms += now - movedAt;
        movedAt = now;
        lastPoses = poses;
        msg.robots.forEach((s, i) => { if (liveRobots[i]) placeRobot(liveRobots[i], s); });
      }
      if (msg.events.length) addEvents(msg.events);
      // The panel's text at most five times a second: each change costs a layout.
      const now = performance.now();
      if (!playing && now - panelAt >= 200) {
        panelAt = now;
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
  for (const r of liveRobots) { r.group.visible = v; r.lines.visible = v; }
  for (const r of playRobots) { r.group.visible = !v; r.lines.visible = !v; }
  redraw();
}

$('trace-file').addEventListener('change', async (e) => {
  const file = e.target.files[0];
  if (!file) return;
  try {
    const trace = parseTrace(await file.text());
    for (const r of playRobots) removeRobot(r);
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
    if (!(el.data.IfcClass || '').startsWith(classPrefix) || !el.pieces.length || !building.drawn(el)) continue;
    const box = el.box.clone().applyMatrix4(scene.matrixWorld);
    const p = box.getCenter(new THREE.Vector3());
    p.y = xray ? box.max.y : Math.min(box.max.y, cutPlane.constant - 0.01);
    const ndc = p.clone().project(camera);
    if (Math.abs(ndc.x) > 0.9 || Math.abs(ndc.y) > 0.9) continue;
    const hit = pickAt(new THREE.Vector2(ndc.x, ndc.y), false);
    if (!hit || hit.id !== id) continue;
    return { id, x: rect.left + ((ndc.x + 1) / 2) * rect.width, y: rect.top + ((1 - ndc.y) / 2) * rect.height };
  }
  return null;
};
// The displayed colour and status of the element named `name`.
hook.elementColour = (name) => {
  const wanted = name.replace(/\s/g, '_');
  for (const [id, el] of elementsById) {
    if (el.name !== wanted && el.name !== name) continue;
    return { id, status: el.data.AccessibilityStatus ?? null, colour: `#${el.colour.getHexString()}` };
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
hook.doors = () => [...(doors?.items.values() ?? [])].map((d) => ({ id: d.id, status: elementsById.get(d.id)?.data.AccessibilityStatus ?? d.status, colour: d.shown }));
// What drawing the whole view costs: draw calls and triangles (all, and the building's); the
// draw calls and pixels of the last frame (with the still picture: copying it, then the
// robots); frames drawn; whether WebGL is software (and so the still picture used).
hook.renderInfo = () => ({
  calls: costs.calls, triangles: costs.triangles, frame_calls: costs.frameCalls, frame_pixels: costs.pixels, frames: hook.frames,
  building: building.cost(), software: hook.software,
});
// Milliseconds one frame takes to draw, averaged over `n` frames drawn back to back (each
// waited for by reading a pixel back), as the view is now: `whole` draws everything again
// (the camera moved), otherwise only the robots moved.
hook.renderTime = (n = 10, whole = true) => {
  const gl = renderer.getContext();
  const px = new Uint8Array(4);
  const once = () => {
    if (whole) redraw();
    draw();
    gl.readPixels(0, 0, 1, 1, gl.RGBA, gl.UNSIGNED_BYTE, px);
  };
  once();
  const t0 = performance.now();
  for (let k = 0; k < n; k += 1) once();
  return (performance.now() - t0) / n;
};
// Pixels of the view as shown now (with the still picture: kept, then robots drawn over it)
// that differ (sum of |dr|+|dg|+|db| over `tol`) from the view drawn whole again.
hook.stillDiff = (tol = 24) => {
  const grab = () => {
    const c = document.createElement('canvas');
    c.width = renderer.domElement.width;
    c.height = renderer.domElement.height;
    const g = c.getContext('2d');
    g.drawImage(renderer.domElement, 0, 0);
    return g.getImageData(0, 0, c.width, c.height).data;
  };
  const shown = grab();
  redraw();
  draw();
  const whole = grab();
  let differ = 0;
  for (let i = 0; i < shown.length; i += 4) {
    if (Math.abs(shown[i] - whole[i]) + Math.abs(shown[i + 1] - whole[i + 1]) + Math.abs(shown[i + 2] - whole[i + 2]) > tol) differ += 1;
  }
  return { differ, pixels: shown.length / 4 };
};
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

// ---------------------------------------------------------------- the still picture
// Under software WebGL the scene without the robots is drawn once into `still` (colour and
// depth) and kept while the camera, the cut, the colours and the building stay; a frame where
// only robots moved copies it back (a quad writing colour and depth) and draws the robots and
// their rays over it, both only within the rectangle where the robots were and are (the
// canvas keeps its other pixels: preserveDrawingBuffer), so moving robots cost what they draw
// and the few pixels around them, not what the building does.
let still = null;
const quadCamera = new THREE.OrthographicCamera(-1, 1, 1, -1, 0, 1);
const quadScene = new THREE.Scene();
const quad = new THREE.Mesh(new THREE.PlaneGeometry(2, 2), new THREE.ShaderMaterial({
  uniforms: { colour: { value: null }, depth: { value: null } },
  vertexShader: 'varying vec2 vUv; void main() { vUv = uv; gl_Position = vec4(position.xy, 0.0, 1.0); }',
  fragmentShader: `uniform sampler2D colour; uniform sampler2D depth; varying vec2 vUv;
    void main() {
      gl_FragColor = texture2D(colour, vUv);
      gl_FragDepth = texture2D(depth, vUv).r;
      #include <colorspace_fragment>
    }`,
  depthFunc: THREE.AlwaysDepth,
}));
quad.frustumCulled = false;
quadScene.add(quad);
const drawingSize = new THREE.Vector2();
const costs = { calls: 0, triangles: 0, frameCalls: 0, pixels: 0 };
let moverRectBefore = null; // where the robots were drawn last frame: [x0, y0, x1, y1], or null

// The drawing-buffer rectangle (origin bottom left) holding the robots and their rays as the
// camera sees them; null when one is behind the camera (then the whole view).
const rectBox = new THREE.Box3();
const rectPoint = new THREE.Vector3();
function moverRect() {
  rectBox.makeEmpty();
  for (const r of [...liveRobots, ...playRobots]) {
    if (!r.group.visible) continue;
    rectBox.expandByObject(r.group);
    const p = r.lines.geometry.attributes.position;
    for (let i = 0; i < r.lines.geometry.drawRange.count && i < p.count; i += 1) rectBox.expandByPoint(rectPoint.fromBufferAttribute(p, i));
  }
  if (rectBox.isEmpty()) return [0, 0, 0, 0];
  let [x0, y0, x1, y1] = [Infinity, Infinity, -Infinity, -Infinity];
  for (let k = 0; k < 8; k += 1) {
    rectPoint.set(k & 1 ? rectBox.max.x : rectBox.min.x, k & 2 ? rectBox.max.y : rectBox.min.y, k & 4 ? rectBox.max.z : rectBox.min.z);
    rectPoint.project(camera);
    if (!(rectPoint.z >= -1 && rectPoint.z <= 1)) return null;
    const x = ((rectPoint.x + 1) / 2) * drawingSize.x;
    const y = ((rectPoint.y + 1) / 2) * drawingSize.y;
    x0 = Math.min(x0, x); y0 = Math.min(y0, y); x1 = Math.max(x1, x); y1 = Math.max(y1, y);
  }
  const clamp = (v, hi) => Math.max(0, Math.min(hi, v));
  return [clamp(Math.floor(x0) - 3, drawingSize.x), clamp(Math.floor(y0) - 3, drawingSize.y),
    clamp(Math.ceil(x1) + 3, drawingSize.x), clamp(Math.ceil(y1) + 3, drawingSize.y)];
}

function movers() {
  return [...liveRobots, ...playRobots].flatMap((r) => [r.group, r.lines]);
}

function drawStill() {
  renderer.getDrawingBufferSize(drawingSize);
  if (!still || still.width !== drawingSize.x || still.height !== drawingSize.y) {
    still?.dispose();
    still = new THREE.WebGLRenderTarget(drawingSize.x, drawingSize.y, {
      minFilter: THREE.NearestFilter, magFilter: THREE.NearestFilter, colorSpace: THREE.SRGBColorSpace,
      depthTexture: new THREE.DepthTexture(drawingSize.x, drawingSize.y),
    });
    quad.material.uniforms.colour.value = still.texture;
    quad.material.uniforms.depth.value = still.depthTexture;
    stale = true;
  }
  if (stale) {
    hook.stillDraws += 1;
    const hidden = movers().map((o) => [o, o.visible]);
    for (const [o] of hidden) o.visible = false;
    renderer.setRenderTarget(still);
    renderer.render(scene, camera);
    renderer.setRenderTarget(null);
    for (const [o, v] of hidden) o.visible = v;
    costs.calls = renderer.info.render.calls;
    costs.triangles = renderer.info.render.triangles;
    stale = false;
    moverRectBefore = null;
  }
  // The still picture, then the robots alone over it, where they were and are.
  const now = moverRect();
  const before = moverRectBefore;
  moverRectBefore = now;
  const rect = now && before
    ? [Math.min(now[0], before[0]), Math.min(now[1], before[1]), Math.max(now[2], before[2]), Math.max(now[3], before[3])]
    : [0, 0, drawingSize.x, drawingSize.y];
  costs.pixels = Math.max(0, rect[2] - rect[0]) * Math.max(0, rect[3] - rect[1]);
  if (costs.pixels === 0) return;
  const ratio = renderer.getPixelRatio();
  renderer.setScissor(rect[0] / ratio, rect[1] / ratio, (rect[2] - rect[0]) / ratio, (rect[3] - rect[1]) / ratio);
  renderer.setScissorTest(true);
  const shown = new Set(movers());
  const hidden = scene.children.filter((o) => !o.isLight && !shown.has(o)).map((o) => [o, o.visible]);
  const background = scene.background;
  renderer.autoClear = false;
  renderer.render(quadScene, quadCamera);
  for (const [o] of hidden) o.visible = false;
  scene.background = null;
  renderer.render(scene, camera);
  costs.frameCalls = 1 + renderer.info.render.calls;
  scene.background = background;
  for (const [o, v] of hidden) o.visible = v;
  renderer.autoClear = true;
  renderer.setScissorTest(false);
}

function draw() {
  if (hook.software && !renderer.xr.isPresenting) {
    drawStill();
    return;
  }
  renderer.render(scene, camera);
  costs.calls = renderer.info.render.calls;
  costs.triangles = renderer.info.render.triangles;
  costs.frameCalls = costs.calls;
}

// ---------------------------------------------------------------- start
const clock = new THREE.Timer();
function frame(time) {
  clock.update(time);
  advancePlayback(Math.min(clock.getDelta(), 0.1));
  followRobot();
  if (!dirty && !renderer.xr.isPresenting) return;
  dirty = false;
  draw();
  hook.frames += 1;
  if (performance.now() - movedAt < 250) hook.motion.frames += 1;
  const now = performance.now();
  if (hook.firstFrameMs === null) hook.firstFrameMs = now;
  if (hook.storeyFrameMs === null && hook.storeyMs !== null) hook.storeyFrameMs = now;
  if (hook.buildingFrameMs === null && hook.buildingMs !== null) hook.buildingFrameMs = now;
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
