// The building as a few merged meshes: each GLB part (a storey) becomes one mesh per kind of
// material (opaque, or translucent at one opacity), its elements' triangles in world
// coordinates. Software WebGL pays per draw call, per lit fragment and for every fragment a
// clipping plane may discard, so the building costs a handful of draw calls with unlit vertex
// colours (the page's lights baked in from the flat normals), and when the section plane moves
// each mesh's triangles are reordered: elements wholly below the plane (drawn without
// clipping), those it cuts (drawn clipped), those wholly above it (not drawn, or translucent
// in X-ray view). A click is found from the elements' boxes, then their triangles; an
// element's colour is a range of the colour attribute.
import * as THREE from 'three';

// The page's lights (viewer.js): hemisphere sky white, ground #94a3b8 at 2.2, the sun from
// (30, 60, 20) at 1.6; Lambert's diffuse is irradiance / pi.
const SUN = new THREE.Vector3(30, 60, 20).normalize();
const GROUND = new THREE.Color(0x94a3b8);
const GROUND_LUMA = 0.2126 * GROUND.r + 0.7152 * GROUND.g + 0.0722 * GROUND.b;
function shade(n) {
  const up = 0.5 * n.y + 0.5;
  const hemi = 2.2 * (up + (1 - up) * GROUND_LUMA);
  return (hemi + 1.6 * Math.max(0, n.dot(SUN))) / Math.PI;
}
const HIGHLIGHT = new THREE.Color(0x1d4ed8);
const XRAY_OPACITY = 0.18;

export class Building {
  // `below`: the section plane keeping what lies under the cut; `above`: its opposite.
  constructor(below, above) {
    this.group = new THREE.Group();
    this.group.name = 'building';
    this.elements = new Map(); // GlobalId -> element (see addPart)
    this.batches = [];
    this.parts = 0;
    this.cutY = Infinity;
    this.xray = false;
    this.solid = new Map(); // `${opacity} ${clipped}` -> material
    this.planes = { below: [below], above: [above] };
    this.xrayMaterial = new THREE.MeshBasicMaterial({
      vertexColors: true, side: THREE.DoubleSide, transparent: true, opacity: XRAY_OPACITY,
      depthWrite: false, clippingPlanes: this.planes.above,
    });
  }

  material(opacity, clipped) {
    const key = `${opacity} ${clipped}`;
    if (!this.solid.has(key)) {
      this.solid.set(key, new THREE.MeshBasicMaterial({
        vertexColors: true, side: THREE.DoubleSide, clippingPlanes: clipped ? this.planes.below : null,
        transparent: opacity < 1, opacity, depthWrite: opacity >= 1,
      }));
    }
    return this.solid.get(key);
  }

  // Merges one loaded GLB (`root`, its scene, not added to the page's scene) and frees its
  // geometry. Returns the elements it added.
  addPart(root, part) {
    root.updateMatrixWorld(true);
    const buckets = new Map(); // opacity -> [{ el, mesh }]
    const added = [];
    const box = new THREE.Box3();
    root.traverse((o) => {
      const d = o.userData || {};
      if (!d.GlobalId || d.IfcClass === 'IfcBuildingStorey') return;
      const el = {
        id: d.GlobalId, data: d, name: o.name, part, bottom: Infinity, top: -Infinity, box: new THREE.Box3(),
        pieces: [], colour: null, override: null, highlight: false,
      };
      o.traverse((m) => {
        if (!m.isMesh) return;
        const mat = m.material;
        const opacity = mat.transparent ? Math.round(mat.opacity * 100) / 100 : 1;
        if (!buckets.has(opacity)) buckets.set(opacity, []);
        buckets.get(opacity).push({ el, mesh: m, base: mat.color.clone() });
        el.colour ??= mat.color.clone();
        if (!m.geometry.boundingBox) m.geometry.computeBoundingBox();
        box.copy(m.geometry.boundingBox).applyMatrix4(m.matrixWorld);
        el.bottom = Math.min(el.bottom, box.min.y);
        el.top = Math.max(el.top, box.max.y);
      });
      el.colour ??= new THREE.Color(0xe2e8f0);
      this.elements.set(el.id, el);
      added.push(el);
    });
    for (const [opacity, pieces] of buckets) this.merge(pieces, opacity);
    root.traverse((o) => { if (o.isMesh) o.geometry.dispose(); });
    this.parts += 1;
    this.setCut(this.cutY, this.xray);
    return added;
  }

