//! Profiles bounded by an open curve: `IfcCenterLineProfileDef` (the area `Thickness` wide
//! around its centre line: both sides offset by half the thickness, corners mitred, ends
//! square; a closed centre line gives a ring), `IfcArbitraryOpenProfileDef` and IFC4X3's
//! `IfcOpenCrossProfileDef` (widths and slopes from an offset point) as polylines, and open
//! profiles extruded (a surface, not a solid: one quad per segment of the curve, meshed as an
//! open part).

use glam::DVec2;
use poinav_ifc::Entity;

use crate::cartesian_point::point2;
use crate::curve;
use crate::error::{degenerate, missing, required_ref, unsupported, GeomError};
use crate::extrusion::extrusion_frame;
use crate::mesh::Mesh;
use crate::polygon;
use crate::profile::ProfileArea;
use crate::unit_assignment::Units;

/// Smallest cosine between a mitre and the segments' normals it joins: sharper corners are
/// cut off at four times half the thickness from the centre line.
const MIN_MITRE_COSINE: f64 = 0.25;

/// The area of an `IfcCenterLineProfileDef`, metres.
pub fn center_line_area(profile: Entity<'_>, units: &Units) -> Result<ProfileArea, GeomError> {
    let curve = required_ref(&profile, "Curve", "IfcCurve")?;
    let thickness = profile
        .get_f64("Thickness")
        .ok_or_else(|| missing(&profile, "Thickness"))?
        * units.metres_per_unit;
    if !(thickness.is_finite() && thickness > 0.0) {
        return Err(degenerate(&profile, "Thickness is not a positive number"));
    }
    let mut pts = curve::polyline(curve, units)?;
    let scale = pts.iter().map(|p| p.length()).fold(1.0, f64::max);
    let closed = pts.len() > 3 && pts[0].distance(pts[pts.len() - 1]) <= 1e-9 * scale;
    if closed {
        pts.pop();
    }
    let offsets = offsets(&pts, thickness / 2.0, closed)
        .ok_or_else(|| degenerate(&profile, "centre line has no length"))?;
    let left: Vec<DVec2> = pts.iter().zip(&offsets).map(|(p, o)| *p + *o).collect();
    let right: Vec<DVec2> = pts.iter().zip(&offsets).map(|(p, o)| *p - *o).collect();
    let no_area = || degenerate(&profile, "profile encloses no area");
    if closed {
        let (a, b) = (
            polygon::clean(left).ok_or_else(no_area)?,
            polygon::clean(right).ok_or_else(no_area)?,
        );
        let (mut outer, mut hole) = if polygon::signed_area(&a) >= polygon::signed_area(&b) {
            (a, b)
        } else {
            (b, a)
        };
        outer = polygon::clean(outer).ok_or_else(no_area)?;
        hole.reverse();
        return Ok(ProfileArea {
            outer,
            holes: vec![hole],
        });
    }
    let mut ring = left;
    ring.extend(right.into_iter().rev());
    Ok(ProfileArea {
        outer: polygon::clean(ring).ok_or_else(no_area)?,
        holes: Vec::new(),
    })
}

/// At every point of `pts`, the offset (length `half` along each segment's left normal,
/// mitred at corners) to its left side; `None` when a segment has no length.
fn offsets(pts: &[DVec2], half: f64, closed: bool) -> Option<Vec<DVec2>> {
    let n = pts.len();
    if n < 2 {
        return None;
    }
    let segs = if closed { n } else { n - 1 };
    let normals: Vec<DVec2> = (0..segs)
        .map(|i| {
            (pts[(i + 1) % n] - pts[i])
                .try_normalize()
                .map(|d| d.perp())
        })
        .collect::<Option<_>>()?;
    Some(
        (0..n)
            .map(|i| {
                let incoming = match i {
                    0 if closed => Some(normals[segs - 1]),
                    0 => None,
                    _ => Some(normals[i - 1]),
                };
                let outgoing = normals.get(i).copied();
                match (incoming, outgoing) {
                    (Some(a), Some(b)) => {
                        let m = (a + b).try_normalize().unwrap_or(a);
                        m * half / m.dot(a).max(MIN_MITRE_COSINE)
                    }
                    (Some(a), None) | (None, Some(a)) => a * half,
                    (None, None) => DVec2::ZERO,
                }
            })
            .collect(),
    )
}

/// True for a profile bounded by an open curve that bounds no area: an
/// `IfcArbitraryOpenProfileDef` other than a centre line profile, or an
/// `IfcOpenCrossProfileDef`.
pub fn is_open_profile(p: &Entity<'_>) -> bool {
    (p.is_a("IfcArbitraryOpenProfileDef") && !p.is_a("IfcCenterLineProfileDef"))
        || p.is_a("IfcOpenCrossProfileDef")
}

/// The polyline of an open profile ([`is_open_profile`]) in metres, at least two points.
///
/// An `IfcOpenCrossProfileDef` starts at its `OffsetPoint` (else the origin) and goes on by
/// each of its `Widths` at the angle of the matching `Slopes` entry, as IfcOpenShell 0.9 reads
/// it: along the slope (x grows by the width times the cosine, y by the width times the sine),
/// or with `HorizontalWidths` the width is horizontal (x falls by it, y by the width times the
/// tangent). Its `ProfileType` must be `CURVE`.
pub fn open_profile_points(profile: Entity<'_>, units: &Units) -> Result<Vec<DVec2>, GeomError> {
    let pts = if profile.is_a("IfcOpenCrossProfileDef") {
        cross_profile_points(profile, units)?
    } else if is_open_profile(&profile) {
        curve::polyline(required_ref(&profile, "Curve", "IfcCurve")?, units)?
    } else {
        return Err(unsupported(&profile, "expected an open profile"));
    };
    if pts.len() < 2 {
        return Err(degenerate(&profile, "open profile has no length"));
    }
    Ok(pts)
}

