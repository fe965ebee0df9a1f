//! The heavy benchmark model's generator (`scripts/make-heavy-model.py`, small mode): the same
//! arguments give the same bytes, IfcOpenShell reads the unit as feet and meshes every
//! furnishing with 1,000-10,000 triangles, and `poinav inspect` reads the same building.

mod common;

use std::ffi::OsStr;
use std::path::Path;
use std::process::Command;

use serde_json::Value;

/// Runs the generator in small mode into `out`; its JSON summary.
fn generate(python: &Path, out: &Path) -> Value {
    let run = Command::new(python)
        .arg(common::root().join("scripts/make-heavy-model.py"))
        .arg(out)
        .arg("--small")
        .output()
        .expect("python runs");
    assert!(
        run.status.success(),
        "make-heavy-model.py failed: {}",
        String::from_utf8_lossy(&run.stderr)
    );
    serde_json::from_slice(&run.stdout).expect("one JSON summary line")
}

#[test]
fn small_heavy_model_is_read_alike_by_ifcopenshell_and_poinav() {
    let python = common::python();
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("heavy-small.ifc");
    let again = dir.path().join("again.ifc");
    let summary = generate(&python, &file);
    generate(&python, &again);
    assert_eq!(
        std::fs::read(&file).unwrap(),
        std::fs::read(&again).unwrap(),
        "the same arguments give the same bytes"
    );
    let bytes = summary["bytes"].as_u64().unwrap();
    assert!((1_000_000..=3_000_000).contains(&bytes), "{bytes} bytes");

    // IfcOpenShell: the unit, the building, every furnishing meshed.
    let r = common::ifcos("heavy_model.py", &[file.as_os_str()]);
    assert_eq!(r["schema"], "IFC2X3");
    assert_eq!(r["length_unit_name"], "FOOT");
    assert!((r["length_unit_m"].as_f64().unwrap() - 0.3048).abs() < 1e-12);
    let counts = &r["counts"];
    for (class, n) in [
        ("IfcBuildingStorey", 5),
        ("IfcSpace", 40),
        ("IfcDoor", 37),
        ("IfcOpeningElement", 37),
        ("IfcRelVoidsElement", 37),
        ("IfcRelFillsElement", 37),
        ("IfcWall", 52),
        ("IfcSlab", 5),
        ("IfcStair", 3),
        ("IfcStairFlight", 3),
        ("IfcBooleanClippingResult", 22),
        ("IfcHalfSpaceSolid", 22),
        ("IfcRelSpaceBoundary", 273),
        ("IfcFurnishingElement", 11),
        ("IfcRepresentationMap", 2),
        ("IfcMappedItem", 9),
        ("IfcFacetedBrep", 16),
    ] {
        assert_eq!(counts[class], n, "{class}");
    }
    assert_eq!(r["mapped"], 9, "furnishings with a mapped body");
    let meshed = r["furnishings"].as_object().unwrap();
    assert_eq!(meshed.len(), 11, "every furnishing meshed");
    let mut triangles: Vec<u64> = meshed.values().map(|t| t.as_u64().unwrap()).collect();
    triangles.sort_unstable();
    assert!(
        triangles.iter().all(|t| (1000..=10_000).contains(t)),
        "{triangles:?}"
    );
    // 8 chairs of 1728 (one mapped type), a plant of 1280, a custom table of 1792 and a
    // mapped table of 3584: IfcOpenShell keeps every closed-shell triangle.
    assert_eq!(
        triangles,
        [1280, 1728, 1728, 1728, 1728, 1728, 1728, 1728, 1728, 1792, 3584]
    );
    assert_eq!(
        triangles.iter().sum::<u64>(),
        summary["furnishing triangles"].as_u64().unwrap()
    );

    // poinav reads the same building.
    let (code, out, err) = common::poinav(&[
        OsStr::new("inspect"),
        file.as_os_str(),
        OsStr::new("--json"),
    ]);
    assert_eq!(code, 0, "{err}");
    let ours: Value = serde_json::from_str(&out).unwrap();
    assert!((ours["length_unit_m"].as_f64().unwrap() - 0.3048).abs() < 1e-12);
    assert_eq!(ours["diagnostics"], 0, "{}", ours["diagnostic_list"]);
    assert_eq!(ours["storeys"].as_array().unwrap().len(), 5);
    assert_eq!(ours["spaces"].as_array().unwrap().len(), 40);
    let doors = ours["doors"].as_array().unwrap();
    assert_eq!(doors.len(), 37);
    for d in doors {
        let w = d["overall_width_m"].as_f64().unwrap();
        assert!((w - 1.0668).abs() < 1e-9, "{d}");
    }
    for (class, n) in [("IfcFurnishingElement", 11), ("IfcDoor", 37)] {
        assert_eq!(ours["counts"][class], n, "{class}");
    }
    let on = |storey: &str| {
        ours["spaces"]
            .as_array()
            .unwrap()
            .iter()
            .filter(|s| s["storey"] == storey)
            .count()
    };
    for level in 1..=4 {
        assert_eq!(on(&format!("Level {level}")), 10, "spaces on Level {level}");
    }
    assert_eq!(on("Roof"), 0);
}
