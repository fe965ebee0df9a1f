//! Hostile-input tests for `poinav inspect`: broken, damaged and extreme IFC files run through the real binary.

use std::path::{Path, PathBuf};
use std::process::Command;

use serde_json::Value;

/// A small valid IFC4 model: project with a millimetre unit, one storey, a wall, a door
/// (900 x 2100 mm) and a chain of local placements. Line numbers matter to the tests:
/// the DATA section is lines 8-20, #5 (the wall) is line 12, #6 (the door) line 13.
const TEMPLATE: [&str; 22] = [
    "ISO-10303-21;",
    "HEADER;",
    "FILE_DESCRIPTION(('ViewDefinition [DesignTransferView]'),'2;1');",
    "FILE_NAME('template.ifc','2024-01-01T00:00:00',('poinav'),('poinav'),'poinav tests','poinav tests','');",
    "FILE_SCHEMA(('IFC4'));",
    "ENDSEC;",
    "DATA;",
    "#1=IFCPROJECT('0YvctVUKr0kugbFTf53O9L',$,'Project',$,$,$,$,$,#2);",
    "#2=IFCUNITASSIGNMENT((#3));",
    "#3=IFCSIUNIT(*,.LENGTHUNIT.,.MILLI.,.METRE.);",
    "#4=IFCBUILDINGSTOREY('1YvctVUKr0kugbFTf53O9L',$,'Ground Floor',$,$,#12,$,$,.ELEMENT.,0.);",
    "#5=IFCWALL('2YvctVUKr0kugbFTf53O9L',$,'Wall',$,$,#13,$,$,.STANDARD.);",
    "#6=IFCDOOR('3YvctVUKr0kugbFTf53O9L',$,'Door',$,$,#14,$,$,2100.,900.,.DOOR.,.SINGLE_SWING_LEFT.,$);",
    "#7=IFCRELAGGREGATES('4YvctVUKr0kugbFTf53O9L',$,$,$,#1,(#4));",
    "#8=IFCRELCONTAINEDINSPATIALSTRUCTURE('5YvctVUKr0kugbFTf53O9L',$,$,$,(#5,#6),#4);",
    "#10=IFCCARTESIANPOINT((0.,0.,0.));",
    "#11=IFCAXIS2PLACEMENT3D(#10,$,$);",
    "#12=IFCLOCALPLACEMENT($,#11);",
    "#13=IFCLOCALPLACEMENT(#12,#11);",
    "#14=IFCLOCALPLACEMENT(#13,#11);",
    "ENDSEC;",
    "END-ISO-10303-21;",
];

/// The template with `eol` after every line.
fn template_with(eol: &str) -> String {
    TEMPLATE.iter().map(|l| format!("{l}{eol}")).collect()
}

/// The template with LF line ends.
fn template() -> String {
    template_with("\n")
}

/// The first `n` template lines (LF ends, the last one included).
fn first_lines(n: usize) -> String {
    TEMPLATE[..n].iter().map(|l| format!("{l}\n")).collect()
}

/// Replaces the one occurrence of `from` in `text` (fails the test if there is not exactly one).
fn replace_once(text: &[u8], from: &str, to: &[u8]) -> Vec<u8> {
    let from = from.as_bytes();
    let hits: Vec<usize> = (0..=text.len().saturating_sub(from.len()))
        .filter(|&i| text[i..].starts_with(from))
        .collect();
    assert_eq!(
        hits.len(),
        1,
        "test bug: `{}` must occur once",
        String::from_utf8_lossy(from)
    );
    let at = hits[0];
    [&text[..at], to, &text[at + from.len()..]].concat()
}

// One damage each; they compose (see `all_damage_kinds_at_once_are_each_reported_once`).

/// `#8` (the containment) refers to `#99`, which does not exist.
fn dangling(text: &[u8]) -> Vec<u8> {
    replace_once(text, "(#5,#6),#4);", b"(#5,#6,#99),#4);")
}

