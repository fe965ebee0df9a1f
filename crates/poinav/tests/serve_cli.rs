//! `poinav serve` on real buildings: it listens on loopback and prints the URL, places two
//! robots in the largest space of a corpus building, serves the building's GLB and what a
//! click shows (GlobalId, class, POI roles, property sets), and refuses bad input with exit 2.

mod common;

use std::path::Path;

use common::{http_get as get, serve};
use serde_json::Value;

#[test]
fn serves_a_corpus_building_with_two_robots_on_loopback() {
    let file = common::shared().join("ifc/fzk-haus-ifc4.ifc");
    let server = serve(&[file.as_os_str()], Path::new(".")).unwrap();
    let addr = server.addr.as_str();
    assert!(addr.starts_with("127.0.0.1:"), "{addr}");
    let (status, body) = get(addr, "/api/scene");
    assert_eq!(status, 200);
    let scene: Value = serde_json::from_slice(&body).unwrap();
    assert_eq!(scene["robots"].as_array().unwrap().len(), 2);
    assert_eq!(scene["robots"][0]["keys"], "arrows");
    assert_eq!(scene["robots"][1]["keys"], "wasd");
    assert_eq!(scene["robots"][0]["ray_hit"], "#ef4444");
    assert_eq!(scene["robots"][1]["ray_hit"], "#3b82f6");
    assert!(
        scene["zones"].as_array().unwrap().len() >= 5,
        "{}",
        scene["zones"]
    );
    assert!(!scene["doors"].as_array().unwrap().is_empty());
    // The building in parts, one GLB per storey, each as the scene lists it.
    let parts = scene["model"].as_array().unwrap();
    assert!(!parts.is_empty());
    let mut bytes = 0;
    for part in parts {
        let (status, glb) = get(addr, part["url"].as_str().unwrap());
        assert_eq!(status, 200);
        assert_eq!(&glb[..4], b"glTF");
        assert_eq!(glb.len() as u64, part["bytes"].as_u64().unwrap());
        bytes += glb.len();
    }
    assert!(bytes > 100_000, "GLB {bytes} bytes");
    assert!(parts.iter().any(|p| p["storey"] == scene["current"]));
    // A door: what a click shows.
    let door = scene["doors"][0]["id"].as_str().unwrap().to_string();
    let (status, body) = get(addr, &format!("/api/element/{door}"));
    assert_eq!(status, 200);
    let info: Value = serde_json::from_slice(&body).unwrap();
    assert_eq!(info["GlobalId"], door.as_str());
    assert_eq!(info["Class"], "IfcDoor");
    assert!(info["POI"]["POI_PrimaryRoles"]
        .as_str()
        .unwrap()
        .contains("A-2"));
    assert!(info["POI"]["AccessibilityStatus"].is_string());
    assert!(
        !info["PropertySets"].as_object().unwrap().is_empty(),
        "{info}"
    );
    let (status, _) = get(addr, "/api/element/no-such-id");
    assert_eq!(status, 404);
}

#[test]
fn bad_input_exits_2_with_the_reason() {
    let dir = tempfile::tempdir().unwrap();
    let missing = dir.path().join("missing.ifc");
    let (code, _, err) = common::poinav(&["serve".as_ref(), missing.as_os_str()]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("missing.ifc"), "{err}");
    let bad = dir.path().join("bad.ifc");
    std::fs::write(
        &bad,
        "ISO-10303-21;\nHEADER;\nENDSEC;\nDATA;\n#1=IFCWALL('x',$,$,$,$,$,$,$;\n",
    )
    .unwrap();
    let (code, _, err) = common::poinav(&["serve".as_ref(), bad.as_os_str()]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("bad.ifc"), "{err}");
    let (code, _, err) = common::poinav(&["serve".as_ref()]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("<FILE>"), "{err}");
}

/// Doors, zones and outlines of `floor` as `/api/scene` shows them (ids and rings).
fn floor_view(floor: &poinav_nav::Floor) -> Value {
    let ring = |r: &[glam::DVec2]| r.iter().map(|p| [p.x, p.y]).collect::<Vec<_>>();
    let outlines = |structure: bool| -> Vec<Value> {
        floor
            .obstacles
            .iter()
            .filter(|o| (o.kind == poinav_nav::ObstacleKind::Structure) == structure)
            .flat_map(|o| {
                o.rings
                    .iter()
                    .filter(|r| r.len() >= 3)
                    .map(|r| serde_json::json!({"id": o.id, "ring": ring(r)}))
            })
            .collect()
    };
    serde_json::json!({
        "storey": floor.name,
        "doors": floor.doors.iter().map(|d| serde_json::json!({"id": d.id, "ring": ring(&d.ring)})).collect::<Vec<_>>(),
        "zones": floor.zones.iter().map(|z| serde_json::json!({"id": z.id, "ring": ring(&z.ring)})).collect::<Vec<_>>(),
        "structure": outlines(true),
        "obstacles": outlines(false),
    })
}

/// The same fields of a scene storey.
fn scene_view(storey: &Value) -> Value {
    let pick = |list: &Value| -> Vec<Value> {
        list.as_array()
            .unwrap()
            .iter()
            .map(|x| serde_json::json!({"id": x["id"], "ring": x["ring"]}))
            .collect()
    };
    serde_json::json!({
        "storey": storey["storey"],
        "doors": pick(&storey["doors"]),
        "zones": pick(&storey["zones"]),
        "structure": pick(&storey["structure"]),
        "obstacles": pick(&storey["obstacles"]),
    })
}

#[test]
fn serve_runs_a_scenario_on_the_floor_simulate_prepares() {
    // `poinav simulate` runs on `poinav_bridge::prepare`'s floor; `serve --scenario` must show
    // and drive the same one (it used to cut the test building's IFC plan again instead).
    let dir = tempfile::tempdir().unwrap();
    let (_, text) = poinav_sim::SHIPPED
        .iter()
        .find(|(n, _)| *n == "separation")
        .unwrap();
    let file = dir.path().join("separation.toml");
    std::fs::write(&file, text).unwrap();
    let scenario = poinav_sim::Scenario::load(&file).unwrap();
    let prepared = poinav_bridge::prepare(&scenario, None).unwrap();
    let expected = floor_view(prepared.floor()).to_string();

    let server = serve(&["--scenario".as_ref(), file.as_os_str()], dir.path()).unwrap();
    let (status, body) = get(&server.addr, "/api/scene");
    assert_eq!(status, 200);
    let scene: Value = serde_json::from_slice(&body).unwrap();
    assert_eq!(scene["storeys"].as_array().unwrap().len(), 1);
    assert_eq!(scene["current"], 0);
    let shown = scene_view(&scene).to_string();
    assert_eq!(shown, expected);
    // The test building: 4 exterior and 2 corridor walls, 2 x 3 rooms' doors and partitions.
    assert_eq!(prepared.floor().doors.len(), 6);
    assert_eq!(prepared.floor().zones.len(), 7);
    assert_eq!(scene["robots"].as_array().unwrap().len(), 2);
}
