//! `poinav enrich` on every corpus file, checked with IfcOpenShell: the property sets it reads
//! equal our CSV, validation finds no new error, every original line is kept byte for byte,
//! re-enriching is byte-identical, the input is untouched, and lengths are in the file's unit.

mod common;

use std::collections::HashMap;
use std::ffi::OsStr;
use std::path::Path;

use serde_json::Value;

const EPOCH: &str = "1795314600";
const STAMP: &str = "2026-11-22T02:30:00";

fn enrich(input: &Path, output: &Path, extra: &[&OsStr]) -> Value {
    let mut args: Vec<&OsStr> = vec![
        OsStr::new("enrich"),
        input.as_os_str(),
        OsStr::new("-o"),
        output.as_os_str(),
        OsStr::new("--json"),
    ];
    args.extend_from_slice(extra);
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_poinav"))
        .args(&args)
        .env("SOURCE_DATE_EPOCH", EPOCH)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}: {}",
        input.display(),
        String::from_utf8_lossy(&out.stderr)
    );
    serde_json::from_slice(&out.stdout).unwrap()
}

fn number(s: &str) -> Value {
    Value::from(s.parse::<f64>().unwrap())
}

/// What IfcOpenShell must read for one CSV row.
fn expected_sets(row: &HashMap<String, String>, prefix: &str, ifc2x3: bool) -> Value {
    let list = |s: &str| Value::from(s.split(';').filter(|x| !x.is_empty()).collect::<Vec<_>>());
    let mut class = serde_json::json!({
        "POI_Category": [row["POI_Category"]],
        "POI_Type": [row["POI_Type"]],
        "POI_PrimaryRoles": list(&row["POI_PrimaryRoles"]),
    });
    if !row["POI_ConditionalRoles"].is_empty() {
        class["POI_ConditionalRoles"] = list(&row["POI_ConditionalRoles"]);
    } else if !ifc2x3 {
        class["POI_ConditionalRoles"] = Value::Null;
    }
    let mut sets = serde_json::Map::new();
    sets.insert(format!("{prefix}POI_Classification"), class);
    if !row["AccessibilityStatus"].is_empty() {
        sets.insert(
            format!("{prefix}RobotAccessibility"),
            serde_json::json!({
                "MinClearanceWidth": number(&row["MinClearanceWidth"]),
                "MinClearanceHeight": number(&row["MinClearanceHeight"]),
                "AccessibilityStatus": [row["AccessibilityStatus"]],
                "ValidationMethod": [row["ValidationMethod"]],
                "LastValidated": row["LastValidated"],
            }),
        );
    }
    if !row["MaxSimultaneousRobots"].is_empty() {
        sets.insert(
            format!("{prefix}RobotCoordination"),
            serde_json::json!({
                "MaxSimultaneousRobots": row["MaxSimultaneousRobots"].parse::<i64>().unwrap(),
                "MinInterRobotSeparation": number(&row["MinInterRobotSeparation"]),
                "CoordinationProtocol": [row["CoordinationProtocol"]],
                "AppliesTo": [row["AppliesTo"]],
            }),
        );
    }
    Value::Object(sets)
}

fn read_csv(path: &Path) -> Vec<HashMap<String, String>> {
    let mut r = csv::Reader::from_path(path).unwrap();
    let headers = r.headers().unwrap().clone();
    r.records()
        .map(|rec| {
            headers
                .iter()
                .zip(rec.unwrap().iter())
                .map(|(h, v)| (h.to_string(), v.to_string()))
                .collect()
        })
        .collect()
}

