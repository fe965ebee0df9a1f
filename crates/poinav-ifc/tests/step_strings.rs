//! Real-world STEP string quirks, read by poinav and, live, by IfcOpenShell on the same small
//! crafted files: `\S\'` (the `\S\` directive on an apostrophe), lone backslashes, `\X\` at
//! the end of a string, `\X2\` without `\X0\` and a string that never closes.

use std::path::Path;

use poinav_ifc::{DiagnosticKind, EntityId, Model};

/// A small IFC4 file: `file_name` as FILE_NAME's first argument, `name` as the Name of wall
/// `#1` (both written as is, quotes included), and a wall `#2` named `next` after it.
fn file(file_name: &str, name: &str) -> String {
    format!(
        "ISO-10303-21;\nHEADER;\nFILE_DESCRIPTION(('ViewDefinition [x]'),'2;1');\n\
         FILE_NAME({file_name},'2020-01-01T00:00:00',(''),(''),'','','');\n\
         FILE_SCHEMA(('IFC4'));\nENDSEC;\nDATA;\n\
         #1=IFCWALL('0abcdefghijklmnopqrstu',$,{name},$,$,$,$,$,$);\n\
         #2=IFCWALL('1abcdefghijklmnopqrstu',$,'next',$,$,$,$,$,$);\n\
         ENDSEC;\nEND-ISO-10303-21;\n"
    )
}

/// IfcOpenShell's reading: `[file name, name of #1, name of #2]`, or `None` when it refuses
/// the file.
fn ifcopenshell(path: &Path) -> Option<Vec<String>> {
    let py = poinav_testkit::python("ifcopenshell");
    let script = "import sys, json, ifcopenshell\n\
                  try:\n    m = ifcopenshell.open(sys.argv[1])\n\
                  except Exception:\n    print('null'); sys.exit(0)\n\
                  print(json.dumps([m.header.file_name.name, m.by_id(1).Name, m.by_id(2).Name]))";
    serde_json::from_value(poinav_testkit::python_json(
        &py,
        script,
        &[path.as_os_str()],
    ))
    .expect("a list of names, or null")
}

/// poinav's reading, in the same form, and the model's diagnostics.
fn poinav(text: &str) -> (Vec<String>, Vec<DiagnosticKind>) {
    let model = Model::from_bytes("crafted.ifc", text.as_bytes().to_vec()).expect("read");
    let range = model.header().file_name_args.clone().expect("FILE_NAME");
    let args = poinav_ifc::value::parse_args(&model.bytes()[range]).expect("FILE_NAME args");
    let name = |id| {
        model
            .entity(EntityId(id))
            .and_then(|e| e.get_str("Name"))
            .unwrap_or_else(|| "<unreadable>".into())
    };
    let read = vec![args[0].as_str().unwrap().into_owned(), name(1), name(2)];
    let kinds = model.diagnostics().iter().map(|d| d.kind).collect();
    (read, kinds)
}

#[test]
fn quirky_strings_read_like_ifcopenshell_or_where_it_refuses_as_written() {
    let dir = tempfile::tempdir().unwrap();
    let cases: &[(&str, &str, &str, [&str; 3], bool)] = &[
        // (label, FILE_NAME, Name, poinav's reading, IfcOpenShell reads the file too)
        // The Vectorworks header: `\S\'` is 0xA7, `\X\91` is U+0091.
        (
            "S-apostrophe in the header",
            r"'a\S\'\X\91b.ifc'",
            "'n'",
            ["a\u{a7}\u{91}b.ifc", "n", "next"],
            true,
        ),
        (
            "S-apostrophe in a name",
            "'x'",
            r"'a\S\'b'",
            ["x", "a\u{a7}b", "next"],
            true,
        ),
        (
            "S-apostrophe as the last character",
            "'x'",
            r"'a\S\''",
            ["x", "a\u{a7}", "next"],
            true,
        ),
        (
            "S-apostrophe before a parenthesis",
            "'x'",
            r"'a\S\')b'",
            ["x", "a\u{a7})b", "next"],
            true,
        ),
        // IfcOpenShell refuses the rest; poinav reads them, the odd escape as written.
        (
            "a string ending in \\S\\",
            "'x'",
            r"'C:\S\'",
            ["x", r"C:\S\", "next"],
            false,
        ),
        (
            "lone backslashes",
            "'x'",
            r"'C:\temp\a b'",
            ["x", r"C:\temp\a b", "next"],
            false,
        ),
        (
            "a trailing backslash",
            "'x'",
            r"'ab\'",
            ["x", r"ab\", "next"],
            false,
        ),
        (
            "\\X\\ at the end",
            "'x'",
            r"'ab\X\'",
            ["x", r"ab\X\", "next"],
            false,
        ),
        (
            "\\X2\\ without \\X0\\",
            "'x'",
            r"'a\X2\00E400F6'",
            ["x", "a\u{e4}\u{f6}", "next"],
            false,
        ),
    ];
    for (label, file_name, name, want, ifcos_reads) in cases {
        let text = file(file_name, name);
        let (read, kinds) = poinav(&text);
        assert_eq!(read, want.map(String::from), "{label}");
        let path = dir.path().join("crafted.ifc");
        std::fs::write(&path, &text).unwrap();
        let theirs = ifcopenshell(&path);
        if *ifcos_reads {
            assert_eq!(theirs.as_ref(), Some(&read), "{label}: IfcOpenShell");
            assert!(kinds.is_empty(), "{label}: {kinds:?}");
        } else {
            assert_eq!(theirs, None, "{label}: IfcOpenShell now reads it: compare");
            // One diagnostic for the instance whose string holds the odd escape.
            assert_eq!(kinds, [DiagnosticKind::BadValue], "{label}");
        }
    }
}

#[test]
fn a_string_that_never_closes_is_a_diagnostic_of_its_instance() {
    // Wall #1's Name opens a string that the line does not close: it would run to the end.
    let text = file(
        "'x'",
        "'broken,$,$,$,$,$,$);\n#3=IFCWALL('2abcdefghijklmnopqrstu',$,'b'",
    );
    let model = Model::from_bytes("crafted.ifc", text.into_bytes()).expect("read");
    assert_eq!(model.len(), 3);
    let broken: Vec<_> = model
        .diagnostics()
        .iter()
        .filter(|d| d.id == Some(EntityId(1)))
        .collect();
    assert_eq!(broken.len(), 1, "{:?}", model.diagnostics());
    assert!(
        broken[0].message.contains("never closed"),
        "{}",
        broken[0].message
    );
    assert!(model.entity(EntityId(1)).unwrap().get_str("Name").is_none());
    let next = model.entity(EntityId(2)).unwrap();
    assert_eq!(next.get_str("Name").as_deref(), Some("next"));
}
