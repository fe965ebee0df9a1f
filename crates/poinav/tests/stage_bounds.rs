//! The size bounds of rasterising and the graph ([`poinav_nav::bounds`]) through the CLI and on
//! the corpus: `audit --json` and `export nav2 --json` list an element given up on (a door 58 m
//! wide, whose passage search passes the cell bound) and print it through the warning summary;
//! office-a and duplex-apartment hit no bound.

mod common;

use poinav_author::{demo_building, DemoBuilding};
use poinav_ifc::Model;
use poinav_nav::{NavOptions, Navigator};
use poinav_poi::{classify, RobotProfile, RuleSet};

#[test]
fn audit_and_nav2_json_list_a_door_given_up_on_and_warn() {
    // One room each side of the corridor; Room 1's door is 58 m wide: the search through its
    // passage would visit about 1.4 million cells, past the bound of 1,000,000.
    let spec = DemoBuilding {
        rooms_per_side: 1,
        room_width_m: 60.0,
        door_width_m: 58.0,
        room2_door_width_m: 1.0,
        ..DemoBuilding::default()
    };
    let dir = tempfile::tempdir().unwrap();
    let ifc = dir.path().join("wide-door.ifc");
    std::fs::write(&ifc, demo_building(&spec, "2026-11-27T00:00:00").unwrap()).unwrap();
    let model = Model::open(&ifc).unwrap();
    let profile = RobotProfile::paper();
    let c = classify(&model, &RuleSet::defaults(), &profile);
    let building = poinav_bridge::building(&model, &c, &poinav_bridge::Stages::of(&model)).building;
    let wide = building.floors[0]
        .doors
        .iter()
        .find(|d| d.name.as_deref() == Some("Door Room 1"))
        .expect("Room 1's door")
        .id
        .clone();

    let report = dir.path().join("report.html");
    let (code, out, err) = common::poinav(&[
        "audit".as_ref(),
        ifc.as_os_str(),
        "--output".as_ref(),
        report.as_os_str(),
        "--start".as_ref(),
        "Corridor".as_ref(),
        "--json".as_ref(),
    ]);
    assert_eq!(code, 0, "{err}");
    let json: serde_json::Value = serde_json::from_str(&out).unwrap();
    let gave_up = json["gave_up"].as_array().unwrap();
    assert_eq!(gave_up.len(), 1, "{gave_up:?}");
    assert_eq!(gave_up[0]["element"], wide.as_str());
    assert_eq!(gave_up[0]["class"], "IfcDoor");
    assert_eq!(gave_up[0]["stage"], "graph");
    let bound = gave_up[0]["bound"].as_str().unwrap();
    assert!(bound.starts_with("passage cells: ") && bound.ends_with(" > 1000000"));
    let warned = format!("IfcDoor {wide}: graph bound passed (passage cells: ");
    assert!(
        err.lines()
            .any(|l| l.starts_with("warning: storey ") && l.contains(&warned)),
        "{err}"
    );
    // The door is not passable: Room 1 is unreachable, Room 2 reachable.
    let p = &json["profiles"][0];
    let passable: Vec<(&str, bool)> = p["doors"]
        .as_array()
        .unwrap()
        .iter()
        .map(|d| {
            (
                d["name"].as_str().unwrap(),
                d["grid_passable"].as_bool().unwrap(),
            )
        })
        .collect();
    assert_eq!(passable, [("Door Room 1", false), ("Door Room 2", true)]);
    let reachable = |name: &str| {
        p["spaces"]
            .as_array()
            .unwrap()
            .iter()
            .find(|s| s["name"] == name)
            .map(|s| s["reachable"].as_bool().unwrap())
    };
    assert_eq!(reachable("Room 1"), Some(false), "{p}");
    assert_eq!(reachable("Room 2"), Some(true), "{p}");

    let bundle = dir.path().join("nav2");
    let (code, out, err) = common::poinav(&[
        "export".as_ref(),
        "nav2".as_ref(),
        ifc.as_os_str(),
        "--output".as_ref(),
        bundle.as_os_str(),
        "--json".as_ref(),
    ]);
    assert_eq!(code, 0, "{err}");
    let json: serde_json::Value = serde_json::from_str(&out).unwrap();
    assert_eq!(json["gave_up"][0]["element"], wide.as_str());
    assert!(json["warnings"]
        .as_array()
        .unwrap()
        .iter()
        .any(|w| w["id"] == wide.as_str() && w["class"] == "IfcDoor"));
}

#[test]
fn corpus_buildings_hit_no_bound() {
    let profile = RobotProfile::paper();
    for name in ["office-a", "duplex-apartment"] {
        let file = common::shared().join("ifc").join(format!("{name}.ifc"));
        let model = Model::open(&file).unwrap();
        let c = classify(&model, &RuleSet::defaults(), &profile);
        let building =
            poinav_bridge::building(&model, &c, &poinav_bridge::Stages::of(&model)).building;
        let nav = Navigator::new(&building, &profile, &NavOptions::default()).unwrap();
        assert!(nav.gave_up.is_empty(), "{name}: {:?}", nav.gave_up);
        let grids: Vec<_> = nav.floors.iter().map(|f| f.grid.occupancy.len()).collect();
        assert!(grids.iter().sum::<usize>() > 0, "{name}");
    }
}
