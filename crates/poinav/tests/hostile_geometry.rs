//! Hostile geometry: `scripts/make-hostile-corpus.py` writes small damaged models (NaN/Inf coordinates, zero-length extrusions, degenerate profiles, huge openings, truncations); each gets its exact outcome asserted for `inspect`, `export glb` and `plan`.

mod common;

use std::collections::BTreeSet;
use std::ffi::OsStr;
use std::path::{Path, PathBuf};
use std::process::Command;

use serde_json::Value;

/// Runs the corpus script into a fresh temporary folder.
fn corpus() -> (tempfile::TempDir, PathBuf) {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path().join("hostile");
    let out = Command::new("python3")
        .arg(common::root().join("scripts/make-hostile-corpus.py"))
        .arg(&dir)
        .output()
        .expect("python3 runs");
    assert!(
        out.status.success(),
        "make-hostile-corpus.py failed: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    (tmp, dir)
}

/// Runs poinav; (exit code, stdout, stderr), and never a panic.
fn run(args: &[&OsStr]) -> (i32, String, String) {
    let (code, stdout, stderr) = common::poinav(args);
    assert!(!stderr.contains("panicked"), "{args:?}: {stderr}");
    (code, stdout, stderr)
}

/// The names of the element nodes of a GLB (storey nodes left out), checked to be unique.
fn glb_elements(path: &Path) -> BTreeSet<String> {
    let bytes = std::fs::read(path).unwrap();
    assert_eq!(&bytes[..4], b"glTF");
    let len = u32::from_le_bytes(bytes[12..16].try_into().unwrap()) as usize;
    assert_eq!(&bytes[16..20], b"JSON");
    let json: Value = serde_json::from_slice(&bytes[20..20 + len]).unwrap();
    let mut names = BTreeSet::new();
    for node in json["nodes"].as_array().unwrap() {
        let class = node["extras"]["IfcClass"].as_str();
        if class.is_some_and(|c| c != "IfcBuildingStorey") {
            let name = node["name"].as_str().unwrap().to_string();
            assert!(names.insert(name.clone()), "{name} twice");
        }
    }
    names
}

/// Every element of the base model, by name.
const ALL: [&str; 5] = ["Door 1", "Slab", "Wall A", "Wall B", "Wall C"];

/// Readable files whose wall A (#100) cannot be meshed: (file, exact warning for #100).
const DAMAGED_WALL_A: [(&str, &str); 8] = [
    (
        "inf-placement.ifc",
        "#104: degenerate geometry: coordinate is not a finite number",
    ),
    (
        "nan-placement.ifc",
        "#104: IfcCartesianPoint has no usable `Coordinates`",
    ),
    (
        "inf-profile.ifc",
        "#107: degenerate geometry: dimension is not a positive number",
    ),
    (
        "nan-profile.ifc",
        "#107: IfcRectangleProfileDef has no usable `XDim`",
    ),
    (
        "zero-depth.ifc",
        "#106: degenerate geometry: Depth is not a positive number",
    ),
    (
        "rect-xdim-zero.ifc",
        "#107: degenerate geometry: dimension is not a positive number",
    ),
    (
        "polyline-2-points.ifc",
        "#107: degenerate geometry: profile encloses no area",
    ),
    (
        "opening-bigger-than-wall.ifc",
        "#100: IfcWall has no surface left: its openings or clippings remove all of its body",
    ),
];

/// Truncated copies of the base model: (file, what follows `error: PATH` on stderr), or
/// `None` when the cut leaves a readable model (only `END-ISO-10303-21;` lost).
const TRUNCATED: [(&str, Option<&str>); 19] = [
    (
        "truncated-00-before-iso1030321.ifc",
        Some(":1: file is empty"),
    ),
    (
        "truncated-01-after-iso1030321.ifc",
        Some(":1: malformed HEADER section: expected `HEADER;`"),
    ),
    (
        "truncated-02-before-header.ifc",
        Some(":2: malformed HEADER section: expected `HEADER;`"),
    ),
    (
        "truncated-03-after-header.ifc",
        Some(":2: file is truncated: the HEADER section is not closed by `ENDSEC;`"),
    ),
    (
        "truncated-04-before-file_description.ifc",
        Some(":3: file is truncated: the HEADER section is not closed by `ENDSEC;`"),
    ),
    (
        "truncated-05-after-file_description.ifc",
        Some(":3: file is truncated: the HEADER section is not closed by `ENDSEC;`"),
    ),
    (
        "truncated-06-before-file_name.ifc",
        Some(":4: file is truncated: the HEADER section is not closed by `ENDSEC;`"),
    ),
    (
        "truncated-07-after-file_name.ifc",
        Some(":4: file is truncated: the HEADER section is not closed by `ENDSEC;`"),
    ),
    (
        "truncated-08-before-file_schema.ifc",
        Some(":5: file is truncated: the HEADER section is not closed by `ENDSEC;`"),
    ),
    (
        "truncated-09-after-file_schema.ifc",
        Some(":5: file is truncated: the HEADER section is not closed by `ENDSEC;`"),
    ),
    (
        "truncated-10-before-endsec.ifc",
        Some(":6: file is truncated: the HEADER section is not closed by `ENDSEC;`"),
    ),
    (
        "truncated-11-after-endsec.ifc",
        Some(":6: file is truncated: the file ends before its DATA section"),
    ),
    (
        "truncated-12-before-data.ifc",
        Some(":7: file is truncated: the file ends before its DATA section"),
    ),
    (
        "truncated-13-after-data.ifc",
        Some(":7: file is truncated: the DATA section is not closed by `ENDSEC;`"),
    ),
    (
        "truncated-14-mid-string-200.ifc",
        Some(":32: #200: string literal is never closed"),
    ),
    (
        "truncated-15-mid-instance-200.ifc",
        Some(":32: #200: file is truncated: the file ends inside an entry (no closing `;`)"),
    ),
    (
        "truncated-16-before-data-endsec.ifc",
        Some(":82: #511: file is truncated: the DATA section is not closed by `ENDSEC;`"),
    ),
    ("truncated-17-after-data-endsec.ifc", None),
    ("truncated-18-before-endiso1030321.ifc", None),
];

/// `inspect --json`: exit 0 and the number of diagnostics.
fn inspect_ok(file: &Path) -> usize {
    let (code, stdout, stderr) = run(&[OsStr::new("inspect"), file.as_os_str(), "--json".as_ref()]);
    assert_eq!(code, 0, "{}: {stderr}", file.display());
    let r: Value = serde_json::from_str(&stdout).unwrap();
    r["diagnostics"].as_u64().unwrap() as usize
}

/// `export glb`: exit 0; (element names in the GLB, warning lines on stderr).
fn glb(file: &Path, out: &Path) -> (BTreeSet<String>, Vec<String>) {
    let (code, stdout, stderr) = run(&[
        OsStr::new("export"),
        "glb".as_ref(),
        file.as_os_str(),
        "-o".as_ref(),
        out.as_os_str(),
    ]);
    assert_eq!(code, 0, "{}: {stderr}", file.display());
    let names = glb_elements(out);
    let count = names.len();
    assert!(
        stdout.contains(&format!(": {count} elements (")),
        "{stdout}"
    );
    let warnings = stderr
        .lines()
        .filter(|l| l.starts_with("warning: "))
        .map(str::to_string)
        .collect();
    (names, warnings)
}

/// `plan`: exit 0; the summary line's (items, doors, problems); one stderr warning per
/// problem, naming its `#id`.
fn plan(file: &Path, out: &Path) -> (usize, usize, usize) {
    let (code, stdout, stderr) = run(&[
        OsStr::new("plan"),
        file.as_os_str(),
        "-o".as_ref(),
        out.as_os_str(),
    ]);
    assert_eq!(code, 0, "{}: {stderr}", file.display());
    assert!(std::fs::read_to_string(out).unwrap().contains("</svg>"));
    let tail = stdout
        .split_once("(")
        .and_then(|(_, t)| t.split_once(")"))
        .unwrap_or_else(|| panic!("plan summary: {stdout}"))
        .0;
    let nums: Vec<usize> = tail
        .split(", ")
        .map(|p| p.split(' ').next().unwrap().parse().unwrap())
        .collect();
    let warnings: Vec<&str> = stderr
        .lines()
        .filter(|l| l.starts_with("warning: #"))
        .collect();
    assert_eq!(
        warnings.len(),
        nums[2],
        "{}: one warning per problem: {stderr}",
        file.display()
    );
    (nums[0], nums[1], nums[2])
}

fn set(names: &[&str]) -> BTreeSet<String> {
    names.iter().map(|s| s.to_string()).collect()
}

#[test]
fn the_script_writes_every_listed_file_and_the_base_model_is_clean() {
    let (_tmp, dir) = corpus();
    let mut listed: Vec<&str> = vec![
        "base.ifc",
        "door-without-geometry.ifc",
        "polyline-self-intersecting.ifc",
        "opening-zero-depth.ifc",
    ];
    listed.extend(DAMAGED_WALL_A.iter().map(|d| d.0));
    listed.extend(TRUNCATED.iter().map(|d| d.0));
    listed.sort();
    let mut written: Vec<String> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().into_string().unwrap())
        .collect();
    written.sort();
    assert_eq!(written, listed);
    for f in &written {
        assert!(
            std::fs::metadata(dir.join(f)).unwrap().len() < 16 * 1024,
            "{f} is small"
        );
    }
    let base = dir.join("base.ifc");
    assert_eq!(inspect_ok(&base), 0);
    let (names, warnings) = glb(&base, &dir.join("base.glb"));
    assert_eq!(names, set(&ALL));
    assert!(warnings.is_empty(), "{warnings:?}");
    assert_eq!(plan(&base, &dir.join("base.svg")), (5, 1, 0));
}

