//! `IfcProfileDef`: the outer boundary of a profile as a counter-clockwise 2D polygon in
//! metres, in the profile's own coordinates (its `Position` applied).
//!
//! Supported: `IfcRectangleProfileDef` (and subtypes, whose rounded or hollow parts do not
//! change the outer rectangle enough to matter here: roundings are ignored),
//! `IfcCircleProfileDef` (and hollow), `IfcEllipseProfileDef`, and
//! `IfcArbitraryClosedProfileDef` (and `...WithVoids`: voids are ignored) bounded by any curve
//! [`crate::curve`] reads. Anything else is [`GeomError::Unsupported`] naming the profile.

use std::f64::consts::TAU;

use glam::DVec2;
use poinav_ifc::Entity;

use crate::axis2_placement::axis2placement_2d;
use crate::curve::{self, MAX_ARC_STEP};
use crate::error::{degenerate, missing, required_ref, unsupported, GeomError};
use crate::polygon;
use crate::unit_assignment::Units;

/// The outer boundary of `profile`: counter-clockwise, without a repeated closing point,
/// lengths in metres (file lengths times `units.metres_per_unit`), `Position` applied.
pub fn outline(profile: Entity<'_>, units: &Units) -> Result<Vec<DVec2>, GeomError> {
    let s = units.metres_per_unit;
    let dim = |name: &'static str| -> Result<f64, GeomError> {
        let v = profile
            .get_f64(name)
            .ok_or_else(|| missing(&profile, name))?;
        if v.is_finite() && v > 0.0 {
            Ok(v * s)
        } else {
            Err(degenerate(&profile, "dimension is not a positive number"))
        }
    };
    let local: Vec<DVec2> = if profile.is_a("IfcRectangleProfileDef") {
        let (x, y) = (dim("XDim")? / 2.0, dim("YDim")? / 2.0);
        vec![
            DVec2::new(-x, -y),
            DVec2::new(x, -y),
            DVec2::new(x, y),
            DVec2::new(-x, y),
        ]
    } else if profile.is_a("IfcCircleProfileDef") {
        ellipse(dim("Radius")?, dim("Radius")?)
    } else if profile.is_a("IfcEllipseProfileDef") {
        ellipse(dim("SemiAxis1")?, dim("SemiAxis2")?)
    } else if profile.is_a("IfcArbitraryClosedProfileDef") {
        let curve = required_ref(&profile, "OuterCurve", "IfcCurve")?;
        curve::polyline(curve, units)?
    } else {
        return Err(unsupported(&profile, "profile"));
    };
    // Parameterised profiles have a Position (optional in IFC4, absent for arbitrary ones).
    let placed = match profile.get("Position") {
        Some(_) => {
            let position = profile
                .get_ref("Position")
                .ok_or_else(|| missing(&profile, "Position"))?;
            let a = axis2placement_2d(position, s)?;
            local.into_iter().map(|p| a.transform_point2(p)).collect()
        }
        None => local,
    };
    polygon::clean(placed).ok_or_else(|| degenerate(&profile, "profile encloses no area"))
}

/// An ellipse with semi-axes `a` (x) and `b` (y), as chords.
fn ellipse(a: f64, b: f64) -> Vec<DVec2> {
    let n = (TAU / MAX_ARC_STEP).round() as usize;
    (0..n)
        .map(|i| {
            let t = TAU * i as f64 / n as f64;
            DVec2::new(a * t.cos(), b * t.sin())
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use poinav_ifc::{EntityId, Model};

    fn model(data: &str) -> Model {
        let text = format!(
            "ISO-10303-21;HEADER;FILE_SCHEMA(('IFC4'));ENDSEC;DATA;\n{data}\nENDSEC;END-ISO-10303-21;"
        );
        Model::from_bytes("t.ifc", text.into_bytes()).unwrap()
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
        let (min, max) = polygon::bounds(&p);
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
            "#1=IFCCIRCLEPROFILEDEF(.AREA.,$,$,0.5);#2=IFCISHAPEPROFILEDEF(.AREA.,$,$,1.,1.,0.1,0.1,$,$,$,$);\
             #3=IFCRECTANGLEPROFILEDEF(.AREA.,$,$,0.,1.);",
        );
        let c = outline_of(&m, 1, &Units::SI).unwrap();
        assert_eq!(c.len(), 72);
        assert!((polygon::signed_area(&c) - std::f64::consts::PI * 0.25).abs() < 0.002);
        let err = outline_of(&m, 2, &Units::SI).unwrap_err();
        assert_eq!(err.id(), EntityId(2));
        assert!(err.to_string().contains("IfcIShapeProfileDef"), "{err}");
        assert!(matches!(
            outline_of(&m, 3, &Units::SI),
            Err(GeomError::Degenerate { .. })
        ));
    }
}
