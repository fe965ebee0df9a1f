//! What the CLI prints on standard error besides its output: warnings summarised per class and
//! reason (the full list with `--verbose` and in `--json`), nothing with `--quiet`, each
//! stage's wall time with `--timings`, and a refusal (exit 2) of a model that gave no geometry
//! unless `--allow-empty`.

mod common;

use std::ffi::OsStr;
use std::path::PathBuf;

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

fn out(dir: &tempfile::TempDir, name: &str) -> String {
    let p: PathBuf = dir.path().join(name);
    p.to_string_lossy().into_owned()
}

/// A model of 1,234 elements none of which can be meshed (extrusions of depth 0) in three
/// classes, with no storey and no building.
fn no_geometry(dir: &tempfile::TempDir) -> String {
    let mut data = String::from(
        "#1=IFCPROJECT('2owbYvk3v1EgNud5LiRBMN',$,'Default Project',$,$,$,$,$,#2);\n\
         #2=IFCUNITASSIGNMENT((#3));#3=IFCSIUNIT(*,.LENGTHUNIT.,$,.METRE.);\n\
         #4=IFCCARTESIANPOINT((0.,0.,0.));#5=IFCAXIS2PLACEMENT3D(#4,$,$);\n\
         #6=IFCLOCALPLACEMENT($,#5);#7=IFCRECTANGLEPROFILEDEF(.AREA.,$,$,1.,1.);\n\
         #8=IFCDIRECTION((0.,0.,1.));#9=IFCEXTRUDEDAREASOLID(#7,#5,#8,0.);\n\
         #10=IFCSHAPEREPRESENTATION($,'Body','SweptSolid',(#9));\n\
         #11=IFCPRODUCTDEFINITIONSHAPE($,$,(#10));\n",
    );
    for i in 0..1234 {
        let class = match i {
            0..1000 => "IFCBUILDINGELEMENTPROXY",
            1000..1200 => "IFCCOLUMN",
            _ => "IFCBEAM",
        };
        data.push_str(&format!(
            "#{}={class}('{}',$,$,$,$,#6,#11,$,$);\n",
            100 + i,
            poinav_ifc::GlobalId(0x5eed_0000 + i as u128)
        ));
    }
    let text = format!(
        "ISO-10303-21;HEADER;FILE_DESCRIPTION((''),'2;1');FILE_NAME('','',(''),(''),'','','');\n\
         FILE_SCHEMA(('IFC4'));ENDSEC;DATA;\n{data}ENDSEC;END-ISO-10303-21;\n"
    );
    let path = out(dir, "no-geometry.ifc");
    std::fs::write(&path, text).unwrap();
    path
}

#[test]
fn plan_summarises_thousands_of_warnings_and_refuses_a_model_without_geometry() {
    let dir = tempfile::tempdir().unwrap();
    let file = no_geometry(&dir);
    let svg = out(&dir, "rail.svg");
    let (code, stdout, err) = run(&["plan", &file, "-o", &svg]);
    let lines: Vec<&str> = err.lines().collect();
    assert!(lines.len() <= 30, "{} lines:\n{err}", lines.len());
    assert!(
        lines.contains(&"note: 1,234 warnings summarised in 3 lines; --verbose lists each one"),
        "{err}"
    );
    assert_eq!(
        lines.last().copied(),
        Some(
            format!(
                "error: no geometry in {file}: none of its elements could be meshed (1,234 failed); nothing to draw or navigate (--allow-empty writes the outputs anyway)"
            )
            .as_str()
        ),
        "{err}"
    );
    assert_eq!(code, 2);
    assert_eq!(stdout, "");
    assert!(!std::path::Path::new(&svg).exists());

    // --allow-empty: the (empty) plan is written, exit 0; --quiet: not a line on stderr.
    let (code, stdout, err) = run(&["plan", &file, "-o", &svg, "--allow-empty", "--quiet"]);
    assert_eq!((code, err.as_str()), (0, ""));
    assert!(
        stdout.starts_with(&format!("wrote {svg}: storey")),
        "{stdout}"
    );
    assert!(std::path::Path::new(&svg).exists());

    // --verbose: every warning on its own line.
    let (code, _, err) = run(&["plan", &file, "-o", &svg, "--allow-empty", "--verbose"]);
    assert_eq!(code, 0);
    assert_eq!(
        err.lines().filter(|l| l.starts_with("warning: #")).count(),
        1234
    );
}

