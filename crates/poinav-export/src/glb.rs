//! Binary glTF 2.0 (`.glb`) of a building's element meshes, grouped under storey nodes.
//!
//! The node layout, coordinate frame and pivots are [`crate::scene`]'s: one node per storey
//! (plus a [`NO_STOREY`](crate::scene::NO_STOREY) node when needed) whose children are one node
//! per element, named by the element's Name (else its class). Element nodes carry `extras`:
//! `GlobalId`, `IfcClass`, `Storey` (name or null) and, when the scene has a classification
//! for the element, `POI_Category`, `POI_Type`, `POI_PrimaryRoles`, `POI_ConditionalRoles`
//! (arrays of role codes) and `AccessibilityStatus` (when assessed). Storey nodes carry
//! `GlobalId`, `IfcClass` (`IfcBuildingStorey`) and `Elevation` (metres).
//!
//! Geometry ([`GlbOptions`]): one mesh with one triangle primitive per element that has
//! triangles, except that an element whose geometry is a rigid copy of an earlier element's
//! (found by [`crate::instances`]: mapped items placed again, moved, rotated or mirrored)
//! references that element's mesh, its node's `rotation` and `scale` (-1 in x for a mirror)
//! placing it. Flat `NORMAL`s (a vertex is shared only by triangles of the same plane:
//! architecture has sharp edges). By default the geometry is quantised
//! (`KHR_mesh_quantization`, required): `POSITION` as `SHORT` integers (with integer
//! `min`/`max`) in steps of [`crate::quantise::position_step`], which the node's uniform
//! `scale` undoes, `NORMAL` as normalised `BYTE`s, indices `u16` where a mesh has fewer than
//! 65,535 vertices; [`GlbOptions::PLAIN`] writes `f32` positions and normals and `u32`
//! indices, no extension and one mesh per element, for readers without the extension. All data
//! sits in one buffer with up to four buffer views (positions, normals, `u32` and `u16`
//! indices), each 4-byte aligned. One material per distinct colour (`pbrMetallicRoughness`,
//! metallic 0, roughness 1, double-sided, `BLEND` when not opaque); IFC colours are sRGB and
//! are converted to the linear `baseColorFactor`.
//!
//! The JSON is written with `serde_json` rather than the `gltf-json` crate: the subset written
//! is small and fixed, `serde_json` is already a dependency, and `gltf-json` would add a
//! procedural-macro dependency tree and a feature flag for `extras` without making the output
//! more correct — the Khronos glTF-Validator is the check (see this crate's tests). Keys are
//! written in sorted order, so the same scene gives the same bytes.

use std::io::Write;
use std::path::Path;

use rustc_hash::FxHashMap;
use serde_json::{json, Map, Value};

use glam::{DMat3, DQuat, DVec3};

use crate::instances::{Instances, Placement};
use crate::palette::srgb_to_linear;
use crate::quantise;
use crate::scene::{prepare_with, Element, SceneInput};
use crate::ExportError;

/// `glTF` magic, little-endian.
pub const GLB_MAGIC: u32 = 0x4654_6C67;
/// JSON chunk type.
pub const CHUNK_JSON: u32 = 0x4E4F_534A;
/// BIN chunk type.
pub const CHUNK_BIN: u32 = 0x004E_4942;

const ARRAY_BUFFER: u32 = 34962;
const ELEMENT_ARRAY_BUFFER: u32 = 34963;
const BYTE: u32 = 5120;
const SHORT: u32 = 5122;
const UNSIGNED_SHORT: u32 = 5123;
const UNSIGNED_INT: u32 = 5125;
const FLOAT: u32 = 5126;
const KHR_MESH_QUANTIZATION: &str = "KHR_mesh_quantization";

/// `asset.generator`: `poinav <version>`.
pub fn generator() -> String {
    format!("poinav {}", env!("CARGO_PKG_VERSION"))
}

/// An f32 as the JSON number that reads back as exactly that f32.
fn num(v: f32) -> Value {
    json!(f64::from(v))
}

/// One element's geometry with flat normals: a vertex is shared only by triangles of the same
/// plane (same normal bits), so normals can be per vertex.
struct Flat {
    positions: Vec<[f32; 3]>,
    normals: Vec<[f32; 3]>,
    indices: Vec<u32>,
}

