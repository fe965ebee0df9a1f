//! Property tests of enrichment (the write path of `poinav enrich`): for generated models
//! (IFC4 or IFC2X3, LF or CRLF line ends, any number of doors, spaces and walls, widths known
//! or not, names with quotes and non-ASCII text, with or without an existing property set) the
//! output reads back without diagnostics, keeps every original instance byte for byte, attaches
//! a classification set to every classified element plus the accessibility and coordination
//! sets where they apply, and enriching the enriched file again gives the same bytes.

use poinav_ifc::Model;
use poinav_poi::{classify, write_enrichment, RobotProfile, RuleSet, WriteOptions};
use proptest::prelude::*;

#[derive(Debug, Clone)]
struct Spec {
    ifc2x3: bool,
    crlf: bool,
    doors: Vec<(Option<f64>, String)>,
    spaces: Vec<String>,
    walls: usize,
    pset_on_first_door: bool,
}

/// A STEP string literal for `s`: quotes doubled, non-ASCII as `\X2\` hex.
fn literal(s: &str) -> String {
    let mut out = String::from("'");
    for c in s.chars() {
        match c {
            '\'' => out.push_str("''"),
            '\\' => out.push_str("\\\\"),
            c if c.is_ascii() && !c.is_ascii_control() => out.push(c),
            c => {
                let mut buf = [0u16; 2];
                out.push_str("\\X2\\");
                for u in c.encode_utf16(&mut buf) {
                    out.push_str(&format!("{u:04X}"));
                }
                out.push_str("\\X0\\");
            }
        }
    }
    out.push('\'');
    out
}

fn text(spec: &Spec) -> String {
    let nl = if spec.crlf { "\r\n" } else { "\n" };
    let schema = if spec.ifc2x3 { "IFC2X3" } else { "IFC4" };
    let guid = |n: usize| format!("'{n:0>22}'");
    let mut lines = vec![
        format!("#1=IFCPROJECT({},$,'P',$,$,$,$,$,#2);", guid(1)),
        "#2=IFCUNITASSIGNMENT((#3));".to_string(),
        "#3=IFCSIUNIT(*,.LENGTHUNIT.,$,.METRE.);".to_string(),
    ];
    let mut id = 100;
    for (width, name) in &spec.doors {
        let w = width.map_or("$".to_string(), |w| format!("{w:?}"));
        lines.push(if spec.ifc2x3 {
            format!(
                "#{id}=IFCDOOR({},$,{},$,$,$,$,$,2.1,{w});",
                guid(id),
                literal(name)
            )
        } else {
            format!(
                "#{id}=IFCDOOR({},$,{},$,$,$,$,$,2.1,{w},.DOOR.,$,$);",
                guid(id),
                literal(name)
            )
        });
        id += 1;
    }
    for name in &spec.spaces {
        // IFC2X3's InteriorOrExteriorSpace and IFC4's PredefinedType both take .INTERNAL. here.
        lines.push(format!(
            "#{id}=IFCSPACE({},$,{},$,$,$,$,$,.ELEMENT.,.INTERNAL.,$);",
            guid(id),
            literal(name)
        ));
        id += 1;
    }
    for _ in 0..spec.walls {
        let predefined = if spec.ifc2x3 { "" } else { ",$" };
        lines.push(format!(
            "#{id}=IFCWALL({},$,'W',$,$,$,$,${predefined});",
            guid(id)
        ));
        id += 1;
    }
    if spec.pset_on_first_door && !spec.doors.is_empty() {
        lines.push(format!(
            "#900=IFCPROPERTYSINGLEVALUE('FireRating',$,IFCLABEL('EI30'),$);{nl}\
             #901=IFCPROPERTYSET({},$,'Pset_DoorCommon',$,(#900));{nl}\
             #902=IFCRELDEFINESBYPROPERTIES({},$,$,$,(#100),#901);",
            guid(901),
            guid(902)
        ));
    }
    format!(
        "ISO-10303-21;{nl}HEADER;{nl}FILE_DESCRIPTION((''),'2;1');{nl}FILE_NAME('p.ifc','2026-01-01T00:00:00',(''),(''),'','','');{nl}FILE_SCHEMA(('{schema}'));{nl}ENDSEC;{nl}DATA;{nl}{}{nl}ENDSEC;{nl}END-ISO-10303-21;{nl}",
        lines.join(nl)
    )
}

fn spec() -> impl Strategy<Value = Spec> {
    let name = "[A-Za-z0-9 ']{0,12}|[äöüßé漢字 ]{1,6}|Corridor|Flur|Room [0-9]";
    (
        any::<bool>(),
        any::<bool>(),
        prop::collection::vec((prop::option::of(0.3f64..2.5), name), 0..5),
        prop::collection::vec(name, 0..4),
        0usize..3,
        any::<bool>(),
    )
        .prop_map(
            |(ifc2x3, crlf, doors, spaces, walls, pset_on_first_door)| Spec {
                ifc2x3,
                crlf,
                doors,
                spaces,
                walls,
                pset_on_first_door,
            },
        )
}

fn enrich(model: &Model) -> Vec<u8> {
    let opts = WriteOptions {
        prefix: "Pset_".into(),
        timestamp: "2026-01-01T00:00:00".into(),
    };
    let c = classify(model, &RuleSet::defaults(), &RobotProfile::paper());
    write_enrichment(model, &c, &opts).unwrap().to_bytes()
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(192))]

    #[test]
    fn enrichment_reads_back_keeps_the_original_and_is_idempotent(spec in spec()) {
        let input = text(&spec);
        let model = Model::from_bytes("p.ifc", input.clone().into_bytes()).unwrap();
        prop_assert!(model.diagnostics().is_empty(), "{:?}\n{input}", model.diagnostics());
        let c = classify(&model, &RuleSet::defaults(), &RobotProfile::paper());
        // Pset_POI_Classification for every element, the accessibility and coordination sets
        // where they apply.
        let expected_sets = c.elements.len()
            + c.elements.iter().filter(|e| e.accessibility.is_some()).count()
            + c.elements.iter().filter(|e| e.coordination.is_some()).count();
        prop_assert!(c.elements.len() >= spec.doors.len() + spec.walls);
        let once = enrich(&model);
        let reread = Model::from_bytes("once.ifc", once.clone()).unwrap();
        prop_assert!(reread.diagnostics().is_empty(), "{:?}", reread.diagnostics());
        for e in model.entities() {
            let w = reread.entity(e.id());
            prop_assert!(w.is_some_and(|w| w.raw() == e.raw()), "#{} changed", e.id());
        }
        // (element, set) pairs: identical sets may be shared by several elements.
        let poinav_sets: usize = reread
            .instances_of("IfcRelDefinesByProperties")
            .iter()
            .filter(|r| {
                r.get_ref("RelatingPropertyDefinition").is_some_and(|p| {
                    p.get_str("Description").as_deref() == Some("poinav POI enrichment")
                })
            })
            .map(|r| r.get_refs("RelatedObjects").len())
            .sum();
        prop_assert_eq!(poinav_sets, expected_sets);
        let twice = enrich(&reread);
        prop_assert!(twice == once, "re-enrichment changed the file");
        // Line ends stay the file's own.
        let s = String::from_utf8(once).unwrap();
        prop_assert_eq!(s.matches("\r\n").count() > 0, spec.crlf);
    }
}