/// A second `#5` is inserted just before `#10`.
fn duplicate(text: &[u8]) -> Vec<u8> {
    replace_once(
        text,
        "#10=IFCCARTESIANPOINT",
        b"#5=IFCWALL('6YvctVUKr0kugbFTf53O9L',$,'Second wall',$,$,$,$,$,$);\n#10=IFCCARTESIANPOINT",
    )
}

/// The storey placement `#12` is made relative to `#14`: #12 -> #14 -> #13 -> #12.
fn cyclic_placement(text: &[u8]) -> Vec<u8> {
    replace_once(
        text,
        "#12=IFCLOCALPLACEMENT($,#11);",
        b"#12=IFCLOCALPLACEMENT(#14,#11);",
    )
}

/// `#9` makes the storey the whole of the project, which already aggregates the storey.
fn cyclic_aggregation(text: &[u8]) -> Vec<u8> {
    replace_once(
        text,
        "#10=IFCCARTESIANPOINT",
        b"#9=IFCRELAGGREGATES('7YvctVUKr0kugbFTf53O9L',$,$,$,#4,(#1));\n#10=IFCCARTESIANPOINT",
    )
}

/// The door loses its last attribute (12 instead of IFC4's 13).
fn wrong_count(text: &[u8]) -> Vec<u8> {
    replace_once(text, ".SINGLE_SWING_LEFT.,$);", b".SINGLE_SWING_LEFT.);")
}

/// The door's name is `Tür` in ISO 8859-1 (the byte 0xFC), not UTF-8.
fn non_utf8(text: &[u8]) -> Vec<u8> {
    replace_once(text, "'Door'", b"'T\xFCr'")
}

/// What one run of the binary gave.
struct Run {
    code: Option<i32>,
    stdout: String,
    stderr: String,
}

fn inspect(path: &Path, extra: &[&str]) -> Run {
    let out = Command::new(env!("CARGO_BIN_EXE_poinav"))
        .arg("inspect")
        .arg(path)
        .args(extra)
        .output()
        .expect("run poinav");
    Run {
        code: out.status.code(),
        stdout: String::from_utf8_lossy(&out.stdout).into_owned(),
        stderr: String::from_utf8_lossy(&out.stderr).into_owned(),
    }
}

fn write(dir: &tempfile::TempDir, name: &str, bytes: impl AsRef<[u8]>) -> PathBuf {
    let path = dir.path().join(name);
    std::fs::write(&path, bytes).expect("write test file");
    path
}

/// Runs `inspect --json` on `bytes`; must exit 0 and print JSON.
fn report(bytes: impl AsRef<[u8]>) -> Value {
    let dir = tempfile::tempdir().unwrap();
    let path = write(&dir, "model.ifc", bytes);
    let run = inspect(&path, &["--json"]);
    assert_eq!(run.code, Some(0), "stderr: {}", run.stderr);
    assert!(!run.stderr.contains("panicked"), "{}", run.stderr);
    serde_json::from_str(&run.stdout).expect("stdout is JSON")
}

/// Writes `bytes`, runs `inspect --json`; must exit exactly 2 with a clean error naming the
/// file, the line and the instance (`expect` is what follows `error: PATH`, e.g. `:12: #5: `).
fn fatal(name: &str, bytes: impl AsRef<[u8]>, expect: &str) -> String {
    let dir = tempfile::tempdir().unwrap();
    let path = write(&dir, name, bytes);
    let run = inspect(&path, &["--json"]);
    assert_fatal(&run, &path, expect)
}

fn assert_fatal(run: &Run, path: &Path, expect: &str) -> String {
    assert_eq!(
        run.code,
        Some(2),
        "stdout: {}\nstderr: {}",
        run.stdout,
        run.stderr
    );
    assert!(!run.stderr.contains("panicked"), "{}", run.stderr);
    let head = format!("error: {}{expect}", path.display());
    assert!(
        run.stderr.starts_with(&head),
        "stderr should start with {head:?}: {}",
        run.stderr
    );
    assert!(
        run.stdout.trim().is_empty() || serde_json::from_str::<Value>(&run.stdout).is_err(),
        "a fatal error must not print a JSON report: {}",
        run.stdout
    );
    run.stderr.clone()
}

