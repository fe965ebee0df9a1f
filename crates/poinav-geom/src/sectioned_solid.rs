//! `IfcSectionedSolidHorizontal` and `IfcSectionedSurface`: profiles placed at distances along
//! a directrix (an alignment's basis curve, [`crate::gradient_curve`]) and lofted between
//! consecutive ones, point by point: areas into a closed solid, open profiles
//! (`IfcOpenCrossProfileDef`, `IfcArbitraryOpenProfileDef`) into an open surface.
//!
//! Each cross section stands square to the curve: profile x to the left of travel (horizontal),
//! profile y along the curve's normal (up, tilted by the gradient), as IfcOpenShell places
//! them. Between two positions the profile points and the lateral and vertical offsets are
//! interpolated linearly by distance along; the curve is sampled where it bends, intervals
//! halved until the curve's midpoint lies within [`SAG_TOLERANCE`] of the chord and the tangent
//! turns by at most [`MAX_TURN`]. Consecutive sections need the same number of points per ring;
//! sections with explicit `Axis` / `RefDirection` are not supported. A position may also be an
//! `IfcPointByDistanceExpression` itself, as IFC4X3_RC2 files write them.

use glam::{DVec2, DVec3};
use poinav_ifc::Entity;

use crate::error::{degenerate, missing, required_ref, unsupported, GeomError};
use crate::gradient_curve::{BasisCurve, Frame3};
use crate::mesh::Mesh;
use crate::open_profile::open_profile_points;
use crate::profile::{areas, ProfileArea};
use crate::triangulation::triangulate_2d;
use crate::unit_assignment::Units;

/// Largest distance between the curve and the chord of one loft step (metres).
pub const SAG_TOLERANCE: f64 = 0.002;

/// Largest turn of the tangent over one loft step (radians, 2 degrees).
pub const MAX_TURN: f64 = 0.035;

/// Most loft steps one solid may have.
pub const MAX_STEPS: usize = 100_000;

/// One cross section: distance along (file units), offsets (metres), profile rings (metres).
struct Section {
    along: f64,
    lateral: f64,
    vertical: f64,
    area: ProfileArea,
}

fn offset(e: &Entity<'_>, name: &'static str) -> Result<f64, GeomError> {
    match e.get(name) {
        None => Ok(0.0),
        Some(v) => v
            .as_f64()
            .filter(|x| x.is_finite())
            .ok_or_else(|| missing(e, name)),
    }
}

/// The mesh of an `IfcSectionedSolidHorizontal` in metres, in the coordinates of its
/// directrix `curve` (read from the item's `Directrix`).
pub fn sectioned_solid_horizontal(
    item: Entity<'_>,
    units: &Units,
    curve: &BasisCurve,
) -> Result<Mesh, GeomError> {
    let (rings, area) = lofted(item, units, curve, false)?;
    loft(&rings, &area).ok_or_else(|| degenerate(&item, "cross section cannot be triangulated"))
}

/// The open surface of an `IfcSectionedSurface` (open profiles) in metres, in the
/// coordinates of its directrix `curve`: one strip of quads per segment of the profiles.
pub fn sectioned_surface(
    item: Entity<'_>,
    units: &Units,
    curve: &BasisCurve,
) -> Result<Mesh, GeomError> {
    let (rings, _) = lofted(item, units, curve, true)?;
    Ok(strip(&rings))
}

/// The sections of `item` placed along `curve` at every loft step, and the first section's
/// profile (its ring layout); `open` reads the profiles as open polylines.
fn lofted(
    item: Entity<'_>,
    units: &Units,
    curve: &BasisCurve,
    open: bool,
) -> Result<(Vec<Vec<DVec3>>, ProfileArea), GeomError> {
    let profiles = item.get_refs("CrossSections");
    let positions = item.get_refs("CrossSectionPositions");
    if profiles.len() < 2 || profiles.len() != positions.len() {
        return Err(degenerate(
            &item,
            "needs as many cross section positions as cross sections, at least two",
        ));
    }
    let s = units.metres_per_unit;
    let mut sections = Vec::with_capacity(profiles.len());
    for (profile, position) in profiles.into_iter().zip(positions) {
        let p = if position.is_a("IfcPointByDistanceExpression") {
            // IFC4X3_RC2 (Allplan) gives the positions as the points themselves.
            position
        } else if position.is_a("IfcAxis2PlacementLinear") {
            if position.get("Axis").is_some() || position.get("RefDirection").is_some() {
                return Err(unsupported(&position, "cross section with its own axes"));
            }
            required_ref(&position, "Location", "IfcPointByDistanceExpression")?
        } else {
            return Err(unsupported(
                &position,
                "expected an IfcAxis2PlacementLinear",
            ));
        };
        let along = p
            .get("DistanceAlong")
            .and_then(|v| v.as_f64())
            .filter(|x| x.is_finite())
            .ok_or_else(|| missing(&p, "DistanceAlong"))?;
        let area = if open {
            ProfileArea {
                outer: open_profile_points(profile, units)?,
                holes: Vec::new(),
            }
        } else {
            let mut a = areas(profile, units)?;
            if a.len() != 1 {
                return Err(unsupported(&profile, "cross section of several areas"));
            }
            a.remove(0)
        };
        sections.push(Section {
            along,
            lateral: offset(&p, "OffsetLateral")? * s,
            vertical: offset(&p, "OffsetVertical")? * s,
            area,
        });
    }
    sections.sort_by(|a, b| a.along.total_cmp(&b.along));
    let shape = |a: &ProfileArea| {
        std::iter::once(a.outer.len())
            .chain(a.holes.iter().map(Vec::len))
            .collect::<Vec<_>>()
    };
    let first = shape(&sections[0].area);
    if sections.iter().any(|x| shape(&x.area) != first) {
        return Err(unsupported(
            &item,
            "cross sections with different point counts",
        ));
    }
    if sections.last().map(|x| x.along) <= Some(sections[0].along) {
        return Err(degenerate(&item, "cross sections span no distance"));
    }
    // Distances to place a section at.
    let mut steps = vec![sections[0].along];
    for w in sections.windows(2) {
        refine(curve, w[0].along, w[1].along, &mut steps, 0);
        if steps.len() > MAX_STEPS {
            return Err(degenerate(&item, "directrix needs too many loft steps"));
        }
    }
    let rings: Vec<Vec<DVec3>> = steps
        .iter()
        .map(|&d| ring(curve.frame(d), &sections, d))
        .collect();
    Ok((rings, sections.swap_remove(0).area))
}

