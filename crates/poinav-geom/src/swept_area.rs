//! Profiles swept along a directrix: `IfcSurfaceCurveSweptAreaSolid` (the profile's x axis
//! along the reference surface's normal: an `IfcPlane`, `IfcCylindricalSurface` or
//! `IfcSurfaceOfLinearExtrusion`),
//! `IfcFixedReferenceSweptAreaSolid` (x axis towards the `FixedReference` direction) and its
//! IFC4X3 subtype `IfcDirectrixDerivedReferenceSweptAreaSolid` (read as its supertype), the
//! concrete kinds of the abstract IFC4X3 `IfcDirectrixCurveSweptAreaSolid`. The profile comes
//! from [`crate::profile::areas`], the directrix (trimmed to `StartParam`..`EndParam`) from
//! [`crate::swept_disk::directrix_path`], the surface from [`crate::sweep`]; `Position` is
//! applied last.

use glam::DVec3;
use poinav_ifc::Entity;

use crate::axis2_placement::optional_position;
use crate::direction::direction;
use crate::error::{degenerate, missing, required_ref, unsupported, GeomError};
use crate::mesh::Mesh;
use crate::profile;
use crate::sweep::{sweep, SectionAxes};
use crate::swept_disk::directrix_path;
use crate::unit_assignment::Units;

/// True for the swept area solids this file meshes.
pub fn is_directrix_swept_area_solid(item: &Entity<'_>) -> bool {
    item.is_a("IfcSurfaceCurveSweptAreaSolid")
        || item.is_a("IfcFixedReferenceSweptAreaSolid")
        || item.is_a("IfcDirectrixCurveSweptAreaSolid")
}

/// The closed mesh of a swept area solid along a directrix, in its representation's
/// coordinates (metres).
pub fn directrix_swept_area_solid(item: Entity<'_>, units: &Units) -> Result<Mesh, GeomError> {
    let s = units.metres_per_unit;
    let surface = if item.is_a("IfcSurfaceCurveSweptAreaSolid") {
        Some(ReferenceSurface::read(
            required_ref(&item, "ReferenceSurface", "IfcSurface")?,
            units,
        )?)
    } else {
        None
    };
    let normal = |p: DVec3, d: DVec3| surface.as_ref().map_or(DVec3::Z, |r| r.normal(p, d));
    let axes = if item.is_a("IfcFixedReferenceSweptAreaSolid") {
        SectionAxes::Fixed(direction(required_ref(
            &item,
            "FixedReference",
            "IfcDirection",
        )?)?)
    } else if let Some(ReferenceSurface::Plane(n)) = surface {
        SectionAxes::Fixed(n)
    } else if surface.is_some() {
        SectionAxes::Towards(&normal)
    } else {
        return Err(unsupported(&item, "kind of swept area solid"));
    };
    let profile = required_ref(&item, "SweptArea", "IfcProfileDef")?;
    let areas = profile::areas(profile, units)?;
    let path = directrix_path(item, units)?;
    let mut mesh = sweep(&areas, &path.points, axes).ok_or_else(|| {
        degenerate(
            &item,
            "the profile cannot be triangulated or the directrix has no length",
        )
    })?;
    mesh.transform(&optional_position(&item, s)?);
    Ok(mesh)
}

/// The reference surface of an `IfcSurfaceCurveSweptAreaSolid`, for its normal.
#[derive(Debug, Clone, PartialEq)]
enum ReferenceSurface {
    /// An `IfcPlane`: its normal.
    Plane(DVec3),
    /// An `IfcCylindricalSurface`: a point of its axis and the axis (normals point away).
    Cylinder { origin: DVec3, axis: DVec3 },
    /// An `IfcSurfaceOfLinearExtrusion`: its swept curve placed (metres) and the extrusion's
    /// direction (normals are the curve's direction cross the extrusion's).
    Extrusion { curve: Vec<DVec3>, along: DVec3 },
}

impl ReferenceSurface {
    fn read(surface: Entity<'_>, units: &Units) -> Result<ReferenceSurface, GeomError> {
        let s = units.metres_per_unit;
        let position = |e: &Entity<'_>| optional_position(e, s);
        if surface.is_a("IfcPlane") {
            Ok(ReferenceSurface::Plane(position(&surface)?.matrix3.z_axis))
        } else if surface.is_a("IfcCylindricalSurface") {
            let p = position(&surface)?;
            Ok(ReferenceSurface::Cylinder {
                origin: p.translation,
                axis: p.matrix3.z_axis,
            })
        } else if surface.is_a("IfcSurfaceOfLinearExtrusion") {
            let p = position(&surface)?;
            let profile = required_ref(&surface, "SweptCurve", "IfcProfileDef")?;
            let curve = profile
                .get_ref("Curve")
                .or_else(|| profile.get_ref("OuterCurve"))
                .ok_or_else(|| missing(&profile, "Curve"))?;
            let curve = crate::curve::polyline(curve, units)?
                .into_iter()
                .map(|q| p.transform_point3(q.extend(0.0)))
                .collect::<Vec<_>>();
            let along = p.transform_vector3(direction(required_ref(
                &surface,
                "ExtrudedDirection",
                "IfcDirection",
            )?)?);
            if curve.len() < 2 {
                return Err(degenerate(&surface, "swept curve has no length"));
            }
            Ok(ReferenceSurface::Extrusion { curve, along })
        } else {
            Err(unsupported(&surface, "reference surface of a swept area"))
        }
    }

