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
