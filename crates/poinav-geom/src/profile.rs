//! `IfcProfileDef`: the area of a profile as polygons with holes in metres, in the profile's
//! own coordinates (its `Position` applied), and its outer boundary for footprints.
//!
//! Supported: every parameterized profile of `parameterized_profile.rs` (rectangles,
//! rounded and hollow rectangles, circles and hollow circles, ellipses, trapezia, I, L, T, U,
//! C and Z shapes), `IfcArbitraryClosedProfileDef` and `...WithVoids` bounded by any curve
//! [`crate::curve`] reads, `IfcCenterLineProfileDef` ([`crate::open_profile`]),
//! `IfcDerivedProfileDef` (a parent profile moved, mirrored or scaled),
//! `IfcMirroredProfileDef` (a parent mirrored about its y axis) and `IfcCompositeProfileDef`
//! (several areas). Anything else is [`GeomError::Unsupported`] naming the profile. A boundary
//! that crosses itself (a star drawn in one stroke) or a hole that crosses it is resolved into
//! the simple areas it encloses.

use glam::{DAffine2, DVec2};
use poinav_ifc::Entity;

use crate::axis2_placement::axis2placement_2d;
use crate::cartesian_transformation_operator::transformation;
use crate::curve;
use crate::error::{degenerate, missing, required_ref, unsupported, GeomError};
use crate::open_profile;
use crate::parameterized_profile;
use crate::polygon;
use crate::self_crossing::{self, Crossings};
use crate::unit_assignment::Units;

/// Deepest nesting of derived and composite profiles followed.
const MAX_DEPTH: usize = 16;

/// One connected area of a profile: a counter-clockwise outer boundary and clockwise holes,
/// without repeated closing points, in metres.
#[derive(Debug, Clone, PartialEq)]
pub struct ProfileArea {
    /// The outer boundary, counter-clockwise.
    pub outer: Vec<DVec2>,
    /// The holes, clockwise.
    pub holes: Vec<Vec<DVec2>>,
}

impl ProfileArea {
    /// Enclosed area less the holes, square metres.
    pub fn area(&self) -> f64 {
        polygon::signed_area(&self.outer)
            + self
                .holes
                .iter()
                .map(|h| polygon::signed_area(h))
                .sum::<f64>()
    }

    fn transformed(self, a: &DAffine2) -> ProfileArea {
        let map = |ring: Vec<DVec2>| ring.into_iter().map(|p| a.transform_point2(p)).collect();
        let mut out = ProfileArea {
            outer: map(self.outer),
            holes: self.holes.into_iter().map(map).collect(),
        };
        if a.matrix2.determinant() < 0.0 {
            out.outer.reverse();
            out.holes.iter_mut().for_each(|h| h.reverse());
        }
        out
    }
}

/// The outer boundary of `profile`: counter-clockwise, without a repeated closing point,
/// lengths in metres (file lengths times `units.metres_per_unit`), `Position` applied. Voids
/// are ignored; of a composite profile the largest area is taken.
pub fn outline(profile: Entity<'_>, units: &Units) -> Result<Vec<DVec2>, GeomError> {
    let areas = areas(profile, units)?;
    areas
        .into_iter()
        .max_by(|a, b| polygon::signed_area(&a.outer).total_cmp(&polygon::signed_area(&b.outer)))
        .map(|a| a.outer)
        .ok_or_else(|| degenerate(&profile, "profile encloses no area"))
}

/// The areas of `profile` (one, except for composite profiles), holes included, lengths in
/// metres, `Position` applied.
pub fn areas(profile: Entity<'_>, units: &Units) -> Result<Vec<ProfileArea>, GeomError> {
    areas_at(profile, units, 0)
}