/// `(kind, id, line)` of every diagnostic in a JSON report, checked against its count.
fn diagnostics(r: &Value) -> Vec<(String, Option<u64>, Option<u64>)> {
    let list = r["diagnostic_list"].as_array().expect("diagnostic_list");
    assert_eq!(r["diagnostics"].as_u64(), Some(list.len() as u64));
    list.iter()
        .map(|d| {
            (
                d["kind"].as_str().expect("kind").to_string(),
                d["id"].as_u64(),
                d["line"].as_u64(),
            )
        })
        .collect()
}

fn diag(kind: &str, id: u64, line: u64) -> (String, Option<u64>, Option<u64>) {
    (kind.to_string(), Some(id), Some(line))
}

/// The door `#6` is reported with its storey and its size converted from millimetres.
fn assert_door(r: &Value, name: &str) {
    let doors = r["doors"].as_array().expect("doors");
    assert_eq!(doors.len(), 1, "{doors:?}");
    let d = &doors[0];
    assert_eq!(d["id"], 6);
    assert_eq!(d["guid"], "3YvctVUKr0kugbFTf53O9L");
    assert_eq!(d["name"], name);
    assert_eq!(d["storey"], "Ground Floor");
    assert_eq!(d["storey_id"], 4);
    assert_eq!(d["overall_width_m"].as_f64(), Some(0.9));
    assert_eq!(d["overall_height_m"].as_f64(), Some(2.1));
}

/// The rest of the template model: unit, one storey at 0 m.
fn assert_rest_of_model(r: &Value) {
    assert_eq!(r["schema"], "IFC4");
    assert_eq!(r["length_unit"], "MILLI METRE");
    assert_eq!(r["length_unit_m"].as_f64(), Some(0.001));
    let storeys = r["storeys"].as_array().expect("storeys");
    assert_eq!(storeys.len(), 1);
    assert_eq!(storeys[0]["id"], 4);
    assert_eq!(storeys[0]["name"], "Ground Floor");
    assert_eq!(storeys[0]["elevation_m"].as_f64(), Some(0.0));
}

/// A damaged file: exit 0 with exactly `expected` diagnostics, and exit 2 under `--strict`.
fn damaged(bytes: &[u8], expected: &[(String, Option<u64>, Option<u64>)]) -> Value {
    let dir = tempfile::tempdir().unwrap();
    let path = write(&dir, "damaged.ifc", bytes);
    let run = inspect(&path, &["--json"]);
    assert_eq!(run.code, Some(0), "stderr: {}", run.stderr);
    let r: Value = serde_json::from_str(&run.stdout).expect("stdout is JSON");
    assert_eq!(diagnostics(&r), expected);
    let strict = inspect(&path, &["--json", "--strict"]);
    assert_eq!(strict.code, Some(2), "stderr: {}", strict.stderr);
    assert!(!strict.stderr.contains("panicked"), "{}", strict.stderr);
    assert!(
        strict.stderr.contains(&format!(
            "{} diagnostics in {} (--strict)",
            expected.len(),
            path.display()
        )),
        "{}",
        strict.stderr
    );
    r
}

#[test]
fn clean_template_has_no_diagnostics() {
    let r = report(template());
    assert_eq!(diagnostics(&r), []);
    assert_eq!(r["instances"], 13);
    assert_eq!(r["counts"]["IfcWall"], 1);
    assert_eq!(r["counts"]["IfcLocalPlacement"], 3);
    assert_door(&r, "Door");
    assert_rest_of_model(&r);
}

// a. Fatal: exit code 2, an error naming file, line and instance, no report.

#[test]
fn empty_file_is_fatal() {
    fatal("empty.ifc", b"", ":1: file is empty");
}

