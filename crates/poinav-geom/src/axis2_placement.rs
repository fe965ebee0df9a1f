//! `IfcAxis2Placement3D` / `IfcAxis2Placement2D`: a location and right-handed axes, as an affine map.
//!
//! Axes follow the IFC rules (`IfcBuildAxes`): a missing `Axis` is +Z; a missing
//! `RefDirection` is +X (or +Y when `Axis` is along X); `RefDirection` is made orthogonal to
//! `Axis` by Gram-Schmidt, so the result is always a rotation even for sloppy input.

use glam::{DAffine2, DAffine3, DMat2, DMat3, DVec3};
use poinav_ifc::Entity;

use crate::cartesian_point::point3;
use crate::direction::{optional_direction, MIN_LENGTH};
use crate::error::{degenerate, missing, required_ref, unsupported, GeomError};

/// The orthonormal right-handed axes (x, y, z) for a z axis and a wished-for x direction.
pub(crate) fn build_axes(z: DVec3, ref_direction: Option<DVec3>) -> Option<(DVec3, DVec3, DVec3)> {
    let z = z.try_normalize()?;
    let default = if (z - DVec3::X).length() < 1e-9 {
        DVec3::Y
    } else {
        DVec3::X
    };
    let project = |v: DVec3| {
        let x = v - v.dot(z) * z;
        (x.length() > MIN_LENGTH.sqrt()).then(|| x.normalize())
    };
    let x = ref_direction
        .and_then(project)
        .or_else(|| project(default))
        .or_else(|| project(DVec3::Y))?;
    let y = z.cross(x);
    Some((x, y, z))
}

/// An `IfcAxis2Placement3D` as the map from its local coordinates to its parent's, with the
/// translation multiplied by `scale` (pass `metres_per_unit` to get metres, 1.0 for file units).
pub fn axis2placement_3d(e: Entity<'_>, scale: f64) -> Result<DAffine3, GeomError> {
    if !e.is_a("IfcAxis2Placement3D") {
        return Err(unsupported(&e, "expected an IfcAxis2Placement3D"));
    }
    let location = location(&e)?;
    let z = optional_direction(&e, "Axis", DVec3::Z)?;
    let r = match e.get("RefDirection") {
        Some(_) => Some(optional_direction(&e, "RefDirection", DVec3::X)?),
        None => None,
    };
    let (x, y, z) = build_axes(z, r).ok_or_else(|| degenerate(&e, "axes are degenerate"))?;
    Ok(DAffine3::from_mat3_translation(
        DMat3::from_cols(x, y, z),
        location * scale,
    ))
}

/// The `IfcAxis2Placement3D` in attribute `Position` of `e` as [`axis2placement_3d`] maps it;
/// the identity when it is `$`.
pub(crate) fn optional_position(e: &Entity<'_>, scale: f64) -> Result<DAffine3, GeomError> {
    match e.get("Position") {
        None => Ok(DAffine3::IDENTITY),
        Some(_) => axis2placement_3d(
            e.get_ref("Position")
                .ok_or_else(|| missing(e, "Position"))?,
            scale,
        ),
    }
}

/// An `IfcAxis2Placement2D` as a 2D map, translation multiplied by `scale`.
pub fn axis2placement_2d(e: Entity<'_>, scale: f64) -> Result<DAffine2, GeomError> {
    if !e.is_a("IfcAxis2Placement2D") {
        return Err(unsupported(&e, "expected an IfcAxis2Placement2D"));
    }
    let location = location(&e)?.truncate();
    let r = optional_direction(&e, "RefDirection", DVec3::X)?.truncate();
    let x = r
        .try_normalize()
        .ok_or_else(|| degenerate(&e, "RefDirection has no x or y component"))?;
    Ok(DAffine2::from_mat2_translation(
        DMat2::from_cols(x, x.perp()),
        location * scale,
    ))
}

/// An `IfcAxis2Placement2D` or `IfcAxis2Placement3D` as a 3D map (2D ones keep z).
pub fn axis2placement(e: Entity<'_>, scale: f64) -> Result<DAffine3, GeomError> {
    if e.is_a("IfcAxis2Placement2D") {
        Ok(affine2_to_3(axis2placement_2d(e, scale)?))
    } else if e.is_a("IfcAxis2Placement3D") {
        axis2placement_3d(e, scale)
    } else {
        Err(unsupported(
            &e,
            "expected an IfcAxis2Placement2D or IfcAxis2Placement3D",
        ))
    }
}

/// A 2D map as the 3D map that leaves z alone.
pub(crate) fn affine2_to_3(a: DAffine2) -> DAffine3 {
    let m = a.matrix2;
    DAffine3::from_mat3_translation(
        DMat3::from_cols(m.x_axis.extend(0.0), m.y_axis.extend(0.0), DVec3::Z),
        a.translation.extend(0.0),
    )
}

fn location(e: &Entity<'_>) -> Result<DVec3, GeomError> {
    point3(required_ref(e, "Location", "IfcCartesianPoint")?)
}