#[test]
fn quiet_prints_nothing_on_stderr_and_json_carries_every_warning() {
    let dir = tempfile::tempdir().unwrap();
    let file = no_geometry(&dir);
    let nav2 = out(&dir, "nav2");
    let (code, stdout, err) = run(&[
        "-q",
        "export",
        "nav2",
        &file,
        "-o",
        &nav2,
        "--json",
        "--allow-empty",
    ]);
    assert_eq!((code, err.as_str()), (0, ""), "{stdout}");
    let json: serde_json::Value = serde_json::from_str(&stdout).unwrap();
    let warnings = json["warnings"].as_array().unwrap();
    assert_eq!(warnings.len(), 1, "{warnings:?}");
    assert_eq!(
        warnings[0]["message"],
        "nothing to navigate: its one storey `Default Project` has no spaces, doors, walls or other obstacles (a model without a building, such as infrastructure, or without geometry); the maps are empty"
    );
    assert_eq!(json["storeys"].as_array().unwrap().len(), 0);
    assert_eq!(json["skipped"][0]["reason"], "nothing on it");
}

#[test]
fn timings_list_every_stage() {
    let dir = tempfile::tempdir().unwrap();
    let file = corpus("office-a.ifc");
    let svg = out(&dir, "level-1.svg");
    let (code, _, err) = run(&[
        "--timings",
        "plan",
        &file,
        "--storey",
        "Level 1",
        "-o",
        &svg,
    ]);
    assert_eq!(code, 0, "{err}");
    let stages: Vec<&str> = err
        .lines()
        .skip_while(|l| *l != "timings (wall clock):")
        .skip(1)
        .map(|l| l.split_whitespace().next().unwrap())
        .collect();
    assert_eq!(
        stages,
        [
            "reading",
            "meshing",
            "sectioning",
            "classifying",
            "writing",
            "total"
        ],
        "{err}"
    );
    for line in err.lines().skip(1) {
        assert!(line.ends_with(" s"), "{line}");
    }

    let nav2 = out(&dir, "nav2");
    let (code, _, err) = run(&["--timings", "-q", "export", "nav2", &file, "-o", &nav2]);
    assert_eq!(code, 0, "{err}");
    let stages: Vec<&str> = err
        .lines()
        .skip(1)
        .map(|l| l.split_whitespace().next().unwrap())
        .collect();
    assert_eq!(
        stages,
        [
            "reading",
            "classifying",
            "meshing",
            "sectioning",
            "graph",
            "rasterising",
            "writing",
            "total"
        ],
        "{err}"
    );
}

#[test]
fn office_a_nav2_maps_cover_each_storey_and_skip_the_roof() {
    let dir = tempfile::tempdir().unwrap();
    let file = corpus("office-a.ifc");
    let nav2 = out(&dir, "nav2");
    let (code, stdout, err) = run(&["-q", "export", "nav2", &file, "-o", &nav2]);
    assert_eq!((code, err.as_str()), (0, ""), "{stdout}");
    // The roof storey holds only its parapet walls: no folder, one line saying why.
    assert!(
        stdout.ends_with("  skipped storey Roof: no spaces or doors (10 walls)\n"),
        "{stdout}"
    );
    assert!(!dir.path().join("nav2/02-roof").exists());
    assert!(stdout.contains(": 2 storeys,"), "{stdout}");
    // Each map is its storey's own extent (walls, spaces, doors) plus the 1 m entrance aprons
    // and the 0.5 m border, at 0.05 m.
    assert!(
        stdout.contains("  00-level-1/ (Level 1): map 1071 x 777 cells, origin (-2.00, -37.85)"),
        "{stdout}"
    );
    assert!(
        stdout.contains("  01-level-2/ (Level 2): map 1031 x 757 cells, origin (-1.00, -36.85)"),
        "{stdout}"
    );
}
