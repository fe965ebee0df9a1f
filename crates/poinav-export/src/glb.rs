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
//! Geometry: one mesh with one triangle primitive per element that has triangles; `POSITION`
//! (f32, with the `min`/`max` glTF requires), flat `NORMAL`s (a vertex is shared only by
//! triangles of the same plane: architecture has sharp edges) and `u32` indices. All data
//! sits in one buffer with three buffer views (positions, normals, indices), each 4-byte
//! aligned. One material per distinct colour (`pbrMetallicRoughness`, metallic 0, roughness
//! 1, double-sided, `BLEND` when not opaque); IFC colours are sRGB and are converted to the
//! linear `baseColorFactor`.
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

use crate::palette::srgb_to_linear;
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
const FLOAT: u32 = 5126;
const UNSIGNED_INT: u32 = 5125;

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

/// A prepared GLB: its JSON chunk (padded) and the element geometry its BIN chunk holds.
struct Document {
    json: Vec<u8>,
    flats: Vec<Flat>,
    /// Unpadded length of the BIN chunk's data.
    bin_len: usize,
}

impl Document {
    /// Prepares `scene`: each element is localised and flattened in turn, so the scene's
    /// geometry is held once (as [`Flat`]s), and the JSON is serialised.
    fn new(scene: &SceneInput<'_>) -> Document {
        let (value, flats, bin_len) = json_and_flats(scene);
        let mut json = serde_json::to_vec(&value).expect("serialising JSON to memory");
        drop(value);
        while json.len() % 4 != 0 {
            json.push(b' ');
        }
        Document {
            json,
            flats,
            bin_len,
        }
    }

    /// Total GLB length in bytes.
    fn len(&self) -> usize {
        let bin = if self.bin_len == 0 {
            0
        } else {
            8 + self.bin_len.next_multiple_of(4)
        };
        12 + 8 + self.json.len() + bin
    }

