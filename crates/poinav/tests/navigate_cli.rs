//! `poinav route`, `poinav audit` and `poinav export nav2` on the paper's test building and on
//! office-a.ifc: routes through the right doors, a narrowed door makes its room unreachable
//! with the door named, and the Nav2 bundle follows nav2_map_server's conventions; a hillside
//! house's upper door onto the terrain is an entrance the audit names; storeys with nothing to
//! navigate (office-a's roof, the railway's parts) are skipped with a line; `plan --all-storeys`
//! writes every storey as `plan --storey` does.

mod common;

use std::ffi::OsStr;
use std::path::Path;

fn run(args: &[&OsStr]) -> (i32, String, String) {
    common::poinav(args)
}

/// `poinav route FILE --from A --to B --json`: the doors passed (names) and the route JSON.
fn route_json(file: &Path, from: &str, to: &str) -> (Vec<String>, serde_json::Value) {
    let (code, out, err) = run(&[
        OsStr::new("route"),
        file.as_os_str(),
        OsStr::new("--from"),
        OsStr::new(from),
        OsStr::new("--to"),
        OsStr::new(to),
        OsStr::new("--json"),
    ]);
    assert_eq!(code, 0, "{err}");
    let route: serde_json::Value = serde_json::from_str(&out).unwrap();
    let doors = route["doors"]
        .as_array()
        .unwrap()
        .iter()
        .map(|d| d["name"].as_str().unwrap().to_string())
        .collect();
    (doors, route)
}

fn demo(dir: &Path) -> std::path::PathBuf {
    let path = dir.join("demo.ifc");
    let (code, _, err) = run(&[
        OsStr::new("demo-building"),
        OsStr::new("-o"),
        path.as_os_str(),
    ]);
    assert_eq!(code, 0, "{err}");
    path
}

#[test]
fn routes_pass_the_expected_doors_and_a_narrowed_door_is_named_as_the_blocker() {
    let dir = tempfile::tempdir().unwrap();
    let building = demo(dir.path());
    let (doors, route) = route_json(&building, "Room 1", "Room 6");
    assert_eq!(doors, ["Door Room 1", "Door Room 6"]);
    // Room 1 (0..4, 0..4) to Room 6 (8.4..12.4, 6.8..10.8) through the corridor: 12 to 16 m.
    let length = route["length_m"].as_f64().unwrap();
    assert!((12.0..16.0).contains(&length), "{length}");
    assert!(
        route["time_s"].as_f64().unwrap() > length / 5.0,
        "no faster than the top speed"
    );

    let narrow = dir.path().join("narrow.ifc");
    let (code, _, err) = run(&[
        OsStr::new("patch"),
        OsStr::new("door-width"),
        building.as_os_str(),
        OsStr::new("-o"),
        narrow.as_os_str(),
        OsStr::new("--door"),
        OsStr::new("Door Room 2"),
        OsStr::new("--width"),
        OsStr::new("0.60"),
    ]);
    assert_eq!(code, 0, "{err}");
    let (code, _, err) = run(&[
        OsStr::new("route"),
        narrow.as_os_str(),
        OsStr::new("--from"),
        OsStr::new("Room 1"),
        OsStr::new("--to"),
        OsStr::new("Room 2"),
    ]);
    assert_eq!(code, 1);
    assert!(
        err.contains("Door Room 2") && err.contains("BLOCKED"),
        "{err}"
    );

    let report = dir.path().join("audit/report.html");
    std::fs::create_dir_all(report.parent().unwrap()).unwrap();
    let (code, _, err) = run(&[
        OsStr::new("audit"),
        narrow.as_os_str(),
        OsStr::new("-o"),
        report.as_os_str(),
        OsStr::new("--start"),
        OsStr::new("Corridor"),
        OsStr::new("--require-reachable"),
        OsStr::new("Room 1"),
        OsStr::new("Room 2"),
    ]);
    assert_eq!(code, 1, "Room 2 is behind a 0.60 m door: {err}");
    assert!(
        err.contains("Room 2") && err.contains("Door Room 2"),
        "{err}"
    );
    assert!(!err.contains("Room 1 "), "Room 1 stays reachable: {err}");
    let html = std::fs::read_to_string(&report).unwrap();
    assert!(html.contains("<svg") && html.contains("Door Room 2"));
    let audit: serde_json::Value =
        serde_json::from_slice(&std::fs::read(dir.path().join("audit/audit.json")).unwrap())
            .unwrap();
    assert!(audit.to_string().contains("BLOCKED"));
    let (code, _, err) = run(&[
        OsStr::new("audit"),
        building.as_os_str(),
        OsStr::new("-o"),
        report.as_os_str(),
        OsStr::new("--start"),
        OsStr::new("Corridor"),
        OsStr::new("--require-reachable"),
        OsStr::new("Room 2"),
    ]);
    assert_eq!(
        code, 0,
        "the original 0.80 m door is RESTRICTED but passable: {err}"
    );
}

