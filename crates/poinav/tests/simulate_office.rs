//! `poinav simulate` on a real building: a robot approaches doors of office-a.ifc, its sensors
//! estimate their clear widths, and R5's status agrees with the enrichment's geometric status;
//! `poinav demo` passes and is byte-identical run to run.

mod common;

use std::ffi::OsStr;
use std::path::Path;

use glam::DVec2;
use poinav_geom::{floor_plans, PlanItemKind, PlanOptions};
use poinav_ifc::Model;
use poinav_nav::polygon::{boundary_distance, contains};
use poinav_poi::{classify, RobotProfile, RuleSet};

#[test]
fn doorway_scenario_on_office_a_agrees_with_the_geometric_status() {
    let file = common::shared().join("ifc/office-a.ifc");
    let model = Model::open(&file).unwrap();
    let classification = classify(&model, &RuleSet::defaults(), &RobotProfile::paper());
    let plans = floor_plans(&model, &PlanOptions::default());
    let plan = plans
        .iter()
        .find(|p| p.storey_name.as_deref() == Some("Level 1"))
        .expect("Level 1");
    let spaces: Vec<_> = plan.items_of(PlanItemKind::Space).collect();
    let tmp = tempfile::tempdir().unwrap();
    let mut checked = Vec::new();
    for (width, want) in [(0.813, "RESTRICTED"), (0.915, "FULL_ACCESS")] {
        // The first door of that width with a space 1.5 m in front of it (the 0.813 m doors are
        // toilet stalls: the robot drives up to the stall door from the washroom).
        let (d, start, dir) = plan
            .doors
            .iter()
            .filter(|d| (d.clear_width_m - width).abs() < 1e-3)
            .find_map(|d| {
                let in_space = |p: DVec2| {
                    spaces
                        .iter()
                        .any(|s| s.regions.iter().any(|r| contains(&r.outer, p)))
                };
                // Room for the robot (half its diagonal is 0.53 m) clear of every obstacle.
                let clear = |p: DVec2| {
                    plan.obstacles()
                        .all(|r| !contains(&r.outer, p) && boundary_distance(&r.outer, p) > 0.56)
                };
                [d.across, -d.across].into_iter().find_map(|side| {
                    [1.5, 1.3, 1.15]
                        .into_iter()
                        .map(|k| d.center + side * k)
                        .find(|&p| in_space(p) && clear(p))
                        .map(|start| (d, start, -side))
                })
            })
            .expect("a door of that width with a space in front");
        let status = classification
            .elements
            .iter()
            .find(|e| e.global_id == d.global_id)
            .unwrap()
            .accessibility
            .as_ref()
            .unwrap()
            .status;
        assert_eq!(
            status.label(),
            want,
            "the enrichment's geometric status of {}",
            d.global_id
        );
        let heading = dir.y.atan2(dir.x).to_degrees();
        let scenario = format!(
            "name = \"office-a doorway\"\nduration_s = 3.0\n\n[building]\nifc = {file:?}\nstorey = \"Level 1\"\n\n[poi]\nstart = \"clear\"\n\n\
             [[robot]]\nname = \"Robot2\"\nprofile = \"paper\"\nstart = {{ x = {:.4}, y = {:.4}, heading_deg = {heading:.3} }}\ncontroller = {{ kind = \"keys\", scheme = \"arrows\", script = [{{ t = 0.0, key = \"Up\", down = true }}, {{ t = 1.2, key = \"Up\", down = false }}] }}\n\n\
             [[expect]]\nkind = \"clearance-estimate\"\ndoor = \"{}\"\ntolerance_m = 0.05\n\n[[expect]]\nkind = \"door-status\"\ndoor = \"{}\"\nstatus = \"{want}\"\n",
            start.x,
            start.y,
            d.global_id,
            d.global_id,
        );
        let path = tmp.path().join(format!("office-{width}.toml"));
        std::fs::write(&path, scenario).unwrap();
        let out = tmp.path().join(format!("out-{width}"));
        let (code, stdout, stderr) = common::poinav(&[
            OsStr::new("simulate"),
            path.as_os_str(),
            OsStr::new("-o"),
            out.as_os_str(),
        ]);
        assert_eq!(code, 0, "{stdout}\n{stderr}");
        let summary: serde_json::Value =
            serde_json::from_slice(&std::fs::read(out.join("summary.json")).unwrap()).unwrap();
        let text = summary.to_string();
        assert!(text.contains(want), "{text}");
        checked.push((d.global_id.clone(), width));
    }
    assert_eq!(checked.len(), 2);
}