/// Splits `e`'s vertices by triangle normal, taking its geometry (nothing else reads it
/// afterwards). `seen` is scratch space, reused across elements: (vertex, normal bits) to the
/// new vertex, numbered in order of first use, so the output does not depend on the hasher.
fn flatten(e: &mut Element<'_>, seen: &mut FxHashMap<(u32, [u32; 3]), u32>) -> Flat {
    let positions = std::mem::take(&mut e.positions);
    let triangles = std::mem::take(&mut e.triangles);
    let normals = std::mem::take(&mut e.normals);
    seen.clear();
    seen.reserve(positions.len());
    let mut f = Flat {
        positions: Vec::with_capacity(positions.len()),
        normals: Vec::with_capacity(positions.len()),
        indices: Vec::with_capacity(triangles.len() * 3),
    };
    for (t, n) in triangles.iter().zip(&normals) {
        let bits = n.map(f32::to_bits);
        for &i in t {
            let idx = *seen.entry((i, bits)).or_insert_with(|| {
                f.positions.push(positions[i as usize]);
                f.normals.push(*n);
                (f.positions.len() - 1) as u32
            });
            f.indices.push(idx);
        }
    }
    f.positions.shrink_to_fit();
    f.normals.shrink_to_fit();
    f
}

/// How the GLB is written.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct GlbOptions {
    /// Elements whose geometry is a rigid copy of an earlier element's (mapped items: the
    /// same furniture placed many times) reference that element's mesh instead of a copy.
    pub share_copies: bool,
    /// `KHR_mesh_quantization`: 16-bit integer positions (the node's scale holds the step),
    /// normalised 8-bit normals, 16-bit indices where a mesh has fewer than 65,535 vertices.
    pub quantise: bool,
}

impl GlbOptions {
    /// Every element its own mesh, `f32` positions and normals, `u32` indices: what any
    /// glTF 2.0 reader opens, with no extension.
    pub const PLAIN: GlbOptions = GlbOptions {
        share_copies: false,
        quantise: false,
    };
    /// Shared copies and quantised geometry: the default, about a third of the plain size
    /// on furnished models.
    pub const COMPACT: GlbOptions = GlbOptions {
        share_copies: true,
        quantise: true,
    };
}

impl Default for GlbOptions {
    fn default() -> Self {
        GlbOptions::COMPACT
    }
}

/// Where each part of the BIN chunk starts, and how each mesh is encoded.
struct Layout {
    quantise: bool,
    /// Per mesh: the position step (1 when not quantised) and whether its indices are `u32`.
    steps: Vec<f64>,
    wide: Vec<bool>,
    /// Lengths in bytes of the positions, normals, `u32` indices and `u16` indices.
    parts: [usize; 4],
}

impl Layout {
    fn new(flats: &[Flat], quantise: bool) -> Layout {
        let steps: Vec<f64> = flats
            .iter()
            .map(|f| {
                if quantise {
                    quantise::position_step(&f.positions)
                } else {
                    1.0
                }
            })
            .collect();
        let wide: Vec<bool> = flats
            .iter()
            .map(|f| !quantise || f.positions.len() >= usize::from(u16::MAX))
            .collect();
        let n_pos: usize = flats.iter().map(|f| f.positions.len()).sum();
        let idx = |w: bool| -> usize {
            flats
                .iter()
                .zip(&wide)
                .filter(|(_, &x)| x == w)
                .map(|(f, _)| f.indices.len())
                .sum()
        };
        let parts = if quantise {
            [n_pos * 8, n_pos * 4, idx(true) * 4, idx(false) * 2]
        } else {
            [n_pos * 12, n_pos * 12, idx(true) * 4, 0]
        };
        Layout {
            quantise,
            steps,
            wide,
            parts,
        }
    }

    /// Byte offset of part `k` in the BIN chunk.
    fn at(&self, k: usize) -> usize {
        self.parts[..k].iter().sum()
    }

    /// Unpadded length of the BIN chunk's data.
    fn bin_len(&self) -> usize {
        self.parts.iter().sum()
    }
}

