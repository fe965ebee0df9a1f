//! The GLB and FBX exports checked by the real tools: a hand-made building (boxes on two
//! storeys, styled and palette colours, a translucent window, an element without geometry,
//! one without a storey, one far from the origin, a classified door) is exported, the GLB is
//! run through the Khronos glTF-Validator (`tests/js/validate-gltf.cjs`, 0 errors and 0
//! warnings) and the FBX through assimp (`assimp info`: one mesh per element with triangles,
//! node names carrying the GlobalIds, the structure and bounds assimp reads from the plain GLB),
//! and both are read back to check hierarchy, metadata, the Y-up frame and the geometry (the
//! default GLB's shared, quantised meshes decoded and placed as a glTF reader does); the GLB
//! split per storey passes the validator part by part and places every element as the whole
//! GLB does. Missing tools fail the test, naming the install command
//! (`bash tests/js/setup.sh`).

mod common;

use std::path::{Path, PathBuf};
use std::process::Command;

use glam::DVec3;
use poinav_export::glb::GlbOptions;
use poinav_export::scene::{z_up_to_y_up, NO_STOREY};
use poinav_export::{fbx, glb, glb_chunks, SceneInput};
use poinav_geom::{ElementMesh, Mesh};
use poinav_ifc::spatial::Storey;
use poinav_ifc::EntityId;
use poinav_poi::{
    Accessibility, AccessibilityKind, AccessibilityStatus, Category, Classification, Classified,
    Facts, PoiType, RobotProfile, Role, ValidationMethod,
};
use serde_json::Value;

const SETUP: &str = "bash tests/js/setup.sh (npm ci --prefix tests/js; apt-get update && \
                     apt-get install -y assimp-utils)";

/// A closed box, triangles counter-clockwise seen from outside.
fn cuboid(min: DVec3, max: DVec3) -> Mesh {
    let positions = (0..8)
        .map(|i| {
            DVec3::new(
                if i & 1 == 0 { min.x } else { max.x },
                if i & 2 == 0 { min.y } else { max.y },
                if i & 4 == 0 { min.z } else { max.z },
            )
        })
        .collect();
    let quads = [
        [0, 2, 3, 1],
        [4, 5, 7, 6],
        [0, 1, 5, 4],
        [2, 6, 7, 3],
        [0, 4, 6, 2],
        [1, 3, 7, 5],
    ];
    let triangles = quads
        .iter()
        .flat_map(|[a, b, c, d]| [[*a, *b, *c], [*a, *c, *d]])
        .collect();
    Mesh {
        positions,
        triangles,
    }
}

fn v(x: f64, y: f64, z: f64) -> DVec3 {
    DVec3::new(x, y, z)
}

struct Building {
    storeys: Vec<Storey>,
    elements: Vec<ElementMesh>,
    poi: Classification,
}

const L0: EntityId = EntityId(100);
const L1: EntityId = EntityId(200);

fn element(
    id: u64,
    guid: &str,
    class: &str,
    name: Option<&str>,
    storey: Option<EntityId>,
    mesh: Mesh,
    color: Option<[f32; 4]>,
) -> ElementMesh {
    ElementMesh {
        product: EntityId(id),
        global_id: guid.into(),
        class: class.into(),
        name: name.map(str::to_string),
        storey,
        mesh,
        color,
    }
}

fn building() -> Building {
    let red = Some([0.8, 0.1, 0.1, 1.0]);
    let storeys = vec![
        Storey {
            id: L0,
            global_id: Some("0StoreyGround0000000001".into()),
            name: Some("Ground floor".into()),
            elevation_m: Some(0.0),
        },
        Storey {
            id: L1,
            global_id: Some("0StoreyFirst$000000_002".into()),
            name: Some("First floor".into()),
            elevation_m: Some(3.0),
        },
    ];
    let elements = vec![
        element(
            1,
            "1Wall$A0000000000000001",
            "IfcWallStandardCase",
            Some("Wall A"),
            Some(L0),
            cuboid(v(0.0, 0.0, 0.0), v(5.0, 0.2, 3.0)),
            None,
        ),
        element(
            2,
            "1Slab_00000000000000002",
            "IfcSlab",
            Some("Floor slab"),
            Some(L0),
            cuboid(v(0.0, 0.0, -0.3), v(5.0, 4.0, 0.0)),
            red,
        ),
        element(
            3,
            "1Door000000000000000003",
            "IfcDoor",
            Some("Door D1"),
            Some(L1),
            cuboid(v(1.0, 0.0, 3.0), v(1.9, 0.2, 5.1)),
            red,
        ),
        element(
            4,
            "1Window00000000000000004",
            "IfcWindow",
            None,
            Some(L1),
            cuboid(v(3.0, 0.0, 4.0), v(4.2, 0.1, 5.2)),
            None,
        ),
        element(
            5,
            "1Opening0000000000000005",
            "IfcBuildingElementProxy",
            Some("No geometry"),
            Some(L1),
            Mesh::default(),
            Some([0.2, 0.9, 0.2, 1.0]),
        ),
        element(
            6,
            "1Chair00000000000000006",
            "IfcFurniture",
            Some("Chair"),
            None,
            cuboid(v(2.0, 2.0, 0.0), v(2.5, 2.5, 0.9)),
            None,
        ),
        // Georeferenced: 600 km east, 5000 km north.
        element(
            7,
            "1Survey0000000000000007",
            "IfcColumn",
            Some("Survey column"),
            Some(L0),
            cuboid(
                v(600_000.0, 5_000_000.0, 0.0),
                v(600_000.3, 5_000_000.3, 3.0),
            ),
            Some([0.3, 0.3, 0.9, 1.0]),
        ),
    ];
    let door = Classified {
        id: EntityId(3),
        global_id: "1Door000000000000000003".into(),
        class: "IfcDoor".into(),
        name: Some("Door D1".into()),
        storey: Some("First floor".into()),
        rule: "R2-door".into(),
        category: Category::Structural,
        poi_type: PoiType::TransitionElement,
        primary: vec![Role::Transition],
        conditional: vec![Role::Narrow],
        accessibility_kind: AccessibilityKind::ClearWidth,
        accessibility: Some(Accessibility {
            min_clearance_width_m: 0.9,
            min_clearance_height_m: 2.0,
            status: AccessibilityStatus::Restricted,
            method: ValidationMethod::GeometricAnalysis,
            reason: "clear width 0.850 m".into(),
        }),
        coordination: None,
        facts: Facts::default(),
    };
    Building {
        storeys,
        elements,
        poi: Classification {
            profile: RobotProfile::paper(),
            elements: vec![door],
        },
    }
}

