//! `IfcExtrudedAreaSolid`: a profile (holes included) swept along a direction, as a closed
//! triangle mesh: the two caps triangulated with their holes, one quad per profile edge.

use glam::{DAffine3, DVec3};
use poinav_ifc::Entity;

use crate::axis2_placement::axis2placement_3d;
use crate::direction::direction;
use crate::error::{degenerate, missing, required_ref, GeomError};
use crate::mesh::Mesh;
use crate::profile::{self, ProfileArea};
use crate::triangulation::triangulate_2d;
use crate::unit_assignment::Units;

/// The mesh of an `IfcExtrudedAreaSolid` in the coordinates of the representation it is an
/// item of (metres): its `Position` applied.
pub fn extruded_area_solid(item: Entity<'_>, units: &Units) -> Result<Mesh, GeomError> {
    let profile = required_ref(&item, "SweptArea", "IfcProfileDef")?;
    let areas = profile::areas(profile, units)?;
    let (position, sweep) = extrusion_frame(item, units)?;
    let mut mesh = extrude(&areas, sweep).ok_or_else(|| {
        degenerate(
            &item,
            "the profile cannot be triangulated or is swept along its own plane",
        )
    })?;
    mesh.transform(&position);
    Ok(mesh)
}

/// The `Position` of an `IfcExtrudedAreaSolid` and its sweep (ExtrudedDirection x Depth), both
/// in metres; an error when Depth is missing or not positive.
pub fn extrusion_frame(item: Entity<'_>, units: &Units) -> Result<(DAffine3, DVec3), GeomError> {
    let s = units.metres_per_unit;
    let position = match item.get("Position") {
        Some(_) => axis2placement_3d(
            item.get_ref("Position")
                .ok_or_else(|| missing(&item, "Position"))?,
            s,
        )?,
        None => DAffine3::IDENTITY,
    };
    let dir = direction(required_ref(&item, "ExtrudedDirection", "IfcDirection")?)?;
    let depth = item
        .get_f64("Depth")
        .ok_or_else(|| missing(&item, "Depth"))?;
    if !(depth.is_finite() && depth > 0.0) {
        return Err(degenerate(&item, "Depth is not a positive number"));
    }
    Ok((position, dir * depth * s))
}

/// The closed mesh of `areas` (in the plane z = 0) swept by `sweep`, triangles facing out.
/// `None` when `sweep` lies in the profile's plane or a cap cannot be triangulated.
pub fn extrude(areas: &[ProfileArea], sweep: DVec3) -> Option<Mesh> {
    if !sweep.is_finite() || sweep.z.abs() <= 1e-9 * sweep.abs().max_element() {
        return None;
    }
    let mut mesh = Mesh::default();
    for area in areas {
        let base = mesh.positions.len() as u32;
        let rings: Vec<&[glam::DVec2]> = std::iter::once(&area.outer[..])
            .chain(area.holes.iter().map(|h| &h[..]))
            .collect();
        let n = rings.iter().map(|r| r.len()).sum::<usize>() as u32;
        let cap = triangulate_2d(&area.outer, &area.holes)?;
        for ring in &rings {
            mesh.positions.extend(ring.iter().map(|p| p.extend(0.0)));
        }
        for ring in &rings {
            mesh.positions
                .extend(ring.iter().map(|p| p.extend(0.0) + sweep));
        }
        // Bottom cap faces against the sweep, the top cap with it.
        for t in &cap {
            mesh.triangles.push([base + t[0], base + t[2], base + t[1]]);
            mesh.triangles.push(t.map(|i| base + n + i));
        }
        // Sides: the outer ring is counter-clockwise and holes clockwise, so the right of
        // each edge is outside the material.
        let mut start = base;
        for ring in &rings {
            let len = ring.len() as u32;
            for i in 0..len {
                let a = start + i;
                let b = start + (i + 1) % len;
                mesh.triangles.push([a, b, b + n]);
                mesh.triangles.push([a, b + n, a + n]);
            }
            start += len;
        }
    }
    if sweep.z < 0.0 {
        mesh.flip();
    }
    Some(mesh)
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec2;

    #[test]
    fn slanted_box_with_a_hole_is_closed_and_faces_out() {
        let sq = |h: f64| {
            vec![
                DVec2::new(-h, -h),
                DVec2::new(h, -h),
                DVec2::new(h, h),
                DVec2::new(-h, h),
            ]
        };
        let mut hole = sq(0.5);
        hole.reverse();
        let area = ProfileArea {
            outer: sq(1.0),
            holes: vec![hole],
        };
        for sweep in [DVec3::new(0.0, 0.0, 2.0), DVec3::new(1.0, 0.0, -2.0)] {
            let m = extrude(std::slice::from_ref(&area), sweep).unwrap();
            // Volume is area times height whatever the slant.
            assert!((m.volume() - 3.0 * 2.0).abs() < 1e-12, "{}", m.volume());
        }
        assert!(extrude(&[area], DVec3::X).is_none());
    }

    #[test]
    fn points_on_straight_edges_are_shared_by_caps_and_sides() {
        // A 4 x 2 rectangle with a point in the middle of each side, and a hole: bridging
        // the hole, the ear clipper leaves those four points out of the caps; put back, every
        // edge of the closed mesh is used once each way (no T-junction between a cap and the
        // sides).
        let ring = |pts: &[(f64, f64)]| -> Vec<DVec2> {
            pts.iter().map(|&(x, y)| DVec2::new(x, y)).collect()
        };
        let area = ProfileArea {
            outer: ring(&[
                (0., 0.),
                (2., 0.),
                (4., 0.),
                (4., 1.),
                (4., 2.),
                (2., 2.),
                (0., 2.),
                (0., 1.),
            ]),
            holes: vec![ring(&[
                (0.5, 0.25),
                (0.5, 0.75),
                (0.75, 0.75),
                (0.75, 0.25),
            ])],
        };
        let m = extrude(&[area], DVec3::Z).unwrap();
        let mut directed = std::collections::BTreeMap::new();
        for t in &m.triangles {
            for k in 0..3 {
                *directed.entry((t[k], t[(k + 1) % 3])).or_insert(0) += 1;
            }
        }
        assert!(
            directed
                .iter()
                .all(|(&(a, b), &n)| n == 1 && directed.get(&(b, a)) == Some(&1)),
            "{:?}",
            m.triangles
        );
        assert!((m.volume() - 7.875).abs() < 1e-12);
    }
}