fn areas_at(
    profile: Entity<'_>,
    units: &Units,
    depth: usize,
) -> Result<Vec<ProfileArea>, GeomError> {
    if depth > MAX_DEPTH {
        return Err(degenerate(&profile, "profiles nested too deeply"));
    }
    let s = units.metres_per_unit;
    let no_area = || degenerate(&profile, "profile encloses no area");
    if profile.is_a("IfcCompositeProfileDef") {
        let parts = profile.get_refs("Profiles");
        if parts.is_empty() {
            return Err(missing(&profile, "Profiles"));
        }
        let mut out = Vec::new();
        for part in parts {
            out.extend(areas_at(part, units, depth + 1)?);
        }
        return Ok(out);
    }
    if profile.is_a("IfcMirroredProfileDef") {
        // Its Operator is derived: a mirror about the parent's y axis (x becomes -x).
        let parent = required_ref(&profile, "ParentProfile", "IfcProfileDef")?;
        let mirror = DAffine2::from_scale(DVec2::new(-1.0, 1.0));
        return Ok(areas_at(parent, units, depth + 1)?
            .into_iter()
            .map(|area| area.transformed(&mirror))
            .collect());
    }
    if profile.is_a("IfcDerivedProfileDef") {
        let parent = required_ref(&profile, "ParentProfile", "IfcProfileDef")?;
        let op = required_ref(&profile, "Operator", "IfcCartesianTransformationOperator2D")?;
        let t = transformation(op, s)?;
        let a = DAffine2::from_cols(
            t.matrix3.x_axis.truncate(),
            t.matrix3.y_axis.truncate(),
            t.translation.truncate(),
        );
        return Ok(areas_at(parent, units, depth + 1)?
            .into_iter()
            .map(|area| area.transformed(&a))
            .collect());
    }
    let (outer, holes) = if profile.is_a("IfcParameterizedProfileDef") {
        parameterized_profile::shape(profile, s)?
    } else if profile.is_a("IfcArbitraryClosedProfileDef") {
        let curve = required_ref(&profile, "OuterCurve", "IfcCurve")?;
        let outer = curve::polyline(curve, units)?;
        let mut holes = Vec::new();
        if profile.is_a("IfcArbitraryProfileDefWithVoids") {
            for inner in profile.get_refs("InnerCurves") {
                holes.push(curve::polyline(inner, units)?);
            }
        }
        (outer, holes)
    } else if profile.is_a("IfcCenterLineProfileDef") {
        let area = open_profile::center_line_area(profile, units)?;
        (area.outer, area.holes)
    } else {
        return Err(unsupported(&profile, "profile"));
    };
    // A ring that crosses itself may enclose area with none in sum (a bow tie): resolved
    // below, not refused.
    let outer = match polygon::clean(outer.clone()) {
        Some(outer) => outer,
        None => polygon::without_repeats(outer)
            .filter(|r| self_crossing::crossings(&[r]) != Crossings::None)
            .ok_or_else(no_area)?,
    };
    let holes = holes
        .into_iter()
        .filter_map(polygon::clean)
        .map(|mut h| {
            h.reverse();
            h
        })
        .collect();
    let areas = simple_areas(&profile, ProfileArea { outer, holes })?;
    // Parameterised profiles have a Position (optional in IFC4, absent for arbitrary ones).
    Ok(match profile.get("Position") {
        Some(_) => {
            let position = profile
                .get_ref("Position")
                .ok_or_else(|| missing(&profile, "Position"))?;
            let a = axis2placement_2d(position, s)?;
            areas.into_iter().map(|area| area.transformed(&a)).collect()
        }
        None => areas,
    })
}