  // One mesh of `pieces`, world coordinates.
  merge(pieces, opacity) {
    let vertices = 0;
    let indices = 0;
    for (const { mesh } of pieces) {
      const g = mesh.geometry;
      vertices += g.attributes.position.count;
      indices += g.index ? g.index.count : g.attributes.position.count;
    }
    const position = new Float32Array(vertices * 3);
    const colour = new Float32Array(vertices * 3);
    const light = new Float32Array(vertices);
    const index = vertices > 65535 ? new Uint32Array(indices) : new Uint16Array(indices);
    // `source`: the triangles in merge order; `index` (drawn) holds them reordered by setCut.
    const source = vertices > 65535 ? new Uint32Array(indices) : new Uint16Array(indices);
    const batch = { mesh: null, colour: null, light, source, pieces: [], total: indices, dirty: false };
    const p = new THREE.Vector3();
    const n = new THREE.Vector3();
    const normalMatrix = new THREE.Matrix3();
    let v0 = 0;
    let i0 = 0;
    for (const { el, mesh, base } of pieces) {
      const g = mesh.geometry;
      const pos = g.attributes.position;
      const nrm = g.attributes.normal;
      const m = mesh.matrixWorld;
      normalMatrix.getNormalMatrix(m);
      for (let v = 0; v < pos.count; v += 1) {
        p.fromBufferAttribute(pos, v).applyMatrix4(m);
        position[3 * (v0 + v)] = p.x;
        position[3 * (v0 + v) + 1] = p.y;
        position[3 * (v0 + v) + 2] = p.z;
        el.box.expandByPoint(p);
        light[v0 + v] = nrm ? shade(n.fromBufferAttribute(nrm, v).applyMatrix3(normalMatrix).normalize()) : 1;
      }
      // A mirrored copy turns its triangles over: wind them back, so both sides light alike.
      const flip = m.determinant() < 0;
      const count = g.index ? g.index.count : pos.count;
      for (let k = 0; k < count; k += 3) {
        const a = g.index ? g.index.getX(k) : k;
        const b = g.index ? g.index.getX(k + 1) : k + 1;
        const c = g.index ? g.index.getX(k + 2) : k + 2;
        source[i0 + k] = v0 + a;
        source[i0 + k + 1] = v0 + (flip ? c : b);
        source[i0 + k + 2] = v0 + (flip ? b : c);
      }
      // [s0, s1): its triangles in `source`; [i0, i1): in the drawn order.
      const piece = { batch, el, base, v0, v1: v0 + pos.count, s0: i0, s1: i0 + count, i0, i1: i0 + count };
      el.pieces.push(piece);
      batch.pieces.push(piece);
      v0 += pos.count;
      i0 += count;
    }
    const geometry = new THREE.BufferGeometry();
    geometry.setAttribute('position', new THREE.BufferAttribute(position, 3));
    batch.colour = new THREE.BufferAttribute(colour, 3);
    geometry.setAttribute('color', batch.colour);
    index.set(source);
    geometry.setIndex(new THREE.BufferAttribute(index, 1));
    geometry.computeBoundingSphere();
    geometry.computeBoundingBox();
    batch.mesh = new THREE.Mesh(geometry, [this.material(opacity, false), this.material(opacity, true), this.xrayMaterial]);
    batch.mesh.name = `building part ${this.parts}, opacity ${opacity}`;
    batch.mesh.matrixAutoUpdate = false;
    this.group.add(batch.mesh);
    this.batches.push(batch);
    for (const { el } of pieces) this.paint(el);
    batch.dirty = false;
  }

  // Writes `el`'s displayed colours (each piece's own, or the one set for the element; tinted
  // when highlighted) into its vertices.
  paint(el) {
    for (const piece of el.pieces) {
      const own = el.override ?? piece.base;
      const c = el.highlight ? own.clone().lerp(HIGHLIGHT, 0.6) : own;
      const { colour, light } = piece.batch;
      const a = colour.array;
      for (let v = piece.v0; v < piece.v1; v += 1) {
        a[3 * v] = c.r * light[v];
        a[3 * v + 1] = c.g * light[v];
        a[3 * v + 2] = c.b * light[v];
      }
      piece.batch.dirty = true;
    }
  }

  // Sets element `id`'s colour (a THREE.Color for all of it; null: each piece its own; undefined:
  // unchanged) and highlight (undefined: unchanged); call flush() after. `colour` of an
  // element is what it shows (its first piece's when it has its own).
  setColour(id, colour, highlight) {
    const el = this.elements.get(id);
    if (!el) return;
    const override = colour === undefined ? el.override : colour;
    const on = highlight ?? el.highlight;
    const same = override === el.override || (override && el.override && override.equals(el.override));
    if (same && el.highlight === on) return;
    el.override = override ? override.clone() : null;
    el.highlight = on;
    el.colour.copy(el.override ?? el.pieces[0]?.base ?? el.colour);
    this.paint(el);
  }

