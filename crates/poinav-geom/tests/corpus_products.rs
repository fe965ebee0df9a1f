//! Every door and every product with a representation on every corpus file: door frames and
//! footprints are read without a panic, doors get the footprint of the opening they fill and
//! sit in it, and the products whose geometry cannot be read are the kinds listed here.

mod common;

use std::collections::BTreeMap;

use poinav_geom::{door_geometry, footprint_of, PlacementCache};
use poinav_ifc::Model;

#[test]
fn doors_sit_in_the_openings_they_fill() {
    let (mut doors, mut in_opening) = (0, 0);
    let mut problems = Vec::new();
    for file in common::corpus() {
        let name = file.file_name().unwrap().to_string_lossy().into_owned();
        let model = Model::open(&file).unwrap();
        let mut cache = PlacementCache::new(&model);
        for door in model.instances_of("IfcDoor") {
            doors += 1;
            let g = door_geometry(&mut cache, door)
                .unwrap_or_else(|e| panic!("{name}: door {}: {e}", door.id()));
            let origin = g.placement.translation;
            let Some(f) = &g.footprint else {
                problems.push(format!(
                    "{name}: door {} has no footprint: {:?}",
                    door.id(),
                    g.problems
                ));
                continue;
            };
            let opening = door
                .inverse("FillsVoids")
                .iter()
                .find_map(|r| r.get_ref("RelatingOpeningElement"));
            if opening.is_some() && g.footprint_of == opening.map(|o| o.id()) {
                in_opening += 1;
            }
            // The door's origin lies on (or within 30 cm of) the footprint, at its floor
            // level or above, and the centre is inside the footprint.
            let d = f.distance_to(origin.truncate());
            if d > 0.3 || origin.z < f.z_min - 0.05 || origin.z > f.z_max {
                problems.push(format!(
                    "{name}: door {} origin {origin} is {d:.3} m from its footprint, z {:.3}..{:.3}",
                    door.id(),
                    f.z_min,
                    f.z_max
                ));
            }
            if !f.contains(g.center.truncate()) {
                problems.push(format!(
                    "{name}: door {} centre outside its footprint",
                    door.id()
                ));
            }
            let h = f.height();
            if !(1.5..=4.0).contains(&h) {
                problems.push(format!(
                    "{name}: door {} footprint {h:.3} m high",
                    door.id()
                ));
            }
        }
    }
    eprintln!("{in_opening} of {doors} doors have their opening's footprint");
    assert!(doors >= 579, "only {doors} doors");
    assert!(in_opening + 1 >= doors, "{in_opening} of {doors}");
    assert!(problems.is_empty(), "{}", problems.join("\n"));
}

#[test]
fn every_product_footprint_is_read_or_a_named_error() {
    let mut report = BTreeMap::new();
    for file in common::corpus() {
        let name = file.file_name().unwrap().to_string_lossy().into_owned();
        let model = Model::open(&file).unwrap();
        let mut cache = PlacementCache::new(&model);
        let (mut n, mut ok) = (0usize, 0usize);
        let mut errors: BTreeMap<String, usize> = BTreeMap::new();
        // The railway's 9,477 sleepers all read the same 7,000-point map: every 25th product
        // of it stands for the rest (reading them all takes minutes in a debug build).
        let step = if name == "railway-track-ifc4x3.ifc" {
            25
        } else {
            1
        };
        for product in model.instances_of("IfcProduct").into_iter().step_by(step) {
            if product.get("Representation").is_none() {
                continue;
            }
            n += 1;
            match footprint_of(&mut cache, product) {
                Ok(f) => {
                    ok += 1;
                    let fp = &f.footprint;
                    assert!(fp.area() > 0.0 && fp.z_min <= fp.z_max, "{name}: {fp:?}");
                }
                Err(e) => {
                    let msg = e.to_string();
                    assert!(msg.starts_with(&e.id().to_string()), "{msg}");
                    let what = msg.split_once(": ").map_or(&msg[..], |m| m.1);
                    *errors
                        .entry(format!("{} {what}", product.type_name()))
                        .or_default() += 1;
                }
            }
        }
        // Outside the infrastructure model every product but annotations has a footprint.
        if name != "railway-track-ifc4x3.ifc" {
            let annotations: usize = errors
                .iter()
                .filter(|(k, _)| k.starts_with("IfcAnnotation "))
                .map(|(_, v)| v)
                .sum();
            assert_eq!(ok + annotations, n, "{name}: {errors:#?}");
        }
        report.insert(name, (ok, n, errors));
    }
    eprintln!("footprints read per file (ok, products with a representation, errors): {report:#?}");
}