#[test]
fn damaged_geometry_drops_only_the_damaged_wall_and_names_it() {
    let (_tmp, dir) = corpus();
    for (name, why) in DAMAGED_WALL_A {
        let file = dir.join(name);
        // Geometry is not checked on reading: no diagnostics, except for the bare `NaN` token,
        // which is not STEP (a bad-value diagnostic of its instance).
        let bare_nan = usize::from(name.starts_with("nan-"));
        assert_eq!(inspect_ok(&file), bare_nan, "{name}");
        let (names, warnings) = glb(&file, &dir.join(format!("{name}.glb")));
        assert_eq!(
            names,
            set(&["Door 1", "Slab", "Wall B", "Wall C"]),
            "{name}"
        );
        let expected = if why.starts_with("#100:") {
            format!("warning: {why}")
        } else {
            format!("warning: #100: {why}")
        };
        assert_eq!(warnings, vec![expected], "{name}");
        // The plan keeps the other four items and names the one problem (#100) on stderr.
        assert_eq!(
            plan(&file, &dir.join(format!("{name}.svg"))),
            (4, 1, 1),
            "{name}"
        );
    }
}

#[test]
fn a_bow_tie_profile_is_resolved_and_its_wall_kept() {
    // Wall A's profile crosses itself (0,0)-(5,0.2)-(5,0)-(0,0.2): no area in sum, two
    // triangles filled; IfcOpenShell meshes the wall too (one triangle of it).
    let (_tmp, dir) = corpus();
    let file = dir.join("polyline-self-intersecting.ifc");
    let (names, warnings) = glb(&file, &dir.join("bow-tie.glb"));
    assert_eq!(names, set(&ALL));
    assert!(warnings.is_empty(), "{warnings:?}");
    assert_eq!(plan(&file, &dir.join("bow-tie.svg")), (5, 1, 0));
}

