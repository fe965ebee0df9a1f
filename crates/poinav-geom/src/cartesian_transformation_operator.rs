//! `IfcCartesianTransformationOperator` (2D, 3D, uniform and non-uniform): the map a mapped
//! item applies, translation in metres, possibly mirrored and scaled.

use glam::{DAffine3, DMat3, DVec3};
use poinav_ifc::Entity;

use crate::axis2_placement::build_axes;
use crate::cartesian_point::point3;
use crate::direction::optional_direction;
use crate::error::{degenerate, required_ref, unsupported, GeomError};

/// The operator as an affine map, the `LocalOrigin` multiplied by `metres_per_unit`.
///
/// Axes follow IFC's `IfcBaseAxis`: `Axis3` (default +Z) first, `Axis1` (default +X) made
/// orthogonal to it, `Axis2` only decides the sign of the third axis (a mirror), as in
/// IfcOpenShell. `Scale` (default 1) scales all axes; `Scale2`/`Scale3` of the non-uniform
/// kinds default to `Scale`.
pub fn transformation(op: Entity<'_>, metres_per_unit: f64) -> Result<DAffine3, GeomError> {
    if !op.is_a("IfcCartesianTransformationOperator") {
        return Err(unsupported(
            &op,
            "expected an IfcCartesianTransformationOperator",
        ));
    }
    let origin = point3(required_ref(&op, "LocalOrigin", "IfcCartesianPoint")?)? * metres_per_unit;
    let three_d = op.is_a("IfcCartesianTransformationOperator3D");
    let axis3 = if three_d {
        optional_direction(&op, "Axis3", DVec3::Z)?
    } else {
        DVec3::Z
    };
    let axis1 = match op.get("Axis1") {
        Some(_) => Some(optional_direction(&op, "Axis1", DVec3::X)?),
        None => None,
    };
    let (x, mut y, z) =
        build_axes(axis3, axis1).ok_or_else(|| degenerate(&op, "axes are degenerate"))?;
    if op.get("Axis2").is_some() && optional_direction(&op, "Axis2", DVec3::Y)?.dot(y) < 0.0 {
        y = -y;
    }
    let s1 = op.get_f64("Scale").unwrap_or(1.0);
    let (s2, s3) = if op.is_a("IfcCartesianTransformationOperator3DnonUniform")
        || op.is_a("IfcCartesianTransformationOperator2DnonUniform")
    {
        (
            op.get_f64("Scale2").unwrap_or(s1),
            op.get_f64("Scale3").unwrap_or(s1),
        )
    } else {
        (s1, s1)
    };
    let s3 = if three_d { s3 } else { 1.0 };
    if ![s1, s2, s3].iter().all(|s| s.is_finite() && *s > 0.0) {
        return Err(degenerate(&op, "scale is not a positive number"));
    }
    Ok(DAffine3::from_mat3_translation(
        DMat3::from_cols(x * s1, y * s2, z * s3),
        origin,
    ))
}