/// A prepared GLB: its JSON chunk (padded) and the distinct meshes its BIN chunk holds.
struct Document {
    json: Vec<u8>,
    flats: Vec<Flat>,
    layout: Layout,
}

impl Document {
    /// Prepares `scene`: each element is localised and flattened in turn (or recognised as a
    /// copy of an earlier one), so the scene's geometry is held once, and the JSON is
    /// serialised.
    fn new(scene: &SceneInput<'_>, options: GlbOptions) -> Document {
        let (value, flats, layout) = json_and_flats(scene, options);
        let mut json = serde_json::to_vec(&value).expect("serialising JSON to memory");
        drop(value);
        while json.len() % 4 != 0 {
            json.push(b' ');
        }
        Document {
            json,
            flats,
            layout,
        }
    }

    /// Total GLB length in bytes.
    fn len(&self) -> usize {
        let bin_len = self.layout.bin_len();
        let bin = if bin_len == 0 {
            0
        } else {
            8 + bin_len.next_multiple_of(4)
        };
        12 + 8 + self.json.len() + bin
    }

    /// Writes the GLB: a 12-byte header, the JSON chunk (padded with spaces to 4 bytes) and,
    /// when there is geometry, the BIN chunk (positions, normals, `u32` then `u16` indices;
    /// padded with zeros).
    fn write(&self, w: &mut impl Write) -> std::io::Result<()> {
        let mut head = Vec::with_capacity(28);
        head.extend_from_slice(&GLB_MAGIC.to_le_bytes());
        head.extend_from_slice(&2u32.to_le_bytes());
        head.extend_from_slice(&(self.len() as u32).to_le_bytes());
        head.extend_from_slice(&(self.json.len() as u32).to_le_bytes());
        head.extend_from_slice(&CHUNK_JSON.to_le_bytes());
        w.write_all(&head)?;
        w.write_all(&self.json)?;
        let bin_len = self.layout.bin_len();
        if bin_len == 0 {
            return Ok(());
        }
        let padded = bin_len.next_multiple_of(4);
        head.clear();
        head.extend_from_slice(&(padded as u32).to_le_bytes());
        head.extend_from_slice(&CHUNK_BIN.to_le_bytes());
        w.write_all(&head)?;
        let mut buf = ChunkBuffer::new(w);
        let l = &self.layout;
        if l.quantise {
            for (f, &step) in self.flats.iter().zip(&l.steps) {
                for p in &f.positions {
                    let [x, y, z] = quantise::position(*p, step);
                    for c in [x, y, z, 0] {
                        buf.bytes(&c.to_le_bytes())?;
                    }
                }
            }
            for f in &self.flats {
                for n in &f.normals {
                    let [x, y, z] = quantise::normal(*n);
                    buf.bytes(&[x as u8, y as u8, z as u8, 0])?;
                }
            }
        } else {
            for f in &self.flats {
                buf.f32s(f.positions.iter().flatten())?;
            }
            for f in &self.flats {
                buf.f32s(f.normals.iter().flatten())?;
            }
        }
        for (f, _) in self.flats.iter().zip(&l.wide).filter(|(_, &w)| w) {
            for i in &f.indices {
                buf.bytes(&i.to_le_bytes())?;
            }
        }
        for (f, _) in self.flats.iter().zip(&l.wide).filter(|(_, &w)| !w) {
            for &i in &f.indices {
                buf.bytes(&(i as u16).to_le_bytes())?;
            }
        }
        buf.bytes(&[0; 3][..padded - bin_len])?;
        buf.flush()
    }
}

/// Little-endian values collected into 64 KiB blocks before they reach the writer.
struct ChunkBuffer<'w, W: Write> {
    w: &'w mut W,
    buf: Vec<u8>,
}

impl<'w, W: Write> ChunkBuffer<'w, W> {
    const SIZE: usize = 1 << 16;

    fn new(w: &'w mut W) -> Self {
        ChunkBuffer {
            w,
            buf: Vec::with_capacity(Self::SIZE),
        }
    }

    fn bytes(&mut self, b: &[u8]) -> std::io::Result<()> {
        if self.buf.len() + b.len() > Self::SIZE {
            self.flush()?;
        }
        self.buf.extend_from_slice(b);
        Ok(())
    }

