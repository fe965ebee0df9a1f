//! IFC4X3 alignments agree with IfcOpenShell's (run live, `tests/ifcos/alignment.py`):
//! proxies placed by `IfcLinearPlacement` along an alignment the test authors with
//! `ifcopenshell.api.alignment` (line, clothoids, circular arc; constant gradients, a
//! parabolic and a circular arc) sit within 1 cm of IfcOpenShell's placements with axes within
//! 0.1 degree,
//! and their meshes' and a sectioned solid's bounding boxes are within 1 cm, and so are those
//! of open surfaces (IFC4X3 `IfcSectionedSurface` of `IfcOpenCrossProfileDef` and
//! `IfcArbitraryOpenProfileDef` sections, an extruded open cross profile), their areas within
//! 1 %, and of sectioned solids along `IfcOffsetCurveByDistances` (constant and growing
//! offsets) and along a plain 3D `IfcPolyline` (its heights kept, distance along measured in
//! space); on the corpus's
//! railway track, every product of a fixed sample IfcOpenShell meshes (track elements spread
//! over the track, courses and a rail) is meshed here too, boxes within 1 cm, and every track
//! element's linear placement resolves. The authored model has no storey and no building: it
//! gets a plan per railway part (and one for its site, holding the uncontained courses), each
//! over its whole height.

mod common;

use glam::{DMat3, DVec3};
use poinav_geom::{floor_plans, mesh_product, PlacementCache, PlanOptions};
use poinav_ifc::{EntityId, Model};
use serde_json::Value;

/// Positions and bounding boxes agree to this (metres).
const TOLERANCE: f64 = 0.01;

/// Axes agree to this (degrees).
const ANGLE_TOLERANCE: f64 = 0.1;

fn vec3(v: &Value) -> DVec3 {
    let a: Vec<f64> = v
        .as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect();
    DVec3::new(a[0], a[1], a[2])
}

/// The rotation and translation of IfcOpenShell's row-major 4 x 4 matrix.
fn matrix(v: &Value) -> (DMat3, DVec3) {
    let rows: Vec<Vec<f64>> = v
        .as_array()
        .unwrap()
        .iter()
        .map(|r| {
            r.as_array()
                .unwrap()
                .iter()
                .map(|x| x.as_f64().unwrap())
                .collect()
        })
        .collect();
    let col = |j: usize| DVec3::new(rows[0][j], rows[1][j], rows[2][j]);
    (DMat3::from_cols(col(0), col(1), col(2)), col(3))
}

fn box_error(ours: (DVec3, DVec3), theirs: &Value) -> f64 {
    let (lo, hi) = (vec3(&theirs["min"]), vec3(&theirs["max"]));
    (ours.0 - lo)
        .abs()
        .max_element()
        .max((ours.1 - hi).abs().max_element())
}

