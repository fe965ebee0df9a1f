//! Storeys joined by the stairs, ramps and lifts found in the IFC: office-a's lift takes the
//! paper robot from Level 1 to Level 2 (its stairs are BLOCKED for it) and opens Level 2 to the
//! audit; duplex-apartment's two stairs are BLOCKED for the wheeled paper robot and climbed by
//! a legged one.

mod common;

use std::ffi::OsStr;
use std::path::Path;

fn run(args: &[&str]) -> (i32, String, String) {
    let args: Vec<&OsStr> = args.iter().map(OsStr::new).collect();
    common::poinav(&args)
}

fn corpus(name: &str) -> String {
    common::shared()
        .join("ifc")
        .join(name)
        .to_string_lossy()
        .into_owned()
}

/// The paper robot's profile with `locomotion = "legged"`, written into `dir`.
fn legged_profile(dir: &Path) -> String {
    let paper = std::fs::read_to_string(
        common::root().join("crates/poinav-roles/profiles/paper-robot.toml"),
    )
    .unwrap();
    assert!(paper.contains("locomotion = \"wheeled\""), "{paper}");
    let legged = paper.replace("locomotion = \"wheeled\"", "locomotion = \"legged\"");
    let path = dir.join("legged.toml");
    std::fs::write(&path, legged).unwrap();
    path.to_string_lossy().into_owned()
}

fn audit_json(file: &str, dir: &Path, profile: Option<&str>) -> serde_json::Value {
    let report = dir.join("audit/report.html");
    let report = report.to_string_lossy();
    let mut args = vec!["audit", file, "-o", &report, "--json"];
    if let Some(p) = profile {
        args.extend(["--profile", p]);
    }
    let (code, out, err) = run(&args);
    assert_eq!(code, 0, "{err}");
    serde_json::from_str(&out).unwrap()
}

#[test]
fn office_a_level_2_is_reached_through_the_lift_not_the_stairs() {
    let file = corpus("office-a.ifc");
    let (code, out, err) = run(&["route", &file, "--from", "101", "--to", "210", "--json"]);
    assert_eq!(code, 0, "{err}");
    let route: serde_json::Value = serde_json::from_str(&out).unwrap();
    let connections = route["connections"].as_array().unwrap();
    assert_eq!(connections.len(), 1, "{connections:?}");
    let lift = &connections[0];
    assert_eq!(lift["kind"], "lift");
    assert_eq!(lift["name"], "ELEV 124");
    assert_eq!(
        (lift["from_floor"].as_str(), lift["to_floor"].as_str()),
        (Some("Level 1"), Some("Level 2"))
    );
    let floors: Vec<&str> = route["legs"]
        .as_array()
        .unwrap()
        .iter()
        .map(|l| l["floor_name"].as_str().unwrap())
        .collect();
    assert_eq!(floors, ["Level 1", "Level 2"]);
    // Waiting for the lift and 4.27 m at 1 m/s.
    assert!(
        (lift["time_s"].as_f64().unwrap() - 34.27).abs() < 0.01,
        "{lift}"
    );

    let dir = tempfile::tempdir().unwrap();
    let audit = audit_json(&file, dir.path(), None);
    let profile = &audit["profiles"][0];
    let transitions = profile["transitions"].as_array().unwrap();
    let kinds: Vec<(&str, &str)> = transitions
        .iter()
        .map(|t| (t["kind"].as_str().unwrap(), t["status"].as_str().unwrap()))
        .collect();
    assert_eq!(
        kinds,
        [
            ("stair", "BLOCKED"),
            ("stair", "BLOCKED"),
            ("lift", "FULL_ACCESS")
        ],
        "two half-turn stairs and the lift shaft 124"
    );
    // The lift has no IfcDoor: its doors are an IfcFlowTerminal standing in an opening of the
    // shaft wall, and that doorway (1.232 m, Doorway #1057) gives the lift its width.
    let lift = &transitions[2];
    assert_eq!(
        lift["reason"], "lift; clear width 1.232 m >= required 0.900 m",
        "{lift}"
    );
    assert!(
        (lift["clear_width_m"].as_f64().unwrap() - 1.2319).abs() < 1e-6,
        "{lift}"
    );
    let spaces = profile["spaces"].as_array().unwrap();
    let reachable = spaces.iter().filter(|s| s["reachable"] == true).count();
    // 59 of 99 without vertical connections: Level 1 only. The lift's own space 124 is
    // reached at its landings.
    assert_eq!((reachable, spaces.len()), (99, 99));
    let shaft = spaces.iter().find(|s| s["name"] == "124").unwrap();
    assert!(
        shaft["reason"]
            .as_str()
            .unwrap()
            .starts_with("the lift ELEV 124 itself, entered at its landings (reachable)"),
        "{shaft}"
    );
    let level_2 = spaces
        .iter()
        .filter(|s| s["floor_name"] == "Level 2" && s["reachable"] == true)
        .count();
    assert!(level_2 >= 38, "{level_2} Level 2 spaces reachable");
}

#[test]
fn duplex_stairs_are_blocked_for_wheels_and_climbed_by_legs() {
    let file = corpus("duplex-apartment.ifc");
    let dir = tempfile::tempdir().unwrap();
    let audit = audit_json(&file, dir.path(), None);
    let transitions = audit["profiles"][0]["transitions"].as_array().unwrap();
    assert_eq!(transitions.len(), 2, "one stair per flat");
    for t in transitions {
        assert_eq!(t["kind"], "stair");
        assert_eq!(t["status"], "BLOCKED", "{t}");
        assert_eq!(t["floors"], serde_json::json!(["Level 1", "Level 2"]));
        assert!(
            (t["clear_width_m"].as_f64().unwrap() - 0.9144).abs() < 1e-3,
            "{t}"
        );
    }

    let (code, _, err) = run(&["route", &file, "--from", "A101", "--to", "A202"]);
    assert_eq!(code, 1, "{err}");
    assert!(
        err.contains("stairs are not passable for a wheeled robot"),
        "{err}"
    );
    // The stair blocks once, not once per landing.
    assert_eq!(err.matches("stairs are not passable").count(), 1, "{err}");
    let level_2: Vec<&serde_json::Value> = audit["profiles"][0]["spaces"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|s| s["floor_name"] == "Level 2")
        .collect();
    assert_eq!(level_2.len(), 10, "eight rooms and the two hallways");
    for s in level_2 {
        assert_eq!(s["reachable"], false, "{s}");
        let stairs = s["blocked_by"]
            .as_array()
            .unwrap()
            .iter()
            .filter(|b| b["kind"] == "landing")
            .count();
        assert_eq!(stairs, 1, "{s}");
    }

    let legged = legged_profile(dir.path());
    let (code, out, err) = run(&[
        "route",
        &file,
        "--from",
        "A101",
        "--to",
        "A202",
        "--json",
        "--profile",
        &legged,
    ]);
    assert_eq!(code, 0, "{err}");
    let route: serde_json::Value = serde_json::from_str(&out).unwrap();
    let connections = route["connections"].as_array().unwrap();
    assert_eq!(connections.len(), 1, "{connections:?}");
    assert_eq!(connections[0]["kind"], "stair");
    assert_eq!(connections[0]["status"], "FULL_ACCESS");
    assert_eq!(connections[0]["to_floor"], "Level 2");
}
