//! The IDS export checked live by IfcOpenShell's ifctester (`tests/ifcos/ids_check.py`): for
//! every corpus file and both set prefixes, the enriched copy passes every specification of its
//! IDS, each classified element is applicable exactly once per property set it carries and no
//! other element is; a changed value or a missing set makes the IDS fail.

mod common;

use std::collections::{BTreeMap, BTreeSet};
use std::ffi::OsStr;
use std::path::{Path, PathBuf};
use std::time::Instant;

use poinav_export::ids::{to_ids, write_ids};
use poinav_ifc::{Arg, Editor, EntityId, Model};
use poinav_poi::{
    classify, write_enrichment, AccessibilityStatus, Classification, RobotProfile, RuleSet,
    WriteOptions,
};
use serde_json::Value;

const STAMP: &str = "2026-11-22T02:30:00";

fn opts(prefix: &str) -> WriteOptions {
    WriteOptions {
        prefix: prefix.into(),
        timestamp: STAMP.into(),
    }
}

fn classification(model: &Model) -> Classification {
    classify(model, &RuleSet::defaults(), &RobotProfile::paper())
}

/// Writes the enriched copy of `model` and its IDS into `dir`; returns their paths.
fn enrich(model: &Model, c: &Classification, prefix: &str, dir: &Path) -> (PathBuf, PathBuf) {
    let stem = model
        .file()
        .file_stem()
        .unwrap()
        .to_string_lossy()
        .into_owned();
    let ifc = dir.join(format!("{stem}.{}.ifc", prefix.trim_end_matches('_')));
    let ids = dir.join(format!("{stem}.{}.ids", prefix.trim_end_matches('_')));
    write_enrichment(model, c, &opts(prefix))
        .unwrap()
        .write(&ifc)
        .unwrap();
    write_ids(&ids, model, c, &opts(prefix)).unwrap();
    (ifc, ids)
}

/// Runs ifctester on (IDS, IFC) pairs in one Python process; one result per pair.
fn ifctester(pairs: &[(PathBuf, PathBuf)]) -> Vec<Value> {
    let args: Vec<&OsStr> = pairs
        .iter()
        .flat_map(|(ids, ifc)| [ids.as_os_str(), ifc.as_os_str()])
        .collect();
    let out = common::ifcos("ids_check.py", &args);
    let results = out.as_array().expect("a JSON list").clone();
    assert_eq!(results.len(), pairs.len());
    results
}

fn specs(result: &Value) -> &Vec<Value> {
    result["specifications"].as_array().unwrap()
}

/// How often each element must be applicable: once per property set it carries.
fn expected_applicable(c: &Classification) -> BTreeMap<u64, usize> {
    c.elements
        .iter()
        .map(|e| {
            let sets =
                1 + usize::from(e.accessibility.is_some()) + usize::from(e.coordination.is_some());
            (e.id.0, sets)
        })
        .collect()
}

/// Number of specifications: distinct (class, set, values); one "nothing enriched" spec when
/// nothing was classified.
fn expected_spec_count(c: &Classification) -> usize {
    let mut keys = BTreeSet::new();
    for e in &c.elements {
        keys.insert(format!(
            "{} C {:?} {:?} {:?} {:?}",
            e.class, e.category, e.poi_type, e.primary, e.conditional
        ));
        if let Some(a) = &e.accessibility {
            keys.insert(format!(
                "{} A {:?} {:?} {} {}",
                e.class, a.status, a.method, a.min_clearance_width_m, a.min_clearance_height_m
            ));
        }
        if let Some(k) = &e.coordination {
            keys.insert(format!("{} K {k:?}", e.class));
        }
    }
    keys.len().max(1)
}

