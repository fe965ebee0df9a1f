//! What a new user trips over (issue 18), each with its exact message and exit code: ambiguous
//! and unknown space names (exit 2, the candidates listed), exit codes (2 bad input, 1 the
//! answer is no), the route text naming every door and lift with the JSON's time, messages for
//! a folder given as output and for a file that is not a scenario, the audit's entrance names,
//! door passages and legend, and `--help`'s exit-code table.

mod common;

use std::ffi::OsStr;
use std::path::Path;

fn run(args: &[&str]) -> (i32, String, String) {
    let args: Vec<&OsStr> = args.iter().map(OsStr::new).collect();
    common::poinav(&args)
}

fn office() -> String {
    poinav_testkit::corpus_file("office-a.ifc")
        .display()
        .to_string()
}

#[test]
fn an_ambiguous_name_is_refused_with_its_candidates_and_exits_2() {
    let office = office();
    let (code, out, err) = run(&["route", &office, "--from", "SERVER RM", "--to", "203"]);
    assert_eq!(code, 2, "{err}");
    assert_eq!(out, "");
    assert_eq!(
        err,
        "error: `SERVER RM` is ambiguous: 2 spaces have that Name or LongName; name one of them as shown (a Name or LongName no other space has, `Name@Storey`, or the GlobalId):\n  144  (Name 144, LongName SERVER RM, storey `Level 1`, GlobalId 04Sq57eS5FffNezn2ilgC4)\n  157  (Name 157, LongName SERVER RM, storey `Level 1`, GlobalId 04Sq57eS5FffNezn2ilg3j)\n"
    );
    // CORRIDOR: six spaces on two storeys; `CORRIDOR@Level 2` still fits three.
    let (code, _, err) = run(&[
        "route",
        &office,
        "--from",
        "CORRIDOR@Level 2",
        "--to",
        "101",
    ]);
    assert_eq!(code, 2, "{err}");
    assert!(
        err.starts_with(
            "error: `CORRIDOR@Level 2` is ambiguous: 3 spaces have that Name or LongName"
        ),
        "{err}"
    );
    assert_eq!(
        err.matches("storey `Level 2`, GlobalId ").count(),
        3,
        "{err}"
    );
    // audit --start and --require-reachable refuse it too, before writing anything.
    let dir = tempfile::tempdir().unwrap();
    let report = dir.path().join("report.html");
    let report = report.to_str().unwrap();
    let (code, _, err) = run(&["audit", &office, "-o", report, "--start", "CORRIDOR"]);
    assert_eq!(code, 2, "{err}");
    assert!(
        err.contains("error: `CORRIDOR` is ambiguous: 6 spaces"),
        "{err}"
    );
    let (code, _, err) = run(&[
        "audit",
        &office,
        "-o",
        report,
        "--require-reachable",
        "SERVER RM",
    ]);
    assert_eq!(code, 2, "{err}");
    assert!(
        err.contains("error: `SERVER RM` is ambiguous: 2 spaces"),
        "{err}"
    );
    assert!(!Path::new(report).exists());
}

#[test]
fn a_global_id_a_unique_name_or_name_at_storey_selects_exactly_one_space() {
    let office = office();
    let json = |from: &str| {
        let (code, out, err) = run(&["route", &office, "--from", from, "--to", "144", "--json"]);
        assert_eq!(code, 0, "{from}: {err}");
        let r: serde_json::Value = serde_json::from_str(&out).unwrap();
        (
            r["from"].as_str().unwrap().to_string(),
            r["length_m"].as_f64().unwrap(),
        )
    };
    // 101 ENTRY by GlobalId and as LongName@Storey: the same route (the other forms are
    // unit-tested in poinav-nav's space_name.rs).
    let by_id = json("04Sq57eS5FffNezn2ilgn0");
    let by_name = json("ENTRY@Level 1");
    assert_eq!(by_id.1, by_name.1);
    assert_eq!(by_name.0, "ENTRY@Level 1");
}

