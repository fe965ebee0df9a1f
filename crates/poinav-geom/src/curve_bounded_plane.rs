//! `IfcCurveBoundedPlane`: a piece of a plane bounded by a closed curve in the plane's own
//! coordinates, less the areas its inner boundaries enclose, as an open triangle mesh facing
//! the plane's normal.

use glam::DVec2;
use poinav_ifc::Entity;

use crate::axis2_placement::axis2placement_3d;
use crate::curve;
use crate::error::{degenerate, missing, required_ref, GeomError};
use crate::mesh::Mesh;
use crate::polygon;
use crate::self_crossing::{crossings, resolve, Crossings};
use crate::triangulation::triangulate_2d;
use crate::unit_assignment::Units;

/// The mesh of an `IfcCurveBoundedPlane` in the coordinates of the representation it is an
/// item of (metres). Its boundaries are read as profile boundaries are ([`curve::polyline`]);
/// boundaries that cross are resolved as a profile's are.
pub fn curve_bounded_plane(item: Entity<'_>, units: &Units) -> Result<Mesh, GeomError> {
    let plane = required_ref(&item, "BasisSurface", "IfcPlane")?;
    let position = plane
        .get_ref("Position")
        .ok_or_else(|| missing(&plane, "Position"))?;
    let position = axis2placement_3d(position, units.metres_per_unit)?;
    let no_area = || degenerate(&item, "the boundary encloses no area");
    let outer = curve::polyline(required_ref(&item, "OuterBoundary", "IfcCurve")?, units)?;
    let outer = polygon::clean(outer).ok_or_else(no_area)?;
    let mut holes = Vec::new();
    for inner in item.get_refs("InnerBoundaries") {
        if let Some(mut h) = polygon::clean(curve::polyline(inner, units)?) {
            h.reverse();
            holes.push(h);
        }
    }
    let rings: Vec<&[DVec2]> = std::iter::once(&outer[..])
        .chain(holes.iter().map(Vec::as_slice))
        .collect();
    let areas: Vec<(Vec<DVec2>, Vec<Vec<DVec2>>)> = match crossings(&rings) {
        Crossings::None => vec![(outer, holes)],
        Crossings::Some(_) => resolve(&outer, &holes)
            .into_iter()
            .map(|r| (r.outer, r.holes))
            .collect(),
        Crossings::TooComplex => {
            return Err(degenerate(
                &item,
                "the boundary crosses itself too often to be resolved",
            ))
        }
    };
    let mut mesh = Mesh::default();
    for (outer, holes) in &areas {
        let base = mesh.positions.len() as u32;
        let tris = triangulate_2d(outer, holes).ok_or_else(no_area)?;
        mesh.positions.extend(
            outer
                .iter()
                .chain(holes.iter().flatten())
                .map(|p| position.transform_point3(p.extend(0.0))),
        );
        mesh.triangles
            .extend(tris.iter().map(|t| t.map(|i| base + i)));
    }
    if mesh.is_empty() {
        return Err(no_area());
    }
    Ok(mesh)
}

#[cfg(test)]
mod tests {
    use super::*;
    use poinav_ifc::EntityId;

    #[test]
    fn a_square_with_a_hole_on_a_raised_plane() {
        let m = crate::test_model::ifc4(
            "#1=IFCCARTESIANPOINT((0.,0.,2.));#2=IFCAXIS2PLACEMENT3D(#1,$,$);#3=IFCPLANE(#2);\
             #4=IFCCARTESIANPOINT((0.,0.));#5=IFCCARTESIANPOINT((4.,0.));\
             #6=IFCCARTESIANPOINT((4.,4.));#7=IFCCARTESIANPOINT((0.,4.));\
             #8=IFCPOLYLINE((#4,#5,#6,#7,#4));\
             #9=IFCCARTESIANPOINT((1.,1.));#10=IFCCARTESIANPOINT((1.,2.));\
             #11=IFCCARTESIANPOINT((2.,2.));#12=IFCPOLYLINE((#9,#10,#11,#9));\
             #13=IFCCURVEBOUNDEDPLANE(#3,#8,(#12));#14=IFCCURVEBOUNDEDPLANE(#3,#12,());\
             #15=IFCPOLYLINE((#4,#5,#4));#16=IFCCURVEBOUNDEDPLANE(#3,#15,());",
        );
        let mesh = curve_bounded_plane(m.entity(EntityId(13)).unwrap(), &Units::SI).unwrap();
        assert!((mesh.area() - 15.5).abs() < 1e-12, "{}", mesh.area());
        assert!(mesh.positions.iter().all(|p| p.z == 2.0));
        // Facing the plane's normal (+z): the triangles' areas add up with their sign.
        let up: f64 = mesh
            .triangles
            .iter()
            .map(|t| {
                let [a, b, c] = t.map(|i| mesh.positions[i as usize]);
                (b - a).cross(c - a).z / 2.0
            })
            .sum();
        assert!((up - 15.5).abs() < 1e-12, "{up}");
        let small = curve_bounded_plane(m.entity(EntityId(14)).unwrap(), &Units::SI).unwrap();
        assert!((small.area() - 0.5).abs() < 1e-12);
        let err = curve_bounded_plane(m.entity(EntityId(16)).unwrap(), &Units::SI).unwrap_err();
        assert_eq!(err.id(), EntityId(16));
    }
}