    fn f32s<'v>(&mut self, values: impl Iterator<Item = &'v f32>) -> std::io::Result<()> {
        for v in values {
            self.bytes(&v.to_le_bytes())?;
        }
        Ok(())
    }

    fn flush(&mut self) -> std::io::Result<()> {
        self.w.write_all(&self.buf)?;
        self.buf.clear();
        Ok(())
    }
}

/// Which mesh an element node shows, and where (`None` for an element without triangles).
struct Use {
    mesh: usize,
    /// Relative to the mesh's own element; `None` for that element itself.
    placement: Option<Placement>,
}

/// The node properties (`translation`, `rotation`, `scale`) that put mesh vertices, in
/// steps of `step`, where `placement` (when a copy) and `translation` put them.
fn node_transform(
    node: &mut Map<String, Value>,
    translation: DVec3,
    placement: Option<&Placement>,
    step: f64,
) {
    let (t, linear) = match placement {
        Some(p) => (translation + p.offset, p.linear),
        None => (translation, DMat3::IDENTITY),
    };
    if t != DVec3::ZERO {
        node.insert("translation".into(), json!(t.to_array()));
    }
    // An orthogonal map is a rotation, or a rotation after mirroring x.
    let (rotation, sign) = if linear.determinant() < 0.0 {
        (
            linear * DMat3::from_diagonal(DVec3::new(-1.0, 1.0, 1.0)),
            -1.0,
        )
    } else {
        (linear, 1.0)
    };
    if rotation != DMat3::IDENTITY {
        let mut q = DQuat::from_mat3(&rotation).normalize();
        if q.w < 0.0 {
            q = -q;
        }
        node.insert("rotation".into(), json!(q.to_array()));
    }
    if sign != 1.0 || step != 1.0 {
        node.insert("scale".into(), json!([sign * step, step, step]));
    }
}