/// Reads a binary PGM (P5): width, height, max value and pixels.
fn read_pgm(bytes: &[u8]) -> (usize, usize, u32, Vec<u8>) {
    let pgm = poinav_testkit::read_pgm(bytes);
    (pgm.width, pgm.height, pgm.maxval, pgm.pixels)
}

#[test]
fn nav2_bundle_of_office_a_follows_the_map_server_conventions() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("nav2");
    let file = common::shared().join("ifc/office-a.ifc");
    let (code, stdout, err) = run(&[
        OsStr::new("export"),
        OsStr::new("nav2"),
        file.as_os_str(),
        OsStr::new("-o"),
        out.as_os_str(),
    ]);
    assert_eq!(code, 0, "{err}");
    assert!(out.join("README.md").exists());
    let storey = out.join("00-level-1");
    let yaml = std::fs::read_to_string(storey.join("map.yaml")).unwrap();
    for key in [
        "image: map.pgm",
        "resolution: 0.05",
        "origin: [",
        "negate: 0",
        "occupied_thresh: 0.65",
        "mode: trinary",
    ] {
        assert!(yaml.contains(key), "{key} missing in\n{yaml}");
    }
    let (w, h, max, pixels) = read_pgm(&std::fs::read(storey.join("map.pgm")).unwrap());
    assert_eq!(max, 255);
    assert_eq!(pixels.len(), w * h);
    assert!(
        pixels.iter().all(|p| [0, 205, 254].contains(p)),
        "trinary values only"
    );
    // The summary says what was written, storey by storey.
    assert!(
        stdout.contains(&format!("00-level-1/ (Level 1): map {w} x {h} cells")),
        "{stdout}"
    );
    let free = pixels.iter().filter(|&&p| p == 254).count() as f64 * 0.05 * 0.05;
    let occupied = pixels.iter().filter(|&&p| p == 0).count() as f64 * 0.05 * 0.05;
    // Level 1 of office-a: about 1,900 m² of rooms and corridors, walls a few hundred m².
    assert!((1000.0..3000.0).contains(&free), "free area {free} m²");
    assert!(
        (100.0..800.0).contains(&occupied),
        "occupied area {occupied} m²"
    );
    let filters = std::fs::read_to_string(storey.join("costmap_filter_info.yaml")).unwrap();
    assert!(
        filters.contains("type: 0")
            && filters.contains("type: 1")
            && filters.contains("multiplier"),
        "{filters}"
    );
    let graph: serde_json::Value =
        serde_json::from_slice(&std::fs::read(storey.join("route_graph.geojson")).unwrap())
            .unwrap();
    let features = graph["features"].as_array().unwrap();
    let mut ids: Vec<u64> = features
        .iter()
        .map(|f| f["properties"]["id"].as_u64().unwrap())
        .collect();
    let n = ids.len();
    ids.sort_unstable();
    ids.dedup();
    assert_eq!(ids.len(), n, "ids unique across nodes and edges");
    let edges = features
        .iter()
        .filter(|f| f["geometry"]["type"] == "MultiLineString")
        .count();
    assert!(edges > 100, "{edges} edges");
}

fn corpus_file(name: &str) -> std::path::PathBuf {
    common::shared().join("ifc").join(name)
}