#[test]
fn whitespace_only_file_is_fatal_as_empty() {
    fatal("blank.ifc", b" \n\t\r\n  \r ", ":1: file is empty");
}

#[test]
fn binary_garbage_is_fatal_not_step() {
    let garbage: Vec<u8> = (0..=255u8).cycle().take(256 * 64).collect();
    fatal(
        "garbage.ifc",
        garbage,
        ":1: not an IFC/STEP file: it must start with `ISO-10303-21;`",
    );
}

#[test]
fn file_starting_with_data_section_is_fatal_not_step() {
    let text: String = TEMPLATE[6..].iter().map(|l| format!("{l}\n")).collect();
    assert!(text.starts_with("DATA;"));
    fatal("no-header.ifc", text, ":1: not an IFC/STEP file");
}

#[test]
fn missing_header_section_is_fatal_bad_header_on_line_2() {
    let text = format!("{}\n{}", TEMPLATE[0], TEMPLATE[6..].join("\n"));
    fatal(
        "no-header-section.ifc",
        text,
        ":2: malformed HEADER section: expected `HEADER;`",
    );
}

#[test]
fn unknown_schema_is_fatal_and_named() {
    let text = replace_once(template().as_bytes(), "'IFC4'", b"'IFC2X2_FINAL'");
    fatal("ifc2x2.ifc", text, ":5: unknown schema `IFC2X2_FINAL`");
}

#[test]
fn unterminated_string_names_instance_and_line() {
    // Line 12 opens a string that never closes: no quote follows to the end of the file.
    let text = format!(
        "{}#5=IFCWALL('abc\n#10=IFCCARTESIANPOINT((0.,0.,0.));\nENDSEC;\nEND-ISO-10303-21;\n",
        first_lines(11)
    );
    fatal(
        "unterminated.ifc",
        text,
        ":12: #5: string literal is never closed",
    );
}

#[test]
fn truncation_inside_an_instance_names_the_cut_instance() {
    let door = TEMPLATE[12];
    let cut = &door[..door.find("#14,").unwrap() + 4];
    let text = format!("{}{cut}", first_lines(12));
    fatal(
        "cut-instance.ifc",
        text,
        ":13: #6: file is truncated: the file ends inside an entry",
    );
}

#[test]
fn truncation_inside_a_string_names_the_cut_instance() {
    let text = format!("{}#6=IFCDOOR('3YvctVUKr0", first_lines(12));
    fatal(
        "cut-string.ifc",
        text,
        ":13: #6: string literal is never closed",
    );
}

#[test]
fn truncation_after_a_complete_instance_names_the_last_instance() {
    // Lines 1-15 with their line ends: the file ends at the start of line 16, after #8.
    fatal(
        "cut-after-line.ifc",
        first_lines(15),
        ":16: #8: file is truncated: the DATA section is not closed by `ENDSEC;`",
    );
    // Without the last line end the file ends on line 15.
    fatal(
        "cut-at-semicolon.ifc",
        first_lines(15).trim_end(),
        ":15: #8: file is truncated: the DATA section is not closed by `ENDSEC;`",
    );
}

#[test]
fn nonexistent_path_is_fatal_and_named() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("no such dir").join("missing.ifc");
    let run = inspect(&path, &["--json"]);
    // No line and no instance: the path is followed directly by the message.
    assert_fatal(&run, &path, ": cannot read file: ");
}

// b. Damaged but readable: diagnostics name the instance, the rest of the model is reported.

#[test]
fn dangling_reference_is_reported_on_the_referring_instance() {
    let r = damaged(
        &dangling(template().as_bytes()),
        &[diag("dangling-reference", 8, 15)],
    );
    assert!(r["diagnostic_list"][0]["message"]
        .as_str()
        .unwrap()
        .contains("#99"));
    assert_door(&r, "Door");
    assert_rest_of_model(&r);
}

