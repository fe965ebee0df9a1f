//! `poinav export glb` and `poinav export fbx` on every corpus building: the Khronos
//! glTF-Validator reports no error and one node per element; assimp opens the FBX with one mesh
//! per element that has geometry; both name elements by GlobalId.

mod common;

use std::ffi::OsStr;
use std::path::Path;
use std::process::Command;

use serde_json::Value;

const SETUP: &str =
    "`bash tests/js/setup.sh` (npm ci --prefix tests/js; apt-get install -y assimp-utils)";

fn validate_glb(file: &Path) -> Value {
    let script = common::root().join("tests/js/validate-gltf.cjs");
    let out = Command::new("node")
        .arg(script)
        .arg(file)
        .output()
        .unwrap_or_else(|e| panic!("node cannot be run ({e}): run {SETUP}"));
    assert!(
        out.status.success(),
        "glTF-Validator failed ({}): run {SETUP}",
        String::from_utf8_lossy(&out.stderr)
    );
    serde_json::from_slice::<Value>(&out.stdout).unwrap()[0].clone()
}

fn assimp_count(file: &Path, label: &str) -> usize {
    let out = Command::new("assimp")
        .arg("info")
        .arg(file)
        .arg("-r")
        .output()
        .unwrap_or_else(|e| panic!("assimp cannot be run ({e}): run {SETUP}"));
    let text = String::from_utf8_lossy(&out.stdout).into_owned();
    assert!(
        out.status.success(),
        "assimp info {} failed: {text}",
        file.display()
    );
    text.lines()
        .find_map(|l| l.trim().strip_prefix(label))
        .unwrap_or_else(|| panic!("no {label} in assimp's output:\n{text}"))
        .trim()
        .parse()
        .unwrap()
}

#[test]
fn exports_of_every_corpus_building_pass_the_validators() {
    let dir = tempfile::tempdir().unwrap();
    for file in common::corpus() {
        let name = file.file_stem().unwrap().to_string_lossy().into_owned();
        if name.starts_with("railway") {
            continue; // infrastructure: 9,937 meshes, 23 M triangles; too heavy for validators
        }
        let model = poinav_ifc::Model::open(&file).unwrap();
        let meshes = poinav_geom::mesh_model(&model);
        let with_triangles = meshes
            .elements
            .iter()
            .filter(|e| !e.mesh.triangles.is_empty())
            .count();
        let storeys = model.count_of("IfcBuildingStorey");

        let glb = dir.path().join(format!("{name}.glb"));
        let (code, _, err) = common::poinav(&[
            OsStr::new("export"),
            OsStr::new("glb"),
            file.as_os_str(),
            OsStr::new("-o"),
            glb.as_os_str(),
        ]);
        assert_eq!(code, 0, "{name}: {err}");
        let report = validate_glb(&glb);
        assert_eq!(
            report["issues"]["numErrors"], 0,
            "{name}: {}",
            report["issues"]
        );
        let bytes = std::fs::read(&glb).unwrap();
        let json_len = u32::from_le_bytes(bytes[12..16].try_into().unwrap()) as usize;
        let gltf: Value = serde_json::from_slice(&bytes[20..20 + json_len]).unwrap();
        let nodes = gltf["nodes"].as_array().unwrap();
        let groups = gltf["scenes"][0]["nodes"].as_array().unwrap().len();
        let no_storey = usize::from(meshes.elements.iter().any(|e| e.storey.is_none()));
        assert_eq!(groups, storeys + no_storey, "{name}: one group per storey");
        assert_eq!(
            nodes.len() - groups,
            meshes.elements.len(),
            "{name}: one node per element"
        );
        // One node with a mesh per element with triangles; copies share their original's
        // mesh, and the validator counts one draw call per distinct mesh.
        let shown = nodes.iter().filter(|n| n.get("mesh").is_some()).count();
        assert_eq!(shown, with_triangles, "{name}");
        let distinct = gltf["meshes"].as_array().map_or(0, Vec::len);
        assert_eq!(
            report["info"]["drawCallCount"].as_u64().unwrap() as usize,
            distinct,
            "{name}"
        );
        assert!(distinct <= with_triangles, "{name}");
        eprintln!(
            "{name}: {} bytes, {with_triangles} elements with triangles, {distinct} meshes",
            bytes.len()
        );

        let fbx = dir.path().join(format!("{name}.fbx"));
        let (code, _, err) = common::poinav(&[
            OsStr::new("export"),
            OsStr::new("fbx"),
            file.as_os_str(),
            OsStr::new("-o"),
            fbx.as_os_str(),
        ]);
        assert_eq!(code, 0, "{name}: {err}");
        assert_eq!(
            assimp_count(&fbx, "Meshes:"),
            with_triangles,
            "{name}: one FBX mesh per element with geometry"
        );
    }
}
