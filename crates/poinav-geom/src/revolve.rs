//! `IfcRevolvedAreaSolid` and `IfcRevolvedAreaSolidTapered`: a profile turned about an axis
//! in its own plane, in angle steps of at most [`MAX_ARC_STEP`], capped unless it turns all
//! the way round; a tapered one changes linearly into its `EndSweptArea` over the turn.

use std::f64::consts::TAU;

use glam::{DAffine3, DVec2, DVec3};
use poinav_ifc::Entity;

use crate::axis2_placement::axis2placement_3d;
use crate::cartesian_point::point3;
use crate::curve::MAX_ARC_STEP;
use crate::direction::optional_direction;
use crate::error::{degenerate, missing, required_ref, GeomError};
use crate::loft::{loft, Stations};
use crate::mesh::Mesh;
use crate::profile::{self, ProfileArea};
use crate::unit_assignment::Units;

/// Turns within this many radians of a full turn are full turns.
const FULL_TURN_TOLERANCE: f64 = 1e-6;

/// The closed mesh of `start` (changing into `end` when given) turned by `angle` radians
/// (counter-clockwise about `direction`, signed) about the line through `origin` along
/// `direction`, all in the profile's plane (z = 0). `None` for a zero angle, a zero
/// direction, profiles that do not match, or a profile on the axis.
pub fn revolve(
    start: &[ProfileArea],
    end: Option<&[ProfileArea]>,
    origin: DVec2,
    direction: DVec2,
    angle: f64,
) -> Option<Mesh> {
    let a = direction.try_normalize()?.extend(0.0);
    if !angle.is_finite() || angle == 0.0 {
        return None;
    }
    let full = angle.abs() >= TAU - FULL_TURN_TOLERANCE;
    let angle = angle.clamp(-TAU, TAU);
    let steps = ((angle.abs() / MAX_ARC_STEP).ceil() as usize).max(1);
    let wrap = full && end.is_none();
    let count = if wrap { steps } else { steps + 1 };
    let o = origin.extend(0.0);
    let extent = start
        .iter()
        .flat_map(|s| s.outer.iter())
        .map(|p| (*p - origin).length())
        .fold(0.0, f64::max);
    let eps = 1e-9 * extent.max(1e-3);
    let place = |p: DVec2, k: usize| {
        let theta = if wrap {
            TAU * angle.signum() * k as f64 / steps as f64
        } else {
            angle * k as f64 / steps as f64
        };
        let v = p.extend(0.0) - o;
        let along = a * a.dot(v);
        let perp = v - along;
        o + along + perp * theta.cos() + a.cross(perp) * theta.sin()
    };
    let pinned = |p: DVec2| {
        let v = p.extend(0.0) - o;
        (v - a * a.dot(v)).length() <= eps
    };
    loft(
        start,
        end,
        &Stations {
            count,
            wrap,
            place: &place,
            pinned: &pinned,
        },
    )
}

/// The mesh of an `IfcRevolvedAreaSolid` (or `...Tapered`) in the coordinates of the
/// representation it is an item of (metres), its `Position` applied.
pub fn revolved_area_solid(item: Entity<'_>, units: &Units) -> Result<Mesh, GeomError> {
    let s = units.metres_per_unit;
    let start = profile::areas(required_ref(&item, "SweptArea", "IfcProfileDef")?, units)?;
    let end = if item.is_a("IfcRevolvedAreaSolidTapered") {
        Some(profile::areas(
            required_ref(&item, "EndSweptArea", "IfcProfileDef")?,
            units,
        )?)
    } else {
        None
    };
    let axis = required_ref(&item, "Axis", "IfcAxis1Placement")?;
    let origin = point3(required_ref(&axis, "Location", "IfcCartesianPoint")?)? * s;
    let direction = optional_direction(&axis, "Axis", DVec3::Z)?;
    let angle = item
        .get_f64("Angle")
        .ok_or_else(|| missing(&item, "Angle"))?
        * units.radians_per_unit;
    let mut mesh = revolve(
        &start,
        end.as_deref(),
        origin.truncate(),
        direction.truncate(),
        angle,
    )
    .ok_or_else(|| {
        degenerate(
            &item,
            "the revolution has no volume or its end profile does not match its start",
        )
    })?;
    mesh.transform(&position(&item, s)?);
    Ok(mesh)
}