    /// The surface's normal near `p` (on a path going along `d`).
    fn normal(&self, p: DVec3, d: DVec3) -> DVec3 {
        match self {
            ReferenceSurface::Plane(n) => *n,
            ReferenceSurface::Cylinder { origin, axis } => {
                let r = p - *origin;
                r - r.dot(*axis) * *axis
            }
            ReferenceSurface::Extrusion { curve, along } => {
                // The segment of the curve nearest to p, seen along the extrusion.
                let flat = |q: DVec3| q - q.dot(*along) * *along;
                let p = flat(p);
                let mut best = (f64::INFINITY, d);
                for w in curve.windows(2) {
                    let (a, b) = (flat(w[0]), flat(w[1]));
                    let ab = b - a;
                    let f = if ab.length_squared() > 0.0 {
                        ((p - a).dot(ab) / ab.length_squared()).clamp(0.0, 1.0)
                    } else {
                        0.0
                    };
                    let dist = p.distance(a + ab * f);
                    if dist < best.0 {
                        best = (dist, w[1] - w[0]);
                    }
                }
                best.1.cross(*along)
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use poinav_ifc::{EntityId, Model};

    #[test]
    fn fixed_reference_keeps_the_profile_upright_round_a_corner() {
        // A 0.4 (x) by 0.1 (y) rectangle on its corner at the origin, x towards +z, along an
        // L in the ground plane: 3 m along x, then 2 m along y.
        let text = "ISO-10303-21;HEADER;FILE_SCHEMA(('IFC4'));ENDSEC;DATA;\n\
            #1=IFCCARTESIANPOINT((0.2,0.05));#2=IFCAXIS2PLACEMENT2D(#1,$);\
            #3=IFCRECTANGLEPROFILEDEF(.AREA.,$,#2,0.4,0.1);\
            #4=IFCCARTESIANPOINT((0.,0.,0.));#5=IFCCARTESIANPOINT((3.,0.,0.));\
            #6=IFCCARTESIANPOINT((3.,2.,0.));#7=IFCPOLYLINE((#4,#5,#6));#8=IFCDIRECTION((0.,0.,1.));\
            #9=IFCFIXEDREFERENCESWEPTAREASOLID(#3,$,#7,$,$,#8);\
            #10=IFCAXIS2PLACEMENT3D(#4,$,$);#11=IFCPLANE(#10);\
            #12=IFCSURFACECURVESWEPTAREASOLID(#3,$,#7,$,$,#11);\n\
            ENDSEC;END-ISO-10303-21;";
        let m = Model::from_bytes("t.ifc", text.as_bytes().to_vec()).unwrap();
        for id in [9, 12] {
            let mesh =
                directrix_swept_area_solid(m.entity(EntityId(id)).unwrap(), &Units::SI).unwrap();
            let (lo, hi) = mesh.bounds().unwrap();
            // y = direction x x: -y along the first leg, +x along the second.
            assert!(
                lo.distance(DVec3::new(0.0, -0.1, 0.0)) < 1e-9,
                "#{id}: {lo}"
            );
            assert!(hi.distance(DVec3::new(3.1, 2.0, 0.4)) < 1e-9, "#{id}: {hi}");
            // Mitred: both legs (0.04 m2 x 5 m) and the square at the outside of the corner
            // (0.1 x 0.1 x 0.4 m): 0.204 m3, as IfcOpenShell 0.9 gives.
            let v = mesh.volume();
            assert!((v - 0.204).abs() < 1e-9, "#{id}: {v}");
        }
    }

    #[test]
    fn ifc4x3_lengths_trim_along_the_directrix() {
        // StartParam and EndParam as IfcLengthMeasure: 1 m and 5 m along an L of 3 m + 4 m
        // (the polyline's parameters would be 1/3 and 1.5).
        let text = "ISO-10303-21;HEADER;FILE_SCHEMA(('IFC4X3_ADD2'));ENDSEC;DATA;\n\
            #1=IFCCARTESIANPOINT((0.,0.));#2=IFCAXIS2PLACEMENT2D(#1,$);\
            #3=IFCRECTANGLEPROFILEDEF(.AREA.,$,#2,0.2,0.2);\
            #4=IFCCARTESIANPOINT((0.,0.,0.));#5=IFCCARTESIANPOINT((3.,0.,0.));\
            #6=IFCCARTESIANPOINT((3.,4.,0.));#7=IFCPOLYLINE((#4,#5,#6));#8=IFCDIRECTION((0.,0.,1.));\
            #9=IFCFIXEDREFERENCESWEPTAREASOLID(#3,$,#7,IFCLENGTHMEASURE(1.),IFCLENGTHMEASURE(5.),#8);\n\
            ENDSEC;END-ISO-10303-21;";
        let m = Model::from_bytes("t.ifc", text.as_bytes().to_vec()).unwrap();
        let mesh = directrix_swept_area_solid(m.entity(EntityId(9)).unwrap(), &Units::SI).unwrap();
        let (lo, hi) = mesh.bounds().unwrap();
        assert!(lo.distance(DVec3::new(1.0, -0.1, -0.1)) < 1e-9, "{lo}");
        assert!(hi.distance(DVec3::new(3.1, 2.0, 0.1)) < 1e-9, "{hi}");
    }
}