/// The glTF JSON document, the distinct meshes' flattened geometry and the BIN layout.
fn json_and_flats(scene: &SceneInput<'_>, options: GlbOptions) -> (Value, Vec<Flat>, Layout) {
    let mut flats: Vec<Flat> = Vec::new();
    let mut mesh_names: Vec<(String, usize)> = Vec::new();
    let mut uses: Vec<Option<Use>> = Vec::with_capacity(scene.elements.len());
    let mut copies = Instances::default();
    let mut seen = FxHashMap::default();
    let p = prepare_with(scene, |e| {
        if e.triangles.is_empty() {
            uses.push(None);
            return;
        }
        if options.share_copies {
            if let Some((mesh, placement)) = copies.find(e.material, &e.positions, &e.triangles) {
                e.positions = Vec::new();
                e.triangles = Vec::new();
                e.normals = Vec::new();
                uses.push(Some(Use {
                    mesh,
                    placement: Some(placement),
                }));
                return;
            }
            copies.add(
                flats.len(),
                e.material,
                e.positions.clone(),
                e.triangles.clone(),
            );
        }
        uses.push(Some(Use {
            mesh: flats.len(),
            placement: None,
        }));
        mesh_names.push((e.label.clone(), e.material));
        flats.push(flatten(e, &mut seen));
    });
    drop((seen, copies));
    let layout = Layout::new(&flats, options.quantise);
    let bin_len = layout.bin_len();

    // Buffer views: positions, normals, u32 indices, u16 indices; empty ones left out.
    let mut views = Vec::new();
    let mut view_of = [usize::MAX; 4];
    for (k, &len) in layout.parts.iter().enumerate() {
        if len == 0 {
            continue;
        }
        view_of[k] = views.len();
        let mut view = json!({"buffer": 0, "byteOffset": layout.at(k), "byteLength": len});
        match (k, layout.quantise) {
            (0, false) | (1, false) => view["byteStride"] = json!(12),
            (0, true) => view["byteStride"] = json!(8),
            (1, true) => view["byteStride"] = json!(4),
            _ => {}
        }
        view["target"] = json!(if k < 2 {
            ARRAY_BUFFER
        } else {
            ELEMENT_ARRAY_BUFFER
        });
        views.push(view);
    }

    let mut accessors = Vec::new();
    let mut meshes = Vec::new();
    let (pos_size, nrm_size) = if layout.quantise { (8, 4) } else { (12, 12) };
    let (mut pos_off, mut idx32_off, mut idx16_off) = (0usize, 0usize, 0usize);
    for (m, (f, (label, material))) in flats.iter().zip(&mesh_names).enumerate() {
        let a = accessors.len();
        if layout.quantise {
            let step = layout.steps[m];
            let (mut lo, mut hi) = ([i16::MAX; 3], [i16::MIN; 3]);
            for v in &f.positions {
                let q = quantise::position(*v, step);
                for k in 0..3 {
                    lo[k] = lo[k].min(q[k]);
                    hi[k] = hi[k].max(q[k]);
                }
            }
            accessors.push(json!({
                "bufferView": view_of[0], "byteOffset": pos_off * pos_size,
                "componentType": SHORT, "count": f.positions.len(), "type": "VEC3",
                "min": lo, "max": hi,
            }));
            accessors.push(json!({
                "bufferView": view_of[1], "byteOffset": pos_off * nrm_size,
                "componentType": BYTE, "normalized": true,
                "count": f.positions.len(), "type": "VEC3",
            }));
        } else {
            let (mut lo, mut hi) = ([f32::INFINITY; 3], [f32::NEG_INFINITY; 3]);
            for v in &f.positions {
                for k in 0..3 {
                    lo[k] = lo[k].min(v[k]);
                    hi[k] = hi[k].max(v[k]);
                }
            }
            accessors.push(json!({
                "bufferView": view_of[0], "byteOffset": pos_off * pos_size,
                "componentType": FLOAT, "count": f.positions.len(), "type": "VEC3",
                "min": lo.map(num), "max": hi.map(num),
            }));
            accessors.push(json!({
                "bufferView": view_of[1], "byteOffset": pos_off * nrm_size,
                "componentType": FLOAT, "count": f.positions.len(), "type": "VEC3",
            }));
        }
        if layout.wide[m] {
            accessors.push(json!({
                "bufferView": view_of[2], "byteOffset": idx32_off * 4,
                "componentType": UNSIGNED_INT, "count": f.indices.len(), "type": "SCALAR",
            }));
            idx32_off += f.indices.len();
        } else {
            accessors.push(json!({
                "bufferView": view_of[3], "byteOffset": idx16_off * 2,
                "componentType": UNSIGNED_SHORT, "count": f.indices.len(), "type": "SCALAR",
            }));
            idx16_off += f.indices.len();
        }
        pos_off += f.positions.len();
        meshes.push(json!({
            "name": label,
            "primitives": [{
                "attributes": {"POSITION": a, "NORMAL": a + 1},
                "indices": a + 2,
                "material": material,
            }],
        }));
    }

    let mut nodes = Vec::new();
    let mut roots = Vec::new();
    let first_element = p.groups.len();
    let mut element_node = vec![0usize; p.elements.len()];
    let mut next = first_element;
    for g in &p.groups {
        for &i in &g.elements {
            element_node[i] = next;
            next += 1;
        }
    }
    for (gi, g) in p.groups.iter().enumerate() {
        roots.push(gi);
        let mut node = Map::new();
        node.insert("name".into(), json!(g.label));
        if g.origin != DVec3::ZERO {
            node.insert("translation".into(), json!(g.origin.to_array()));
        }
        if !g.elements.is_empty() {
            let children: Vec<usize> = g.elements.iter().map(|&i| element_node[i]).collect();
            node.insert("children".into(), json!(children));
        }
        if let Some(s) = g.storey {
            let mut extras = Map::new();
            extras.insert("IfcClass".into(), json!("IfcBuildingStorey"));
            if let Some(guid) = &s.global_id {
                extras.insert("GlobalId".into(), json!(guid));
            }
            if let Some(e) = s.elevation_m.filter(|e| e.is_finite()) {
                extras.insert("Elevation".into(), json!(e));
            }
            node.insert("extras".into(), Value::Object(extras));
        }
        nodes.push(Value::Object(node));
    }
    for g in &p.groups {
        for &i in &g.elements {
            let e = &p.elements[i];
            let mut node = Map::new();
            node.insert("name".into(), json!(e.label));
            match &uses[i] {
                Some(u) => {
                    node.insert("mesh".into(), json!(u.mesh));
                    let step = layout.steps[u.mesh];
                    node_transform(&mut node, e.translation, u.placement.as_ref(), step);
                }
                None if e.translation != DVec3::ZERO => {
                    node.insert("translation".into(), json!(e.translation.to_array()));
                }
                None => {}
            }
            let mut extras = Map::new();
            extras.insert("GlobalId".into(), json!(e.source.global_id));
            extras.insert("IfcClass".into(), json!(e.source.class));
            extras.insert("Storey".into(), json!(e.storey_name));
            for (k, v) in e.poi_pairs() {
                let v = if k.ends_with("Roles") {
                    json!(v.split(';').filter(|s| !s.is_empty()).collect::<Vec<_>>())
                } else {
                    json!(v)
                };
                extras.insert(k.into(), v);
            }
            node.insert("extras".into(), Value::Object(extras));
            nodes.push(Value::Object(node));
        }
    }

    let materials: Vec<Value> = p
        .materials
        .iter()
        .map(|m| {
            let [r, g, b, a] = m.rgba;
            let mut mat = json!({
                "name": m.name,
                "doubleSided": true,
                "pbrMetallicRoughness": {
                    "baseColorFactor": [
                        num(srgb_to_linear(r)), num(srgb_to_linear(g)),
                        num(srgb_to_linear(b)), num(a),
                    ],
                    "metallicFactor": 0.0,
                    "roughnessFactor": 1.0,
                },
            });
            if a < 1.0 {
                mat["alphaMode"] = json!("BLEND");
            }
            mat
        })
        .collect();

    let mut doc = Map::new();
    doc.insert(
        "asset".into(),
        json!({"version": "2.0", "generator": generator()}),
    );
    if layout.quantise && bin_len > 0 {
        doc.insert("extensionsUsed".into(), json!([KHR_MESH_QUANTIZATION]));
        doc.insert("extensionsRequired".into(), json!([KHR_MESH_QUANTIZATION]));
    }
    doc.insert("scene".into(), json!(0));
    let mut scene_obj = Map::new();
    scene_obj.insert("name".into(), json!("poinav"));
    if !roots.is_empty() {
        scene_obj.insert("nodes".into(), json!(roots));
    }
    doc.insert("scenes".into(), json!([Value::Object(scene_obj)]));
    let mut put = |key: &str, v: Vec<Value>| {
        if !v.is_empty() {
            doc.insert(key.into(), Value::Array(v));
        }
    };
    put("nodes", nodes);
    put("meshes", meshes);
    put("materials", materials);
    put("accessors", accessors);
    if bin_len > 0 {
        put("bufferViews", views);
        // The BIN chunk's length: `u16` indices may end 2 bytes short of it.
        put(
            "buffers",
            vec![json!({"byteLength": bin_len.next_multiple_of(4)})],
        );
    }
    (Value::Object(doc), flats, layout)
}