fn check_file(file: &Path, dir: &Path, prefix: &str) -> Vec<String> {
    let mut problems = Vec::new();
    let name = file.file_stem().unwrap().to_string_lossy().into_owned();
    let before = std::fs::read(file).unwrap();
    let out = dir.join(format!("{name}.{prefix}ifc"));
    let csv_path = dir.join(format!("{name}.{prefix}csv"));
    let summary = enrich(
        file,
        &out,
        &[
            OsStr::new("--csv"),
            csv_path.as_os_str(),
            OsStr::new("--pset-prefix"),
            OsStr::new(prefix),
        ],
    );
    assert_eq!(
        std::fs::read(file).unwrap(),
        before,
        "{name}: input modified"
    );

    // Every original instance is byte-identical in the output.
    let original = poinav_ifc::Model::open(file).unwrap();
    let written = poinav_ifc::Model::open(&out).unwrap();
    assert!(
        written.diagnostics().is_empty(),
        "{name}: enriched file has diagnostics: {:?}",
        written.diagnostics().first()
    );
    for e in original.entities() {
        match written.entity(e.id()) {
            Some(w) if w.raw() == e.raw() => {}
            _ => problems.push(format!("{name}: {} not kept byte for byte", e.id())),
        }
    }

    // Enriching the output again gives the same bytes.
    let again = dir.join(format!("{name}.{prefix}again.ifc"));
    enrich(
        &out,
        &again,
        &[OsStr::new("--pset-prefix"), OsStr::new(prefix)],
    );
    if std::fs::read(&again).unwrap() != std::fs::read(&out).unwrap() {
        problems.push(format!("{name}: re-enrichment is not byte-identical"));
    }

    // IfcOpenShell reads exactly the CSV's values, and validation finds nothing new.
    let rows = read_csv(&csv_path);
    assert_eq!(
        rows.len() as u64,
        summary["elements"].as_u64().unwrap(),
        "{name}: CSV rows"
    );
    // Nothing added (a model without elements to classify, the railway): the data section is
    // the original's byte for byte, so IfcOpenShell's validation (the slowest part of this test,
    // 90 s on the 19 MB railway) could only repeat the original's findings.
    let mut args = vec![file.as_os_str(), out.as_os_str(), OsStr::new(prefix)];
    if summary["instances_added"].as_u64() == Some(0) {
        let data = |b: &[u8]| {
            let at = b.windows(5).position(|w| w == b"DATA;").unwrap();
            b[at..].to_vec()
        };
        assert!(
            data(&before) == data(&std::fs::read(&out).unwrap()),
            "{name}: nothing added, yet the data section changed"
        );
        args.push(OsStr::new("--no-validate"));
    }
    let check = common::ifcos("enrich_check.py", &args);
    let ifc2x3 = original.schema() == poinav_ifc::Schema::Ifc2x3;
    let psets = check["psets"].as_object().unwrap();
    if psets.len() != rows.len() {
        problems.push(format!(
            "{name}: IfcOpenShell sees {} enriched elements, CSV has {}",
            psets.len(),
            rows.len()
        ));
    }
    for row in &rows {
        let want = expected_sets(row, prefix, ifc2x3);
        let got = &psets.get(&row["GlobalId"]).cloned().unwrap_or(Value::Null);
        if *got != want {
            problems.push(format!(
                "{name}: {} {}: IfcOpenShell {got} vs CSV {want}",
                row["GlobalId"], row["IfcClass"]
            ));
        }
        // Where IfcOpenShell places the element in a storey, the CSV names that storey.
        if let Some(storey) = check["storeys"][&row["GlobalId"]].as_str() {
            if row["Storey"] != storey {
                problems.push(format!(
                    "{name}: {} {}: storey `{}` vs IfcOpenShell's `{storey}`",
                    row["GlobalId"], row["IfcClass"], row["Storey"]
                ));
            }
        }
        // Clear widths carry no float noise from unit conversion: at most 6 decimals (1 µm).
        let width = &row["ClearWidth_m"];
        if width.split_once('.').is_some_and(|(_, d)| d.len() > 6) {
            problems.push(format!(
                "{name}: {} ClearWidth_m {width} has float noise",
                row["GlobalId"]
            ));
        }
        if !row["LastValidated"].is_empty() && row["LastValidated"] != STAMP {
            problems.push(format!(
                "{name}: LastValidated {} is not SOURCE_DATE_EPOCH",
                row["LastValidated"]
            ));
        }
    }
    for e in check["new_errors"].as_array().unwrap() {
        problems.push(format!("{name}: new validation error: {e}"));
    }
    problems
}

#[test]
fn enrichment_round_trips_through_ifcopenshell_on_every_corpus_file() {
    let dir = tempfile::tempdir().unwrap();
    // Two workers take the largest file left first (the IfcOpenShell checks of the two
    // biggest files take most of the time; halves in file order left one worker with both).
    let mut files = common::corpus();
    files.sort_by_key(|f| std::fs::metadata(f).map(|m| m.len()).unwrap_or(0));
    let queue = std::sync::Mutex::new(files);
    let problems: Vec<String> = std::thread::scope(|s| {
        let handles: Vec<_> = (0..2)
            .map(|_| {
                s.spawn(|| {
                    let mut found = Vec::new();
                    while let Some(f) = {
                        let next = queue.lock().unwrap().pop();
                        next
                    } {
                        found.extend(check_file(&f, dir.path(), "Pset_"));
                    }
                    found
                })
            })
            .collect();
        handles
            .into_iter()
            .flat_map(|h| h.join().unwrap())
            .collect()
    });
    assert!(
        problems.is_empty(),
        "{} problems:\n{}",
        problems.len(),
        problems.join("\n")
    );
}

