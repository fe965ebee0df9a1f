//! STEP syntax defects from the fixture set of IfcOpenShell's validator `step-file-parser` (which
//! buildingSMART's validation service runs), each written here as our own small file: poinav
//! names each defect's kind, line and `#id`, and IfcOpenShell's `simple_spf` (that validator,
//! run live) rejects the same texts and reads the clean ones.

use poinav_ifc::{Diagnostic, DiagnosticKind, EntityId, Model, ReadErrorKind};

const DESCRIPTION: &str = "FILE_DESCRIPTION(('ViewDefinition [x]'),'2;1');";
const NAME: &str = "FILE_NAME('s.ifc','2024-01-01T00:00:00',(''),(''),'','','');";
const PERSON: &str = "#1=IFCPERSON($,$,'Ada',$,$,$,$,$);";
const POINT: &str = "#2=IFCCARTESIANPOINT((0.,1.,2.));";
const WALL: &str = "#3=IFCWALL('0abcdefghijklmnopqrstu',$,'W',$,$,$,$,$,$);";

/// An IFC4 file: `description` and `name` on lines 3 and 4, `DATA;` on line 7 and `data` one
/// entry a line from line 8.
fn file(description: &str, name: &str, data: &[&str]) -> String {
    let mut text = format!(
        "ISO-10303-21;\nHEADER;\n{description}\n{name}\nFILE_SCHEMA(('IFC4'));\nENDSEC;\nDATA;\n"
    );
    for line in data {
        text.push_str(line);
        text.push('\n');
    }
    text.push_str("ENDSEC;\nEND-ISO-10303-21;\n");
    text
}

/// The clean file with `line` 8, 9 or 10 replaced.
fn with_line(at: usize, line: &str) -> String {
    let mut data = [PERSON, POINT, WALL];
    data[at - 8] = line;
    file(DESCRIPTION, NAME, &data)
}

/// Every text of this file: name, text, and whether it is free of defects.
fn texts() -> Vec<(&'static str, String, bool)> {
    vec![
        ("clean", with_line(8, PERSON), true),
        (
            "quote_backslash_page",
            with_line(
                8,
                "#1=IFCPERSON($, $,'It''s C:\\\\x abc\\S\\'def',$,$,$,$,$);",
            ),
            true,
        ),
        (
            "empty_attribute",
            with_line(8, "#1=IFCPERSON($,$,'Ada',,$,$,$,$);"),
            false,
        ),
        (
            "empty_first_attribute",
            with_line(8, "#1=IFCPERSON(,$,'Ada',$,$,$,$,$);"),
            false,
        ),
        (
            "empty_last_attribute",
            with_line(8, "#1=IFCPERSON($,$,'Ada',$,$,$,$,);"),
            false,
        ),
        (
            "empty_list_item",
            with_line(9, "#2=IFCCARTESIANPOINT((0., ,2.));"),
            false,
        ),
        (
            "second_semicolon",
            with_line(9, "#2=IFCCARTESIANPOINT((0.,1.,2.));;"),
            false,
        ),
        (
            "instance_zero",
            with_line(8, "#0=IFCPERSON($,$,'Ada',$,$,$,$,$);"),
            false,
        ),
        (
            "duplicate_id",
            with_line(
                10,
                "#1=IFCWALL('0abcdefghijklmnopqrstu',$,'W',$,$,$,$,$,$);",
            ),
            false,
        ),
        (
            "header_counts",
            file(
                "FILE_DESCRIPTION(('ViewDefinition [x]'));",
                "FILE_NAME('s.ifc','2024-01-01T00:00:00',(''),(''),'','','','');",
                &[PERSON, POINT, WALL],
            ),
            false,
        ),
        (
            "lone_backslash",
            with_line(8, "#1=IFCPERSON($,$,'C:\\temp',$,$,$,$,$);"),
            false,
        ),
        (
            "python_hex_escape",
            with_line(8, "#1=IFCPERSON($,$,'W\\xc3\\xa4nd',$,$,$,$,$);"),
            false,
        ),
        (
            "no_header_keyword",
            file(DESCRIPTION, NAME, &[PERSON, POINT, WALL]).replacen("HEADER;\n", "", 1),
            false,
        ),
    ]
}

