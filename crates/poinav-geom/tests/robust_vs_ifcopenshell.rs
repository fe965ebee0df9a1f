//! Elements with broken or odd parts are meshed as IfcOpenShell meshes them (run live:
//! `tests/ifcos/author_robust.py` writes one element per case with IfcOpenShell's API and
//! meshes them): a profile drawn as a star in one stroke, walls whose opening cannot be made
//! (kept uncut, a warning naming the opening), boolean results whose second operand cannot be
//! made (the first operand kept, a warning naming the operand), boolean results whose first
//! operand cannot be made (left out with a warning, as IfcOpenShell leaves it out), a surface
//! model's face of 401 points drawn as a star in one stroke (filled, its area within 1 %), a
//! surface model's disc bounded by an edge loop of two half circles and a face with two
//! outer bounds (their areas within 1 %), mirrored profiles and a curve bounded plane. Every case is meshed, its bounding box within
//! 1 cm of IfcOpenShell's and, for closed solids, its volume within 1 %.

mod common;

use std::collections::BTreeMap;

use poinav_geom::{footprint_of, mesh_model, GeomError, PlacementCache};
use poinav_ifc::{EntityId, Model};

/// Bounding boxes agree when every coordinate of both corners is this close (metres).
const BOX_TOLERANCE: f64 = 0.01;

/// Volumes of closed solids agree within this fraction.
const VOLUME_TOLERANCE: f64 = 0.01;

/// The cases the script writes.
const CASES: usize = 20;

#[test]
fn broken_and_odd_parts_are_meshed_as_ifcopenshell_meshes_them() {
    let python = common::python();
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("robust.ifc");
    let reference = poinav_testkit::ifcos_with(&python, "author_robust.py", &[path.as_os_str()]);
    let reference = reference.as_object().unwrap();
    assert_eq!(reference.len(), CASES, "cases written");
    let model = Model::open(&path).unwrap();
    let meshes = mesh_model(&model);
    assert!(meshes.failures.is_empty(), "{:?}", meshes.failures);
    let ours: BTreeMap<String, _> = meshes
        .elements
        .iter()
        .map(|e| (e.name.clone().unwrap(), e))
        .collect();
    let mut problems = Vec::new();
    for (name, theirs) in reference {
        let Some(e) = ours.get(name) else {
            problems.push(format!("{name}: not meshed"));
            continue;
        };
        let (lo, hi) = e.mesh.bounds().unwrap();
        let reference = common::ReferenceBox::of(theirs, name);
        let box_err = reference.error((lo, hi));
        let (rlo, rhi) = (reference.lo, reference.hi);
        let their_volume = theirs["volume"].as_f64().unwrap();
        let volume = e.mesh.volume();
        eprintln!(
            "{name:34} box within {box_err:.1e} m, volume {volume:.6} vs {their_volume:.6} m3"
        );
        if box_err > BOX_TOLERANCE {
            problems.push(format!(
                "{name}: box {lo}..{hi}, IfcOpenShell {rlo:?}..{rhi:?}"
            ));
        }
        // The curve bounded plane is a surface: no volume. (IfcOpenShell 0.9 also draws its
        // hole as a face of its own; its area here is the schema's, 6 - 0.5 m2.)
        if name == "curve_bounded_plane" {
            if (e.mesh.area() - 5.5).abs() > 1e-9 {
                problems.push(format!("{name}: area {}", e.mesh.area()));
            }
        } else if [
            "star_face_401",
            "edge_loop_disc_face",
            "two_outer_bounds_face",
        ]
        .contains(&name.as_str())
        {
            // Surfaces too: their area (the star filled, the disc, both rectangles of the
            // face with two outer bounds) within 1 %.
            let their_area = theirs["area"].as_f64().unwrap();
            eprintln!("{name:34} area {:.6} vs {their_area:.6} m2", e.mesh.area());
            if (e.mesh.area() / their_area - 1.0).abs() > VOLUME_TOLERANCE {
                problems.push(format!(
                    "{name}: area {} m2, IfcOpenShell {their_area}",
                    e.mesh.area()
                ));
            }
        } else if (volume / their_volume - 1.0).abs() > VOLUME_TOLERANCE {
            problems.push(format!(
                "{name}: volume {volume} m3, IfcOpenShell {their_volume} m3"
            ));
        }
        // What could not be made is named in one warning each, and nothing else is.
        let expected: Vec<EntityId> = theirs
            .get("left_out")
            .and_then(|v| v.as_array())
            .map(|ids| ids.iter().map(|i| EntityId(i.as_u64().unwrap())).collect())
            .unwrap_or_default();
        let warned: Vec<EntityId> = meshes
            .uncut
            .iter()
            .filter(|(id, _)| *id == e.product)
            .map(|(_, w)| match w {
                GeomError::LeftUncut { operand, .. } => *operand,
                other => panic!("{name}: {other}"),
            })
            .collect();
        if warned != expected {
            problems.push(format!(
                "{name}: warned about {warned:?}, expected {expected:?}"
            ));
        }
    }
    assert!(problems.is_empty(), "{}", problems.join("\n"));

    // The star: 1,001 crossings resolved into the regular 1001-gon less its notches.
    let star = &ours["star_1001"].mesh;
    assert!(
        (star.volume() - std::f64::consts::PI).abs() < 1e-4,
        "{}",
        star.volume()
    );
    // The disc bounded by an edge loop has a footprint too: its 2 m box (5 m along y per case).
    let disc = ours["edge_loop_disc_face"];
    let product = model.entity(disc.product).unwrap();
    let footprint = footprint_of(&mut PlacementCache::new(&model), product)
        .unwrap()
        .footprint;
    let (lo, hi) = footprint.polygon.iter().fold(
        (glam::DVec2::splat(f64::MAX), glam::DVec2::splat(f64::MIN)),
        |(lo, hi), p| (lo.min(*p), hi.max(*p)),
    );
    let y = disc.mesh.bounds().unwrap().0.y + 1.0;
    assert!(
        (lo - glam::DVec2::new(-1.0, y - 1.0)).abs().max_element() < 1e-6
            && (hi - glam::DVec2::new(1.0, y + 1.0)).abs().max_element() < 1e-6,
        "{lo}..{hi}"
    );
    // A wall kept whole names the opening element that could not be made, and why.
    let (wall, warning) = meshes
        .uncut
        .iter()
        .find(|(id, _)| *id == ours["opening_depth_zero"].product)
        .unwrap();
    let opening = model.entity(*wall).unwrap().inverse("HasOpenings")[0]
        .get_ref("RelatedOpeningElement")
        .unwrap();
    assert_eq!(
        warning.to_string(),
        format!(
            "{wall}: IfcWall is meshed without {} (IfcOpeningElement): \
             {}: degenerate geometry: Depth is not a positive number",
            opening.id(),
            opening
                .get_ref("Representation")
                .unwrap()
                .get_refs("Representations")[0]
                .get_refs("Items")[0]
                .id()
        )
    );
    assert!(std::error::Error::source(warning).is_some());
}
