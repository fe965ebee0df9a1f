//! `IfcHalfSpaceSolid` and its subtypes `IfcPolygonalBoundedHalfSpace` (the half-space cut
//! down to an infinite prism over a polygon) and `IfcBoxedHalfSpace` (its box only bounds the
//! computation, so it is read as a plain half-space).

use glam::{DAffine3, DVec2, DVec3};
use poinav_ifc::Entity;

use crate::axis2_placement::axis2placement_3d;
use crate::curve;
use crate::error::{degenerate, required_ref, unsupported, GeomError};
use crate::polygon;
use crate::unit_assignment::Units;

/// A half-space in metres, in the coordinates of the representation item it belongs to.
#[derive(Debug, Clone, PartialEq)]
pub struct HalfSpace {
    /// A point on the bounding plane.
    pub origin: DVec3,
    /// The plane's unit normal, pointing away from the half-space's material.
    pub outward: DVec3,
    /// For a polygonal bounded half-space: the prism it is limited to.
    pub prism: Option<Prism>,
}

/// An infinite prism: a counter-clockwise polygon in the XY plane of `placement`, extended
/// along that placement's z axis both ways.
#[derive(Debug, Clone, PartialEq)]
pub struct Prism {
    /// The prism's frame (rigid).
    pub placement: DAffine3,
    /// The polygon in the frame's XY plane, counter-clockwise.
    pub polygon: Vec<DVec2>,
}

impl HalfSpace {
    /// Signed distance of `p` from the plane, positive outside the material.
    pub fn distance(&self, p: DVec3) -> f64 {
        (p - self.origin).dot(self.outward)
    }
}

/// Reads an `IfcHalfSpaceSolid` (or subtype) whose `BaseSurface` is an `IfcPlane`.
pub fn half_space(e: Entity<'_>, units: &Units) -> Result<HalfSpace, GeomError> {
    let s = units.metres_per_unit;
    if !e.is_a("IfcHalfSpaceSolid") {
        return Err(unsupported(&e, "expected an IfcHalfSpaceSolid"));
    }
    let surface = required_ref(&e, "BaseSurface", "IfcSurface")?;
    if !surface.is_a("IfcPlane") {
        return Err(unsupported(&surface, "half-space surface (only IfcPlane)"));
    }
    let plane = axis2placement_3d(
        required_ref(&surface, "Position", "IfcAxis2Placement3D")?,
        s,
    )?;
    // AgreementFlag true: the normal points away from the material.
    let agreement = e.get("AgreementFlag").and_then(|v| v.as_enum()) != Some("F");
    let normal = plane.matrix3.z_axis;
    let mut out = HalfSpace {
        origin: plane.translation,
        outward: if agreement { normal } else { -normal },
        prism: None,
    };
    if e.is_a("IfcPolygonalBoundedHalfSpace") {
        let placement = axis2placement_3d(required_ref(&e, "Position", "IfcAxis2Placement3D")?, s)?;
        let boundary = required_ref(&e, "PolygonalBoundary", "IfcCurve")?;
        let polygon = polygon::clean(curve::polyline(boundary, units)?)
            .ok_or_else(|| degenerate(&boundary, "boundary encloses no area"))?;
        out.prism = Some(Prism { placement, polygon });
    }
    Ok(out)
}