fn text(name: &str) -> String {
    texts()
        .into_iter()
        .find(|t| t.0 == name)
        .unwrap_or_else(|| panic!("test bug: no text {name}"))
        .1
}

fn read(name: &str) -> Model {
    Model::from_bytes(format!("{name}.ifc"), text(name).into_bytes())
        .unwrap_or_else(|e| panic!("{name}: {e}"))
}

/// The model's one diagnostic, checked for kind, `#id` and line.
fn only(model: &Model, kind: DiagnosticKind, id: Option<u64>, line: usize) -> Diagnostic {
    let d = model.diagnostics();
    assert_eq!(d.len(), 1, "{d:#?}");
    assert_eq!(
        (d[0].kind, d[0].id, d[0].line),
        (kind, id.map(EntityId), Some(line)),
        "{}",
        d[0]
    );
    d[0].clone()
}

#[test]
fn an_empty_attribute_between_commas_is_a_syntax_diagnostic_and_the_others_read() {
    let m = read("empty_attribute");
    let d = only(&m, DiagnosticKind::Syntax, Some(1), 8);
    assert!(
        d.message.starts_with("attribute 4 (MiddleNames) is empty"),
        "{d}"
    );
    let person = m.entity(EntityId(1)).unwrap();
    assert_eq!(person.get_str("GivenName").as_deref(), Some("Ada"));
    assert!(
        person.attr("MiddleNames").is_err(),
        "the empty value is no value"
    );
}

#[test]
fn an_empty_first_or_last_attribute_is_a_syntax_diagnostic() {
    let d = only(
        &read("empty_first_attribute"),
        DiagnosticKind::Syntax,
        Some(1),
        8,
    );
    assert!(
        d.message
            .starts_with("attribute 1 (Identification) is empty"),
        "{d}"
    );
    let d = only(
        &read("empty_last_attribute"),
        DiagnosticKind::Syntax,
        Some(1),
        8,
    );
    assert!(
        d.message.starts_with("attribute 8 (Addresses) is empty"),
        "{d}"
    );
}

#[test]
fn an_empty_list_item_names_the_attribute_holding_the_list() {
    let d = only(&read("empty_list_item"), DiagnosticKind::Syntax, Some(2), 9);
    assert!(
        d.message
            .starts_with("a list in attribute 1 (Coordinates) has an empty item"),
        "{d}"
    );
}

#[test]
fn a_second_semicolon_names_the_instance_it_follows() {
    let m = read("second_semicolon");
    let d = only(&m, DiagnosticKind::Syntax, Some(2), 9);
    assert!(d.message.contains("second `;`"), "{d}");
    assert_eq!(m.len(), 3);
}

#[test]
fn instance_name_zero_is_a_syntax_diagnostic_and_the_instance_is_kept() {
    let m = read("instance_zero");
    let d = only(&m, DiagnosticKind::Syntax, Some(0), 8);
    assert!(
        d.message.contains("`#0` is not a valid instance name"),
        "{d}"
    );
    assert_eq!(m.len(), 3);
    let person = m.entity(EntityId(0)).expect("kept");
    assert_eq!(person.get_str("GivenName").as_deref(), Some("Ada"));
}

#[test]
fn a_duplicate_id_names_the_second_definition() {
    let m = read("duplicate_id");
    only(&m, DiagnosticKind::DuplicateId, Some(1), 10);
    assert!(m.entity(EntityId(1)).unwrap().is_a("IfcPerson"));
}

