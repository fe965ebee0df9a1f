//! Every element and space IfcOpenShell meshes, poinav meshes too: on the small corpus files
//! (IfcOpenShell live, one Python process), the elements meshed by IfcOpenShell and not by
//! [`mesh_model`] are none, and those meshed by poinav alone are the listed ones. The larger
//! files are compared by `bench/coverage_vs_ifcopenshell.py` (IfcOpenShell takes minutes on
//! them); its table is in the README.

mod common;

use std::collections::{BTreeMap, BTreeSet};

use poinav_geom::mesh_model;
use poinav_ifc::Model;

/// The files compared here: every corpus file IfcOpenShell meshes in a few seconds.
const FILES: [&str; 7] = [
    "ifc4-test-model.ifc",
    "ifcopenhouse-ifc4.ifc",
    "nested-mapped-item.ifc",
    "ramps-extract.ifc",
    "revit-japanese-x2.ifc",
    "wall-door-column-ifc4x3.ifc",
    "wall-opening-window-ifc4x3.ifc",
];

/// Products poinav meshes and IfcOpenShell 0.9 does not (it returns no shape for them): a
/// stair of 33 faceted breps and a railing of 39 mapped items, both real obstacles.
const POINAV_ONLY: [(&str, &str); 2] = [
    ("nested-mapped-item.ifc", "2Kkkz43YFqUW00000007yI"),
    ("nested-mapped-item.ifc", "2Kkkz43YFqUW00000007yQ"),
];

#[test]
fn every_element_ifcopenshell_meshes_is_meshed() {
    let python = common::python();
    let paths: Vec<_> = FILES.iter().map(|f| common::corpus_file(f)).collect();
    let args: Vec<&std::ffi::OsStr> = paths.iter().map(|p| p.as_os_str()).collect();
    let ios = poinav_testkit::ifcos_with(&python, "meshed_guids.py", &args);
    let mut ios_total = 0;
    let mut missing = Vec::new();
    let mut extra = BTreeSet::new();
    for (name, path) in FILES.iter().zip(&paths) {
        let theirs: BTreeMap<String, String> =
            serde_json::from_value(ios[path.to_string_lossy().as_ref()].clone())
                .unwrap_or_else(|e| panic!("{name}: IfcOpenShell's listing: {e}"));
        let model = Model::open(path).unwrap();
        let m = mesh_model(&model);
        let ours: BTreeSet<String> = m
            .elements
            .iter()
            .chain(&m.spaces)
            .map(|e| model.entity(e.product).unwrap().global_id().unwrap())
            .collect();
        let failures: BTreeMap<String, String> = m
            .failures
            .iter()
            .map(|(id, e)| {
                let guid = model.entity(*id).unwrap().global_id().unwrap_or_default();
                (guid, e.to_string())
            })
            .collect();
        // IfcOpenShell also meshes sites, annotations and the like, which poinav does not.
        let candidates: BTreeSet<String> = model
            .instances_of("IfcElement")
            .into_iter()
            .chain(model.instances_of("IfcSpace"))
            .filter(|p| !p.is_a("IfcFeatureElementSubtraction"))
            .filter_map(|p| p.global_id())
            .collect();
        let theirs: BTreeMap<_, _> = theirs
            .into_iter()
            .filter(|(g, _)| candidates.contains(g))
            .collect();
        assert!(!theirs.is_empty(), "{name}: IfcOpenShell meshed nothing");
        ios_total += theirs.len();
        for (guid, class) in &theirs {
            if !ours.contains(guid) {
                let why = failures.get(guid).map_or("not meshed", String::as_str);
                missing.push(format!("{name}: {class} {guid}: {why}"));
            }
        }
        extra.extend(
            ours.iter()
                .filter(|g| !theirs.contains_key(*g))
                .map(|g| (name.to_string(), g.clone())),
        );
    }
    assert!(
        missing.is_empty(),
        "{} of {ios_total} elements meshed by IfcOpenShell and not by poinav:\n{}",
        missing.len(),
        missing.join("\n")
    );
    let expected: BTreeSet<(String, String)> = POINAV_ONLY
        .iter()
        .map(|(f, g)| (f.to_string(), g.to_string()))
        .collect();
    assert_eq!(extra, expected, "meshed by poinav and not by IfcOpenShell");
    // 22 + 34 + 55 + 3 + 22 + 3 + 2 elements and spaces.
    assert_eq!(
        ios_total, 141,
        "elements IfcOpenShell meshes in these files"
    );
}
