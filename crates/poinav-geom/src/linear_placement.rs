//! `IfcLinearPlacement` with `IfcAxis2PlacementLinear`: a placement at a distance along a basis
//! curve ([`crate::gradient_curve`]), offset laterally (to the left), vertically (along the
//! curve's normal) and longitudinally (along its tangent), as IfcOpenShell evaluates
//! `IfcPointByDistanceExpression`.
//!
//! The axes default to the curve's frame there (x the direction of travel, z its normal);
//! a given `Axis` / `RefDirection` is read relative to that frame (IFC 4.3 8.9.3.4: "relative to
//! the curve used for linear referencing"). Like IfcOpenShell, a linear placement is taken as a
//! root: the basis curve's coordinates are the world's and `PlacementRelTo` is not applied.

use glam::{DAffine3, DMat3, DVec3};
use poinav_ifc::{Entity, Value};

use crate::axis2_placement::build_axes;
use crate::direction::direction;
use crate::error::{degenerate, missing, required_ref, unsupported, GeomError};
use crate::gradient_curve::{BasisCurve, Frame3};
use crate::unit_assignment::Units;

/// A distance or offset of an `IfcPointByDistanceExpression` in file units (`$` is zero);
/// a parameter value (`IfcParameterValue`) is not supported.
fn length(e: &Entity<'_>, name: &'static str, required: bool) -> Result<f64, GeomError> {
    match e.get(name) {
        None if !required => Ok(0.0),
        None => Err(missing(e, name)),
        Some(Value::Typed(kind, _)) if kind.eq_ignore_ascii_case("IFCPARAMETERVALUE") => {
            Err(unsupported(e, "distance along as a parameter value"))
        }
        Some(v) => v
            .as_f64()
            .filter(|x| x.is_finite())
            .ok_or_else(|| missing(e, name)),
    }
}

/// The point of an `IfcPointByDistanceExpression` and the curve's frame there (metres);
/// `curve` reads (or recalls) the basis curve.
pub fn point_by_distance<'m>(
    e: Entity<'m>,
    units: &Units,
    curve: &mut dyn FnMut(Entity<'m>) -> Result<std::sync::Arc<BasisCurve>, GeomError>,
) -> Result<(DVec3, Frame3), GeomError> {
    if !e.is_a("IfcPointByDistanceExpression") {
        return Err(unsupported(&e, "expected an IfcPointByDistanceExpression"));
    }
    let d = length(&e, "DistanceAlong", true)?;
    let lateral = length(&e, "OffsetLateral", false)?;
    let vertical = length(&e, "OffsetVertical", false)?;
    let longitudinal = length(&e, "OffsetLongitudinal", false)?;
    let basis = curve(required_ref(&e, "BasisCurve", "IfcCurve")?)?;
    let f = basis.frame(d);
    let s = units.metres_per_unit;
    let p = f.origin + (f.left * lateral + f.normal * vertical + f.tangent * longitudinal) * s;
    if !p.is_finite() {
        return Err(degenerate(&e, "point along the curve is not finite"));
    }
    Ok((p, f))
}

/// An `IfcAxis2PlacementLinear` as the map from its local coordinates to the world's (metres).
pub fn axis2placement_linear<'m>(
    e: Entity<'m>,
    units: &Units,
    curve: &mut dyn FnMut(Entity<'m>) -> Result<std::sync::Arc<BasisCurve>, GeomError>,
) -> Result<DAffine3, GeomError> {
    if !e.is_a("IfcAxis2PlacementLinear") {
        return Err(unsupported(&e, "expected an IfcAxis2PlacementLinear"));
    }
    let location = required_ref(&e, "Location", "IfcPointByDistanceExpression")?;
    let (origin, f) = point_by_distance(location, units, curve)?;
    let frame = DMat3::from_cols(f.tangent, f.left, f.normal);
    let relative = |name: &'static str| -> Result<Option<DVec3>, GeomError> {
        match e.get(name) {
            None => Ok(None),
            Some(_) => Ok(Some(
                frame * direction(e.get_ref(name).ok_or_else(|| missing(&e, name))?)?,
            )),
        }
    };
    let z = relative("Axis")?.unwrap_or(f.normal);
    let x = relative("RefDirection")?.unwrap_or(f.tangent);
    let (x, y, z) = build_axes(z, Some(x)).ok_or_else(|| degenerate(&e, "axes are degenerate"))?;
    Ok(DAffine3::from_mat3_translation(
        DMat3::from_cols(x, y, z),
        origin,
    ))
}