/// The glTF JSON of `scene` alone (the document the GLB's JSON chunk holds), as
/// [`to_glb`] writes it.
pub fn to_gltf_json(scene: &SceneInput<'_>) -> serde_json::Value {
    json_and_flats(scene, GlbOptions::default()).0
}

/// The GLB bytes of `scene` ([`GlbOptions::COMPACT`]): a 12-byte header, the JSON chunk
/// (padded with spaces to 4 bytes) and, when there is geometry, the BIN chunk (padded with
/// zeros to 4 bytes).
pub fn to_glb(scene: &SceneInput<'_>) -> Vec<u8> {
    to_glb_with(scene, GlbOptions::default())
}

/// Like [`to_glb`], written as `options` say.
pub fn to_glb_with(scene: &SceneInput<'_>, options: GlbOptions) -> Vec<u8> {
    let doc = Document::new(scene, options);
    let mut out = Vec::with_capacity(doc.len());
    doc.write(&mut out).expect("writing to memory");
    out
}

/// Writes the GLB of `scene` ([`GlbOptions::COMPACT`]) to `path` atomically, streaming the
/// geometry to the file (the whole GLB is never built in memory).
pub fn write_glb(path: &Path, scene: &SceneInput<'_>) -> Result<(), ExportError> {
    write_glb_with(path, scene, GlbOptions::default())
}