#[test]
fn an_unknown_name_or_storey_exits_2_and_an_unreachable_goal_exits_1() {
    let office = office();
    let (code, _, err) = run(&["route", &office, "--from", "Kitchen", "--to", "203"]);
    assert_eq!(
        (code, err.as_str()),
        (2, "error: no space named `Kitchen`\n")
    );
    let (code, _, err) = run(&["route", &office, "--from", "server rm", "--to", "203"]);
    assert_eq!(
        (code, err.as_str()),
        (
            2,
            "error: no space named `server rm` (names are case-sensitive: `SERVER RM`)\n"
        )
    );
    let (code, _, err) = run(&["route", &office, "--from", "101@Level 9", "--to", "203"]);
    assert_eq!(
        (code, err.as_str()),
        (
            2,
            "error: no storey named `Level 9`; storeys: Level 1, Level 2, Roof\n"
        )
    );
    let dir = tempfile::tempdir().unwrap();
    let report = dir.path().join("report.html");
    let (code, _, err) = run(&[
        "audit",
        &office,
        "-o",
        report.to_str().unwrap(),
        "--require-reachable",
        "Kitchen",
    ]);
    assert_eq!(
        (code, err.as_str()),
        (2, "error: no space named `Kitchen`\n")
    );
    // The answer is no: a robot wider than every door of the test building.
    let building = dir.path().join("demo.ifc");
    let building = building.to_str().unwrap();
    assert_eq!(run(&["demo-building", "-o", building]).0, 0);
    let wide = dir.path().join("wide.toml");
    std::fs::write(
        &wide,
        std::fs::read_to_string(
            common::root().join("crates/poinav-roles/profiles/paper-robot.toml"),
        )
        .unwrap()
        .replace("width_m = 0.70", "width_m = 1.50")
        .replace(
            "min_clearance_width_m = 0.90",
            "min_clearance_width_m = 1.70",
        ),
    )
    .unwrap();
    let (code, out, err) = run(&[
        "route",
        building,
        "--from",
        "Room 1",
        "--to",
        "Room 2",
        "--profile",
        wide.to_str().unwrap(),
    ]);
    assert_eq!(code, 1, "{out}{err}");
    assert!(
        err.starts_with("error: Room 2 is unreachable from Room 1"),
        "{err}"
    );
}

#[test]
fn the_route_text_lists_every_door_and_the_lift_with_the_json_time() {
    let office = office();
    let (code, text, err) = run(&["route", &office, "--from", "101", "--to", "203"]);
    assert_eq!(code, 0, "{err}");
    let (code, json, err) = run(&["route", &office, "--from", "101", "--to", "203", "--json"]);
    assert_eq!(code, 0, "{err}");
    let r: serde_json::Value = serde_json::from_str(&json).unwrap();
    let lines: Vec<&str> = text.lines().collect();
    assert_eq!(
        lines[0],
        format!(
            "101 -> 203 for paper-robot: {:.2} m, {:.1} s",
            r["length_m"].as_f64().unwrap(),
            r["time_s"].as_f64().unwrap()
        )
    );
    assert_eq!(lines[0], "101 -> 203 for paper-robot: 38.35 m, 50.2 s");
    assert!(
        lines.contains(&"  lift ELEV 124 from Level 1 to Level 2: 34.3 s (FULL_ACCESS)"),
        "{text}"
    );
    // Every door of the JSON is named in the text, on its storey's line block.
    for d in r["doors"].as_array().unwrap() {
        let name = d["name"].as_str().unwrap();
        assert!(
            text.contains(&format!("through door {name} (")),
            "{name}: {text}"
        );
    }
    // The storey legs add up to the total with the lift.
    let legs: f64 = r["legs"]
        .as_array()
        .unwrap()
        .iter()
        .map(|l| l["travel_time_s"].as_f64().unwrap() + l["turn_time_s"].as_f64().unwrap())
        .sum();
    let lift = r["connections"][0]["time_s"].as_f64().unwrap();
    assert!((legs + lift - r["time_s"].as_f64().unwrap()).abs() < 1e-3);
    assert_eq!(
        lines
            .iter()
            .filter(|l| l.starts_with("  on Level "))
            .count(),
        2,
        "{text}"
    );
}