#[test]
fn duplicate_id_is_reported_on_the_second_definition() {
    let r = damaged(
        &duplicate(template().as_bytes()),
        &[diag("duplicate-id", 5, 16)],
    );
    assert_door(&r, "Door");
    assert_rest_of_model(&r);
}

#[test]
fn cyclic_placement_is_reported_once_on_its_first_instance() {
    let r = damaged(
        &cyclic_placement(template().as_bytes()),
        &[diag("cyclic-placement", 12, 18)],
    );
    let message = r["diagnostic_list"][0]["message"].as_str().unwrap();
    for id in ["#12", "#13", "#14"] {
        assert!(message.contains(id), "{message}");
    }
    assert_door(&r, "Door");
    assert_rest_of_model(&r);
}

#[test]
fn cyclic_aggregation_is_reported_once_on_its_first_instance() {
    let r = damaged(
        &cyclic_aggregation(template().as_bytes()),
        &[diag("cyclic-aggregation", 1, 8)],
    );
    assert_door(&r, "Door");
    assert_rest_of_model(&r);
}

#[test]
fn wrong_attribute_count_is_reported_and_other_attributes_still_read() {
    let r = damaged(
        &wrong_count(template().as_bytes()),
        &[diag("wrong-attribute-count", 6, 13)],
    );
    let message = r["diagnostic_list"][0]["message"].as_str().unwrap();
    assert!(
        message.contains("12") && message.contains("13"),
        "{message}"
    );
    assert_door(&r, "Door");
    assert_rest_of_model(&r);
}

/// The door's Description left empty (`,,`) instead of `$`, and a second `;` after `#14`: the
/// defects of the step-file-parser fixtures `fail_double_comma` and `fail_double_semi`.
#[test]
fn an_empty_attribute_and_a_second_semicolon_are_syntax_diagnostics_and_the_door_reads() {
    let text = replace_once(template().as_bytes(), "'Door',$,$,#14", b"'Door',,$,#14");
    let text = replace_once(&text, "(#13,#11);", b"(#13,#11);;");
    let r = damaged(&text, &[diag("syntax", 6, 13), diag("syntax", 14, 20)]);
    let message = r["diagnostic_list"][0]["message"].as_str().unwrap();
    assert!(
        message.starts_with("attribute 4 (Description) is empty"),
        "{message}"
    );
    assert_door(&r, "Door");
    assert_rest_of_model(&r);
}

#[test]
fn non_utf8_string_is_reported_and_read_as_latin1() {
    let r = damaged(&non_utf8(template().as_bytes()), &[diag("non-utf8", 6, 13)]);
    assert_door(&r, "T\u{fc}r");
    assert_rest_of_model(&r);
}

#[test]
fn all_damage_kinds_at_once_are_each_reported_once() {
    let mut text = template().into_bytes();
    for damage in [
        dangling,
        duplicate,
        cyclic_aggregation,
        cyclic_placement,
        wrong_count,
        non_utf8,
    ] {
        text = damage(&text);
    }
    // The duplicate #5 lands on line 16 and #9 on line 17, so #12 moves to line 20.
    let dir = tempfile::tempdir().unwrap();
    let path = write(&dir, "all.ifc", &text);
    let run = inspect(&path, &["--json"]);
    assert_eq!(run.code, Some(0), "stderr: {}", run.stderr);
    let r: Value = serde_json::from_str(&run.stdout).unwrap();
    let mut got = diagnostics(&r);
    got.sort();
    let mut want = vec![
        diag("cyclic-aggregation", 1, 8),
        diag("wrong-attribute-count", 6, 13),
        diag("non-utf8", 6, 13),
        diag("dangling-reference", 8, 15),
        diag("duplicate-id", 5, 16),
        diag("cyclic-placement", 12, 20),
    ];
    want.sort();
    assert_eq!(got, want);
    assert_door(&r, "T\u{fc}r");
    assert_rest_of_model(&r);
    assert_eq!(inspect(&path, &["--strict"]).code, Some(2));
}

// c. Line ends, id order and extreme sizes.