/// Appends the distances after `a` up to `b` at which to place sections.
fn refine(curve: &BasisCurve, a: f64, b: f64, out: &mut Vec<f64>, depth: u32) {
    let (fa, fb) = (curve.frame(a), curve.frame(b));
    let m = (a + b) / 2.0;
    let fm = curve.frame(m);
    let sag = (fm.origin - (fa.origin + fb.origin) / 2.0).length();
    let turn = fa.tangent.angle_between(fb.tangent);
    if depth < 20 && out.len() < MAX_STEPS && (sag > SAG_TOLERANCE || turn > MAX_TURN) {
        refine(curve, a, m, out, depth + 1);
        refine(curve, m, b, out, depth + 1);
    } else {
        out.push(b);
    }
}

/// The section at distance `d` (profile points and offsets interpolated), in the world.
fn ring(f: Frame3, sections: &[Section], d: f64) -> Vec<DVec3> {
    let i = sections
        .partition_point(|x| x.along <= d)
        .clamp(1, sections.len() - 1);
    let (a, b) = (&sections[i - 1], &sections[i]);
    let t = ((d - a.along) / (b.along - a.along)).clamp(0.0, 1.0);
    let lerp = |x: f64, y: f64| x + (y - x) * t;
    let origin =
        f.origin + f.left * lerp(a.lateral, b.lateral) + f.normal * lerp(a.vertical, b.vertical);
    let pa = points(&a.area);
    let pb = points(&b.area);
    pa.iter()
        .zip(&pb)
        .map(|(p, q)| {
            let p = p.lerp(*q, t);
            origin + f.left * p.x + f.normal * p.y
        })
        .collect()
}

fn points(a: &ProfileArea) -> Vec<DVec2> {
    a.outer
        .iter()
        .chain(a.holes.iter().flatten())
        .copied()
        .collect()
}

/// Side walls between consecutive rings and caps at both ends (`area` gives the ring layout
/// and the cap triangulation); triangles face out.
fn loft(rings: &[Vec<DVec3>], area: &ProfileArea) -> Option<Mesh> {
    let cap = triangulate_2d(&area.outer, &area.holes)?;
    let n = rings.first()?.len() as u32;
    let mut mesh = Mesh {
        positions: rings.iter().flatten().copied().collect(),
        triangles: Vec::new(),
    };
    let last = (rings.len() as u32 - 1) * n;
    for t in &cap {
        mesh.triangles.push([t[0], t[2], t[1]]);
        mesh.triangles.push(t.map(|i| last + i));
    }
    let lens: Vec<u32> = std::iter::once(area.outer.len())
        .chain(area.holes.iter().map(Vec::len))
        .map(|l| l as u32)
        .collect();
    for r in 0..rings.len() as u32 - 1 {
        let (a0, b0) = (r * n, (r + 1) * n);
        let mut start = 0;
        for &len in &lens {
            for i in 0..len {
                let (p, q) = (start + i, start + (i + 1) % len);
                mesh.triangles.push([a0 + p, a0 + q, b0 + q]);
                mesh.triangles.push([a0 + p, b0 + q, b0 + p]);
            }
            start += len;
        }
    }
    Some(mesh)
}

