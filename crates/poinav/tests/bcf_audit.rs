//! `poinav audit --bcf`: the BCF issues of the corpus's office-a for the paper robot, read back
//! with IfcOpenShell's bcf-client (`tests/bcf/check_bcf.py`): one topic per failing door and
//! stair, the door's IfcGuid selected and coloured, the camera at eye height in front of it, a
//! snapshot, the same GUIDs and bytes on every run, BCF 3.0 and 2.1, every XML file valid
//! against buildingSMART's XSDs (`tests/bcf/xsd/`).

mod common;

use std::collections::BTreeSet;
use std::path::{Path, PathBuf};
use std::process::Command;

use serde_json::Value;

/// 2026-11-22T02:30:00Z.
const EPOCH: &str = "1795314600";

/// Runs the audit of office-a with `--bcf` (and `extra` flags) into `dir`; returns the audit
/// JSON and the BCF file.
fn run_audit(dir: &Path, name: &str, extra: &[&str]) -> (Value, PathBuf) {
    let bcf = dir.join(name);
    let out = Command::new(env!("CARGO_BIN_EXE_poinav"))
        .arg("audit")
        .arg(poinav_testkit::corpus_file("office-a.ifc"))
        .arg("-o")
        .arg(dir.join("report.html"))
        .arg("--json")
        .arg("--bcf")
        .arg(&bcf)
        .args(extra)
        .env("SOURCE_DATE_EPOCH", EPOCH)
        .output()
        .expect("poinav runs");
    assert!(
        out.status.success(),
        "audit failed: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    (serde_json::from_slice(&out.stdout).unwrap(), bcf)
}

/// Reads `bcf` with bcf-client and validates it with buildingSMART's XSDs of `version`
/// (`tests/bcf/xsd/`).
fn check(bcf: &Path, version: &str) -> Value {
    let py = poinav_testkit::python("bcf, xmlschema");
    let xsd = common::root().join("tests/bcf/xsd").join(version);
    let out = Command::new(py)
        .arg(common::root().join("tests/bcf/check_bcf.py"))
        .arg(bcf)
        .arg(version)
        .arg("--xsd")
        .arg(&xsd)
        .output()
        .expect("python runs");
    assert!(
        out.status.success(),
        "check_bcf.py failed: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    serde_json::from_slice(&out.stdout).unwrap()
}

fn strs(v: &Value) -> Vec<String> {
    v.as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_str().unwrap().to_string())
        .collect()
}

/// The paper robot's failing doors and transitions, and unreachable spaces, in the audit JSON.
fn failing(audit: &Value) -> (Vec<&Value>, Vec<&Value>, usize) {
    let p = &audit["profiles"][0];
    assert_eq!(p["profile"], "paper-robot");
    let bad = |v: &&Value| matches!(v["status"].as_str(), Some("BLOCKED" | "RESTRICTED"));
    let doors: Vec<&Value> = p["doors"].as_array().unwrap().iter().filter(bad).collect();
    let transitions: Vec<&Value> = p["transitions"]
        .as_array()
        .unwrap()
        .iter()
        .filter(bad)
        .collect();
    let spaces = p["spaces"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|s| s["reachable"] == false)
        .count();
    (doors, transitions, spaces)
}

#[test]
fn office_a_gives_one_bcf_3_topic_per_failing_door_with_its_guid_camera_and_snapshot() {
    let dir = tempfile::tempdir().unwrap();
    // IfcOpenShell's world placements of the doors, to check the cameras' frame against.
    let placements = poinav_testkit::spawn_ifcos(
        &common::python(),
        "placements.py",
        &poinav_testkit::corpus_file("office-a.ifc"),
    );
    let (audit, bcf) = run_audit(dir.path(), "issues.bcf", &[]);
    let placements = poinav_testkit::json_of(placements, "placements.py office-a");
    let (doors, transitions, spaces) = failing(&audit);
    // office-a for the paper robot: five 0.813 m toilet doors RESTRICTED, two stairs BLOCKED.
    assert_eq!(doors.len(), 5, "{doors:?}");
    assert_eq!(transitions.len(), 2);
    assert_eq!(spaces, 0);
    assert_eq!(audit["bcf"]["version"], "3.0");
    assert_eq!(
        audit["bcf"]["topics"].as_array().unwrap().len(),
        doors.len() + transitions.len() + spaces
    );

    let read = check(&bcf, "3.0");
    assert_eq!(read["version"], "3.0");
    let topics = read["topics"].as_array().unwrap();
    assert_eq!(topics.len(), doors.len() + transitions.len() + spaces);
    for d in &doors {
        let id = d["id"].as_str().unwrap();
        let hits: Vec<&Value> = topics
            .iter()
            .filter(|t| t["viewpoints"][0]["selected"] == serde_json::json!([id]))
            .collect();
        assert_eq!(hits.len(), 1, "one topic selects door {id}");
        let t = hits[0];
        let status = d["status"].as_str().unwrap();
        let labels = strs(&t["labels"]);
        assert_eq!(labels, ["paper-robot", status, "door"]);
        assert_eq!(t["topic_type"], "Issue");
        assert_eq!(t["topic_status"], "Open");
        assert!(t["creation_date"]
            .as_str()
            .unwrap()
            .starts_with("2026-11-22T02:30:00"));
        let title = t["title"].as_str().unwrap();
        assert!(
            title.contains("RESTRICTED") && title.contains("0.81 m") && title.contains("0.90 m"),
            "{title}"
        );
        assert!(t["description"].as_str().unwrap().contains(id));
        let vp = &t["viewpoints"][0];
        assert_eq!(vp["coloured"], serde_json::json!([["E8A400", id]]));
        assert_eq!(vp["snapshot"], serde_json::json!([640, 480]));
        // Eye height: 1.6 m above the storey's walking level, looking at the door: at most
        // 2.5 m away in plan, slightly downwards, the up vector perpendicular.
        let floor = d["floor"].as_u64().unwrap() as usize;
        let level = audit["levels"][floor]["walking_level_m"].as_f64().unwrap();
        let cam = &vp["camera"];
        let p: Vec<f64> = cam["position"]
            .as_array()
            .unwrap()
            .iter()
            .map(|x| x.as_f64().unwrap())
            .collect();
        let dir: Vec<f64> = cam["direction"]
            .as_array()
            .unwrap()
            .iter()
            .map(|x| x.as_f64().unwrap())
            .collect();
        let up: Vec<f64> = cam["up"]
            .as_array()
            .unwrap()
            .iter()
            .map(|x| x.as_f64().unwrap())
            .collect();
        assert!((p[2] - (level + 1.6)).abs() < 1e-5, "{p:?} level {level}");
        assert!(dir[2] < 0.0 && dir[2] > -0.5, "{dir:?}");
        let dot: f64 = dir.iter().zip(&up).map(|(a, b)| a * b).sum();
        assert!(dot.abs() < 1e-5 && up[2] > 0.0, "{up:?}");
        assert_eq!(cam["field_of_view"], 60.0);
        // The same frame as the IFC's, in metres: the point looked at, 1 m above the floor,
        // is within the door's width of its IfcOpenShell placement (its origin is a corner of
        // the door), whose height is the storey's.
        let m: Vec<f64> = placements[id]
            .as_array()
            .unwrap()
            .iter()
            .map(|x| x.as_f64().unwrap())
            .collect();
        let t = (level + 1.0 - p[2]) / dir[2];
        let (tx, ty) = (p[0] + t * dir[0], p[1] + t * dir[1]);
        let off = (tx - m[3]).hypot(ty - m[7]);
        assert!(
            off < 0.9,
            "door {id}: looks at ({tx:.2}, {ty:.2}), placed at ({}, {})",
            m[3],
            m[7]
        );
        assert!(
            (m[11] - level).abs() < 0.05,
            "door {id} at z {} on level {level}",
            m[11]
        );
    }
    for c in &transitions {
        let id = c["id"].as_str().unwrap();
        let t = topics
            .iter()
            .find(|t| t["viewpoints"][0]["selected"] == serde_json::json!([id]))
            .unwrap_or_else(|| panic!("a topic for {id}"));
        assert_eq!(strs(&t["labels"]), ["paper-robot", "BLOCKED", "stair"]);
        assert_eq!(
            t["viewpoints"][0]["coloured"],
            serde_json::json!([["D93025", id]])
        );
    }
    // Every XML file valid against buildingSMART's XSDs: bcf.version, project.bcfp,
    // extensions.xml, and per topic markup and viewpoint.
    assert_eq!(read["xsd_checked"], 3 + 2 * topics.len());
}

#[test]
fn bcf_2_1_has_guids_from_profile_element_and_kind_and_the_same_bytes_on_every_run() {
    let dir = tempfile::tempdir().unwrap();
    let (audit, a) = run_audit(dir.path(), "a.bcf", &["--bcf-version", "2.1"]);
    let (_, b) = run_audit(dir.path(), "b.bcf", &["--bcf-version", "2.1"]);
    assert_eq!(std::fs::read(&a).unwrap(), std::fs::read(&b).unwrap());
    assert_eq!(audit["bcf"]["version"], "2.1");
    // The topic GUIDs are UUID v5 of profile, GlobalId and kind: the same in 3.0.
    let (doors, transitions, _) = failing(&audit);
    let expected: BTreeSet<String> = doors
        .iter()
        .map(|d| poinav_bcf::guid::topic_guid("paper-robot", d["id"].as_str().unwrap(), "door"))
        .chain(transitions.iter().map(|c| {
            poinav_bcf::guid::topic_guid(
                "paper-robot",
                c["id"].as_str().unwrap(),
                c["kind"].as_str().unwrap(),
            )
        }))
        .collect();
    assert_eq!(expected.len(), 7);

    let read = check(&a, "2.1");
    assert_eq!(read["version"], "2.1");
    let topics = read["topics"].as_array().unwrap();
    let read_guids: BTreeSet<String> = topics
        .iter()
        .map(|t| t["guid"].as_str().unwrap().to_string())
        .collect();
    assert_eq!(read_guids, expected);
    for d in doors {
        let id = d["id"].as_str().unwrap();
        let t = topics
            .iter()
            .find(|t| t["viewpoints"][0]["selected"] == serde_json::json!([id]))
            .unwrap_or_else(|| panic!("a topic for {id}"));
        assert_eq!(
            t["viewpoints"][0]["coloured"],
            serde_json::json!([["E8A400", id]])
        );
        assert_eq!(
            t["viewpoints"][0]["snapshot"],
            serde_json::json!([640, 480])
        );
        assert_eq!(strs(&t["labels"]), ["paper-robot", "RESTRICTED", "door"]);
    }
    // bcf.version, project.bcfp, and per topic markup and viewpoint, valid.
    assert_eq!(read["xsd_checked"], 2 + 2 * topics.len());
}