#[test]
fn cr_only_line_endings_read_cleanly() {
    let r = report(template_with("\r"));
    assert_eq!(diagnostics(&r), []);
    assert_eq!(r["instances"], 13);
    assert_door(&r, "Door");
    assert_rest_of_model(&r);
}

#[test]
fn cr_only_line_endings_count_lines_in_errors() {
    let text = format!(
        "{}\r#5=IFCWALL('abc\r#10=IFCCARTESIANPOINT((0.,0.,0.));\rENDSEC;\rEND-ISO-10303-21;\r",
        TEMPLATE[..11].join("\r")
    );
    fatal("cr.ifc", text, ":12: #5: string literal is never closed");
}

#[test]
fn crlf_line_endings_count_lines_in_diagnostics() {
    let text = template_with("\r\n");
    let r = report(&text);
    assert_eq!(diagnostics(&r), []);
    let r = report(dangling(text.as_bytes()));
    assert_eq!(diagnostics(&r), [diag("dangling-reference", 8, 15)]);
}

#[test]
fn out_of_order_ids_read_cleanly() {
    // The DATA lines in reverse order, #14 renamed #20: #20 comes first, #1 last.
    let data: Vec<String> = TEMPLATE[7..20]
        .iter()
        .rev()
        .map(|l| l.replace("#14", "#20"))
        .collect();
    let text = format!(
        "{}{}\n{}",
        first_lines(7),
        data.join("\n"),
        TEMPLATE[20..].join("\n")
    );
    assert!(text.contains("DATA;\n#20=IFCLOCALPLACEMENT(#13,#11);\n"));
    let r = report(text);
    assert_eq!(diagnostics(&r), []);
    assert_eq!(r["instances"], 13);
    assert_door(&r, "Door");
    assert_rest_of_model(&r);
}

/// The template with the door's Description (`$`) replaced by `value`.
fn door_description(value: &str) -> Vec<u8> {
    replace_once(
        template().as_bytes(),
        "'Door',$,",
        format!("'Door',{value},").as_bytes(),
    )
}

const DEEP: usize = 1_000_000;

/// Runs a file that might overflow a recursive parser: the process must not abort.
fn survives(bytes: Vec<u8>) -> Run {
    let dir = tempfile::tempdir().unwrap();
    let path = write(&dir, "deep.ifc", bytes);
    let run = inspect(&path, &["--json"]);
    assert!(
        matches!(run.code, Some(0 | 2)),
        "killed or crashed: {:?} {}",
        run.code,
        run.stderr
    );
    for bad in ["panicked", "overflow", "SIGSEGV"] {
        assert!(!run.stderr.contains(bad), "{}", run.stderr);
    }
    run
}

#[test]
fn million_deep_unbalanced_list_does_not_crash_and_is_a_syntax_diagnostic() {
    let run = survives(door_description(&"(".repeat(DEEP)));
    assert_eq!(run.code, Some(0), "{}", run.stderr);
    let r: Value = serde_json::from_str(&run.stdout).unwrap();
    assert_eq!(diagnostics(&r), [diag("syntax", 6, 13)]);
    assert_rest_of_model(&r);
}

#[test]
fn million_deep_balanced_list_does_not_crash() {
    let deep = format!("{}{}", "(".repeat(DEEP), ")".repeat(DEEP));
    let run = survives(door_description(&deep));
    if run.code == Some(0) {
        let r: Value = serde_json::from_str(&run.stdout).unwrap();
        assert_rest_of_model(&r);
        assert_eq!(r["doors"][0]["id"], 6);
    } else {
        assert!(run.stderr.contains(":13: #6: "), "{}", run.stderr);
    }
}