#[cfg(test)]
mod tests {
    use super::*;
    use poinav_ifc::{EntityId, Model};
    use std::sync::Arc;

    fn model(data: &str) -> Model {
        crate::test_model::with_schema("IFC4X3_ADD2", data)
    }

    /// A straight alignment along +y from (100, 0), then a gradient of 2 %.
    const LINE: &str = "#1=IFCCARTESIANPOINT((100.,0.));#2=IFCDIRECTION((0.,1.));\
        #3=IFCAXIS2PLACEMENT2D(#1,#2);#4=IFCCARTESIANPOINT((0.,0.));#5=IFCDIRECTION((1.,0.));\
        #6=IFCVECTOR(#5,1.);#7=IFCLINE(#4,#6);\
        #8=IFCCURVESEGMENT(.CONTINUOUS.,#3,IFCLENGTHMEASURE(0.),IFCLENGTHMEASURE(500.),#7);\
        #9=IFCCOMPOSITECURVE((#8),.F.);\
        #10=IFCCARTESIANPOINT((0.,10.));#11=IFCDIRECTION((1.,0.02));#12=IFCAXIS2PLACEMENT2D(#10,#11);\
        #13=IFCCURVESEGMENT(.CONTINUOUS.,#12,IFCLENGTHMEASURE(0.),IFCLENGTHMEASURE(500.),#7);\
        #14=IFCGRADIENTCURVE((#13),.F.,#9,$);";

    fn place(m: &Model, id: u64) -> DAffine3 {
        let e = m.entity(EntityId(id)).unwrap();
        let mut read = |c: Entity<'_>| BasisCurve::read(c, &Units::SI).map(Arc::new);
        axis2placement_linear(e, &Units::SI, &mut read).unwrap()
    }

    #[test]
    fn offsets_follow_the_curve_frame_and_axes_are_relative_to_it() {
        let m = model(&format!(
            "{LINE}#20=IFCPOINTBYDISTANCEEXPRESSION(IFCLENGTHMEASURE(50.),2.,1.,3.,#14);\
             #21=IFCAXIS2PLACEMENTLINEAR(#20,$,$);\
             #22=IFCDIRECTION((0.,1.,0.));#23=IFCAXIS2PLACEMENTLINEAR(#20,$,#22);"
        ));
        let t = place(&m, 21);
        // 50 m along +y (plus 3 m longitudinally), 2 m to the left (-x), 1 m up; height 10 + 2 % of 50.
        let g = 0.02f64;
        let n = (1.0 + g * g).sqrt();
        let expected = DVec3::new(100.0 - 2.0, 50.0 + 3.0 / n, 10.0 + g * 50.0 + 3.0 * g / n)
            + DVec3::new(0.0, -g, 1.0) / n;
        assert!(
            (t.translation - expected).length() < 1e-9,
            "{}",
            t.translation
        );
        assert!((t.matrix3.x_axis - DVec3::new(0.0, 1.0, g) / n).length() < 1e-12);
        // RefDirection (0,1,0) in the curve's frame is its left: world -x.
        let r = place(&m, 23);
        assert!((r.matrix3.x_axis - DVec3::NEG_X).length() < 1e-12);
        assert!((r.translation - t.translation).length() < 1e-12);
    }
}
