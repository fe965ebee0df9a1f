//! Lossless writing on every corpus file: add a property set to every door (or, in files
//! without doors, to elements), write, and check that every original instance line is
//! byte-identical and that IfcOpenShell reads the new values back.

mod common;

use std::ffi::OsStr;

use poinav_ifc::{Arg, Editor, Model, NewProperty};
use serde_json::json;

const PSET: &str = "Poinav_RoundTrip";

#[test]
fn added_property_sets_round_trip_through_ifcopenshell_and_keep_every_line() {
    let dir = tempfile::tempdir().unwrap();
    let mut checked = 0;
    for file in common::corpus() {
        let name = file.file_name().unwrap().to_string_lossy().into_owned();
        let before = std::fs::read(&file).unwrap();
        let model = Model::open(&file).unwrap();
        let mut targets: Vec<_> = model.instances_of("IfcDoor");
        if targets.is_empty() {
            targets = model
                .instances_of("IfcElement")
                .into_iter()
                .take(25)
                .collect();
        }
        let mut ed = Editor::new(&model);
        let status = ed
            .add_enumeration(
                "PEnum_Status",
                vec![Arg::label("OPEN"), Arg::label("CLOSED")],
            )
            .unwrap();
        let mut expected = serde_json::Map::new();
        for (i, t) in targets.iter().enumerate() {
            let width = 0.5 + i as f64 / 8.0;
            let label = format!("Tür {i} 'quoted' \\ 廊下");
            ed.add_property_set(
                &[t.id()],
                PSET,
                None,
                vec![
                    (
                        "Width".into(),
                        NewProperty::Single(Arg::typed("IfcLengthMeasure", Arg::Real(width))),
                    ),
                    ("Label".into(), NewProperty::Single(Arg::label(&label))),
                    (
                        "Count".into(),
                        NewProperty::Single(Arg::typed("IfcInteger", Arg::Integer(i as i64))),
                    ),
                    (
                        "Status".into(),
                        NewProperty::Enumerated(vec![Arg::label("CLOSED")], Some(status)),
                    ),
                    (
                        "Roles".into(),
                        NewProperty::List(vec![Arg::label("A-2"), Arg::label("B-2")]),
                    ),
                ],
                &format!("{}/{i}", t.global_id().unwrap()),
            )
            .unwrap();
            expected.insert(
                t.global_id().unwrap(),
                json!({"Width": width, "Label": label, "Count": i, "Status": "CLOSED", "Roles": ["A-2", "B-2"]}),
            );
        }
        let out = dir.path().join(&name);
        ed.write(&out).unwrap();
        assert_eq!(
            std::fs::read(&file).unwrap(),
            before,
            "{name}: input changed"
        );

        let written = Model::open(&out).unwrap();
        assert!(
            written.diagnostics().is_empty(),
            "{name}: {:?}",
            &written.diagnostics()[..1]
        );
        assert_eq!(written.len(), model.len() + ed.added_count());
        for e in model.entities() {
            let w = written
                .entity(e.id())
                .unwrap_or_else(|| panic!("{name}: {} lost", e.id()));
            assert_eq!(w.raw(), e.raw(), "{name}: {} changed", e.id());
        }
        assert_eq!(
            &written.bytes()[..model.header().end],
            &before[..model.header().end],
            "{name}: header changed"
        );

        let back = common::ifcos("read_psets.py", &[out.as_os_str(), OsStr::new(PSET)]);
        assert_eq!(
            back.as_object().unwrap().len(),
            targets.len(),
            "{name}: elements with the set"
        );
        for (guid, want) in &expected {
            let got = &back[guid];
            for key in ["Label", "Count", "Status", "Roles"] {
                let g = if key == "Status" && got[key].is_array() {
                    got[key][0].clone()
                } else {
                    got[key].clone()
                };
                assert_eq!(g, want[key], "{name}: {guid} {key}");
            }
            let (g, w) = (
                got["Width"].as_f64().unwrap(),
                want["Width"].as_f64().unwrap(),
            );
            assert!((g - w).abs() < 1e-12, "{name}: {guid} Width {g} vs {w}");
            checked += 1;
        }
    }
    assert!(checked >= 579, "property sets checked: {checked}");
}

#[test]
fn writing_onto_the_input_file_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let src = common::shared().join("ifc/wall-opening-window-ifc4x3.ifc");
    let copy = dir.path().join("copy.ifc");
    std::fs::copy(&src, &copy).unwrap();
    let before = std::fs::read(&copy).unwrap();
    let model = Model::open(&copy).unwrap();
    let ed = Editor::new(&model);
    assert!(matches!(
        ed.write(&copy),
        Err(poinav_ifc::EditError::WouldOverwriteInput(_))
    ));
    assert_eq!(std::fs::read(&copy).unwrap(), before);
}

#[test]
fn global_ids_encode_like_ifcopenshell() {
    let ids: Vec<poinav_ifc::GlobalId> = (0..20u128)
        .map(|i| {
            poinav_ifc::GlobalId(
                i.wrapping_mul(0x9E37_79B9_7F4A_7C15_F39C_C060_5CED_C835) ^ (i << 120),
            )
        })
        .chain([
            poinav_ifc::GlobalId(0),
            poinav_ifc::GlobalId(u128::MAX),
            poinav_ifc::GlobalId::new_random(),
        ])
        .collect();
    let hex: Vec<String> = ids.iter().map(|g| format!("{:032x}", g.0)).collect();
    let script = format!(
        "import json, ifcopenshell.guid as g; print(json.dumps([g.compress(h) for h in {hex:?}]))"
    );
    let out = std::process::Command::new(common::python())
        .args(["-c", &script])
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let theirs: Vec<String> = serde_json::from_slice(&out.stdout).unwrap();
    let ours: Vec<String> = ids.iter().map(|g| g.to_string()).collect();
    assert_eq!(ours, theirs);
}