#[test]
fn routes_start_outside_and_the_cli_warns_of_what_limits_navigation() {
    let dir = tempfile::tempdir().unwrap();
    // FZK-Haus: from outside through the front door (its space boundary: the hall, Flur, and
    // the outside) into the office (Buero, space 2).
    let fzk = corpus_file("fzk-haus-ifc4.ifc");
    let (doors, route) = route_json(&fzk, "outside", "2");
    assert_eq!(doors, ["Haustuer", "Innentuer-3"]);
    // The apron in front of the door is 1 m deep: the route starts half a metre out.
    let length = route["length_m"].as_f64().unwrap();
    assert!((3.0..8.0).contains(&length), "{length}");

    // The audit from outside starts at both entrances; the front door joins the hall and the
    // outside.
    let report = dir.path().join("fzk/report.html");
    let (code, out, err) = run(&[
        OsStr::new("audit"),
        fzk.as_os_str(),
        OsStr::new("-o"),
        report.as_os_str(),
        OsStr::new("--start"),
        OsStr::new("outside"),
        OsStr::new("--json"),
    ]);
    assert_eq!(code, 0, "{err}");
    let audit: serde_json::Value = serde_json::from_str(&out).unwrap();
    let profile = &audit["profiles"][0];
    assert_eq!(
        profile["starts"],
        serde_json::json!([
            "Erdgeschoss door Haustuer into 1 Flur",
            "Erdgeschoss door Terrassentuer into 5 Wohnen"
        ])
    );
    let front = profile["doors"]
        .as_array()
        .unwrap()
        .iter()
        .find(|d| d["name"] == "Haustuer")
        .unwrap();
    assert_eq!(front["zones"], serde_json::json!(["1", "outside"]));
    assert_eq!(front["sides_from_space_boundaries"], true);
    assert_eq!(front["entrance"], "ground");
    assert_eq!(
        (
            front["exterior"].as_bool(),
            front["grid_passable"].as_bool()
        ),
        (Some(true), Some(true))
    );

    // A model without spaces: a clear warning, and no entrance to start from.
    let bare = corpus_file("wall-door-column-ifc4x3.ifc");
    let report = dir.path().join("bare/report.html");
    let (code, out, err) = run(&[
        OsStr::new("audit"),
        bare.as_os_str(),
        OsStr::new("-o"),
        report.as_os_str(),
        OsStr::new("--json"),
    ]);
    assert_eq!(code, 0, "{err}");
    assert!(
        err.contains("warning: storey `L1` has 1 door but no spaces (IfcSpace)"),
        "{err}"
    );
    let audit: serde_json::Value = serde_json::from_str(&out).unwrap();
    assert_eq!(audit["warnings"].as_array().unwrap().len(), 1, "{audit}");
    let html = std::fs::read_to_string(&report).unwrap();
    assert!(html.contains("but no spaces (IfcSpace)"));
    let (code, _, err) = run(&[
        OsStr::new("route"),
        bare.as_os_str(),
        OsStr::new("--from"),
        OsStr::new("outside"),
        OsStr::new("--to"),
        OsStr::new("0,0"),
    ]);
    assert_eq!(code, 1);
    assert!(
        err.contains("the building has no entrance: it has no spaces"),
        "{err}"
    );
    let (code, _, err) = run(&[
        OsStr::new("route"),
        bare.as_os_str(),
        OsStr::new("--from"),
        OsStr::new("Kitchen"),
        OsStr::new("--to"),
        OsStr::new("0,0"),
    ]);
    assert_eq!(code, 2, "an unknown space is bad input");
    assert!(
        err.contains("no space named `Kitchen` (the model has no spaces there: give a point"),
        "{err}"
    );

    // Stairs that connect no storeys are named with the reason, in the report too.
    let stairs = corpus_file("nested-mapped-item.ifc");
    let report = dir.path().join("stairs/report.html");
    let (code, _, err) = run(&[
        OsStr::new("audit"),
        stairs.as_os_str(),
        OsStr::new("-o"),
        report.as_os_str(),
    ]);
    assert_eq!(code, 0, "{err}");
    let expected = "stair STAIR | Standard(1) (2Kkkz43YFqUW00000007yI) is left out, it connects no storeys: it rises from storey `acad_architecture_2010_objects` to z = 2.95 m, no other storey's floor";
    assert!(err.contains(&format!("warning: {expected}")), "{err}");
    let json = std::fs::read_to_string(dir.path().join("stairs/audit.json")).unwrap();
    assert!(json.contains(expected), "{json}");
}

