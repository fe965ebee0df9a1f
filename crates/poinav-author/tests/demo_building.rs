//! The test building opens, validates and meshes (openings cut) in IfcOpenShell; the door-width
//! patch changes exactly the door and its profiles; enrichment sees the design change.

use std::path::{Path, PathBuf};
use std::process::Command;

use poinav_author::{demo_building, patch_door_width, DemoBuilding};
use poinav_ifc::Model;
use poinav_poi::{classify, AccessibilityStatus, RobotProfile, Role, RuleSet};

const STAMP: &str = "2026-11-22T02:30:00";

fn python() -> PathBuf {
    poinav_testkit::python("ifcopenshell")
}

/// IfcOpenShell's view of a file: validation errors and, per named wall or door, mesh area and bounds.
fn ifcopenshell_view(path: &Path) -> serde_json::Value {
    let script = r#"
import json, sys
import numpy as np
import ifcopenshell, ifcopenshell.geom, ifcopenshell.validate
f = ifcopenshell.open(sys.argv[1])
log = ifcopenshell.validate.json_logger()
ifcopenshell.validate.validate(f, log)
errors = [s["message"] for s in log.statements if s.get("level") == "error"]
s = ifcopenshell.geom.settings()
s.set("use-world-coords", True)
it = ifcopenshell.geom.iterator(s, f, include=f.by_type("IfcWall") + f.by_type("IfcDoor") + f.by_type("IfcSlab"))
shapes = {}
if it.initialize():
    while True:
        sh = it.get()
        v = np.array(sh.geometry.verts).reshape(-1, 3)
        t = np.array(sh.geometry.faces).reshape(-1, 3)
        area = 0.5 * np.linalg.norm(np.cross(v[t[:, 1]] - v[t[:, 0]], v[t[:, 2]] - v[t[:, 0]]), axis=1).sum()
        shapes[f.by_id(sh.id).Name] = {"area": float(area), "min": v.min(0).tolist(), "max": v.max(0).tolist()}
        if not it.next():
            break
print(json.dumps({"errors": errors, "shapes": shapes}))
"#;
    let out = Command::new(python())
        .args(["-c", script])
        .arg(path)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    serde_json::from_slice(&out.stdout).unwrap()
}

/// Area of a box wall of `length` x `t` x `h` with doors of `widths` (height `dh`) cut through it
/// from the floor: each door removes its two faces and adds its two reveals.
fn cut_wall_area(length: f64, t: f64, h: f64, widths: &[f64], dh: f64) -> f64 {
    2.0 * (length * h + length * t + h * t)
        + widths
            .iter()
            .map(|w| -2.0 * w * dh + 2.0 * dh * t)
            .sum::<f64>()
}

#[test]
fn test_building_validates_and_meshes_with_openings_cut_in_ifcopenshell() {
    let dir = tempfile::tempdir().unwrap();
    let spec = DemoBuilding::default();
    let bytes = demo_building(&spec, STAMP).unwrap();
    assert_eq!(bytes, demo_building(&spec, STAMP).unwrap(), "deterministic");
    let path = dir.path().join("demo.ifc");
    std::fs::write(&path, &bytes).unwrap();
    let view = ifcopenshell_view(&path);
    assert_eq!(
        view["errors"],
        serde_json::json!([]),
        "IfcOpenShell validation"
    );
    let shapes = view["shapes"].as_object().unwrap();
    assert_eq!(shapes.len(), 10 + 6 + 1, "10 walls, 6 doors, 1 slab meshed");
    let south = &shapes["Corridor wall south"];
    let want = cut_wall_area(spec.length_m(), 0.2, 3.0, &[1.0, 0.8, 1.0], 2.1);
    assert!(
        (south["area"].as_f64().unwrap() - want).abs() < 1e-6,
        "{south} vs {want}"
    );
    let door = &shapes["Door Room 2"];
    assert!(
        (door["max"][0].as_f64().unwrap() - door["min"][0].as_f64().unwrap() - 0.8).abs() < 1e-9
    );

    let model = Model::open(&path).unwrap();
    assert!(model.diagnostics().is_empty());
    let layout = spec.layout();
    assert_eq!(layout.rooms.len(), 6);
    assert_eq!(model.count_of("IfcSpace"), 7);
    assert_eq!(model.count_of("IfcOpeningElement"), 6);
    let c = classify(&model, &RuleSet::defaults(), &RobotProfile::paper());
    let door2 = c
        .elements
        .iter()
        .find(|e| e.name.as_deref() == Some("Door Room 2"))
        .unwrap();
    assert_eq!(
        door2.accessibility.as_ref().unwrap().status,
        AccessibilityStatus::Restricted
    );
    assert_eq!(door2.conditional, [Role::Narrow]);
    let corridor = c
        .elements
        .iter()
        .find(|e| e.name.as_deref() == Some("Corridor"))
        .unwrap();
    assert_eq!(corridor.primary, [Role::PathGuidance, Role::MultiRobotZone]);
    let rooms = c
        .elements
        .iter()
        .filter(|e| e.primary == [Role::Destination])
        .count();
    assert_eq!(rooms, 6);
}