/// Every specification passed, and the applicable elements are exactly the expected ones.
fn assert_passes(label: &str, result: &Value, c: &Classification) -> (usize, usize) {
    let specs = specs(result);
    for s in specs {
        assert_eq!(
            s["status"],
            Value::Bool(true),
            "{label}: specification {} failed: {}",
            s["name"],
            s["failures"]
        );
        assert_eq!(s["failed"], 0, "{label}: {}", s["name"]);
        assert_eq!(s["passed"], s["applicable"], "{label}: {}", s["name"]);
    }
    assert_eq!(
        specs.len(),
        expected_spec_count(c),
        "{label}: specification count"
    );
    let mut seen: BTreeMap<u64, usize> = BTreeMap::new();
    for s in specs {
        for id in s["applicable_ids"].as_array().unwrap() {
            *seen.entry(id.as_u64().unwrap()).or_default() += 1;
        }
    }
    let want = expected_applicable(c);
    for (id, n) in &want {
        assert!(
            seen.contains_key(id),
            "{label}: classified #{id} is applicable to no specification"
        );
        assert_eq!(
            seen[id], *n,
            "{label}: #{id} applicable {} times, carries {n} sets",
            seen[id]
        );
    }
    let extra: Vec<&u64> = seen.keys().filter(|id| !want.contains_key(id)).collect();
    assert!(
        extra.is_empty(),
        "{label}: unclassified elements are applicable: {extra:?}"
    );
    let total: usize = specs
        .iter()
        .map(|s| s["applicable"].as_u64().unwrap() as usize)
        .sum();
    assert_eq!(
        total,
        want.values().sum::<usize>(),
        "{label}: applicable total"
    );
    (specs.len(), total)
}

#[test]
fn every_corpus_file_passes_its_ids_with_both_prefixes() {
    let start = Instant::now();
    let dir = tempfile::tempdir().unwrap();
    let mut cases = Vec::new();
    let mut pairs = Vec::new();
    for file in common::corpus() {
        let model = Model::open(&file).unwrap();
        let c = classification(&model);
        for prefix in ["Pset_", "POINAV_"] {
            let (ifc, ids) = enrich(&model, &c, prefix, dir.path());
            let text = std::fs::read_to_string(&ids).unwrap();
            assert_eq!(
                text,
                to_ids(&model, &c, &opts(prefix)),
                "{}: output is deterministic",
                file.display()
            );
            let other = if prefix == "Pset_" {
                "POINAV_"
            } else {
                "Pset_"
            };
            assert!(text.contains(&format!("<ids:simpleValue>{prefix}POI_Classification<")));
            assert!(
                !text.contains(&format!("<ids:simpleValue>{other}")),
                "{}: {prefix} IDS names {other} sets",
                file.display()
            );
            let label = format!("{} {prefix}", file.file_name().unwrap().to_string_lossy());
            cases.push((label, model.schema().name(), c.clone()));
            pairs.push((ids, ifc));
        }
    }
    let prepared = start.elapsed();
    let results = ifctester(&pairs);
    let mut table = String::new();
    for ((label, schema, c), result) in cases.iter().zip(&results) {
        let (n, total) = assert_passes(label, result, c);
        table.push_str(&format!(
            "{label:<55} {schema:<12} {:>5} elements {n:>3} specs {total:>5} applicable {:>6.2} s\n",
            c.elements.len(),
            result["seconds"].as_f64().unwrap()
        ));
    }
    eprintln!(
        "{table}enrich + IDS {prepared:.2?}, total {:.2?}",
        start.elapsed()
    );
}

/// The accessibility specification (index into the result) that lists element `id`.
fn spec_of(result: &Value, id: EntityId, set: &str) -> usize {
    specs(result)
        .iter()
        .position(|s| {
            s["name"].as_str().unwrap().contains(set)
                && s["applicable_ids"]
                    .as_array()
                    .unwrap()
                    .contains(&Value::from(id.0))
        })
        .unwrap_or_else(|| panic!("no {set} specification applies to {id}"))
}