/// Like [`write_glb`], written as `options` say.
pub fn write_glb_with(
    path: &Path,
    scene: &SceneInput<'_>,
    options: GlbOptions,
) -> Result<(), ExportError> {
    let doc = Document::new(scene, options);
    poinav_io::write_atomic_with(path, |w| doc.write(w)).map_err(|e| ExportError::Write {
        path: path.display().to_string(),
        message: e.to_string(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec3;
    use poinav_geom::{ElementMesh, Mesh};
    use poinav_ifc::spatial::Storey;
    use poinav_ifc::EntityId;

    fn u32_at(b: &[u8], at: usize) -> u32 {
        u32::from_le_bytes(b[at..at + 4].try_into().unwrap())
    }

    fn scene_of(elements: &[ElementMesh], storeys: &[Storey]) -> Vec<u8> {
        to_glb(&SceneInput {
            storeys,
            elements,
            poi: None,
        })
    }

    fn triangle(id: u64, name: &str) -> ElementMesh {
        ElementMesh {
            product: EntityId(id),
            global_id: format!("g{id}"),
            class: "IfcSlab".into(),
            name: Some(name.into()),
            storey: Some(EntityId(1)),
            mesh: Mesh {
                positions: vec![DVec3::ZERO, DVec3::X, DVec3::Y],
                triangles: vec![[0, 1, 2]],
            },
            color: None,
        }
    }

    #[test]
    fn chunks_are_aligned_and_lengths_add_up() {
        let storeys = [Storey {
            id: EntityId(1),
            global_id: Some("s".into()),
            name: Some("L".into()),
            elevation_m: Some(0.0),
        }];
        // Names of varied lengths make the JSON length vary modulo 4.
        for name in ["a", "ab", "abc", "abcd"] {
            let b = scene_of(&[triangle(7, name)], &storeys);
            assert_eq!(u32_at(&b, 0), GLB_MAGIC);
            assert_eq!(&b[0..4], b"glTF");
            assert_eq!(u32_at(&b, 4), 2);
            assert_eq!(u32_at(&b, 8) as usize, b.len());
            let json_len = u32_at(&b, 12) as usize;
            assert_eq!(u32_at(&b, 16), CHUNK_JSON);
            assert_eq!(json_len % 4, 0);
            let json: Value = serde_json::from_slice(&b[20..20 + json_len]).unwrap();
            let bin_at = 20 + json_len;
            assert_eq!(bin_at % 4, 0);
            let bin_len = u32_at(&b, bin_at) as usize;
            assert_eq!(u32_at(&b, bin_at + 4), CHUNK_BIN);
            assert_eq!(bin_len % 4, 0);
            assert_eq!(bin_at + 8 + bin_len, b.len());
            assert_eq!(json["buffers"][0]["byteLength"], bin_len);
            for v in json["bufferViews"].as_array().unwrap() {
                assert_eq!(v["byteOffset"].as_u64().unwrap() % 4, 0);
            }
            assert_eq!(json["asset"]["generator"], generator());
        }
    }

    #[test]
    fn a_scene_without_geometry_has_no_bin_chunk_and_no_empty_arrays() {
        let mut e = triangle(3, "empty");
        e.mesh = Mesh::default();
        e.storey = None;
        let b = scene_of(&[e], &[]);
        let json_len = u32_at(&b, 12) as usize;
        assert_eq!(b.len(), 20 + json_len);
        let json: Value = serde_json::from_slice(&b[20..]).unwrap();
        assert_eq!(json["nodes"].as_array().unwrap().len(), 2);
        for key in ["meshes", "accessors", "bufferViews", "buffers", "materials"] {
            assert!(json.get(key).is_none(), "{key}");
        }
        let nothing = scene_of(&[], &[]);
        let json: Value = serde_json::from_slice(&nothing[20..]).unwrap();
        assert!(json.get("nodes").is_none());
        assert!(json["scenes"][0].get("nodes").is_none());
    }

    #[test]
    fn the_same_scene_gives_the_same_bytes() {
        let storeys = [];
        let elements = [triangle(1, "x"), triangle(2, "y")];
        assert_eq!(scene_of(&elements, &storeys), scene_of(&elements, &storeys));
    }
}
