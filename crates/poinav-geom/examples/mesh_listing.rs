//! Lists what `mesh_model` meshes, per GlobalId, as one JSON line per file (read by
//! `bench/coverage_vs_ifcopenshell.py`): `cargo run -p poinav-geom --example mesh_listing -- FILE...`.
//!
//! Each line: `{"file", "candidates": [guid...], "meshed": {guid: class},
//! "failed": {guid: [class, reason]}, "without_representation": {guid: class}}`, where the
//! candidates are every element but openings, and every space, with or without geometry.

use std::collections::BTreeMap;

use poinav_geom::mesh_model;
use poinav_ifc::{EntityId, Model};

fn main() {
    for file in std::env::args().skip(1) {
        let model = Model::open(&file).expect("readable IFC");
        let m = mesh_model(&model);
        let guid = |id: EntityId| {
            model
                .entity(id)
                .and_then(|e| e.global_id())
                .unwrap_or_else(|| format!("{id}"))
        };
        let class = |id: EntityId| {
            model
                .entity(id)
                .map(|e| e.type_name().to_string())
                .unwrap_or_default()
        };
        let candidates: Vec<String> = model
            .instances_of("IfcElement")
            .into_iter()
            .chain(model.instances_of("IfcSpace"))
            .filter(|p| !p.is_a("IfcFeatureElementSubtraction"))
            .map(|p| guid(p.id()))
            .collect();
        let meshed: BTreeMap<String, String> = m
            .elements
            .iter()
            .chain(&m.spaces)
            .map(|e| (guid(e.product), e.class.clone()))
            .collect();
        let failed: BTreeMap<String, (String, String)> = m
            .failures
            .iter()
            .map(|(id, e)| (guid(*id), (class(*id), e.to_string())))
            .collect();
        let without: BTreeMap<String, String> = m
            .without_geometry
            .iter()
            .map(|&id| (guid(id), class(id)))
            .collect();
        let line = serde_json::json!({
            "file": file,
            "candidates": candidates,
            "meshed": meshed,
            "failed": failed,
            "without_representation": without,
        });
        println!("{line}");
    }
}
