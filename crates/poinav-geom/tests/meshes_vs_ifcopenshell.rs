//! Element meshes agree with IfcOpenShell's (run live, `tests/ifcos/meshes.py`: its
//! iterator in world coordinates with default settings, so openings are subtracted): every
//! wall, door, slab, column and window IfcOpenShell meshes is meshed here too, with its
//! bounding box within 1 cm for at least 99 % of them, the total surface area of the walls of
//! each file within 1 % (openings are cut as IfcOpenShell cuts them), and the same colour as
//! IfcOpenShell's first surface style wherever both have one.

mod common;

use std::collections::BTreeMap;

use poinav_geom::mesh_model;
use poinav_ifc::Model;

const FILES: [&str; 5] = [
    "fzk-haus-ifc4.ifc",
    "duplex-apartment.ifc",
    "office-a.ifc",
    "ifc4-test-model.ifc",
    "wall-door-column-ifc4x3.ifc",
];

/// Bounding boxes agree when every coordinate of both corners is this close (metres).
const BOX_TOLERANCE: f64 = 0.01;

#[derive(Debug, Default)]
struct FileAgreement {
    compared: usize,
    box_ok: usize,
    worst_box: f64,
    walls: usize,
    wall_area: f64,
    reference_wall_area: f64,
    coloured: usize,
    colour_ok: usize,
}

#[test]
fn meshes_match_ifcopenshell() {
    let python = common::python();
    // IfcOpenShell runs for all files at once (office-a takes it several seconds).
    let children: Vec<_> = FILES
        .iter()
        .map(|f| common::spawn_ifcos(&python, "meshes.py", &common::corpus_file(f)))
        .collect();
    let mut report = BTreeMap::new();
    let mut problems = Vec::new();
    for (name, child) in FILES.iter().zip(children) {
        let model = Model::open(common::corpus_file(name)).unwrap();
        let ours = mesh_model(&model);
        let by_guid: BTreeMap<&str, _> = ours
            .elements
            .iter()
            .map(|e| (e.global_id.as_str(), e))
            .collect();
        let theirs = common::json_of(child, &format!("meshes.py {name}"));
        let mut a = FileAgreement::default();
        for (guid, r) in theirs.as_object().unwrap() {
            a.compared += 1;
            let class = r["class"].as_str().unwrap();
            let Some(e) = by_guid.get(guid.as_str()) else {
                let failure = ours.failures.iter().find(|(id, _)| {
                    model.entity(*id).and_then(|p| p.global_id()) == Some(guid.clone())
                });
                problems.push(format!("{name} {class} {guid}: not meshed: {failure:?}"));
                continue;
            };
            let (lo, hi) = e.mesh.bounds().unwrap();
            let reference = common::ReferenceBox::of(r, name);
            let err = reference.error((lo, hi));
            let (rlo, rhi) = (reference.lo, reference.hi);
            a.worst_box = a.worst_box.max(err);
            if err <= BOX_TOLERANCE {
                a.box_ok += 1;
            } else {
                problems.push(format!(
                    "{name} {class} {} {guid}: box {lo}..{hi}, IfcOpenShell {rlo:?}..{rhi:?}",
                    e.product
                ));
            }
            if class.starts_with("IfcWall") {
                a.walls += 1;
                a.wall_area += e.mesh.area();
                a.reference_wall_area += r["area"].as_f64().unwrap();
            }
            let first = r["colours"].as_array().and_then(|c| c.first());
            if let (Some(c), Some(theirs)) = (e.color, first) {
                a.coloured += 1;
                let t: Vec<f64> = theirs
                    .as_array()
                    .unwrap()
                    .iter()
                    .map(|x| x.as_f64().unwrap())
                    .collect();
                if (0..4).all(|i| (f64::from(c[i]) - t[i]).abs() < 0.01) {
                    a.colour_ok += 1;
                } else {
                    problems.push(format!(
                        "{name} {class} {} {guid}: colour {c:?}, IfcOpenShell {t:?}",
                        e.product
                    ));
                }
            }
        }
        report.insert(*name, a);
    }
    for (name, a) in &report {
        eprintln!(
            "{name}: {} elements compared, boxes within 1 cm {}/{} (worst {:.2e} m), \
             wall area {:.3} m2 vs IfcOpenShell {:.3} m2 over {} walls (ratio {:.5}), colours {}/{}",
            a.compared,
            a.box_ok,
            a.compared,
            a.worst_box,
            a.wall_area,
            a.reference_wall_area,
            a.walls,
            a.wall_area / a.reference_wall_area,
            a.colour_ok,
            a.coloured
        );
    }
    eprintln!("disagreements:\n{}", problems.join("\n"));
    let compared: usize = report.values().map(|a| a.compared).sum();
    assert!(compared >= 800, "only {compared} elements compared");
    for (name, a) in &report {
        assert!(a.compared > 0 && a.walls > 0, "{name}: nothing compared");
        assert!(
            a.box_ok * 100 >= a.compared * 99,
            "{name}: {} of {} boxes within 1 cm:\n{}",
            a.box_ok,
            a.compared,
            problems.join("\n")
        );
        let ratio = a.wall_area / a.reference_wall_area;
        assert!(
            (ratio - 1.0).abs() <= 0.01,
            "{name}: wall area {ratio} of IfcOpenShell's"
        );
        assert!(
            a.colour_ok * 100 >= a.coloured * 95,
            "{name}: colours {}/{}",
            a.colour_ok,
            a.coloured
        );
    }
    assert!(
        !problems.iter().any(|p| p.contains("not meshed")),
        "{}",
        problems.join("\n")
    );
}
