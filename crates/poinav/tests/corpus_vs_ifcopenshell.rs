//! `poinav inspect` on every corpus file agrees with IfcOpenShell, run live: schema, length
//! unit, class counts (subtypes included), door widths, heights and storeys, storeys, spaces.

mod common;

use std::ffi::OsStr;

use serde_json::Value;

fn close(a: &Value, b: &Value) -> bool {
    match (a.as_f64(), b.as_f64()) {
        (Some(x), Some(y)) => (x - y).abs() <= 1e-9 * x.abs().max(1.0),
        _ => a.is_null() && b.is_null(),
    }
}

#[test]
fn inspect_matches_ifcopenshell_on_every_corpus_file() {
    let files = common::corpus();
    let args: Vec<&OsStr> = files.iter().map(|f| f.as_os_str()).collect();
    let reference = common::ifcos("reference.py", &args);
    let mut problems = Vec::new();
    let mut doors_checked = 0;
    for file in &files {
        let name = file.file_name().unwrap().to_string_lossy().into_owned();
        let r = &reference[file.to_str().unwrap()];
        let (code, out, err) = common::poinav(&[
            OsStr::new("inspect"),
            file.as_os_str(),
            OsStr::new("--json"),
        ]);
        assert_eq!(code, 0, "{name}: {err}");
        let ours: Value = serde_json::from_str(&out).unwrap();
        if r["schema_identifier"] != ours["schema_identifier"] {
            problems.push(format!(
                "{name}: schema {} vs {}",
                r["schema_identifier"], ours["schema_identifier"]
            ));
        }
        if !close(&r["length_unit_m"], &ours["length_unit_m"]) {
            problems.push(format!(
                "{name}: unit {} vs {}",
                r["length_unit_m"], ours["length_unit_m"]
            ));
        }
        for (class, n) in r["counts"].as_object().unwrap() {
            let mine = ours["counts"]
                .get(class)
                .and_then(Value::as_u64)
                .unwrap_or(0);
            if Some(mine) != n.as_u64() {
                problems.push(format!("{name}: {class} IfcOpenShell {n}, poinav {mine}"));
            }
        }
        let our_doors: std::collections::HashMap<&str, &Value> = ours["doors"]
            .as_array()
            .unwrap()
            .iter()
            .map(|d| (d["guid"].as_str().unwrap(), d))
            .collect();
        assert_eq!(
            our_doors.len(),
            r["doors"].as_object().unwrap().len(),
            "{name}: door count"
        );
        for (guid, d) in r["doors"].as_object().unwrap() {
            let Some(o) = our_doors.get(guid.as_str()) else {
                problems.push(format!("{name}: door {guid} missing"));
                continue;
            };
            doors_checked += 1;
            for key in ["overall_width_m", "overall_height_m"] {
                if !close(&d[key], &o[key]) {
                    problems.push(format!(
                        "{name}: door {guid} {key} {} vs {}",
                        d[key], o[key]
                    ));
                }
            }
            for key in ["name", "storey"] {
                if d[key] != o[key] {
                    problems.push(format!(
                        "{name}: door {guid} {key} {} vs {}",
                        d[key], o[key]
                    ));
                }
            }
        }
        let key = |s: &Value| {
            format!(
                "{}|{}|{:.9}",
                s["guid"],
                s["name"],
                s["elevation_m"].as_f64().unwrap_or(f64::NAN)
            )
        };
        let mut a: Vec<String> = r["storeys"].as_array().unwrap().iter().map(key).collect();
        let mut b: Vec<String> = ours["storeys"]
            .as_array()
            .unwrap()
            .iter()
            .map(key)
            .collect();
        a.sort();
        b.sort();
        if a != b {
            problems.push(format!("{name}: storeys {a:?} vs {b:?}"));
        }
        let spaces: std::collections::HashMap<&str, &Value> = ours["spaces"]
            .as_array()
            .unwrap()
            .iter()
            .map(|s| (s["guid"].as_str().unwrap(), s))
            .collect();
        for (guid, s) in r["spaces"].as_object().unwrap() {
            match spaces.get(guid.as_str()) {
                Some(o)
                    if o["name"] == s["name"]
                        && o["long_name"] == s["long_name"]
                        && o["storey"] == s["storey"] => {}
                other => problems.push(format!("{name}: space {guid} {s} vs {other:?}")),
            }
        }
        assert_eq!(
            ours["diagnostics"], 0,
            "{name}: the public corpus has no structural damage: {}",
            ours["diagnostic_list"]
        );
    }
    assert!(
        problems.is_empty(),
        "{} differences:\n{}",
        problems.len(),
        problems.join("\n")
    );
    // 14 + 102 + 77 + 5 + 5 + 2 + 1 + 1 + 30 + 7 + 1 + 334 = 579 doors in the corpus (SOURCES.md).
    assert_eq!(doors_checked, 579, "every corpus door compared");
}