#[test]
fn grid_options_change_the_nav2_maps_and_bad_values_are_refused() {
    let dir = tempfile::tempdir().unwrap();
    let file = common::shared().join("ifc/duplex-apartment.ifc");
    let bundle = |name: &str, extra: &[&str]| {
        let out = dir.path().join(name);
        let mut args = vec![
            OsStr::new("export"),
            OsStr::new("nav2"),
            file.as_os_str(),
            OsStr::new("-o"),
            out.as_os_str(),
        ];
        args.extend(extra.iter().map(OsStr::new));
        let (code, _, err) = run(&args);
        assert_eq!(code, 0, "{err}");
        let storey = out.join("01-level-1");
        let yaml = std::fs::read_to_string(storey.join("map.yaml")).unwrap();
        let (w, h, _, pixels) = read_pgm(&std::fs::read(storey.join("map.pgm")).unwrap());
        let count = |v: u8| pixels.iter().filter(|&&p| p == v).count();
        (w, h, [count(0), count(254), count(205)], yaml)
    };
    let (w, h, [occupied, free, unknown], yaml) = bundle("default", &[]);
    assert!(yaml.contains("resolution: 0.05"), "{yaml}");
    // 0.1 m cells: half as many columns and rows, about the same areas.
    let (w2, h2, [occupied2, free2, _], yaml2) = bundle("coarse", &["--resolution", "0.1"]);
    assert!(yaml2.contains("resolution: 0.1"), "{yaml2}");
    assert!(
        w2.abs_diff(w / 2) <= 1 && h2.abs_diff(h / 2) <= 1,
        "{w}x{h} -> {w2}x{h2}"
    );
    let area = |cells: usize, res: f64| cells as f64 * res * res;
    let (a, a2) = (area(free, 0.05), area(free2, 0.1));
    assert!(
        (a2 - a).abs() / a < 0.05,
        "free {a} m² at 0.05 m, {a2} m² at 0.1 m"
    );
    assert!(occupied2 > 0 && area(occupied2, 0.1) > 0.5 * area(occupied, 0.05));
    // Furniture left to the sensors (Level 1): the duplex's beds, tables and cabinets turn from occupied
    // to unknown; no cell becomes free.
    let (_, _, [occupied3, free3, unknown3], _) = bundle("sensors", &["--furniture", "unknown"]);
    let moved = occupied - occupied3;
    assert!(
        area(moved, 0.05) > 5.0,
        "{} m² of furniture",
        area(moved, 0.05)
    );
    assert_eq!(
        unknown3 - unknown,
        moved,
        "occupied furniture cells became unknown"
    );
    assert_eq!(free3, free);
    // Out-of-range values are refused before anything is written.
    for (flag, value) in [
        ("--resolution", "0"),
        ("--resolution", "NaN"),
        ("--entrance-apron", "-1"),
    ] {
        let out = dir.path().join("refused");
        let arg = format!("{flag}={value}");
        let (code, _, err) = run(&[
            OsStr::new("export"),
            OsStr::new("nav2"),
            file.as_os_str(),
            OsStr::new("-o"),
            out.as_os_str(),
            OsStr::new(&arg),
        ]);
        assert_eq!(code, 2, "{flag} {value}: {err}");
        assert!(err.contains(&format!("{flag} must be between")), "{err}");
        assert!(!out.exists());
    }
}