#[test]
fn a_wall_whose_opening_cannot_be_made_is_kept_uncut_and_the_opening_named() {
    let (_tmp, dir) = corpus();
    let file = dir.join("opening-zero-depth.ifc");
    let (names, warnings) = glb(&file, &dir.join("flat-opening.glb"));
    assert_eq!(names, set(&ALL));
    let line = "warning: #100: IfcWall is meshed without #700 (IfcOpeningElement): \
                #706: degenerate geometry: Depth is not a positive number";
    assert_eq!(warnings, [line]);
    // Every command that meshes prints the same summary line: `plan` and the navigation
    // commands too (here `export nav2`), whose `--json` carries the full list.
    let svg = dir.join("flat-opening.svg");
    let (code, _, stderr) = run(&[
        OsStr::new("plan"),
        file.as_os_str(),
        "-o".as_ref(),
        svg.as_os_str(),
    ]);
    assert_eq!(code, 0, "{stderr}");
    // The opening element's own body is a plan problem (left out), as before.
    let opening = "warning: #700: #706: degenerate geometry: Depth is not a positive number \
                   (left out)";
    assert_eq!(
        stderr
            .lines()
            .filter(|l| l.starts_with("warning: "))
            .collect::<Vec<_>>(),
        [opening, line]
    );
    let nav2 = dir.join("flat-opening-nav2");
    let (code, stdout, stderr) = run(&[
        OsStr::new("export"),
        "nav2".as_ref(),
        file.as_os_str(),
        "-o".as_ref(),
        nav2.as_os_str(),
        "--json".as_ref(),
    ]);
    assert_eq!(code, 0, "{stderr}");
    assert!(stderr.lines().any(|l| l == line), "{stderr}");
    let json: Value = serde_json::from_str(&stdout).unwrap();
    let listed: Vec<&str> = json["warnings"]
        .as_array()
        .unwrap()
        .iter()
        .filter_map(|w| w["message"].as_str())
        .filter(|m| m.contains("meshed without"))
        .collect();
    assert_eq!(listed, [line.strip_prefix("warning: ").unwrap()]);
    // `simulate` on the same file meshes it to prepare its floor, and says so too.
    let scenario = dir.join("flat-opening.toml");
    std::fs::write(
        &scenario,
        format!(
            "name = \"flat-opening\"\nduration_s = 0.5\n\n[building]\nifc = {:?}\n\n\
             [[robot]]\nname = \"Robot1\"\nstart = {{ x = 2.0, y = -2.0, heading_deg = 0.0 }}\n\
             controller = {{ kind = \"keys\", scheme = \"arrows\", script = [] }}\n",
            file.display().to_string()
        ),
    )
    .unwrap();
    let out = dir.join("flat-opening-sim");
    let (code, _, stderr) = run(&[
        OsStr::new("simulate"),
        scenario.as_os_str(),
        "-o".as_ref(),
        out.as_os_str(),
        "--no-trace".as_ref(),
    ]);
    assert_eq!(code, 0, "{stderr}");
    assert!(stderr.lines().any(|l| l == line), "{stderr}");
}

