//! Reading one attribute through the argument index gives exactly what parsing the whole
//! argument list gives, on every instance of every corpus file.

use poinav_ifc::Model;

#[test]
fn every_attribute_of_every_corpus_instance_reads_as_in_the_whole_list() {
    let files = poinav_testkit::corpus();
    assert!(files.len() >= 10, "corpus found: {}", files.len());
    let mut checked = 0usize;
    for path in files {
        let Ok(model) = Model::open(&path) else {
            continue;
        };
        for e in model.entities() {
            let Ok(all) = e.args() else {
                continue;
            };
            for (i, v) in all.iter().enumerate() {
                assert_eq!(
                    e.attr_at(i).unwrap().as_ref(),
                    Some(v),
                    "{} {:?} attribute {i}",
                    path.display(),
                    e
                );
                checked += 1;
            }
            assert_eq!(e.attr_at(all.len()).unwrap(), None, "{e:?}");
        }
    }
    // The corpus holds millions of attribute values.
    assert!(checked > 1_000_000, "{checked}");
}

#[test]
fn damaged_lists_read_what_can_be_read() {
    let text = "ISO-10303-21;HEADER;FILE_SCHEMA(('IFC4'));ENDSEC;DATA;\n\
                #1=IFCCARTESIANPOINT((1.,2.));\n\
                #2=IFCDIRECTION((0.,0.,1.) 7);\n\
                #3=IFCWALL('a',$,$,$,$,$,$,$,$;\n\
                #4=IFCLABEL();\n\
                ENDSEC;END-ISO-10303-21;";
    let model = Model::from_bytes("t.ifc", text.as_bytes().to_vec()).unwrap();
    let p = model.entity(poinav_ifc::EntityId(1)).unwrap();
    assert_eq!(p.get("Coordinates").unwrap().as_list().unwrap().len(), 2);
    let d = model.entity(poinav_ifc::EntityId(2)).unwrap();
    let err = d.attr_at(0).unwrap_err().to_string();
    assert!(err.contains("expected `,` or `)`"), "{err}");
    let w = model.entity(poinav_ifc::EntityId(3)).unwrap();
    assert!(
        w.attr_at(0).is_err(),
        "an unbalanced list is split on access and fails"
    );
    let l = model.entity(poinav_ifc::EntityId(4)).unwrap();
    assert_eq!(l.attr_at(0).unwrap(), None);
}