fn assert_only_failure(result: &Value, index: usize, id: EntityId, reason: &str) {
    for (i, s) in specs(result).iter().enumerate() {
        if i != index {
            assert_eq!(
                s["status"],
                Value::Bool(true),
                "{}: {}",
                s["name"],
                s["failures"]
            );
            continue;
        }
        assert_eq!(s["status"], Value::Bool(false), "{} should fail", s["name"]);
        assert_eq!(s["failed"], 1, "{}", s["name"]);
        let failures = s["failures"].as_array().unwrap();
        assert!(!failures.is_empty());
        for f in failures {
            assert_eq!(f["id"], id.0, "{}: {f}", s["name"]);
            assert!(
                f["reason"].as_str().unwrap().contains(reason),
                "{}: {f}",
                s["name"]
            );
        }
    }
}

#[test]
fn the_ids_fails_on_a_changed_status_and_on_a_missing_set() {
    let dir = tempfile::tempdir().unwrap();
    let model = Model::open(common::shared().join("ifc/office-a.ifc")).unwrap();
    let c = classification(&model);
    let (ifc, ids) = enrich(&model, &c, "POINAV_", dir.path());
    let door = c
        .elements
        .iter()
        .find(|e| e.class == "IfcDoor" && e.accessibility.is_some())
        .expect("office-a has doors");
    let old = door.accessibility.as_ref().unwrap().status;

    // 1. An IDS that claims another status for one door.
    let mut changed = c.clone();
    let new = if old == AccessibilityStatus::Blocked {
        AccessibilityStatus::FullAccess
    } else {
        AccessibilityStatus::Blocked
    };
    let k = changed
        .elements
        .iter()
        .position(|e| e.id == door.id)
        .unwrap();
    changed.elements[k].accessibility.as_mut().unwrap().status = new;
    let changed_ids = dir.path().join("changed.ids");
    write_ids(&changed_ids, &model, &changed, &opts("POINAV_")).unwrap();

    // 2. The enriched file with the door taken out of its POINAV_RobotAccessibility relation.
    let enriched = Model::open(&ifc).unwrap();
    let rel = enriched
        .instances_of("IfcRelDefinesByProperties")
        .into_iter()
        .find(|r| {
            r.get_ref("RelatingPropertyDefinition")
                .and_then(|p| p.name())
                .as_deref()
                == Some("POINAV_RobotAccessibility")
                && r.get_refs("RelatedObjects")
                    .iter()
                    .any(|o| o.id() == door.id)
        })
        .expect("the door's accessibility relation");
    let mut ed = Editor::new(&enriched);
    let rest: Vec<Arg> = rel
        .get_refs("RelatedObjects")
        .iter()
        .filter(|o| o.id() != door.id)
        .map(|o| Arg::Ref(o.id()))
        .collect();
    if rest.is_empty() {
        ed.remove(rel.id()).unwrap();
    } else {
        ed.set_attr(rel.id(), "RelatedObjects", Arg::List(rest))
            .unwrap();
    }
    let tampered = dir.path().join("tampered.ifc");
    ed.write(&tampered).unwrap();

    let results = ifctester(&[
        (ids.clone(), ifc.clone()),
        (changed_ids, ifc),
        (ids, tampered),
    ]);
    assert_passes("office-a POINAV_", &results[0], &c);

    let i = spec_of(&results[1], door.id, "POINAV_RobotAccessibility");
    let name = specs(&results[1])[i]["name"].as_str().unwrap();
    assert!(
        name.starts_with("IfcDoor POINAV_RobotAccessibility: ") && name.contains(new.label()),
        "{name}"
    );
    assert_only_failure(
        &results[1],
        i,
        door.id,
        &format!("\"{}\" does not match", old.label()),
    );

    // ifctester still applies the specification to the door (by GlobalId), which now lacks the set.
    let i = spec_of(&results[2], door.id, "POINAV_RobotAccessibility");
    assert_only_failure(
        &results[2],
        i,
        door.id,
        "The required property set does not exist",
    );
}