#[test]
fn a_folder_as_output_and_a_file_that_is_no_scenario_get_clear_messages() {
    let dir = tempfile::tempdir().unwrap();
    let adir = dir.path().join("adir");
    std::fs::create_dir(&adir).unwrap();
    let wall = poinav_testkit::corpus_file("wall-door-column-ifc4x3.ifc");
    let (code, _, err) = run(&[
        "enrich",
        wall.to_str().unwrap(),
        "-o",
        adir.to_str().unwrap(),
    ]);
    assert_eq!(code, 2);
    assert_eq!(
        err,
        format!(
            "error: cannot write {0}: it is a folder; name a file (e.g. {0}/model.poi.ifc)\n",
            adir.display()
        )
    );
    // A cause named once, not twice.
    let file = dir.path().join("afile");
    std::fs::write(&file, "x").unwrap();
    let glb = file.join("x.glb");
    let (code, _, err) = run(&[
        "export",
        "glb",
        wall.to_str().unwrap(),
        "-o",
        glb.to_str().unwrap(),
    ]);
    assert_eq!(code, 2);
    assert_eq!(err.matches("Not a directory").count(), 1, "{err}");
    assert!(
        err.starts_with(&format!("error: cannot write {}: ", glb.display())),
        "{err}"
    );

    let notifc = dir.path().join("notifc.txt");
    std::fs::write(&notifc, "hello world\n").unwrap();
    let (code, _, err) = run(&[
        "simulate",
        notifc.to_str().unwrap(),
        "-o",
        dir.path().join("sim").to_str().unwrap(),
    ]);
    assert_eq!(code, 2);
    assert_eq!(
        err,
        format!(
            "error: {}:1: not a scenario file: it is not TOML (key with no value, expected `=`); a scenario is a TOML file with `name = \"...\"`, `duration_s = 10.0`, a `[building]` table (`demo = {{}}` or `ifc = \"model.ifc\"`), `[[robot]]` tables and optional `[[expect]]` tables (docs/scenarios.md; examples in crates/poinav-sim/scenarios/)\n",
            notifc.display()
        )
    );
}

#[test]
fn the_audit_names_entrances_counts_doorways_and_explains_its_markers() {
    let office = office();
    let dir = tempfile::tempdir().unwrap();
    let report = dir.path().join("report.html");
    let (code, out, err) = run(&["audit", &office, "-o", report.to_str().unwrap()]);
    assert_eq!(code, 0, "{err}");
    assert_eq!(
        out.lines().next().unwrap(),
        "paper-robot: 104 door passages (102 doors, 2 doorways): 99 full, 5 restricted, 0 blocked, 0 pending; spaces 99 reachable, 0 not"
    );
    let html = std::fs::read_to_string(&report).unwrap();
    assert!(
        html.contains("Reachability from: Level 1 door 183872 into 108 ELEC RM, "),
        "{html}"
    );
    assert!(
        !html.contains("Reachability from: M_"),
        "no Revit type names"
    );
    assert!(html.contains("Door passages: 104 (102 doors, 2 doorways, openings without a door)"));
    assert!(html.contains("circles mark the landings of stairs, ramps and lifts"));
    let svg = std::fs::read_dir(dir.path())
        .unwrap()
        .map(|e| e.unwrap().path())
        .find(|p| p.extension().is_some_and(|e| e == "svg"))
        .unwrap();
    let svg = std::fs::read_to_string(svg).unwrap();
    assert!(svg.contains(">stair/ramp/lift landing, status colour</text>"));
}

#[test]
fn help_lists_the_exit_codes_and_every_export_format() {
    let (code, out, _) = run(&["--help"]);
    assert_eq!(code, 0);
    assert!(out.contains("Exit codes:\n  0  done"), "{out}");
    assert!(out.contains("\n  1  the answer is no: "));
    assert!(out.contains("\n  2  bad input: "));
    let (_, out, _) = run(&["export", "--help"]);
    assert!(out.starts_with("Export the model in other formats: 3D (GLB, FBX) and Nav2 maps"));
    let (_, out, _) = run(&["route", "--help"]);
    assert!(out.contains("or `outside` (`outside@Storey`)"), "{out}");
}