  // Uploads the colours changed since the last flush.
  flush() {
    for (const b of this.batches) {
      if (b.dirty) { b.colour.needsUpdate = true; b.dirty = false; }
    }
  }

  // Draws what starts below `cutY` (scene frame): elements wholly below as they are, those
  // the plane cuts clipped by it; in X-ray view also what lies above the plane, translucent.
  setCut(cutY, xray) {
    const moved = cutY !== this.cutY;
    this.cutY = cutY;
    this.xray = xray;
    for (const b of this.batches) {
      if (moved || !b.split) this.reorder(b, cutY);
      const [below, cut] = b.split;
      const g = b.mesh.geometry;
      g.clearGroups();
      if (below > 0) g.addGroup(0, below, 0);
      if (cut > below) g.addGroup(below, cut - below, 1);
      if (xray && b.total > below) g.addGroup(below, b.total - below, 2);
      b.mesh.visible = g.groups.length > 0;
    }
  }

  // Orders `b`'s triangles: elements wholly below `cutY`, those it cuts, those above it.
  reorder(b, cutY) {
    const index = b.mesh.geometry.index;
    const out = index.array;
    let at = 0;
    const place = (piece) => {
      const n = piece.s1 - piece.s0;
      out.set(b.source.subarray(piece.s0, piece.s1), at);
      piece.i0 = at;
      piece.i1 = at + n;
      at += n;
    };
    for (const p of b.pieces) if (p.el.top < cutY) place(p);
    const below = at;
    for (const p of b.pieces) if (p.el.top >= cutY && p.el.bottom < cutY) place(p);
    const cut = at;
    for (const p of b.pieces) if (p.el.bottom >= cutY) place(p);
    b.split = [below, cut];
    index.needsUpdate = true;
  }

  // True when `el` is drawn (some of it below the cut, or X-ray view).
  drawn(el) {
    return this.xray || el.bottom < this.cutY;
  }

  // The nearest drawn element that `ray` (scene frame) hits at a point `keep` accepts:
  // { id, point, distance }, or null.
  pick(ray, keep) {
    const hits = [];
    const at = new THREE.Vector3();
    for (const el of this.elements.values()) {
      if (!el.pieces.length || !this.drawn(el)) continue;
      if (el.box.containsPoint(ray.origin)) hits.push([0, el]);
      else if (ray.intersectBox(el.box, at)) hits.push([at.distanceTo(ray.origin), el]);
    }
    hits.sort((a, b) => a[0] - b[0]);
    let best = null;
    const a = new THREE.Vector3();
    const b = new THREE.Vector3();
    const c = new THREE.Vector3();
    const point = new THREE.Vector3();
    for (const [entry, el] of hits) {
      if (best && entry > best.distance) break;
      for (const piece of el.pieces) {
        const g = piece.batch.mesh.geometry;
        const pos = g.attributes.position;
        const idx = g.index.array;
        for (let k = piece.i0; k < piece.i1; k += 3) {
          a.fromBufferAttribute(pos, idx[k]);
          b.fromBufferAttribute(pos, idx[k + 1]);
          c.fromBufferAttribute(pos, idx[k + 2]);
          if (!ray.intersectTriangle(a, b, c, false, point)) continue;
          const d = point.distanceTo(ray.origin);
          if ((!best || d < best.distance) && keep(point)) best = { id: el.id, point: point.clone(), distance: d };
        }
      }
    }
    return best;
  }

  // Draw calls and triangles the building costs as drawn now: all, opaque below the cut
  // (`solid`, clipped or not) and translucent above it (`xray`).
  cost() {
    const out = { calls: 0, triangles: 0, solid: 0, xray: 0, batches: this.batches.length };
    for (const b of this.batches) {
      if (!b.mesh.visible) continue;
      for (const g of b.mesh.geometry.groups) {
        out.calls += 1;
        out.triangles += g.count / 3;
        out[g.materialIndex < 2 ? 'solid' : 'xray'] += g.count / 3;
      }
    }
    return out;
  }
}

// The first index of the ascending `xs` whose value is >= `y` (xs.length when none).
export function firstAtLeast(xs, y) {
  let lo = 0;
  let hi = xs.length;
  while (lo < hi) {
    const mid = (lo + hi) >> 1;
    if (xs[mid] < y) lo = mid + 1; else hi = mid;
  }
  return lo;
}