/// A small IFC2X3 file where an IfcWallStandardCase is typed by an IfcWallType: IDS applies the
/// IFCWALL entity facet to it too (IFC2X3 rule), so the IfcWall specification must restrict
/// GlobalId. Also an awkward file name and set prefix, to exercise XML escaping end to end.
#[test]
fn ifc2x3_type_rule_and_escaping_hold_under_ifctester() {
    let dir = tempfile::tempdir().unwrap();
    let text = "ISO-10303-21;\nHEADER;\nFILE_DESCRIPTION(('ViewDefinition [CoordinationView]'),'2;1');\n\
        FILE_NAME('t.ifc','2026-01-01T00:00:00',(''),(''),'','','');\nFILE_SCHEMA(('IFC2X3'));\nENDSEC;\nDATA;\n\
        #1=IFCPERSON($,$,'x',$,$,$,$,$);\n#2=IFCORGANIZATION($,'org',$,$,$);\n#3=IFCPERSONANDORGANIZATION(#1,#2,$);\n\
        #4=IFCAPPLICATION(#2,'1','app','app');\n#5=IFCOWNERHISTORY(#3,#4,$,.ADDED.,$,$,$,0);\n\
        #6=IFCSIUNIT(*,.LENGTHUNIT.,.MILLI.,.METRE.);\n#7=IFCUNITASSIGNMENT((#6));\n\
        #8=IFCPROJECT('0YvctVUKr0kugbFTf53O9L',#5,'P',$,$,$,$,$,#7);\n\
        #10=IFCWALL('1YvctVUKr0kugbFTf53O9L',#5,'Wall & <Co>',$,$,$,$,$);\n\
        #11=IFCWALLSTANDARDCASE('2YvctVUKr0kugbFTf53O9L',#5,'Typed wall',$,$,$,$,$);\n\
        #12=IFCWALLTYPE('3YvctVUKr0kugbFTf53O9L',#5,'Type',$,$,$,$,$,$,.STANDARD.);\n\
        #13=IFCRELDEFINESBYTYPE('4YvctVUKr0kugbFTf53O9L',#5,$,$,(#11),#12);\n\
        #14=IFCDOOR('5YvctVUKr0kugbFTf53O9L',#5,'D\\X2\\00FC\\X0\\r',$,$,$,$,$,2100.,1000.);\n\
        #15=IFCDOOR('6YvctVUKr0kugbFTf53O9L',#5,'Narrow',$,$,$,$,$,2100.,700.);\n\
        ENDSEC;\nEND-ISO-10303-21;\n";
    let input = dir.path().join("wälle & \"türen\" <2x3>.ifc");
    std::fs::write(&input, text).unwrap();
    let model = Model::open(&input).unwrap();
    let c = classification(&model);
    let classes: BTreeSet<&str> = c.elements.iter().map(|e| e.class.as_str()).collect();
    assert_eq!(
        classes,
        BTreeSet::from(["IfcDoor", "IfcWall", "IfcWallStandardCase"]),
        "{:#?}",
        c.elements
    );

    let prefix = "Ünï&<\"'>_";
    let out = dir.path().join("out");
    std::fs::create_dir(&out).unwrap();
    let (ifc, ids) = enrich(&model, &c, prefix, &out);
    let text = std::fs::read_to_string(&ids).unwrap();
    assert!(
        text.contains(
            "<ids:title>Robot POI enrichment of wälle &amp; \"türen\" &lt;2x3&gt;.ifc (poinav "
        ),
        "{text}"
    );
    assert!(
        text.contains("<ids:simpleValue>Ünï&amp;&lt;\"'&gt;_POI_Classification</ids:simpleValue>"),
        "{text}"
    );
    let wall_spec = text
        .split("<ids:specification ")
        .find(|s| s.contains("IFCWALL<"))
        .unwrap();
    assert!(
        wall_spec.contains("<xs:enumeration value=\"1YvctVUKr0kugbFTf53O9L\"/>"),
        "{wall_spec}"
    );
    let wsc_spec = text
        .split("<ids:specification ")
        .find(|s| s.contains("IFCWALLSTANDARDCASE<"))
        .unwrap();
    assert!(!wsc_spec.contains("GlobalId"), "{wsc_spec}");

    let results = ifctester(&[(ids, ifc)]);
    assert_passes("handmade IFC2X3", &results[0], &c);
}