/// The `Position` of a swept solid (the identity when `$`), translation in metres.
pub(crate) fn position(item: &Entity<'_>, s: f64) -> Result<DAffine3, GeomError> {
    match item.get("Position") {
        Some(_) => axis2placement_3d(
            item.get_ref("Position")
                .ok_or_else(|| missing(item, "Position"))?,
            s,
        ),
        None => Ok(DAffine3::IDENTITY),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    fn rect(x0: f64, y0: f64, x1: f64, y1: f64) -> ProfileArea {
        ProfileArea {
            outer: vec![
                DVec2::new(x0, y0),
                DVec2::new(x1, y0),
                DVec2::new(x1, y1),
                DVec2::new(x0, y1),
            ],
            holes: Vec::new(),
        }
    }

    /// Volume of a regular n-gon prism-like ring: the exact solid's volume times the
    /// polygon's area ratio n sin(2 pi / n) / (2 pi).
    fn polygon_ratio(n: f64) -> f64 {
        n * (TAU / n).sin() / TAU
    }

    #[test]
    fn full_turn_touching_the_axis_is_a_closed_cylinder() {
        // A 1 x 2 rectangle on the y axis turned about it: a cylinder r = 1, h = 2.
        let m = revolve(
            &[rect(0.0, 0.0, 1.0, 2.0)],
            None,
            DVec2::ZERO,
            DVec2::Y,
            TAU,
        )
        .unwrap();
        let exact = PI * 2.0 * polygon_ratio(72.0);
        assert!((m.volume() - exact).abs() < 1e-9, "{} {exact}", m.volume());
        // Closed: every edge is used exactly twice, once each way.
        let mut edges = std::collections::HashMap::new();
        for t in &m.triangles {
            for i in 0..3 {
                *edges.entry((t[i], t[(i + 1) % 3])).or_insert(0) += 1;
            }
        }
        assert!(edges
            .iter()
            .all(|(&(a, b), &n)| n == 1 && edges.get(&(b, a)) == Some(&1)));
        // Negative angles turn the other way with the same volume.
        let back = revolve(
            &[rect(0.0, 0.0, 1.0, 2.0)],
            None,
            DVec2::ZERO,
            DVec2::Y,
            -TAU,
        )
        .unwrap();
        assert!((back.volume() - exact).abs() < 1e-9);
    }

    #[test]
    fn quarter_turn_of_a_ring_is_capped() {
        // A ring r in [1, 2], h = 1, a quarter turn: V = pi (4 - 1) / 4 (18 steps of 5 deg).
        let m = revolve(
            &[rect(1.0, 0.0, 2.0, 1.0)],
            None,
            DVec2::ZERO,
            DVec2::Y,
            PI / 2.0,
        )
        .unwrap();
        let chord = 18.0 * (MAX_ARC_STEP).sin() / 2.0 / (PI / 2.0 / 2.0);
        let exact = 3.0 * PI / 4.0 * chord;
        assert!((m.volume() - exact).abs() < 1e-9, "{} {exact}", m.volume());
        // Turned about +y from +x, the ring ends on -z.
        let (lo, hi) = m.bounds().unwrap();
        assert!(
            (lo.z + 2.0).abs() < 1e-12 && hi.z.abs() < 1e-12,
            "{lo} {hi}"
        );
        assert!(revolve(
            &[rect(1.0, 0.0, 2.0, 1.0)],
            None,
            DVec2::ZERO,
            DVec2::ZERO,
            1.0
        )
        .is_none());
    }

    #[test]
    fn zero_angles_and_mismatched_end_profiles_are_errors() {
        let text = "ISO-10303-21;HEADER;FILE_SCHEMA(('IFC4'));ENDSEC;DATA;\n\
            #1=IFCRECTANGLEPROFILEDEF(.AREA.,$,$,1.,2.);#2=IFCCARTESIANPOINT((-2.,0.,0.));\
            #3=IFCDIRECTION((0.,1.,0.));#4=IFCAXIS1PLACEMENT(#2,#3);\
            #5=IFCREVOLVEDAREASOLID(#1,$,#4,0.);#6=IFCCIRCLEPROFILEDEF(.AREA.,$,$,0.5);\
            #7=IFCREVOLVEDAREASOLIDTAPERED(#1,$,#4,1.,#6);#8=IFCREVOLVEDAREASOLID(#1,$,#4,1.);\
            ENDSEC;END-ISO-10303-21;";
        let m = poinav_ifc::Model::from_bytes("t.ifc", text.as_bytes().to_vec()).unwrap();
        let at = |id| m.entity(poinav_ifc::EntityId(id)).unwrap();
        for id in [5, 7] {
            let e = revolved_area_solid(at(id), &Units::SI).unwrap_err();
            assert!(
                matches!(e, GeomError::Degenerate { .. }) && e.id().0 == id,
                "{e}"
            );
        }
        // A 1 x 2 rectangle 2 m off the axis turned by one radian: V = 2 * 2 * 1 (Pappus),
        // less the chords' loss.
        let v = revolved_area_solid(at(8), &Units::SI).unwrap().volume();
        assert!((v / 4.0 - 1.0).abs() < 0.002, "{v}");
    }

    #[test]
    fn tapered_full_turn_is_a_cone_frustum() {
        // Radius 1 at the start to 0.5 at the end over a full turn, capped at both ends.
        let m = revolve(
            &[rect(0.0, 0.0, 1.0, 1.0)],
            Some(&[rect(0.0, 0.0, 0.5, 1.0)]),
            DVec2::ZERO,
            DVec2::Y,
            TAU,
        )
        .unwrap();
        assert!(m.volume() > 0.0 && m.volume() < PI);
    }
}