#[test]
fn non_reserved_prefix_writes_the_same_sets_under_another_name() {
    let dir = tempfile::tempdir().unwrap();
    let file = common::shared().join("ifc/fzk-haus-ifc4.ifc");
    let problems = check_file(&file, dir.path(), "POINAV_");
    assert!(problems.is_empty(), "{}", problems.join("\n"));
    let text = std::fs::read_to_string(dir.path().join("fzk-haus-ifc4.POINAV_ifc")).unwrap();
    assert!(
        text.contains("'POINAV_POI_Classification'") && !text.contains("'Pset_POI_Classification'")
    );
}

#[test]
fn lengths_are_stored_in_the_files_unit() {
    let dir = tempfile::tempdir().unwrap();
    for (file, width, height) in [
        (
            "ifc4-test-model.ifc",
            "IFCPOSITIVELENGTHMEASURE(900.0)",
            "IFCPOSITIVELENGTHMEASURE(700.0)",
        ),
        (
            "ifcopenhouse-ifc4.ifc",
            "IFCPOSITIVELENGTHMEASURE(900.0)",
            "IFCPOSITIVELENGTHMEASURE(700.0)",
        ),
        (
            "wall-door-column-ifc4x3.ifc",
            "IFCPOSITIVELENGTHMEASURE(2.952755906)",
            "IFCPOSITIVELENGTHMEASURE(2.296587927)",
        ),
        (
            "office-a.ifc",
            "IFCPOSITIVELENGTHMEASURE(0.9)",
            "IFCPOSITIVELENGTHMEASURE(0.7)",
        ),
    ] {
        let out = dir.path().join(file);
        enrich(&common::shared().join("ifc").join(file), &out, &[]);
        let text = std::fs::read_to_string(&out).unwrap();
        let line = text
            .lines()
            .find(|l| l.contains("'MinClearanceWidth'"))
            .unwrap_or_else(|| panic!("{file}: no MinClearanceWidth"));
        assert!(line.contains(width), "{file}: {line}");
        let line = text
            .lines()
            .find(|l| l.contains("'MinClearanceHeight'"))
            .unwrap();
        assert!(line.contains(height), "{file}: {line}");
    }
}

/// Guards the IfcOpenShell check itself, which validates only the instances enrichment can
/// have changed: an added property set without its (IFC2X3-required) owner history and an
/// added relation reusing a wall's GlobalId must both be reported as new errors.
#[test]
fn the_ifcopenshell_check_reports_errors_in_added_instances() {
    let dir = tempfile::tempdir().unwrap();
    let file = common::shared().join("ifc/revit-japanese-x2.ifc");
    let out = dir.path().join("enriched.ifc");
    enrich(&file, &out, &[]);
    let mut text = std::fs::read_to_string(&out).unwrap();
    // The last property set (an added one) loses its owner history.
    let pset = text.rfind("IFCPROPERTYSET('").unwrap();
    let owner = pset + text[pset..].find(",#").unwrap() + 1;
    let owner_end = owner + text[owner..].find(',').unwrap();
    text.replace_range(owner..owner_end, "$");
    // The last relation (an added one) takes the first wall's GlobalId.
    let wall = text.find("IFCWALLSTANDARDCASE('").unwrap() + "IFCWALLSTANDARDCASE('".len();
    let wall_guid = text[wall..wall + 22].to_owned();
    let rel =
        text.rfind("IFCRELDEFINESBYPROPERTIES('").unwrap() + "IFCRELDEFINESBYPROPERTIES('".len();
    text.replace_range(rel..rel + 22, &wall_guid);
    let broken = text;
    let bad = dir.path().join("broken.ifc");
    std::fs::write(&bad, broken).unwrap();
    let check = common::ifcos(
        "enrich_check.py",
        &[file.as_os_str(), bad.as_os_str(), OsStr::new("Pset_")],
    );
    let errors: Vec<&str> = check["new_errors"]
        .as_array()
        .unwrap()
        .iter()
        .map(|e| e.as_str().unwrap())
        .collect();
    assert!(
        errors
            .iter()
            .any(|e| e.contains("IfcPropertySet.OwnerHistory: Attribute not optional")),
        "{errors:?}"
    );
    assert!(
        errors
            .iter()
            .any(|e| e.starts_with(&format!("GlobalId {wall_guid} of #"))
                && e.ends_with("is not unique")),
        "{errors:?}"
    );
}
