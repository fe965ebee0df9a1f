//! Every element and space of every corpus file is meshed or is a failure naming its `#id`,
//! in file order, without a panic; meshes are finite and well indexed; the result does not
//! depend on the number of threads. Counts per file are printed.

mod common;

use std::collections::BTreeMap;

use poinav_geom::element_mesh::meshed_products;
use poinav_geom::{mesh_model, GeomError, ModelMeshes};
use poinav_ifc::Model;

fn check(name: &str, model: &Model, m: &ModelMeshes) {
    let products = meshed_products(model);
    let mut seen: Vec<_> = m
        .elements
        .iter()
        .chain(&m.spaces)
        .map(|e| e.product)
        .chain(m.failures.iter().map(|f| f.0))
        .collect();
    assert_eq!(
        seen.len(),
        products.len(),
        "{name}: products lost or repeated"
    );
    seen.sort();
    let mut expected: Vec<_> = products.iter().map(|p| p.id()).collect();
    expected.sort();
    assert_eq!(seen, expected, "{name}");
    let position = |id| model.entity(id).unwrap().position();
    for list in [&m.elements, &m.spaces] {
        assert!(
            list.windows(2)
                .all(|w| position(w[0].product) < position(w[1].product)),
            "{name}: not in file order"
        );
    }
    for e in m.elements.iter().chain(&m.spaces) {
        let n = e.mesh.positions.len() as u32;
        assert!(
            !e.mesh.is_empty() && e.mesh.is_finite(),
            "{name} {}",
            e.product
        );
        assert!(
            e.mesh.triangles.iter().flatten().all(|&i| i < n),
            "{name} {}",
            e.product
        );
        assert_eq!(e.class, model.entity(e.product).unwrap().type_name());
        assert!(!e.class.starts_with("IfcOpening"), "{name}: {}", e.class);
    }
    for (id, e) in &m.failures {
        let msg = e.to_string();
        assert!(
            msg.starts_with(&format!("{}: ", e.id())),
            "{name} {id}: {msg}"
        );
    }
}

#[test]
fn every_corpus_element_is_meshed_or_a_named_failure() {
    let mut report = BTreeMap::new();
    for file in common::corpus() {
        let name = file.file_name().unwrap().to_string_lossy().into_owned();
        let model = Model::open(&file).unwrap();
        let m = mesh_model(&model);
        check(&name, &model, &m);
        let mut kinds: BTreeMap<String, usize> = BTreeMap::new();
        for (id, e) in &m.failures {
            let class = model.entity(*id).unwrap().type_name();
            let why = e.to_string();
            let why = why.split_once(": ").map_or(&why[..], |w| w.1);
            *kinds.entry(format!("{class}: {why}")).or_default() += 1;
        }
        // Only elements whose openings remove all of them fail (window frames modelled as
        // walls that their own openings swallow; IfcOpenShell produces no shape for them
        // either); the railway's sleepers, placed along its alignment, and its courses and
        // rails, swept along it, are all meshed.
        assert!(
            m.failures
                .iter()
                .all(|(_, e)| matches!(e, GeomError::Empty { .. })),
            "{name}: {kinds:#?}"
        );
        assert!(!m.elements.is_empty(), "{name}: no element meshed");
        let triangles: usize = m
            .elements
            .iter()
            .chain(&m.spaces)
            .map(|e| e.mesh.triangles.len())
            .sum();
        let coloured = m.elements.iter().filter(|e| e.color.is_some()).count();
        let in_storey = m.elements.iter().filter(|e| e.storey.is_some()).count();
        report.insert(
            name,
            format!(
                "{} elements ({coloured} coloured, {in_storey} in a storey), {} spaces, {} failures, {triangles} triangles; failures: {kinds:?}",
                m.elements.len(),
                m.spaces.len(),
                m.failures.len()
            ),
        );
    }
    eprintln!("meshes per corpus file:");
    for (name, line) in &report {
        eprintln!("  {name}: {line}");
    }
}

#[test]
fn meshes_do_not_depend_on_the_number_of_threads() {
    for name in ["duplex-apartment.ifc", "office-a.ifc"] {
        let model = Model::open(common::corpus_file(name)).unwrap();
        let one = rayon::ThreadPoolBuilder::new()
            .num_threads(1)
            .build()
            .unwrap()
            .install(|| mesh_model(&model));
        let several = rayon::ThreadPoolBuilder::new()
            .num_threads(3)
            .build()
            .unwrap()
            .install(|| mesh_model(&model));
        assert!(
            one == several,
            "{name}: meshes differ between 1 and 3 threads"
        );
    }
}