#[test]
fn a_door_without_representation_is_named_in_the_export() {
    // Not a damaged model (no diagnostic), but the door is missing from every drawing, so the
    // export says so.
    let (_tmp, dir) = corpus();
    let file = dir.join("door-without-geometry.ifc");
    let (code, stdout, _) = run(&[OsStr::new("inspect"), file.as_os_str(), "--json".as_ref()]);
    assert_eq!(code, 0);
    let r: Value = serde_json::from_str(&stdout).unwrap();
    assert_eq!(r["diagnostics"], 0);
    assert_eq!(r["counts"]["IfcDoor"], 2);
    let (names, warnings) = glb(&file, &dir.join("door.glb"));
    assert_eq!(names, set(&ALL));
    assert_eq!(
        warnings,
        ["warning: #600: IfcDoor 'Door 2' has no Representation: not in the export"]
    );
    assert_eq!(plan(&file, &dir.join("door.svg")), (5, 1, 0));
}

#[test]
fn every_truncation_is_an_exact_error_or_a_readable_model() {
    let (_tmp, dir) = corpus();
    for (name, expect) in TRUNCATED {
        let file = dir.join(name);
        let (t_glb, t_svg) = (dir.join("t.glb"), dir.join("t.svg"));
        match expect {
            Some(msg) => {
                let head = format!("error: {}{msg}", file.display());
                for args in [
                    vec![OsStr::new("inspect"), file.as_os_str(), "--json".as_ref()],
                    vec![
                        OsStr::new("export"),
                        "glb".as_ref(),
                        file.as_os_str(),
                        "-o".as_ref(),
                        t_glb.as_os_str(),
                    ],
                    vec![
                        OsStr::new("plan"),
                        file.as_os_str(),
                        "-o".as_ref(),
                        t_svg.as_os_str(),
                    ],
                ] {
                    let (code, stdout, stderr) = run(&args);
                    assert_eq!(code, 2, "{args:?}: {stdout}");
                    assert_eq!(stderr.trim_end(), head, "{args:?}");
                    assert!(!dir.join("t.glb").exists() && !dir.join("t.svg").exists());
                }
            }
            None => {
                // Only `END-ISO-10303-21;` is missing: read, with one truncation diagnostic.
                assert_eq!(inspect_ok(&file), 1, "{name}");
                let (names, warnings) = glb(&file, &dir.join("t.glb"));
                assert_eq!(names, set(&ALL), "{name}");
                assert!(warnings.is_empty());
                assert_eq!(plan(&file, &dir.join("t.svg")), (5, 1, 0), "{name}");
                std::fs::remove_file(dir.join("t.glb")).unwrap();
                std::fs::remove_file(dir.join("t.svg")).unwrap();
            }
        }
    }
}