#[test]
fn widening_the_room_2_door_changes_three_lines_and_removes_b2() {
    let dir = tempfile::tempdir().unwrap();
    let spec = DemoBuilding::default();
    let path = dir.path().join("demo.ifc");
    std::fs::write(&path, demo_building(&spec, STAMP).unwrap()).unwrap();
    let model = Model::open(&path).unwrap();
    let (ed, patch) = patch_door_width(&model, "Door Room 2", 1.20, STAMP).unwrap();
    assert_eq!(
        (patch.old_width_m, patch.new_width_m, patch.profiles.len()),
        (Some(0.8), 1.2, 2)
    );
    assert!(patch.warnings.is_empty(), "{:?}", patch.warnings);
    let wide = dir.path().join("wide.ifc");
    ed.write(&wide).unwrap();
    let before = std::fs::read_to_string(&path).unwrap();
    let after = std::fs::read_to_string(&wide).unwrap();
    let changed: Vec<(&str, &str)> = before
        .lines()
        .zip(after.lines())
        .filter(|(a, b)| a != b)
        .collect();
    assert_eq!(changed.len(), 3, "{changed:?}");
    assert_eq!(before.lines().count(), after.lines().count());

    let view = ifcopenshell_view(&wide);
    assert_eq!(view["errors"], serde_json::json!([]));
    let south = view["shapes"]["Corridor wall south"]["area"]
        .as_f64()
        .unwrap();
    let want = cut_wall_area(spec.length_m(), 0.2, 3.0, &[1.0, 1.2, 1.0], 2.1);
    assert!(
        (south - want).abs() < 1e-6,
        "opening widened: {south} vs {want}"
    );

    let model = Model::open(&wide).unwrap();
    let c = classify(&model, &RuleSet::defaults(), &RobotProfile::paper());
    let door2 = c
        .elements
        .iter()
        .find(|e| e.name.as_deref() == Some("Door Room 2"))
        .unwrap();
    assert_eq!(
        door2.accessibility.as_ref().unwrap().status,
        AccessibilityStatus::FullAccess
    );
    assert!(door2.conditional.is_empty());
}

#[test]
fn patch_finds_doors_by_guid_or_unique_name_and_refuses_bad_requests() {
    let spec = DemoBuilding::default();
    let model = Model::from_bytes("demo.ifc", demo_building(&spec, STAMP).unwrap()).unwrap();
    let guid = model.instances_of("IfcDoor")[0].global_id().unwrap();
    assert_eq!(
        patch_door_width(&model, &guid, 0.9, STAMP)
            .unwrap()
            .1
            .global_id,
        guid
    );
    let err = patch_door_width(&model, "Door Room 9", 1.0, STAMP)
        .unwrap_err()
        .to_string();
    assert!(err.contains("Door Room 9"), "{err}");
    assert!(patch_door_width(&model, "Door Room 1", -1.0, STAMP).is_err());
    assert!(patch_door_width(&model, "Door Room 1", f64::NAN, STAMP).is_err());
    assert!(demo_building(
        &DemoBuilding {
            room2_door_width_m: 9.0,
            ..DemoBuilding::default()
        },
        STAMP
    )
    .is_err());
}

#[test]
fn patching_a_real_revit_door_keeps_every_other_line() {
    let model = Model::open(poinav_testkit::corpus_file("office-a.ifc")).unwrap();
    let door = model.instances_of("IfcDoor")[0];
    let (ed, patch) = patch_door_width(&model, &door.global_id().unwrap(), 1.2, STAMP).unwrap();
    assert!((patch.old_width_m.unwrap() - 0.915).abs() < 1e-9);
    let out = Model::from_bytes("out.ifc", ed.to_bytes()).unwrap();
    let mut changed = 0;
    for e in model.entities() {
        if out.entity(e.id()).unwrap().raw() != e.raw() {
            changed += 1;
        }
    }
    // Revit shares the opening's profile with other openings: it is copied (one instance added)
    // and only this opening's solid points at the copy; the door body is a mapped item (a warning).
    assert_eq!(changed, 2, "the door and its opening's solid");
    assert_eq!(out.len(), model.len() + 1);
    assert_eq!(patch.profiles.len(), 1);
    assert!(model.entity(patch.profiles[0]).is_none(), "a new profile");
    assert_eq!(
        out.entity(patch.profiles[0]).unwrap().get_f64("XDim"),
        Some(1.2)
    );
    assert!(
        patch.warnings.iter().any(|w| w.contains("IfcMappedItem")),
        "{:?}",
        patch.warnings
    );
    assert_eq!(
        out.entity(door.id()).unwrap().get_f64("OverallWidth"),
        Some(1.2)
    );
}