fn tree(dir: &Path) -> Vec<(String, Vec<u8>)> {
    let mut out = Vec::new();
    let mut stack = vec![dir.to_path_buf()];
    while let Some(d) = stack.pop() {
        for e in std::fs::read_dir(&d).unwrap() {
            let p = e.unwrap().path();
            if p.is_dir() {
                stack.push(p);
            } else {
                out.push((
                    p.strip_prefix(dir).unwrap().display().to_string(),
                    std::fs::read(&p).unwrap(),
                ));
            }
        }
    }
    out.sort();
    out
}

#[test]
fn demo_passes_and_is_byte_identical_run_to_run() {
    let dir = tempfile::tempdir().unwrap();
    let run = |name: &str| {
        let out = dir.path().join(name);
        let o = std::process::Command::new(env!("CARGO_BIN_EXE_poinav"))
            .args([OsStr::new("demo"), OsStr::new("-o"), out.as_os_str()])
            .env("SOURCE_DATE_EPOCH", "1795314600")
            .output()
            .unwrap();
        assert!(
            o.status.success(),
            "{}{}",
            String::from_utf8_lossy(&o.stdout),
            String::from_utf8_lossy(&o.stderr)
        );
        let stdout = String::from_utf8_lossy(&o.stdout).into_owned();
        assert!(stdout.contains("every expectation holds"), "{stdout}");
        assert!(!stdout.contains("FAIL"), "{stdout}");
        tree(&out)
    };
    let a = run("a");
    let b = run("b");
    let names: Vec<&str> = a.iter().map(|(n, _)| n.as_str()).collect();
    for must in [
        "report.html",
        "test-building.ifc",
        "test-building.poi.ifc",
        "test-building-wide.poi.ifc",
        "test-building.glb",
        "doorway/door-0.80/trace.jsonl",
        "separation/summary.json",
        "wall-following/trajectories.svg",
        "navigation/report.html",
        "navigation/audit.json",
        "navigation/route-room1-room2.json",
        "navigation-wide/route-room1-room2.json",
        "nav2/00-ground-floor/map.pgm",
        "nav2/00-ground-floor/route_graph.geojson",
    ] {
        assert!(names.contains(&must), "{must} missing from {names:?}");
    }
    assert_eq!(a, b, "demo outputs differ between runs");
    let wide = String::from_utf8(
        a.iter()
            .find(|(n, _)| n == "test-building-wide.poi.ifc")
            .unwrap()
            .1
            .clone(),
    )
    .unwrap();
    assert!(wide.contains("IFCLABEL('FULL_ACCESS')"));
    // The same route on both designs: through the same doors, slower through the 0.80 m door
    // (B-2, half speed) than through the widened one.
    let route = |name: &str| -> serde_json::Value {
        serde_json::from_slice(&a.iter().find(|(n, _)| n == name).unwrap().1).unwrap()
    };
    let (first, widened) = (
        route("navigation/route-room1-room2.json"),
        route("navigation-wide/route-room1-room2.json"),
    );
    for r in [&first, &widened] {
        let doors: Vec<&str> = r["doors"]
            .as_array()
            .unwrap()
            .iter()
            .map(|d| d["name"].as_str().unwrap())
            .collect();
        assert_eq!(doors, ["Door Room 1", "Door Room 2"], "{r}");
    }
    let t = |r: &serde_json::Value| r["time_s"].as_f64().unwrap();
    assert!(
        t(&first) > t(&widened),
        "{} s vs {} s",
        t(&first),
        t(&widened)
    );
    // The audit from the corridor reaches all seven spaces; one door is RESTRICTED.
    let audit: serde_json::Value = serde_json::from_slice(
        &a.iter()
            .find(|(n, _)| n == "navigation/audit.json")
            .unwrap()
            .1,
    )
    .unwrap();
    let p = &audit["profiles"][0];
    assert!(
        p["spaces"]
            .as_array()
            .unwrap()
            .iter()
            .all(|s| s["reachable"] == true),
        "{p}"
    );
    let restricted: Vec<&str> = p["doors"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|d| d["status"] == "RESTRICTED")
        .map(|d| d["name"].as_str().unwrap())
        .collect();
    assert_eq!(restricted, ["Door Room 2"]);
}