    /// Writes the GLB: a 12-byte header, the JSON chunk (padded with spaces to 4 bytes) and,
    /// when there is geometry, the BIN chunk (positions, normals, indices; padded with zeros).
    fn write(&self, w: &mut impl Write) -> std::io::Result<()> {
        let mut head = Vec::with_capacity(28);
        head.extend_from_slice(&GLB_MAGIC.to_le_bytes());
        head.extend_from_slice(&2u32.to_le_bytes());
        head.extend_from_slice(&(self.len() as u32).to_le_bytes());
        head.extend_from_slice(&(self.json.len() as u32).to_le_bytes());
        head.extend_from_slice(&CHUNK_JSON.to_le_bytes());
        w.write_all(&head)?;
        w.write_all(&self.json)?;
        if self.bin_len == 0 {
            return Ok(());
        }
        let padded = self.bin_len.next_multiple_of(4);
        head.clear();
        head.extend_from_slice(&(padded as u32).to_le_bytes());
        head.extend_from_slice(&CHUNK_BIN.to_le_bytes());
        w.write_all(&head)?;
        let mut buf = ChunkBuffer::new(w);
        for f in &self.flats {
            buf.f32s(f.positions.iter().flatten())?;
        }
        for f in &self.flats {
            buf.f32s(f.normals.iter().flatten())?;
        }
        for f in &self.flats {
            for i in &f.indices {
                buf.bytes(&i.to_le_bytes())?;
            }
        }
        buf.bytes(&[0; 3][..padded - self.bin_len])?;
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

/// The glTF JSON document, the flattened geometry and the BIN data's length.
fn json_and_flats(scene: &SceneInput<'_>) -> (Value, Vec<Flat>, usize) {
    let mut flats = Vec::with_capacity(scene.elements.len());
    let mut seen = FxHashMap::default();
    let p = prepare_with(scene, |e| flats.push(flatten(e, &mut seen)));
    drop(seen);
    let n_pos: usize = flats.iter().map(|f| f.positions.len()).sum();
    let n_idx: usize = flats.iter().map(|f| f.indices.len()).sum();
    let normals_at = n_pos * 12;
    let indices_at = normals_at + n_pos * 12;
    let bin_len = indices_at + n_idx * 4;

    let mut accessors = Vec::new();
    let mut meshes = Vec::new();
    let mut mesh_of = vec![None; flats.len()];
    let (mut pos_off, mut idx_off) = (0usize, 0usize);
    for (i, (f, e)) in flats.iter().zip(&p.elements).enumerate() {
        if f.indices.is_empty() {
            continue;
        }
        let (mut lo, mut hi) = ([f32::INFINITY; 3], [f32::NEG_INFINITY; 3]);
        for v in &f.positions {
            for k in 0..3 {
                lo[k] = lo[k].min(v[k]);
                hi[k] = hi[k].max(v[k]);
            }
        }
        let a = accessors.len();
        accessors.push(json!({
            "bufferView": 0, "byteOffset": pos_off * 12, "componentType": FLOAT,
            "count": f.positions.len(), "type": "VEC3",
            "min": lo.map(num), "max": hi.map(num),
        }));
        accessors.push(json!({
            "bufferView": 1, "byteOffset": pos_off * 12, "componentType": FLOAT,
            "count": f.positions.len(), "type": "VEC3",
        }));
        accessors.push(json!({
            "bufferView": 2, "byteOffset": idx_off * 4, "componentType": UNSIGNED_INT,
            "count": f.indices.len(), "type": "SCALAR",
        }));
        pos_off += f.positions.len();
        idx_off += f.indices.len();
        mesh_of[i] = Some(meshes.len());
        meshes.push(json!({
            "name": e.label,
            "primitives": [{
                "attributes": {"POSITION": a, "NORMAL": a + 1},
                "indices": a + 2,
                "material": e.material,
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
        if g.origin != glam::DVec3::ZERO {
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
            if let Some(m) = mesh_of[i] {
                node.insert("mesh".into(), json!(m));
            }
            if e.translation != glam::DVec3::ZERO {
                node.insert("translation".into(), json!(e.translation.to_array()));
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
        put(
            "bufferViews",
            vec![
                json!({"buffer": 0, "byteOffset": 0, "byteLength": normals_at,
                       "byteStride": 12, "target": ARRAY_BUFFER}),
                json!({"buffer": 0, "byteOffset": normals_at,
                       "byteLength": indices_at - normals_at,
                       "byteStride": 12, "target": ARRAY_BUFFER}),
                json!({"buffer": 0, "byteOffset": indices_at,
                       "byteLength": bin_len - indices_at,
                       "target": ELEMENT_ARRAY_BUFFER}),
            ],
        );
        put("buffers", vec![json!({"byteLength": bin_len})]);
    }
    (Value::Object(doc), flats, bin_len)
}

/// The glTF JSON of `scene` alone (the document the GLB's JSON chunk holds).
pub fn to_gltf_json(scene: &SceneInput<'_>) -> serde_json::Value {
    json_and_flats(scene).0
}

/// The GLB bytes of `scene`: a 12-byte header, the JSON chunk (padded with spaces to 4 bytes)
/// and, when there is geometry, the BIN chunk (padded with zeros to 4 bytes).
pub fn to_glb(scene: &SceneInput<'_>) -> Vec<u8> {
    let doc = Document::new(scene);
    let mut out = Vec::with_capacity(doc.len());
    doc.write(&mut out).expect("writing to memory");
    out
}

/// Writes the GLB of `scene` to `path` atomically, streaming the geometry to the file (the
/// whole GLB is never built in memory).
pub fn write_glb(path: &Path, scene: &SceneInput<'_>) -> Result<(), ExportError> {
    let doc = Document::new(scene);
    poinav_ifc::output::write_atomic_with(path, |w| doc.write(w)).map_err(|e| ExportError::Write {
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