#[test]
fn alignments_match_ifcopenshell() {
    let python = common::python();
    let dir = tempfile::tempdir().unwrap();
    let authored = dir.path().join("alignment.ifc");
    let railway = common::corpus_file("railway-track-ifc4x3.ifc");
    let child = std::process::Command::new(&python)
        .arg(common::root().join("tests/ifcos/alignment.py"))
        .arg(&railway)
        .arg(&authored)
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    // The railway file, meanwhile: every track element's placement resolves.
    let rail_model = Model::open(&railway).unwrap();
    let mut rail_cache = PlacementCache::new(&rail_model);
    let mut placed = 0;
    for p in rail_model.instances_of("IfcTrackElement") {
        let t = rail_cache.product(p).unwrap();
        assert!(t.translation.is_finite());
        placed += 1;
    }
    assert_eq!(placed, 9477);
    let theirs = common::json_of(child, "alignment.py");

    // The authored alignment.
    let model = Model::open(&authored).unwrap();
    let mut cache = PlacementCache::new(&model);
    let by_guid: std::collections::HashMap<String, _> = model
        .instances_of("IfcProduct")
        .into_iter()
        .filter_map(|p| Some((p.global_id()?, p)))
        .collect();
    let shapes = theirs["authored"].as_object().unwrap();
    assert_eq!(
        shapes.len(),
        15,
        "IfcOpenShell meshed 7 proxies, the course, 4 surfaces, 2 courses on offset curves \
         and 1 on a 3D polyline"
    );
    let mut surfaces = 0;
    let (mut worst_position, mut worst_angle, mut worst_box) = (0.0f64, 0.0f64, 0.0f64);
    for (guid, shape) in shapes {
        let p = by_guid[guid];
        let mesh = mesh_product(&mut cache, p)
            .unwrap_or_else(|e| panic!("{guid} {}: {e}", shape["class"]));
        worst_box = worst_box.max(box_error(mesh.mesh.bounds().unwrap(), shape));
        // Open surfaces (sectioned surfaces of open cross profiles and open profiles, an
        // extruded open cross profile): their areas within 1 %.
        let name = shape["name"].as_str().unwrap_or_default();
        if name.starts_with("surface ") {
            let theirs = shape["area"].as_f64().unwrap();
            let ours = mesh.mesh.area();
            eprintln!("{name}: area {ours:.3} m2, IfcOpenShell {theirs:.3} m2");
            assert!(
                (ours / theirs - 1.0).abs() < 0.01,
                "{name}: area {ours} m2, IfcOpenShell {theirs} m2"
            );
            surfaces += 1;
        }
        if shape["class"] == "IfcBuildingElementProxy" {
            let (r, t) = matrix(&shape["matrix"]);
            let ours = cache.product(p).unwrap();
            worst_position = worst_position.max((ours.translation - t).length());
            for (a, b) in [
                (ours.matrix3.x_axis, r.x_axis),
                (ours.matrix3.z_axis, r.z_axis),
            ] {
                worst_angle = worst_angle.max(a.angle_between(b).to_degrees());
            }
        }
    }
    assert_eq!(surfaces, 4);
    eprintln!("authored: placements {worst_position:.2e} m, axes {worst_angle:.2e} deg, boxes {worst_box:.2e} m");
    assert!(
        worst_position < TOLERANCE,
        "placement off by {worst_position} m"
    );
    assert!(
        worst_angle < ANGLE_TOLERANCE,
        "axes off by {worst_angle} degrees"
    );
    assert!(worst_box < TOLERANCE, "authored box off by {worst_box} m");

    // Plans per facility part, the proxies' shadows 2 m x 1 m (tilted by at most 2 %).
    let plans = floor_plans(&model, &PlanOptions::default());
    let summary: Vec<(String, usize)> = plans
        .iter()
        .map(|p| (p.storey_name.clone().unwrap_or_default(), p.items.len()))
        .collect();
    let site_items: Vec<String> = plans[0]
        .items
        .iter()
        .map(|i| i.name.clone().unwrap_or_default())
        .collect();
    // The uncontained courses are on the site's plan; the extruded cross profile is a
    // vertical surface, with no shadow: its cut is a line along its three widths (2 + 3 + 1.5 m,
    // the slopes in the profile's plane, which is the plan's), drawn LINE_WIDTH_M wide with
    // square ends.
    assert_eq!(
        site_items,
        [
            "embankment",
            "surface cross slopes",
            "surface cross horizontal",
            "surface open profile",
            "surface cross extruded",
            "offset course",
            "offset course widening",
            "course on a 3D polyline"
        ]
    );
    let extruded = &plans[0].items[4];
    let w = poinav_geom::section_lines::LINE_WIDTH_M;
    let want = (6.5 + w) * w;
    assert!(
        (extruded.area() - want).abs() < w * w,
        "{} {want}",
        extruded.area()
    );
    assert_eq!(
        summary,
        [
            ("Site".to_string(), 8),
            ("West".to_string(), 4),
            ("East".to_string(), 3)
        ]
    );
    for plan in &plans[1..] {
        for item in &plan.items {
            assert!(
                (item.area() - 2.0).abs() < 0.01,
                "{}: {}",
                item.global_id,
                item.area()
            );
        }
    }
    assert!(plans[0].items[0].area() > 500.0, "the course's shadow");

    // The railway sample: all of it meshed by IfcOpenShell, and here, boxes within 1 cm.
    let sample = theirs["railway_sample"].as_array().unwrap();
    let rail = theirs["railway"].as_object().unwrap();
    assert_eq!(
        rail.len(),
        sample.len(),
        "IfcOpenShell meshed the whole sample"
    );
    let mut worst = 0.0f64;
    for id in sample {
        let id: u64 = id.as_str().unwrap()[1..].parse().unwrap();
        let p = rail_model.entity(EntityId(id)).unwrap();
        let mesh = mesh_product(&mut rail_cache, p).unwrap_or_else(|e| panic!("#{id}: {e}"));
        worst = worst.max(box_error(
            mesh.mesh.bounds().unwrap(),
            &rail[&format!("#{id}")],
        ));
    }
    eprintln!("railway: {} products, boxes {worst:.2e} m", sample.len());
    assert!(worst < TOLERANCE, "railway box off by {worst} m");
}