#[test]
fn header_entries_with_too_few_or_too_many_parameters_are_diagnostics_on_their_lines() {
    let m = read("header_counts");
    let d: Vec<(DiagnosticKind, Option<EntityId>, Option<usize>)> = m
        .diagnostics()
        .iter()
        .map(|d| (d.kind, d.id, d.line))
        .collect();
    let kind = DiagnosticKind::WrongAttributeCount;
    assert_eq!(d, [(kind, None, Some(3)), (kind, None, Some(4))]);
    assert!(m.diagnostics()[0]
        .message
        .contains("FILE_DESCRIPTION has 1 parameter, ISO 10303-21 declares 2"));
    assert!(m.diagnostics()[1]
        .message
        .contains("FILE_NAME has 8 parameters, ISO 10303-21 declares 7"));
    // A header entry that cannot be parsed at all is a syntax diagnostic.
    let m = Model::from_bytes(
        "h.ifc",
        file(
            DESCRIPTION,
            "FILE_NAME('s.ifc',,(''),(''),'','','');",
            &[PERSON],
        )
        .into_bytes(),
    )
    .unwrap();
    let d = only(&m, DiagnosticKind::Syntax, None, 4);
    assert_eq!(
        d.message,
        "header entry FILE_NAME cannot be read: expected a value at byte 9 of its parameters"
    );
}

#[test]
fn backslashes_that_are_no_escape_are_bad_values_read_as_written() {
    for (name, shown, value) in [
        ("lone_backslash", "`\\temp`", "C:\\temp"),
        ("python_hex_escape", "`\\xc3\\x`", "W\\xc3\\xa4nd"),
    ] {
        let m = read(name);
        let d = only(&m, DiagnosticKind::BadValue, Some(1), 8);
        assert!(d.message.contains(shown), "{name}: {d}");
        let person = m.entity(EntityId(1)).unwrap();
        assert_eq!(person.get_str("GivenName").as_deref(), Some(value));
    }
}

#[test]
fn a_file_without_the_header_keyword_is_an_error_on_line_2() {
    let e = Model::from_bytes("no_header.ifc", text("no_header_keyword").into_bytes()).unwrap_err();
    assert!(matches!(e.kind, ReadErrorKind::BadHeader(_)), "{e}");
    assert_eq!((e.line, e.id), (Some(2), None));
    assert!(
        e.to_string()
            .starts_with("no_header.ifc:2: malformed HEADER"),
        "{e}"
    );
}

#[test]
fn quotes_double_backslashes_page_escapes_and_spaces_read_without_diagnostics() {
    for name in ["clean", "quote_backslash_page"] {
        let m = read(name);
        assert!(m.diagnostics().is_empty(), "{name}: {:#?}", m.diagnostics());
    }
    let m = read("quote_backslash_page");
    let person = m.entity(EntityId(1)).unwrap();
    assert_eq!(
        person.get_str("GivenName").as_deref(),
        Some("It's C:\\x abc\u{a7}def")
    );
}

#[test]
fn ifcopenshell_simple_spf_rejects_each_defect_and_reads_the_clean_texts() {
    let dir = tempfile::tempdir().unwrap();
    let all = texts();
    for (name, text, _) in &all {
        std::fs::write(dir.path().join(format!("{name}.ifc")), text).unwrap();
    }
    let py = poinav_testkit::python("ifcopenshell.simple_spf");
    let script = "import sys, json, glob, os, ifcopenshell.simple_spf as spf\n\
                  out = {}\n\
                  for f in sorted(glob.glob(os.path.join(sys.argv[1], '*.ifc'))):\n\
                  \x20   try:\n\
                  \x20       spf.open(f); ok = True\n\
                  \x20   except Exception:\n\
                  \x20       ok = False\n\
                  \x20   out[os.path.basename(f)[:-4]] = ok\n\
                  print(json.dumps(out))";
    let verdicts = poinav_testkit::python_json(&py, script, &[dir.path().as_os_str()]);
    for (name, text, clean) in &all {
        assert_eq!(
            verdicts[name].as_bool(),
            Some(*clean),
            "simple_spf on {name}"
        );
        // poinav agrees: a clean text reads without diagnostics, every other is named.
        match Model::from_bytes("t.ifc", text.clone().into_bytes()) {
            Ok(m) => assert_eq!(m.diagnostics().is_empty(), *clean, "poinav on {name}"),
            Err(e) => assert!(!clean, "poinav on {name}: {e}"),
        }
    }
    assert_eq!(all.iter().filter(|t| !t.2).count(), 11);
}