#[test]
fn a_model_without_a_building_skips_every_railway_part_in_the_audit() {
    // The railway model: IfcRailway, alignments and track elements along them, no building:
    // one plan per railway part. Neither part holds a space or a door, so the audit skips
    // both with a line each (the kilometres of track are not rasterised: at 5 cm they would be
    // more than the 400 M-cell bound) and draws neither.
    let dir = tempfile::tempdir().unwrap();
    let file = common::shared().join("ifc/railway-track-ifc4x3.ifc");
    let out = dir.path().join("report.html");
    let (code, stdout, err) = run(&[
        OsStr::new("audit"),
        file.as_os_str(),
        OsStr::new("-o"),
        out.as_os_str(),
    ]);
    assert_eq!(code, 0, "{err}");
    assert!(
        stdout.contains("0 door passages (0 doors, 0 doorways)")
            && stdout.contains("spaces 0 reachable, 0 not"),
        "{stdout}"
    );
    let skipped: Vec<&str> = stdout
        .lines()
        .filter(|l| l.starts_with("  skipped storey "))
        .collect();
    assert_eq!(
        skipped,
        [
            "  skipped storey Binario di corsa: no spaces or doors (9225 other elements)",
            "  skipped storey Binario di corsa: no spaces or doors (712 other elements)",
        ],
        "{stdout}"
    );
    assert!(stdout.contains("wrote "), "{stdout}");
    let mut files: Vec<String> = std::fs::read_dir(dir.path())
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    files.sort();
    assert_eq!(files, ["audit.json", "report.html"]);
}

#[test]
fn the_office_a_audit_skips_the_roof_with_a_line_and_draws_the_other_storeys() {
    // office-a's Roof storey holds only its 10 parapet walls: skipped, as in the Nav2 bundle.
    let dir = tempfile::tempdir().unwrap();
    let file = common::shared().join("ifc/office-a.ifc");
    let out = dir.path().join("report.html");
    let (code, stdout, err) = run(&[
        OsStr::new("-q"),
        OsStr::new("audit"),
        file.as_os_str(),
        OsStr::new("-o"),
        out.as_os_str(),
    ]);
    assert_eq!(code, 0, "{err}");
    assert!(
        stdout.starts_with("paper-robot: 104 door passages (102 doors, 2 doorways): 99 full, 5 restricted, 0 blocked, 0 pending; spaces 99 reachable, 0 not\n  skipped storey Roof: no spaces or doors (10 walls)\nwrote "),
        "{stdout}"
    );
    assert!(dir.path().join("paper-robot-01-level-2.svg").exists());
    assert!(!dir.path().join("paper-robot-02-roof.svg").exists());
    let json: serde_json::Value =
        serde_json::from_slice(&std::fs::read(dir.path().join("audit.json")).unwrap()).unwrap();
    assert_eq!(
        json["skipped"],
        serde_json::json!([{"floor": "Roof", "reason": "no spaces or doors (10 walls)"}])
    );
    assert_eq!(json["crop_margin_m"], 2.0);
    let html = std::fs::read_to_string(&out).unwrap();
    assert!(html.contains(
        "<p class=\"skipped\">Storey Roof is skipped: no spaces or doors (10 walls).</p>"
    ));
    assert_eq!(html.matches("<figure>").count(), 2);
}