#[test]
fn million_deep_balanced_list_is_reported_and_hides_only_its_attribute() {
    let deep = format!("{}{}", "(".repeat(DEEP), ")".repeat(DEEP));
    let run = survives(door_description(&deep));
    assert_eq!(run.code, Some(0), "{}", run.stderr);
    let r: Value = serde_json::from_str(&run.stdout).unwrap();
    let on_door: Vec<_> = diagnostics(&r)
        .into_iter()
        .filter(|d| d.1 == Some(6))
        .collect();
    assert_eq!(on_door.len(), 1, "{on_door:?}");
    assert_eq!(on_door[0].0, "bad-value");
    assert_door(&r, "Door");
}

#[test]
fn duplicate_door_id_is_listed_once_with_its_first_definition() {
    let text = replace_once(
        template().as_bytes(),
        "#10=IFCCARTESIANPOINT",
        b"#6=IFCDOOR('6YvctVUKr0kugbFTf53O9L',$,'Second door',$,$,$,$,$,1000.,500.,$,$,$);\n#10=IFCCARTESIANPOINT",
    );
    let r = damaged(&text, &[diag("duplicate-id", 6, 16)]);
    assert_eq!(r["counts"]["IfcDoor"], 1);
    assert_door(&r, "Door");
}

#[test]
fn hundred_megabyte_string_attribute_reads() {
    let name = format!("'{}'", "a".repeat(100_000_000));
    let text = replace_once(template().as_bytes(), "'Wall'", name.as_bytes());
    let r = report(text);
    assert_eq!(diagnostics(&r), []);
    assert_eq!(r["instances"], 13);
    assert_eq!(r["counts"]["IfcWall"], 1);
    assert_door(&r, "Door");
    assert_rest_of_model(&r);
}

#[test]
fn a_bare_nan_is_a_bad_value_of_its_instance_and_the_rest_still_reads() {
    // `NaN` and `inf` are not STEP tokens (reals are digits with a point); some exporters
    // write them anyway.
    let bytes = replace_once(
        template().as_bytes(),
        "#10=IFCCARTESIANPOINT((0.,0.,0.));",
        b"#10=IFCCARTESIANPOINT((NaN,0.,inf));",
    );
    let r = damaged(&bytes, &[diag("bad-value", 10, 16)]);
    let message = r["diagnostic_list"][0]["message"].as_str().unwrap();
    assert!(
        message.starts_with("`NaN` is not a STEP value"),
        "{message}"
    );
    assert_door(&r, "Door");
    assert_rest_of_model(&r);
}

#[test]
fn typed_values_and_enumerations_are_not_bare_words() {
    let bytes = replace_once(
        template().as_bytes(),
        "#5=IFCWALL('2YvctVUKr0kugbFTf53O9L',$,'Wall',$,$,#13,$,$,.STANDARD.);",
        b"#5=IFCWALL('2YvctVUKr0kugbFTf53O9L',$,'Wall',IFCTEXT ('x'),$,#13,$,$, .STANDARD. );",
    );
    let r = report(bytes);
    assert_eq!(diagnostics(&r), []);
}

#[test]
fn a_missing_end_iso_line_is_a_truncation_diagnostic_and_the_model_reads() {
    let text = template();
    let cut = text.strip_suffix("END-ISO-10303-21;\n").unwrap();
    let r = damaged(cut.as_bytes(), &[("truncated".to_string(), None, Some(22))]);
    let message = r["diagnostic_list"][0]["message"].as_str().unwrap();
    assert_eq!(
        message,
        "the file does not end with `END-ISO-10303-21;`: it may have been cut short after its DATA section"
    );
    assert_eq!(r["instances"], 13);
    assert_door(&r, "Door");
    assert_rest_of_model(&r);
}

#[test]
fn a_file_without_a_data_section_is_fatal_on_its_end_line() {
    // Found by fuzzing enrichment: it used to read as an empty model that could not be edited.
    let text: String = TEMPLATE[..6]
        .iter()
        .chain(&TEMPLATE[21..])
        .map(|l| format!("{l}\n"))
        .collect();
    assert!(!text.contains("DATA;"));
    fatal(
        "no-data.ifc",
        text,
        ":7: syntax error: the file has no DATA section: `END-ISO-10303-21;` follows the header",
    );
}
