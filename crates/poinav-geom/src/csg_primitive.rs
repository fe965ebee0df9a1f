//! The CSG primitives that are not boxes or cylinders: `IfcSphere` (a half disc turned
//! about z), `IfcRightCircularCone` (a triangle turned about z, apex up at `Height`) and
//! `IfcRectangularPyramid` (base from the origin along +x and +y, apex above its centre), as
//! closed meshes in the primitive's own coordinates (its `Position` is the caller's).

use std::f64::consts::{FRAC_PI_2, PI, TAU};

use glam::{DAffine3, DVec2, DVec3};
use poinav_ifc::Entity;

use crate::curve::MAX_ARC_STEP;
use crate::error::{degenerate, missing, unsupported, GeomError};
use crate::mesh::Mesh;
use crate::profile::ProfileArea;
use crate::revolve::revolve;

/// A closed polygon in the (radius, height) plane turned about the height axis, which ends
/// up along z.
fn turned(outer: Vec<DVec2>) -> Option<Mesh> {
    let area = ProfileArea {
        outer,
        holes: Vec::new(),
    };
    let mut m = revolve(&[area], None, DVec2::ZERO, DVec2::Y, TAU)?;
    m.transform(&DAffine3::from_rotation_x(FRAC_PI_2));
    Some(m)
}

/// A sphere of radius `r` about the origin: 36 steps pole to pole, 72 around.
pub fn sphere(r: f64) -> Option<Mesh> {
    let n = (PI / MAX_ARC_STEP).round() as usize;
    let outer = (0..=n)
        .map(|i| DVec2::from_angle(-FRAC_PI_2 + PI * i as f64 / n as f64) * r)
        .map(|p| {
            if p.x.abs() < 1e-12 * r {
                DVec2::new(0.0, p.y)
            } else {
                p
            }
        })
        .collect();
    turned(outer)
}

/// A cone of base radius `r` on z = 0 with its apex at (0, 0, `h`).
pub fn cone(r: f64, h: f64) -> Option<Mesh> {
    turned(vec![DVec2::ZERO, DVec2::new(r, 0.0), DVec2::new(0.0, h)])
}

/// A pyramid on the rectangle (0, 0)..(`x`, `y`) with its apex at (x / 2, y / 2, `h`).
pub fn pyramid(x: f64, y: f64, h: f64) -> Mesh {
    Mesh {
        positions: vec![
            DVec3::ZERO,
            DVec3::new(x, 0.0, 0.0),
            DVec3::new(x, y, 0.0),
            DVec3::new(0.0, y, 0.0),
            DVec3::new(x / 2.0, y / 2.0, h),
        ],
        triangles: vec![
            [0, 2, 1],
            [0, 3, 2],
            [0, 1, 4],
            [1, 2, 4],
            [2, 3, 4],
            [3, 0, 4],
        ],
    }
}

/// A positive length attribute of `e`, times `s`.
fn length(e: &Entity<'_>, name: &'static str, s: f64) -> Result<f64, GeomError> {
    let v = e.get_f64(name).ok_or_else(|| missing(e, name))?;
    if !(v.is_finite() && v > 0.0) {
        return Err(degenerate(e, "dimension is not a positive number"));
    }
    Ok(v * s)
}

/// The mesh of an `IfcSphere`, `IfcRightCircularCone` or `IfcRectangularPyramid` in its own
/// coordinates, metres (`s` metres per file unit).
pub fn csg_primitive(e: Entity<'_>, s: f64) -> Result<Mesh, GeomError> {
    let mesh = if e.is_a("IfcSphere") {
        sphere(length(&e, "Radius", s)?)
    } else if e.is_a("IfcRightCircularCone") {
        cone(length(&e, "BottomRadius", s)?, length(&e, "Height", s)?)
    } else if e.is_a("IfcRectangularPyramid") {
        Some(pyramid(
            length(&e, "XLength", s)?,
            length(&e, "YLength", s)?,
            length(&e, "Height", s)?,
        ))
    } else {
        return Err(unsupported(&e, "CSG primitive"));
    };
    mesh.ok_or_else(|| degenerate(&e, "primitive cannot be meshed"))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn volumes_within_one_percent_and_exact_boxes() {
        let r = 1.5;
        let s = sphere(r).unwrap();
        let exact = 4.0 / 3.0 * PI * r.powi(3);
        assert!(
            (s.volume() / exact - 1.0).abs() < 0.01,
            "{}",
            s.volume() / exact
        );
        let (lo, hi) = s.bounds().unwrap();
        assert!((lo + DVec3::splat(r)).length() < 1e-12 && (hi - DVec3::splat(r)).length() < 1e-12);
        let c = cone(0.5, 2.0).unwrap();
        let exact = PI * 0.25 * 2.0 / 3.0;
        assert!(
            (c.volume() / exact - 1.0).abs() < 0.01,
            "{}",
            c.volume() / exact
        );
        let (lo, hi) = c.bounds().unwrap();
        assert!((lo - DVec3::new(-0.5, -0.5, 0.0)).length() < 1e-12, "{lo}");
        assert!((hi - DVec3::new(0.5, 0.5, 2.0)).length() < 1e-12, "{hi}");
        let p = pyramid(2.0, 3.0, 4.0);
        assert!((p.volume() - 8.0).abs() < 1e-12);
    }
}