fn scene(b: &Building) -> SceneInput<'_> {
    SceneInput {
        storeys: &b.storeys,
        elements: &b.elements,
        poi: Some(&b.poi),
    }
}

/// Runs the Khronos glTF-Validator on `files`; one report each.
fn gltf_validator(files: &[&Path]) -> Vec<Value> {
    let js = common::root().join("tests/js");
    assert!(
        js.join("node_modules/gltf-validator/package.json")
            .is_file(),
        "the Khronos glTF-Validator is not installed in tests/js/node_modules: run {SETUP}"
    );
    let out = Command::new("node")
        .arg(js.join("validate-gltf.cjs"))
        .args(files)
        .output()
        .unwrap_or_else(|e| panic!("node (Node.js) cannot be run ({e}): install it, then {SETUP}"));
    assert!(
        out.status.success(),
        "glTF-Validator failed: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    let reports: Value = serde_json::from_slice(&out.stdout).expect("the validator prints JSON");
    reports.as_array().unwrap().clone()
}

/// `assimp info FILE`'s output; `raw` adds `-r` (no post-processing: assimp's default
/// post-processing merges identical meshes into instances, so only a raw import counts one
/// mesh per element in general).
fn assimp_info(file: &Path, raw: bool) -> String {
    let mut cmd = Command::new("assimp");
    cmd.arg("info").arg(file);
    if raw {
        cmd.arg("-r");
    }
    let out = cmd
        .output()
        .unwrap_or_else(|e| panic!("assimp cannot be run ({e}): run {SETUP}"));
    let text = String::from_utf8_lossy(&out.stdout).into_owned();
    assert!(
        out.status.success(),
        "assimp info {} failed: {text}{}",
        file.display(),
        String::from_utf8_lossy(&out.stderr)
    );
    text
}

/// The JSON chunk of a GLB.
fn glb_json(bytes: &[u8]) -> Value {
    let len = u32::from_le_bytes(bytes[12..16].try_into().unwrap()) as usize;
    serde_json::from_slice(&bytes[20..20 + len]).unwrap()
}

/// A GLB accessor's VEC3 values as read: `f32`, or quantised (`SHORT` positions as the
/// integers stored, normalised `BYTE`s divided by 127), at the buffer view's stride.
fn vec3s(bytes: &[u8], json: &Value, accessor: usize) -> Vec<DVec3> {
    let json_len = u32::from_le_bytes(bytes[12..16].try_into().unwrap()) as usize;
    let bin = &bytes[20 + json_len + 8..];
    let a = &json["accessors"][accessor];
    let view = &json["bufferViews"][a["bufferView"].as_u64().unwrap() as usize];
    let start = (view["byteOffset"].as_u64().unwrap() + a["byteOffset"].as_u64().unwrap()) as usize;
    let (size, read): (usize, &dyn Fn(usize) -> f64) = match a["componentType"].as_u64().unwrap() {
        5126 => (4, &|i| {
            f64::from(f32::from_le_bytes(bin[i..i + 4].try_into().unwrap()))
        }),
        5122 => (2, &|i| {
            f64::from(i16::from_le_bytes(bin[i..i + 2].try_into().unwrap()))
        }),
        5120 => {
            assert_eq!(a["normalized"], true, "signed bytes are normalised normals");
            (1, &|i| f64::from(bin[i] as i8) / 127.0)
        }
        t => panic!("component type {t}"),
    };
    let stride = view["byteStride"].as_u64().map_or(3 * size, |s| s as usize);
    (0..a["count"].as_u64().unwrap() as usize)
        .map(|k| {
            let at = start + stride * k;
            DVec3::new(read(at), read(at + size), read(at + 2 * size))
        })
        .collect()
}

/// A node's `translation`, `rotation` and `scale` (identity where absent) applied to `p`.
fn node_transform(node: &Value, p: DVec3) -> DVec3 {
    let f = |k: &str, i: usize, d: f64| node.get(k).map_or(d, |a| a[i].as_f64().unwrap());
    let t = DVec3::new(
        f("translation", 0, 0.0),
        f("translation", 1, 0.0),
        f("translation", 2, 0.0),
    );
    let r = glam::DQuat::from_xyzw(
        f("rotation", 0, 0.0),
        f("rotation", 1, 0.0),
        f("rotation", 2, 0.0),
        f("rotation", 3, 1.0),
    );
    let s = DVec3::new(f("scale", 0, 1.0), f("scale", 1, 1.0), f("scale", 2, 1.0));
    t + r * (s * p)
}

/// The world (Y up) vertices of element node `n` under group node `g`, decoded and
/// dequantised as a glTF reader does, and the largest error quantisation allows there.
fn world_vertices(bytes: &[u8], json: &Value, g: &Value, n: &Value) -> (Vec<DVec3>, f64) {
    let m = n["mesh"].as_u64().unwrap() as usize;
    let prim = &json["meshes"][m]["primitives"][0];
    let acc = prim["attributes"]["POSITION"].as_u64().unwrap() as usize;
    let step = n.get("scale").map_or(0.0, |s| s[1].as_f64().unwrap());
    let ps = vec3s(bytes, json, acc)
        .into_iter()
        .map(|p| node_transform(g, node_transform(n, p)))
        .collect();
    (ps, step * 0.87 + 1e-6)
}

fn tmp() -> tempfile::TempDir {
    tempfile::tempdir().unwrap()
}

fn outputs(dir: &Path) -> (PathBuf, PathBuf) {
    (dir.join("building.glb"), dir.join("building.fbx"))
}

#[test]
fn glb_passes_the_khronos_validator_with_one_node_per_element() {
    let b = building();
    let dir = tmp();
    let (glb_path, _) = outputs(dir.path());
    glb::write_glb(&glb_path, &scene(&b)).unwrap();
    let bytes = std::fs::read(&glb_path).unwrap();
    assert_eq!(bytes, glb::to_glb(&scene(&b)), "write_glb writes to_glb");
    assert_eq!(
        bytes,
        glb::to_glb_with(&scene(&b), GlbOptions::COMPACT),
        "compact by default"
    );
    check_building_glb(GlbOptions::COMPACT);
    check_building_glb(GlbOptions::PLAIN);
}

/// The building's GLB written as `options` say: the validator's verdict, the hierarchy, the
/// metadata and the geometry read back.
fn check_building_glb(options: GlbOptions) {
    let b = building();
    let dir = tmp();
    let (glb_path, _) = outputs(dir.path());
    glb::write_glb_with(&glb_path, &scene(&b), options).unwrap();
    let bytes = std::fs::read(&glb_path).unwrap();
    assert_eq!(
        bytes,
        glb::to_glb_with(&scene(&b), options),
        "write_glb_with writes to_glb_with"
    );
    assert_eq!(
        bytes,
        glb::to_glb_with(&scene(&b), options),
        "deterministic"
    );

    let report = &gltf_validator(&[&glb_path])[0];
    let issues = &report["issues"];
    eprintln!(
        "glTF-Validator {}: {} errors, {} warnings, {} infos, {} hints",
        report["validatorVersion"],
        issues["numErrors"],
        issues["numWarnings"],
        issues["numInfos"],
        issues["numHints"]
    );
    assert_eq!(issues["numErrors"], 0, "{:#}", issues["messages"]);
    assert_eq!(issues["numWarnings"], 0, "{:#}", issues["messages"]);
    assert_eq!(report["mimeType"], "model/gltf-binary");
    let with_triangles = b.elements.iter().filter(|e| !e.mesh.is_empty()).count();
    assert_eq!(report["info"]["drawCallCount"], with_triangles);

    let json = glb_json(&bytes);
    assert_eq!(
        json["asset"]["generator"],
        format!("poinav {}", env!("CARGO_PKG_VERSION"))
    );
    let nodes = json["nodes"].as_array().unwrap();
    // Two storeys, the "No storey" group, then exactly one node per element.
    assert_eq!(nodes.len(), 3 + b.elements.len());
    let element_nodes: Vec<&Value> = nodes
        .iter()
        .filter(|n| {
            n["extras"]["GlobalId"].is_string() && n["extras"]["IfcClass"] != "IfcBuildingStorey"
        })
        .collect();
    assert_eq!(element_nodes.len(), b.elements.len());
    let roots = json["scenes"][0]["nodes"].as_array().unwrap();
    let group_names: Vec<&str> = roots
        .iter()
        .map(|r| {
            nodes[r.as_u64().unwrap() as usize]["name"]
                .as_str()
                .unwrap()
        })
        .collect();
    assert_eq!(group_names, ["Ground floor", "First floor", NO_STOREY]);
    assert_eq!(nodes[1]["translation"], serde_json::json!([0.0, 3.0, 0.0]));
    assert_eq!(nodes[1]["extras"]["GlobalId"], "0StoreyFirst$000000_002");
    assert_eq!(json["meshes"].as_array().unwrap().len(), with_triangles);
    // Red is shared by the slab and the door; wall, window, chair, column: own colours.
    assert_eq!(json["materials"].as_array().unwrap().len(), 5);

    for (gi, storey_name) in [
        (0, Some("Ground floor")),
        (1, Some("First floor")),
        (2, None),
    ] {
        for c in nodes[gi]["children"].as_array().unwrap() {
            let n = &nodes[c.as_u64().unwrap() as usize];
            let guid = n["extras"]["GlobalId"].as_str().unwrap();
            let e = b.elements.iter().find(|e| e.global_id == guid).unwrap();
            assert_eq!(n["extras"]["IfcClass"], e.class.as_str());
            assert_eq!(n["extras"]["Storey"].as_str(), storey_name);
            let name = e.name.clone().unwrap_or(e.class.clone());
            assert_eq!(n["name"], name.as_str());
            assert_eq!(n.get("mesh").is_some(), !e.mesh.is_empty(), "{guid}");
            let Some(m) = n["mesh"].as_u64() else {
                continue;
            };
            // World bounds (Y up) of the vertices as a reader places them: storey node, then
            // element node (translation, rotation, scale: the quantisation step).
            let (world, tolerance) = world_vertices(&bytes, &json, &nodes[gi], n);
            let (lo, hi) = e.mesh.bounds().unwrap();
            let (a, c) = (z_up_to_y_up(lo), z_up_to_y_up(hi));
            let want_lo = a.min(c);
            let want_hi = a.max(c);
            let got_lo = world.iter().fold(DVec3::INFINITY, |m, p| m.min(*p));
            let got_hi = world.iter().fold(DVec3::NEG_INFINITY, |m, p| m.max(*p));
            assert!(
                (got_lo - want_lo).length() < tolerance,
                "{guid} {options:?}: {got_lo} {want_lo}"
            );
            assert!(
                (got_hi - want_hi).length() < tolerance,
                "{guid} {options:?}: {got_hi} {want_hi}"
            );
            if options == GlbOptions::PLAIN {
                assert!(tolerance <= 1e-6);
            } else {
                // 1/32767 of the half-size: under 0.1 mm for these boxes.
                assert!(tolerance < 1e-4, "{guid}: {tolerance}");
            }
            let prim = &json["meshes"][m as usize]["primitives"][0];
            // Flat normals: every normal is one of the six axis directions of a box.
            let normals = vec3s(
                &bytes,
                &json,
                prim["attributes"]["NORMAL"].as_u64().unwrap() as usize,
            );
            assert_eq!(normals.len(), 24, "4 corners x 6 faces");
            for n in normals {
                assert!((n.length() - 1.0).abs() < 1e-6);
                assert_eq!(n.abs().max_element(), 1.0);
            }
        }
    }
    let door = element_nodes
        .iter()
        .find(|n| n["extras"]["GlobalId"] == "1Door000000000000000003")
        .unwrap();
    assert_eq!(door["extras"]["POI_Category"], "Structural");
    assert_eq!(door["extras"]["POI_Type"], "Transition Element");
    assert_eq!(
        door["extras"]["POI_PrimaryRoles"],
        serde_json::json!(["A-2"])
    );
    assert_eq!(
        door["extras"]["POI_ConditionalRoles"],
        serde_json::json!(["B-2"])
    );
    assert_eq!(door["extras"]["AccessibilityStatus"], "RESTRICTED");
    let wall = element_nodes
        .iter()
        .find(|n| n["name"] == "Wall A")
        .unwrap();
    assert!(wall["extras"].get("POI_Category").is_none());
}

#[test]
fn glb_edge_cases_pass_the_validator() {
    // No elements at all; only empty meshes; no storeys; degenerate-only geometry.
    let degenerate = Mesh {
        positions: vec![DVec3::ZERO, DVec3::X, DVec3::X * 2.0],
        triangles: vec![[0, 1, 2], [0, 0, 1]],
    };
    let e = |id, mesh| {
        element(
            id,
            &format!("2Edge{id:018}"),
            "IfcWall",
            None,
            None,
            mesh,
            None,
        )
    };
    let cases: Vec<Vec<ElementMesh>> = vec![
        vec![],
        vec![e(1, Mesh::default())],
        vec![e(1, degenerate), e(2, cuboid(DVec3::ZERO, DVec3::ONE))],
    ];
    let dir = tmp();
    let mut files = Vec::new();
    let options = [GlbOptions::COMPACT, GlbOptions::PLAIN];
    for (i, (elements, options)) in cases
        .iter()
        .flat_map(|c| options.map(|o| (c, o)))
        .enumerate()
    {
        let path = dir.path().join(format!("case{i}.glb"));
        let s = SceneInput {
            storeys: &[],
            elements,
            poi: None,
        };
        glb::write_glb_with(&path, &s, options).unwrap();
        let json = glb_json(&std::fs::read(&path).unwrap());
        let groups = usize::from(!elements.is_empty());
        assert_eq!(
            json.get("nodes").map_or(0, |n| n.as_array().unwrap().len()),
            elements.len() + groups
        );
        files.push(path);
    }
    let paths: Vec<&Path> = files.iter().map(PathBuf::as_path).collect();
    for r in gltf_validator(&paths) {
        assert_eq!(
            r["issues"]["numErrors"], 0,
            "{}: {:#}",
            r["file"], r["issues"]["messages"]
        );
        assert_eq!(
            r["issues"]["numWarnings"], 0,
            "{}: {:#}",
            r["file"], r["issues"]["messages"]
        );
    }
}

/// A chair's mesh (an irregular solid: a box with one corner raised) moved by `t` after `m`,
/// keeping the vertex order, as the mesh of a mapped item placed again is.
/// Every element node of a GLB: (GlobalId, world vertices) under its group node.
fn element_vertices(bytes: &[u8]) -> Vec<(String, Vec<DVec3>)> {
    let json = glb_json(bytes);
    let nodes = json["nodes"].as_array().unwrap();
    let mut out = Vec::new();
    for r in json["scenes"][0]["nodes"].as_array().unwrap() {
        let g = &nodes[r.as_u64().unwrap() as usize];
        for c in g["children"].as_array().into_iter().flatten() {
            let n = &nodes[c.as_u64().unwrap() as usize];
            let id = n["extras"]["GlobalId"].as_str().unwrap().to_string();
            let ps = if n.get("mesh").is_some() {
                world_vertices(bytes, &json, g, n).0
            } else {
                Vec::new()
            };
            out.push((id, ps));
        }
    }
    out
}

#[test]
fn glb_per_storey_parts_pass_the_validator_and_hold_every_element_once() {
    let b = building();
    let mut elements = b.elements.clone();
    let parts =
        glb_chunks::to_glb_per_storey(&b.storeys, &mut elements, Some(&b.poi), GlbOptions::COMPACT);
    // Ground floor: wall, slab, survey column; first floor: door, window, the element
    // without geometry; then the chair without a storey.
    let storeys: Vec<(Option<usize>, usize)> =
        parts.iter().map(|p| (p.storey, p.elements)).collect();
    assert_eq!(storeys, [(Some(0), 3), (Some(1), 3), (None, 1)]);
    let again = glb_chunks::to_glb_per_storey(
        &b.storeys,
        &mut b.elements.clone(),
        Some(&b.poi),
        GlbOptions::COMPACT,
    );
    assert_eq!(parts, again, "deterministic");

    let dir = tmp();
    let files: Vec<PathBuf> = parts
        .iter()
        .enumerate()
        .map(|(k, p)| {
            let f = dir.path().join(format!("{k}.glb"));
            std::fs::write(&f, &p.glb).unwrap();
            f
        })
        .collect();
    let reports = gltf_validator(&files.iter().map(PathBuf::as_path).collect::<Vec<_>>());
    assert_eq!(reports.len(), 3);
    for (r, want) in reports
        .iter()
        .zip(["Ground floor", "First floor", NO_STOREY])
    {
        let issues = &r["issues"];
        assert_eq!(issues["numErrors"], 0, "{want}: {:#}", issues["messages"]);
        assert_eq!(issues["numWarnings"], 0, "{want}: {:#}", issues["messages"]);
    }
    for (p, want) in parts.iter().zip(["Ground floor", "First floor", NO_STOREY]) {
        let json = glb_json(&p.glb);
        let roots = json["scenes"][0]["nodes"].as_array().unwrap();
        assert_eq!(roots.len(), 1);
        assert_eq!(
            json["nodes"][roots[0].as_u64().unwrap() as usize]["name"],
            want
        );
    }

    // Together the parts hold exactly the whole GLB's elements, each where the whole puts it.
    let mut whole = element_vertices(&glb::to_glb(&scene(&b)));
    let mut split: Vec<_> = parts
        .iter()
        .flat_map(|p| element_vertices(&p.glb))
        .collect();
    whole.sort_by(|a, b| a.0.cmp(&b.0));
    split.sort_by(|a, b| a.0.cmp(&b.0));
    assert_eq!(whole.len(), b.elements.len());
    assert_eq!(split.len(), whole.len());
    for ((id, w), (sid, s)) in whole.iter().zip(&split) {
        assert_eq!(id, sid);
        assert_eq!(w.len(), s.len(), "{id}");
        for (a, c) in w.iter().zip(s) {
            assert!(a.distance(*c) < 1e-3, "{id}: {a} vs {c}");
        }
    }
}

fn chair(m: glam::DMat3, t: DVec3) -> Mesh {
    let mut mesh = cuboid(v(0.0, 0.0, 0.0), v(0.5, 0.45, 0.9));
    mesh.positions[7].z += 0.2;
    for p in &mut mesh.positions {
        *p = m * *p + t;
    }
    mesh
}

#[test]
fn glb_copies_share_one_mesh_and_land_where_their_elements_are() {
    use glam::{DMat3, DQuat};
    let turn = DMat3::from_quat(DQuat::from_rotation_z(0.6));
    let mirror = turn * DMat3::from_diagonal(DVec3::new(1.0, -1.0, 1.0));
    let meshes = [
        chair(DMat3::IDENTITY, v(1.0, 1.0, 0.0)),
        chair(DMat3::IDENTITY, v(4.0, 1.5, 0.0)),
        chair(turn, v(2.0, 5.0, 3.0)),
        chair(mirror, v(-3.0, 2.0, 0.0)),
        // Stretched: not a copy.
        chair(
            DMat3::from_diagonal(DVec3::new(1.2, 1.0, 1.0)),
            v(7.0, 0.0, 0.0),
        ),
        // Same shape, another colour: its own mesh.
        chair(DMat3::IDENTITY, v(9.0, 0.0, 0.0)),
    ];
    let elements: Vec<ElementMesh> = meshes
        .iter()
        .enumerate()
        .map(|(i, m)| {
            let colour = (i == 5).then_some([0.2, 0.2, 0.8, 1.0]);
            let guid = format!("3Chair{i:017}");
            element(
                i as u64 + 1,
                &guid,
                "IfcFurniture",
                None,
                Some(L0),
                m.clone(),
                colour,
            )
        })
        .collect();
    let b = building();
    let s = SceneInput {
        storeys: &b.storeys[..1],
        elements: &elements,
        poi: None,
    };
    let dir = tmp();
    let mut files = Vec::new();
    for (options, distinct) in [(GlbOptions::COMPACT, 3), (GlbOptions::PLAIN, 6)] {
        let path = dir.path().join(format!("chairs-{}.glb", files.len()));
        glb::write_glb_with(&path, &s, options).unwrap();
        let bytes = std::fs::read(&path).unwrap();
        let json = glb_json(&bytes);
        assert_eq!(
            json["meshes"].as_array().unwrap().len(),
            distinct,
            "{options:?}"
        );
        let nodes = json["nodes"].as_array().unwrap();
        for (i, e) in elements.iter().enumerate() {
            let n = &nodes[1 + i];
            assert_eq!(n["extras"]["GlobalId"], e.global_id.as_str());
            // Every vertex where the input has it (the mesh's own vertex order is kept).
            let (world, tolerance) = world_vertices(&bytes, &json, &nodes[0], n);
            for p in &e.mesh.positions {
                let want = z_up_to_y_up(*p);
                let d = world
                    .iter()
                    .map(|w| (*w - want).length())
                    .fold(f64::MAX, f64::min);
                assert!(d < tolerance, "{options:?} chair {i}: {want} off by {d}");
            }
        }
        if options == GlbOptions::COMPACT {
            assert_eq!(nodes[2]["mesh"], nodes[1]["mesh"]);
            assert!(nodes[2].get("rotation").is_none(), "only moved");
            assert_eq!(nodes[3]["mesh"], nodes[1]["mesh"]);
            assert!(nodes[3]["rotation"].is_array(), "turned");
            assert_eq!(nodes[4]["mesh"], nodes[1]["mesh"]);
            assert!(nodes[4]["scale"][0].as_f64().unwrap() < 0.0, "mirrored");
            assert_ne!(nodes[5]["mesh"], nodes[1]["mesh"]);
            assert_ne!(nodes[6]["mesh"], nodes[1]["mesh"]);
            assert_eq!(
                json["extensionsRequired"],
                serde_json::json!(["KHR_mesh_quantization"])
            );
        } else {
            assert!(json.get("extensionsUsed").is_none());
        }
        files.push(path);
    }
    let paths: Vec<&Path> = files.iter().map(PathBuf::as_path).collect();
    for r in gltf_validator(&paths) {
        assert_eq!(r["issues"]["numErrors"], 0, "{:#}", r["issues"]["messages"]);
        assert_eq!(
            r["issues"]["numWarnings"], 0,
            "{:#}",
            r["issues"]["messages"]
        );
        // The validator counts one draw call per primitive of a mesh, however many nodes
        // show it.
        let distinct = if r["file"].as_str().unwrap().ends_with("-0.glb") {
            3
        } else {
            6
        };
        assert_eq!(r["info"]["drawCallCount"], distinct);
    }
}

/// The value after `label` on the first line that has it (`Meshes:       6`).
fn count(info: &str, label: &str) -> usize {
    info.lines()
        .find_map(|l| l.trim().strip_prefix(label))
        .unwrap_or_else(|| panic!("no {label} in assimp's output:\n{info}"))
        .trim()
        .parse()
        .unwrap()
}

#[test]
fn fbx_opens_in_assimp_with_one_mesh_per_element() {
    let b = building();
    let dir = tmp();
    let (_, fbx_path) = outputs(dir.path());
    fbx::write_fbx(&fbx_path, &scene(&b)).unwrap();
    let bytes = std::fs::read(&fbx_path).unwrap();
    assert_eq!(
        bytes,
        fbx::to_fbx(&scene(&b)),
        "write_fbx writes to_fbx, deterministically"
    );
    assert!(bytes.starts_with(fbx::MAGIC));
    assert!(bytes.ends_with(&fbx::FOOTER_MAGIC));

    let info = assimp_info(&fbx_path, true);
    eprintln!("{info}");
    let with_triangles = b.elements.iter().filter(|e| !e.mesh.is_empty()).count();
    assert_eq!(count(&info, "Meshes:"), with_triangles);
    assert_eq!(count(&info, "Faces:"), 12 * with_triangles);
    // Root, three groups, one node per element.
    assert_eq!(count(&info, "Nodes:"), 1 + 3 + b.elements.len());
    // With assimp's default post-processing (validation included) too; the boxes all differ,
    // so no two meshes merge into instances.
    let processed = assimp_info(&fbx_path, false);
    assert_eq!(count(&processed, "Meshes:"), with_triangles);
    for e in &b.elements {
        assert!(
            info.contains(&format!("[{}]", e.global_id)),
            "no node named with {}:\n{info}",
            e.global_id
        );
    }
    // The hierarchy: storey -> elements, meshes only where there are triangles.
    let mut parent_of = std::collections::HashMap::new();
    let mut group = String::new();
    for line in info
        .lines()
        .skip_while(|l| !l.starts_with("Node hierarchy"))
    {
        if let Some(name) = line.strip_prefix("├╴").or(line.strip_prefix("└╴")) {
            group = name.to_string();
        } else if let Some(e) = b.elements.iter().find(|e| line.contains(&e.global_id)) {
            parent_of.insert(e.global_id.clone(), group.clone());
            assert_eq!(line.contains("(mesh "), !e.mesh.is_empty(), "{line}");
        }
    }
    assert_eq!(parent_of.len(), b.elements.len());
    for e in &b.elements {
        let want = match e.storey {
            Some(L0) => "Ground floor [0StoreyGround0000000001]",
            Some(L1) => "First floor [0StoreyFirst$000000_002]",
            _ => NO_STOREY,
        };
        assert_eq!(parent_of[&e.global_id], want, "{}", e.global_id);
    }
    // assimp's world bounds: metres, Y up (IFC y becomes -Z).
    let point = |label: &str| -> Vec<f64> {
        let line = info.lines().find(|l| l.starts_with(label)).unwrap();
        let inner = &line[line.find('(').unwrap() + 1..line.find(')').unwrap()];
        inner
            .split_whitespace()
            .map(|x| x.parse().unwrap())
            .collect()
    };
    let (lo, hi) = (point("Minimum point"), point("Maximum point"));
    assert!(
        (lo[1] - -0.3).abs() < 1e-5 && (hi[1] - 5.2).abs() < 1e-5,
        "{lo:?} {hi:?}"
    );
    assert!(
        lo[0].abs() < 1e-5 && (hi[0] - 600_000.3).abs() < 0.1,
        "{lo:?} {hi:?}"
    );
    assert!(
        (lo[2] - -5_000_000.3).abs() < 1.0 && hi[2].abs() < 1e-5,
        "{lo:?} {hi:?}"
    );

    // The GLB of the same scene, read by the same importer, has the same structure and bounds.
    let glb_path = dir.path().join("building.glb");
    // Plain: assimp 5.2 reads the structure of quantised GLBs but not the dequantising scale.
    glb::write_glb_with(&glb_path, &scene(&b), GlbOptions::PLAIN).unwrap();
    let from_glb = assimp_info(&glb_path, true);
    for label in ["Meshes:", "Nodes:", "Faces:"] {
        assert_eq!(count(&from_glb, label), count(&info, label), "{label}");
    }
    for label in ["Minimum point", "Maximum point"] {
        let line = |text: &str| {
            text.lines()
                .find(|l| l.starts_with(label))
                .unwrap()
                .to_string()
        };
        assert_eq!(line(&from_glb), line(&info));
    }
}

/// A record read back: name, properties (strings and integers only), children.
#[derive(Debug)]
struct Record {
    name: String,
    strings: Vec<String>,
    ints: Vec<i64>,
    children: Vec<Record>,
}

/// Reads the records from `at` to the null record that ends the list; checks that each end
/// offset is exactly where the record's content ends. Returns the records and the position
/// after the null record.
fn read_records(b: &[u8], mut at: usize) -> (Vec<Record>, usize) {
    let u32_at = |i: usize| u32::from_le_bytes(b[i..i + 4].try_into().unwrap()) as usize;
    let mut out = Vec::new();
    loop {
        let end = u32_at(at);
        if end == 0 {
            assert_eq!(&b[at..at + 13], &[0u8; 13]);
            return (out, at + 13);
        }
        let (count, list_len, name_len) = (u32_at(at + 4), u32_at(at + 8), b[at + 12] as usize);
        let name = String::from_utf8(b[at + 13..at + 13 + name_len].to_vec()).unwrap();
        let mut p = at + 13 + name_len;
        let props_start = p;
        let (mut strings, mut ints) = (Vec::new(), Vec::new());
        for _ in 0..count {
            let code = b[p];
            p += 1;
            match code {
                b'C' => p += 1,
                b'Y' => p += 2,
                b'I' => {
                    ints.push(i64::from(i32::from_le_bytes(
                        b[p..p + 4].try_into().unwrap(),
                    )));
                    p += 4
                }
                b'F' => p += 4,
                b'D' => p += 8,
                b'L' => {
                    ints.push(i64::from_le_bytes(b[p..p + 8].try_into().unwrap()));
                    p += 8
                }
                b'S' | b'R' => {
                    let n = u32_at(p);
                    if code == b'S' {
                        strings.push(String::from_utf8(b[p + 4..p + 4 + n].to_vec()).unwrap());
                    }
                    p += 4 + n
                }
                b'i' | b'l' | b'f' | b'd' | b'b' => {
                    assert_eq!(u32_at(p + 4), 0, "uncompressed");
                    let size = match code {
                        b'i' | b'f' => 4,
                        b'b' => 1,
                        _ => 8,
                    };
                    assert_eq!(u32_at(p + 8), u32_at(p) * size);
                    p += 12 + u32_at(p + 8)
                }
                other => panic!("unknown property type {other}"),
            }
        }
        assert_eq!(p - props_start, list_len, "{name}: property list length");
        let mut children = Vec::new();
        if p < end {
            let (c, after) = read_records(b, p);
            children = c;
            p = after;
        }
        assert_eq!(p, end, "{name}: end offset");
        out.push(Record {
            name,
            strings,
            ints,
            children,
        });
        at = end;
    }
}

impl Record {
    fn child(&self, name: &str) -> &Record {
        self.children.iter().find(|c| c.name == name).unwrap()
    }

    /// User properties (`P` with flag `U`) as (name, value).
    fn user_props(&self) -> Vec<(String, String)> {
        self.child("Properties70")
            .children
            .iter()
            .filter(|p| p.strings[3] == "U")
            .map(|p| (p.strings[0].clone(), p.strings[4].clone()))
            .collect()
    }
}

#[test]
fn fbx_records_nest_exactly_and_carry_the_metadata() {
    let b = building();
    let bytes = fbx::to_fbx(&scene(&b));
    let (top, after) = read_records(&bytes, 27);
    let names: Vec<&str> = top.iter().map(|r| r.name.as_str()).collect();
    assert_eq!(
        names,
        [
            "FBXHeaderExtension",
            "FileId",
            "CreationTime",
            "Creator",
            "GlobalSettings",
            "Documents",
            "References",
            "Definitions",
            "Objects",
            "Connections",
            "Takes"
        ]
    );
    // Footer: id, 4 zeros, padding to 16, version, 120 zeros, magic.
    assert_eq!(&bytes[after..after + 16], &fbx::FOOTER_ID);
    let tail = &bytes[after + 20..];
    let pad = tail.len() - 4 - 120 - 16;
    assert!((1..=16).contains(&pad) && (after + 20 + pad) % 16 == 0);
    assert_eq!(
        u32::from_le_bytes(tail[pad..pad + 4].try_into().unwrap()),
        7400
    );

    let settings = top[4].child("Properties70");
    let setting = |k: &str| {
        settings
            .children
            .iter()
            .find(|p| p.strings[0] == k)
            .map(|p| p.ints[0])
    };
    assert_eq!(setting("UpAxis"), Some(1));
    assert_eq!(setting("FrontAxis"), Some(2));
    assert_eq!(setting("CoordAxis"), Some(0));

    let objects = &top[8].children;
    let of = |ty: &str| objects.iter().filter(|o| o.name == ty).count() as i64;
    let definitions = &top[7];
    let total: i64 = definitions.child("Count").ints[0];
    assert_eq!(total, 1 + objects.len() as i64);
    for d in definitions
        .children
        .iter()
        .filter(|d| d.name == "ObjectType")
    {
        if d.strings[0] != "GlobalSettings" {
            assert_eq!(
                d.child("Count").ints[0],
                of(&d.strings[0]),
                "{}",
                d.strings[0]
            );
        }
    }
    let with_triangles = b.elements.iter().filter(|e| !e.mesh.is_empty()).count() as i64;
    assert_eq!(of("Geometry"), with_triangles);
    assert_eq!(of("Model"), (b.elements.len() + 3) as i64);
    assert_eq!(of("Material"), 5);

    let models: Vec<&Record> = objects.iter().filter(|o| o.name == "Model").collect();
    let door = models
        .iter()
        .find(|m| m.strings[0].starts_with("Door D1 [1Door000000000000000003]\0\x01Model"))
        .unwrap();
    assert_eq!(door.strings[1], "Mesh");
    let props = door.user_props();
    let get = |k: &str| props.iter().find(|(n, _)| n == k).map(|(_, v)| v.as_str());
    assert_eq!(get("GlobalId"), Some("1Door000000000000000003"));
    assert_eq!(get("IfcClass"), Some("IfcDoor"));
    assert_eq!(get("Storey"), Some("First floor"));
    assert_eq!(get("POI_PrimaryRoles"), Some("A-2"));
    assert_eq!(get("POI_ConditionalRoles"), Some("B-2"));
    assert_eq!(get("AccessibilityStatus"), Some("RESTRICTED"));
    let empty = models
        .iter()
        .find(|m| m.strings[0].contains("1Opening0000000000000005"))
        .unwrap();
    assert_eq!(empty.strings[1], "Null");

    // Every connection joins existing objects (or the root, 0); each model has one parent.
    let ids: std::collections::HashSet<i64> = objects.iter().map(|o| o.ints[0]).collect();
    let mut parents = std::collections::HashMap::new();
    for c in &top[9].children {
        assert_eq!(c.strings[0], "OO");
        let (child, parent) = (c.ints[0], c.ints[1]);
        assert!(ids.contains(&child) && (parent == 0 || ids.contains(&parent)));
        if models.iter().any(|m| m.ints[0] == child) {
            assert!(parents.insert(child, parent).is_none());
        }
    }
    assert_eq!(parents.len(), models.len());
}