/// `area` as simple areas: itself when its rings neither cross nor overlap, else the areas
/// they enclose (the outer boundary filled by the non-zero rule, less the holes; see
/// [`self_crossing::resolve`]), as IfcOpenShell fills a star drawn in one stroke.
fn simple_areas(profile: &Entity<'_>, area: ProfileArea) -> Result<Vec<ProfileArea>, GeomError> {
    let rings: Vec<&[DVec2]> = std::iter::once(&area.outer[..])
        .chain(area.holes.iter().map(Vec::as_slice))
        .collect();
    match self_crossing::crossings(&rings) {
        Crossings::None => Ok(vec![area]),
        Crossings::Some(_) => {
            let out: Vec<ProfileArea> = self_crossing::resolve(&area.outer, &area.holes)
                .into_iter()
                .map(|r| ProfileArea {
                    outer: r.outer,
                    holes: r.holes,
                })
                .collect();
            if out.is_empty() {
                return Err(degenerate(profile, "profile encloses no area"));
            }
            Ok(out)
        }
        Crossings::TooComplex => Err(degenerate(
            profile,
            "the profile's boundary crosses itself too often to be resolved",
        )),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use poinav_ifc::{EntityId, Model};

    fn model(data: &str) -> Model {
        crate::test_model::ifc4(data)
    }

    fn outline_of(m: &Model, id: u64, units: &Units) -> Result<Vec<DVec2>, GeomError> {
        outline(m.entity(EntityId(id)).unwrap(), units)
    }

    const MM: Units = Units {
        metres_per_unit: 0.001,
        radians_per_unit: 1.0,
    };

    #[test]
    fn rectangle_with_position_in_metres() {
        let m = model(
            "#1=IFCCARTESIANPOINT((1000.,500.));#2=IFCDIRECTION((0.,1.));\
             #3=IFCAXIS2PLACEMENT2D(#1,#2);#4=IFCRECTANGLEPROFILEDEF(.AREA.,$,#3,4000.,2000.);",
        );
        let p = outline_of(&m, 4, &MM).unwrap();
        assert_eq!(p.len(), 4);
        assert!((polygon::signed_area(&p) - 8.0).abs() < 1e-12);
        // Rotated by 90 degrees: 4 m along y, 2 m along x, centred on (1, 0.5).
        let (min, max) = polygon::bounds(&p).unwrap();
        assert!((min - DVec2::new(0.0, -1.5)).length() < 1e-12, "{min}");
        assert!((max - DVec2::new(2.0, 2.5)).length() < 1e-12, "{max}");
    }

    #[test]
    fn clockwise_polyline_becomes_counter_clockwise_without_closing_point() {
        let m = model(
            "#1=IFCCARTESIANPOINT((0.,0.));#2=IFCCARTESIANPOINT((0.,3.));#3=IFCCARTESIANPOINT((4.,3.));\
             #4=IFCCARTESIANPOINT((4.,0.));#5=IFCPOLYLINE((#1,#2,#3,#4,#1));\
             #6=IFCARBITRARYCLOSEDPROFILEDEF(.AREA.,$,#5);",
        );
        let p = outline_of(&m, 6, &Units::SI).unwrap();
        assert_eq!(p.len(), 4);
        assert!((polygon::signed_area(&p) - 12.0).abs() < 1e-12);
    }

    #[test]
    fn indexed_poly_curve_with_an_arc() {
        // A 2 x 1 rectangle whose top is replaced by a half circle of radius 1 bulging up:
        // area 2 + pi / 2 (less the chord loss of 36 chords on the half circle).
        let m = model(
            "#1=IFCCARTESIANPOINTLIST2D(((-1.,0.),(1.,0.),(1.,1.),(0.,2.),(-1.,1.)),$);\
             #2=IFCINDEXEDPOLYCURVE(#1,(IFCLINEINDEX((1,2,3)),IFCARCINDEX((3,4,5)),IFCLINEINDEX((5,1))),$);\
             #3=IFCARBITRARYCLOSEDPROFILEDEF(.AREA.,$,#2);",
        );
        let p = outline_of(&m, 3, &Units::SI).unwrap();
        let half_circle_chords = 36.0 * 0.5 * (std::f64::consts::PI / 36.0).sin();
        assert!((polygon::signed_area(&p) - (2.0 + half_circle_chords)).abs() < 1e-9);
        assert!(p.iter().all(|q| q.y <= 2.0 + 1e-12));
        assert!(
            p.iter().any(|q| (q.y - 2.0).abs() < 1e-12),
            "passes the arc's middle point"
        );
    }

    #[test]
    fn composite_curve_of_polylines_and_trimmed_circle_in_degrees() {
        // A quarter disc of radius 2: two straight edges and a trimmed circle from 0 to 90 deg.
        let m = model(
            "#1=IFCCARTESIANPOINT((0.,0.));#2=IFCCARTESIANPOINT((2.,0.));#3=IFCCARTESIANPOINT((0.,2.));\
             #4=IFCPOLYLINE((#1,#2));#5=IFCPOLYLINE((#3,#1));\
             #6=IFCAXIS2PLACEMENT2D(#1,$);#7=IFCCIRCLE(#6,2.);\
             #8=IFCTRIMMEDCURVE(#7,(IFCPARAMETERVALUE(0.)),(IFCPARAMETERVALUE(90.)),.T.,.PARAMETER.);\
             #9=IFCCOMPOSITECURVESEGMENT(.CONTINUOUS.,.T.,#4);#10=IFCCOMPOSITECURVESEGMENT(.CONTINUOUS.,.T.,#8);\
             #11=IFCCOMPOSITECURVESEGMENT(.CONTINUOUS.,.T.,#5);#12=IFCCOMPOSITECURVE((#9,#10,#11),.F.);\
             #13=IFCARBITRARYCLOSEDPROFILEDEF(.AREA.,$,#12);",
        );
        let degrees = Units {
            metres_per_unit: 1.0,
            radians_per_unit: std::f64::consts::PI / 180.0,
        };
        let p = outline_of(&m, 13, &degrees).unwrap();
        let chords = 18.0 * 0.5 * 4.0 * (std::f64::consts::PI / 36.0).sin();
        assert!((polygon::signed_area(&p) - chords).abs() < 1e-9);
    }

    #[test]
    fn circle_and_unsupported_profiles() {
        let m = model(
            "#1=IFCCIRCLEPROFILEDEF(.AREA.,$,$,0.5);#4=IFCPOLYLINE((#5,#6));\
             #5=IFCCARTESIANPOINT((0.,0.));#6=IFCCARTESIANPOINT((1.,0.));\
             #2=IFCARBITRARYOPENPROFILEDEF(.CURVE.,$,#4);\
             #3=IFCRECTANGLEPROFILEDEF(.AREA.,$,$,0.,1.);",
        );
        let c = outline_of(&m, 1, &Units::SI).unwrap();
        assert_eq!(c.len(), 72);
        assert!((polygon::signed_area(&c) - std::f64::consts::PI * 0.25).abs() < 0.002);
        let err = outline_of(&m, 2, &Units::SI).unwrap_err();
        assert_eq!(err.id(), EntityId(2));
        assert!(
            err.to_string().contains("IfcArbitraryOpenProfileDef"),
            "{err}"
        );
        assert!(matches!(
            outline_of(&m, 3, &Units::SI),
            Err(GeomError::Degenerate { .. })
        ));
    }

    #[test]
    fn a_star_drawn_in_one_stroke_is_resolved_and_a_tangle_refused() {
        // The star {4001/2} (each point joined to the next but one, twice around) encloses
        // the regular 4001-gon less a notch between each two points: nearly pi.
        let star = |n: usize, k: usize| -> String {
            let mut data = String::new();
            for i in 0..n {
                let p = DVec2::from_angle(std::f64::consts::TAU * (i * k % n) as f64 / n as f64);
                data.push_str(&format!(
                    "#{}=IFCCARTESIANPOINT(({},{}));",
                    10 + i,
                    p.x,
                    p.y
                ));
            }
            let refs: Vec<String> = (0..=n).map(|i| format!("#{}", 10 + i % n)).collect();
            data.push_str(&format!(
                "#1=IFCPOLYLINE(({}));#2=IFCARBITRARYCLOSEDPROFILEDEF(.AREA.,$,#1);",
                refs.join(",")
            ));
            data
        };
        let m = model(&star(4001, 2));
        let a = areas(m.entity(EntityId(2)).unwrap(), &Units::SI).unwrap();
        assert_eq!(a.len(), 1);
        assert!(a[0].holes.is_empty());
        assert_eq!(a[0].outer.len(), 2 * 4001);
        assert!(
            (a[0].area() - std::f64::consts::PI).abs() < 5e-6,
            "{}",
            a[0].area()
        );
        // A bow tie: no area in sum, two triangles of 0.25 m2 filled.
        let m = model(
            "#1=IFCCARTESIANPOINT((0.,0.));#2=IFCCARTESIANPOINT((5.,0.2));\
             #3=IFCCARTESIANPOINT((5.,0.));#4=IFCCARTESIANPOINT((0.,0.2));\
             #5=IFCPOLYLINE((#1,#2,#3,#4,#1));#6=IFCARBITRARYCLOSEDPROFILEDEF(.AREA.,$,#5);",
        );
        let a = areas(m.entity(EntityId(6)).unwrap(), &Units::SI).unwrap();
        let total: f64 = a.iter().map(ProfileArea::area).sum();
        assert!((total - 0.5).abs() < 1e-6, "{a:?}");
        // {2001/1000}: every edge crosses nearly every other, a million crossings.
        let m = model(&star(2001, 1000));
        let err = areas(m.entity(EntityId(2)).unwrap(), &Units::SI).unwrap_err();
        assert_eq!(err.id(), EntityId(2));
        assert!(
            err.to_string().contains("crosses itself too often"),
            "{err}"
        );
    }
}