fn cross_profile_points(profile: Entity<'_>, units: &Units) -> Result<Vec<DVec2>, GeomError> {
    if profile.get("ProfileType").and_then(|v| v.as_enum()) != Some("CURVE") {
        return Err(degenerate(
            &profile,
            "ProfileType of an open cross profile is not CURVE",
        ));
    }
    let numbers = |name: &'static str| -> Result<Vec<f64>, GeomError> {
        profile
            .get(name)
            .as_ref()
            .and_then(|v| v.as_list())
            .and_then(|l| {
                l.iter()
                    .map(|x| x.as_f64().filter(|x| x.is_finite()))
                    .collect::<Option<Vec<f64>>>()
            })
            .ok_or_else(|| missing(&profile, name))
    };
    let (widths, slopes) = (numbers("Widths")?, numbers("Slopes")?);
    if widths.len() != slopes.len() {
        return Err(degenerate(&profile, "Widths and Slopes differ in length"));
    }
    let horizontal = profile.get("HorizontalWidths").and_then(|v| v.as_enum()) == Some("T");
    let s = units.metres_per_unit;
    let mut p = match profile.get_ref("OffsetPoint") {
        Some(o) => point2(o)? * s,
        None => DVec2::ZERO,
    };
    let mut out = vec![p];
    for (w, slope) in widths.into_iter().zip(slopes) {
        let w = w * s;
        let a = slope * units.radians_per_unit;
        p += if horizontal {
            DVec2::new(-w, -w * a.tan())
        } else {
            DVec2::new(w * a.cos(), w * a.sin())
        };
        if !p.is_finite() {
            return Err(degenerate(&profile, "a slope is vertical"));
        }
        out.push(p);
    }
    Ok(out)
}

/// True for an `IfcExtrudedAreaSolid` (not tapered) of an open profile ([`is_open_profile`]):
/// a surface.
pub fn is_open_profile_extrusion(item: &Entity<'_>) -> bool {
    item.is_a("IfcExtrudedAreaSolid")
        && !item.is_a("IfcExtrudedAreaSolidTapered")
        && item
            .get_ref("SweptArea")
            .is_some_and(|p| is_open_profile(&p))
}

/// The open surface of an extruded open profile, in the representation's coordinates
/// (metres), `Position` applied.
pub fn extruded_open_profile(item: Entity<'_>, units: &Units) -> Result<Mesh, GeomError> {
    let profile = required_ref(&item, "SweptArea", "IfcProfileDef")?;
    let pts = open_profile_points(profile, units)?;
    let (position, sweep) = extrusion_frame(item, units)?;
    let n = pts.len() as u32;
    let mut mesh = Mesh::default();
    mesh.positions.extend(pts.iter().map(|p| p.extend(0.0)));
    mesh.positions
        .extend(pts.iter().map(|p| p.extend(0.0) + sweep));
    for a in 0..n - 1 {
        mesh.triangles.push([a, a + 1, a + 1 + n]);
        mesh.triangles.push([a, a + 1 + n, a + n]);
    }
    mesh.transform(&position);
    Ok(mesh)
}

#[cfg(test)]
mod tests {
    use super::*;
    use poinav_ifc::{EntityId, Model};

    #[test]
    fn centre_line_l_is_mitred_with_square_ends() {
        let text = "ISO-10303-21;HEADER;FILE_SCHEMA(('IFC4'));ENDSEC;DATA;\n\
            #1=IFCCARTESIANPOINT((0.,0.));#2=IFCCARTESIANPOINT((4000.,0.));\
            #3=IFCCARTESIANPOINT((4000.,3000.));#4=IFCPOLYLINE((#1,#2,#3));\
            #5=IFCCENTERLINEPROFILEDEF(.AREA.,$,#4,200.);\
            #6=IFCPOLYLINE((#1,#2,#3,#1));#7=IFCCENTERLINEPROFILEDEF(.AREA.,$,#6,200.);\n\
            ENDSEC;END-ISO-10303-21;";
        let m = Model::from_bytes("t.ifc", text.as_bytes().to_vec()).unwrap();
        let mm = Units {
            metres_per_unit: 0.001,
            radians_per_unit: 1.0,
        };
        let a = center_line_area(m.entity(EntityId(5)).unwrap(), &mm).unwrap();
        // 7 m of centre line, 0.2 m thick: mitred corners keep the area exact.
        assert!((a.area() - 1.4).abs() < 1e-9, "{}", a.area());
        let (lo, hi) = polygon::bounds(&a.outer).unwrap();
        assert!(lo.distance(DVec2::new(0.0, -0.1)) < 1e-9, "{lo}");
        assert!(hi.distance(DVec2::new(4.1, 3.0)) < 1e-9, "{hi}");
        // A closed triangle of centre lines: a ring whose area is its perimeter (12 m) times
        // the thickness.
        let ring = center_line_area(m.entity(EntityId(7)).unwrap(), &mm).unwrap();
        assert_eq!(ring.holes.len(), 1);
        assert!((ring.area() - 12.0 * 0.2).abs() < 1e-9, "{}", ring.area());
    }
}