/// Quads between consecutive rings, each ring an open polyline (no caps).
fn strip(rings: &[Vec<DVec3>]) -> Mesh {
    let n = rings.first().map_or(0, Vec::len) as u32;
    let mut mesh = Mesh {
        positions: rings.iter().flatten().copied().collect(),
        triangles: Vec::new(),
    };
    for r in 0..(rings.len() as u32).saturating_sub(1) {
        let (a0, b0) = (r * n, (r + 1) * n);
        for i in 0..n.saturating_sub(1) {
            mesh.triangles.push([a0 + i, a0 + i + 1, b0 + i + 1]);
            mesh.triangles.push([a0 + i, b0 + i + 1, b0 + i]);
        }
    }
    mesh
}

#[cfg(test)]
mod tests {
    use super::*;
    use poinav_ifc::{EntityId, Model};

    #[test]
    fn a_box_section_along_a_gradient_line_is_a_closed_prism() {
        let text = "ISO-10303-21;HEADER;FILE_SCHEMA(('IFC4X3_ADD2'));ENDSEC;DATA;\n\
            #1=IFCCARTESIANPOINT((0.,0.));#2=IFCDIRECTION((1.,0.));#3=IFCAXIS2PLACEMENT2D(#1,#2);\
            #6=IFCVECTOR(#2,1.);#7=IFCLINE(#1,#6);\
            #8=IFCCURVESEGMENT(.CONTINUOUS.,#3,IFCLENGTHMEASURE(0.),IFCLENGTHMEASURE(100.),#7);\
            #9=IFCCOMPOSITECURVE((#8),.F.);\
            #20=IFCRECTANGLEPROFILEDEF(.AREA.,$,$,4.,1.);\
            #21=IFCPOINTBYDISTANCEEXPRESSION(IFCLENGTHMEASURE(10.),1.,0.5,$,#9);\
            #22=IFCAXIS2PLACEMENTLINEAR(#21,$,$);\
            #23=IFCPOINTBYDISTANCEEXPRESSION(IFCLENGTHMEASURE(30.),1.,0.5,$,#9);\
            #24=IFCAXIS2PLACEMENTLINEAR(#23,$,$);\
            #25=IFCSECTIONEDSOLIDHORIZONTAL(#9,(#20,#20),(#22,#24));\n\
            ENDSEC;END-ISO-10303-21;";
        let m = Model::from_bytes("t.ifc", text.as_bytes().to_vec()).unwrap();
        let item = m.entity(EntityId(25)).unwrap();
        let curve = BasisCurve::read(m.entity(EntityId(9)).unwrap(), &Units::SI).unwrap();
        let mesh = sectioned_solid_horizontal(item, &Units::SI, &curve).unwrap();
        let (lo, hi) = mesh.bounds().unwrap();
        // 20 m along x, 4 m wide centred 1 m to the left (+y), 1 m high centred 0.5 m up.
        assert!((lo - DVec3::new(10.0, -1.0, 0.0)).length() < 1e-9, "{lo}");
        assert!((hi - DVec3::new(30.0, 3.0, 1.0)).length() < 1e-9, "{hi}");
        assert!((mesh.volume() - 80.0).abs() < 1e-9, "{}", mesh.volume());
    }

    #[test]
    fn ifc4x3_rc2_positions_are_points_along_a_3d_polyline() {
        // As Allplan writes a girder in IFC4X3_RC2: the positions are the points themselves,
        // the directrix a polyline 0.2 m below the origin; a 4 x 1 m rectangle from 10 to 30 m.
        let text = "ISO-10303-21;HEADER;FILE_SCHEMA(('IFC4X3_RC2'));ENDSEC;DATA;\n\
            #1=IFCCARTESIANPOINT((0.,-5.,-0.2));#2=IFCCARTESIANPOINT((45.,-5.,-0.2));\
            #3=IFCPOLYLINE((#1,#2));#20=IFCRECTANGLEPROFILEDEF(.AREA.,$,$,4.,1.);\
            #21=IFCPOINTBYDISTANCEEXPRESSION(IFCNONNEGATIVELENGTHMEASURE(10.),$,$,$,#3);\
            #22=IFCPOINTBYDISTANCEEXPRESSION(IFCNONNEGATIVELENGTHMEASURE(30.),$,$,$,#3);\
            #25=IFCSECTIONEDSOLIDHORIZONTAL(#3,(#20,#20),(#21,#22),.T.);\n\
            ENDSEC;END-ISO-10303-21;";
        let m = Model::from_bytes("t.ifc", text.as_bytes().to_vec()).unwrap();
        let item = m.entity(EntityId(25)).unwrap();
        let curve = BasisCurve::read(m.entity(EntityId(3)).unwrap(), &Units::SI).unwrap();
        let mesh = sectioned_solid_horizontal(item, &Units::SI, &curve).unwrap();
        let (lo, hi) = mesh.bounds().unwrap();
        assert!((lo - DVec3::new(10.0, -7.0, -0.7)).length() < 1e-9, "{lo}");
        assert!((hi - DVec3::new(30.0, -3.0, 0.3)).length() < 1e-9, "{hi}");
        assert!((mesh.volume() - 80.0).abs() < 1e-9, "{}", mesh.volume());
    }
}
