//! The simulator's door estimate and doorway manners on doors as real houses have them (issue
//! 22, point 5), in a building IfcOpenShell writes (`tests/ifcos/author_doorways.py`: doors of
//! 0.70-1.30 m in 0.25 m walls off a corridor, every other one 0.10 m from a room's corner):
//!
//! - a robot turning into each door from the corridor reports only estimates within 5 cm of
//!   the door's clear width (never a loose guess first: a 0.77 m door once read 2.4 m and lost
//!   its B-2), the status the geometry gives, and no contact;
//! - two robots meeting in a 0.77, 0.81 or 0.90 m doorway from its two sides both get through
//!   within 20 s without touching: the one nearer the door goes, the other waits.

use std::path::{Path, PathBuf};

use poinav_bridge::prepare;
use poinav_sim::{run, EventKind, Outcome, Scenario};
use serde_json::Value;

const WIDTHS: [f64; 7] = [0.70, 0.77, 0.81, 0.90, 1.00, 1.20, 1.30];

/// The building, written into `dir`; its doors (name, width, centre, room) as the script prints.
fn building(dir: &Path) -> (PathBuf, Vec<Value>) {
    let out = dir.join("doorways.ifc");
    let py = poinav_testkit::python("ifcopenshell");
    let widths: Vec<String> = WIDTHS.iter().map(|w| format!("{w:.2}")).collect();
    let mut args: Vec<&std::ffi::OsStr> = vec![out.as_os_str()];
    args.extend(widths.iter().map(|w| std::ffi::OsStr::new(w.as_str())));
    let json = poinav_testkit::ifcos_with(&py, "author_doorways.py", &args);
    (out, json["doors"].as_array().unwrap().clone())
}

fn simulate(dir: &Path, name: &str, toml: &str) -> Outcome {
    let path = dir.join(format!("{name}.toml"));
    std::fs::write(&path, toml).unwrap();
    let s = Scenario::load(&path).unwrap();
    let prepared = prepare(&s, None).unwrap();
    run(&s, None, prepared.floor()).unwrap()
}

fn failed(o: &Outcome) -> Vec<String> {
    o.judged
        .iter()
        .filter(|j| !j.pass)
        .map(|j| format!("{} ({}): {}", j.kind, j.expected, j.measured))
        .collect()
}

#[test]
fn door_estimates_on_real_doors_are_measurements_not_guesses() {
    let dir = tempfile::tempdir().unwrap();
    let (_, doors) = building(dir.path());
    assert_eq!(doors.len(), WIDTHS.len());
    let mut problems = Vec::new();
    for door in &doors {
        let width = door["width"].as_f64().unwrap();
        let name = door["name"].as_str().unwrap();
        let room = door["room"].as_str().unwrap();
        let cx = door["centre"][0].as_f64().unwrap();
        let status = if width < 0.90 {
            "RESTRICTED"
        } else {
            "FULL_ACCESS"
        };
        // The paper robot is 0.70 m wide: it measures a 0.70 m door from straight in front
        // (keys: forward) and stops short of it; the others it turns into from the corridor.
        let (start, controller, reach) = if width < 0.75 {
            (
                format!("{{ x = {cx:.3}, y = 0.9, heading_deg = 90.0 }}"),
                "{ kind = \"keys\", scheme = \"arrows\", script = [{ t = 0.0, key = \"Up\", down = true }] }"
                    .to_string(),
                String::new(),
            )
        } else {
            (
                format!("{{ x = {:.3}, y = 1.25, heading_deg = 0.0 }}", cx - 2.5),
                format!("{{ kind = \"route\", to = \"{room}\" }}"),
                format!(
                    "[[expect]]\nkind = \"reaches-zone\"\nrobot = \"Robot1\"\nzone = \"{room}\"\n"
                ),
            )
        };
        let toml = format!(
            "name = \"door\"\nduration_s = 6.0\n[building]\nifc = \"doorways.ifc\"\n\
             [poi]\nstart = \"clear\"\n\
             [[robot]]\nname = \"Robot1\"\nprofile = \"paper\"\nstart = {start}\ncontroller = {controller}\n\
             [[expect]]\nkind = \"clearance-estimate\"\ndoor = \"{name}\"\ntolerance_m = 0.05\n\
             [[expect]]\nkind = \"door-status\"\ndoor = \"{name}\"\nstatus = \"{status}\"\n\
             [[expect]]\nkind = \"no-contact\"\nwalls = true\n{reach}"
        );
        let o = simulate(dir.path(), &format!("door-{width:.2}"), &toml);
        // Every estimate reported, not only the last, is within 5 cm.
        let estimates: Vec<f64> = o
            .data
            .events
            .iter()
            .filter_map(|e| match &e.kind {
                EventKind::Clearance { estimate_m, .. } => Some(*estimate_m),
                _ => None,
            })
            .collect();
        if estimates.is_empty() || estimates.iter().any(|e| (e - width).abs() > 0.05) {
            problems.push(format!("{name}: estimates {estimates:?}"));
        }
        for f in failed(&o) {
            problems.push(format!("{name}: {f}"));
        }
    }
    assert!(problems.is_empty(), "{problems:#?}");
}

#[test]
fn two_robots_meeting_in_a_narrow_doorway_both_get_through() {
    let dir = tempfile::tempdir().unwrap();
    let (_, doors) = building(dir.path());
    let mut problems = Vec::new();
    for door in doors
        .iter()
        .filter(|d| [0.77, 0.81, 0.90].contains(&d["width"].as_f64().unwrap()))
    {
        let name = door["name"].as_str().unwrap();
        let room = door["room"].as_str().unwrap();
        let cx = door["centre"][0].as_f64().unwrap();
        // Robot1 comes along the corridor to turn in; Robot2 leaves the room for the corridor.
        let toml = format!(
            "name = \"meet\"\nduration_s = 20.0\n[building]\nifc = \"doorways.ifc\"\n\
             [[robot]]\nname = \"Robot1\"\nprofile = \"paper\"\nstart = {{ x = {:.3}, y = 1.25, heading_deg = 0.0 }}\n\
             controller = {{ kind = \"route\", to = \"{room}\" }}\n\
             [[robot]]\nname = \"Robot2\"\nprofile = \"paper\"\nstart = {{ x = {cx:.3}, y = 4.6, heading_deg = -90.0 }}\n\
             controller = {{ kind = \"route\", to = \"Corridor\" }}\n\
             [[expect]]\nkind = \"reaches-zone\"\nrobot = \"Robot1\"\nzone = \"{room}\"\n\
             [[expect]]\nkind = \"reaches-zone\"\nrobot = \"Robot2\"\nzone = \"Corridor\"\n\
             [[expect]]\nkind = \"no-contact\"\nwalls = true\n",
            cx - 2.5
        );
        let o = simulate(dir.path(), &format!("meet-{name}"), &toml);
        for f in failed(&o) {
            problems.push(format!("{name}: {f}"));
        }
    }
    assert!(problems.is_empty(), "{problems:#?}");
}