#[test]
fn the_plan_draws_and_counts_office_a_lift_doorway() {
    let dir = tempfile::tempdir().unwrap();
    let file = common::shared().join("ifc/office-a.ifc");
    let out = dir.path().join("level-1.svg");
    let (code, stdout, err) = run(&[
        OsStr::new("plan"),
        file.as_os_str(),
        OsStr::new("--storey"),
        OsStr::new("Level 1"),
        OsStr::new("-o"),
        out.as_os_str(),
    ]);
    assert_eq!(code, 0, "{err}");
    assert!(
        // 575 items: the hydraulic lift (an IfcFlowTerminal of surfaces) is planned as lines.
        stdout.contains("(575 items, 66 doors, 0 problems; 1 doorway without a door)"),
        "{stdout}"
    );
    let svg = std::fs::read_to_string(&out).unwrap();
    assert!(
        svg.contains(r#"data-global-id="27TOPmxCrDgPimmYCM5z6f" data-class="IfcOpeningElement""#),
        "the lift doorway's passage is drawn"
    );
}

#[test]
fn plan_all_storeys_writes_each_storey_as_plan_storey_does() {
    // One reading and meshing for every storey; each file is byte for byte what
    // `plan --storey` writes for that storey.
    let dir = tempfile::tempdir().unwrap();
    let file = common::shared().join("ifc/duplex-apartment.ifc");
    let all = dir.path().join("plans");
    let (code, stdout, err) = run(&[
        OsStr::new("plan"),
        file.as_os_str(),
        OsStr::new("--all-storeys"),
        OsStr::new("-o"),
        all.as_os_str(),
    ]);
    assert_eq!(code, 0, "{err}");
    let mut names: Vec<String> = std::fs::read_dir(&all)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    assert_eq!(
        names,
        [
            "00-t-fdn.svg",
            "01-level-1.svg",
            "02-level-2.svg",
            "03-roof.svg"
        ]
    );
    for counts in [
        "storey T/FDN (7 items, 0 doors, 0 problems)",
        "storey Level 1 (90 items, 6 doors, 0 problems)",
        // 85: the party wall #5399, a surface model, is planned as lines.
        "storey Level 2 (85 items, 8 doors, 0 problems)",
        "storey Roof (8 items, 0 doors, 0 problems)",
    ] {
        assert!(stdout.contains(counts), "{counts} in {stdout}");
    }
    let one = dir.path().join("level-2.svg");
    let (code, _, err) = run(&[
        OsStr::new("plan"),
        file.as_os_str(),
        OsStr::new("--storey"),
        OsStr::new("Level 2"),
        OsStr::new("-o"),
        one.as_os_str(),
    ]);
    assert_eq!(code, 0, "{err}");
    assert!(
        std::fs::read(&one).unwrap() == std::fs::read(all.join("02-level-2.svg")).unwrap(),
        "plan --all-storeys wrote Level 2 otherwise than plan --storey"
    );
    let (code, _, err) = run(&[
        OsStr::new("plan"),
        file.as_os_str(),
        OsStr::new("--all-storeys"),
        OsStr::new("--storey"),
        OsStr::new("Level 2"),
        OsStr::new("-o"),
        all.as_os_str(),
    ]);
    assert_eq!(code, 2, "--storey with --all-storeys is refused: {err}");
}

#[test]
fn the_audit_names_an_entrance_from_the_terrain() {
    // The hillside house (tests/ifcos/author_hillside.py): its upper floor is reached only
    // through the hillside door, which opens onto an IfcGeographicElement TERRAIN.
    let dir = tempfile::tempdir().unwrap();
    let py = poinav_testkit::python("ifcopenshell");
    let info = poinav_testkit::ifcos_with(&py, "author_hillside.py", &[dir.path().as_os_str()]);
    let file = dir
        .path()
        .join(info["files"]["geographic"].as_str().unwrap());
    let report = dir.path().join("audit/report.html");
    let audit = |json: bool| {
        let mut args = vec![
            OsStr::new("audit"),
            file.as_os_str(),
            OsStr::new("-o"),
            report.as_os_str(),
        ];
        if json {
            args.push(OsStr::new("--json"));
        }
        let (code, out, err) = run(&args);
        assert_eq!(code, 0, "{err}");
        out
    };
    let text = audit(false);
    assert!(text.contains("spaces 3 reachable, 0 not"), "{text}");
    assert!(
        text.contains("  entrance from the terrain: Upper floor door Hillside door (storey not at ground level)"),
        "{text}"
    );
    let json: serde_json::Value = serde_json::from_str(&audit(true)).unwrap();
    let profile = &json["profiles"][0];
    let entrances: Vec<(&str, &str)> = profile["doors"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|d| d["exterior"] == true)
        .map(|d| (d["name"].as_str().unwrap(), d["entrance"].as_str().unwrap()))
        .collect();
    assert_eq!(
        entrances,
        [("Front door", "ground"), ("Hillside door", "terrain")]
    );
    assert_eq!(
        profile["starts"][1],
        "Upper floor door Hillside door into Upper hall Upper hall, from the terrain"
    );
}
