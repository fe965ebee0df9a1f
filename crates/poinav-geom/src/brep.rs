//! Boundary representations made of `IfcFace`s: `IfcFacetedBrep` (and `...WithVoids`),
//! `IfcShellBasedSurfaceModel` and `IfcFaceBasedSurfaceModel`, as triangle meshes. Faces are
//! bounded by `IfcPolyLoop`s; inner bounds become holes (several outer bounds, invalid, each
//! a face of its own); vertices are shared through the
//! `IfcCartesianPoint` they are written with, so a closed shell gives a closed mesh.

use rustc_hash::FxHashMap;

use glam::{DVec2, DVec3};
use poinav_ifc::{Entity, EntityId};

use crate::cartesian_point::point3;
use crate::error::{missing, unsupported, GeomError};
use crate::mesh::Mesh;
use crate::triangulation::{newell_normal, triangulate_3d_resolving};
use crate::unit_assignment::Units;

/// Most faces one product's breps may have.
pub const MAX_FACES: usize = 2_000_000;

/// Collects faces into one mesh, sharing vertices by point `#id`.
#[derive(Debug, Default)]
pub(crate) struct FaceMesher {
    mesh: Mesh,
    vertices: FxHashMap<EntityId, u32>,
    faces: usize,
}

impl FaceMesher {
    /// The mesh made so far.
    pub(crate) fn finish(self) -> Mesh {
        self.mesh
    }

    /// Adds the faces (`CfsFaces`) of an `IfcConnectedFaceSet` (open or closed shell).
    pub(crate) fn shell(&mut self, shell: Entity<'_>, s: f64) -> Result<(), GeomError> {
        if !shell.is_a("IfcConnectedFaceSet") {
            return Err(unsupported(
                &shell,
                "shell (expected an IfcConnectedFaceSet)",
            ));
        }
        let faces = shell.get_refs("CfsFaces");
        if faces.is_empty() {
            return Err(missing(&shell, "CfsFaces"));
        }
        for face in faces {
            self.face(face, s)?;
        }
        Ok(())
    }

    /// Adds one `IfcFace`. Faces with no area are left out.
    fn face(&mut self, face: Entity<'_>, s: f64) -> Result<(), GeomError> {
        self.faces += 1;
        if self.faces > MAX_FACES {
            return Err(crate::error::degenerate(&face, "too many faces"));
        }
        let mut loops: Vec<FaceLoop> = Vec::new();
        for bound in face.get_refs("Bounds") {
            let lp = bound
                .get_ref("Bound")
                .ok_or_else(|| missing(&bound, "Bound"))?;
            if !lp.is_a("IfcPolyLoop") {
                return Err(unsupported(&lp, "face loop (only IfcPolyLoop)"));
            }
            let mut ids = lp.get("Polygon").map(|v| v.refs()).unwrap_or_default();
            ids.dedup();
            while ids.len() > 1 && ids.first() == ids.last() {
                ids.pop();
            }
            if ids.len() < 3 {
                continue;
            }
            if bound.get("Orientation").and_then(|v| v.as_enum()) == Some("F") {
                ids.reverse();
            }
            let mut pts = Vec::with_capacity(ids.len());
            for &id in &ids {
                let p = lp
                    .model()
                    .entity(id)
                    .ok_or_else(|| missing(&lp, "Polygon"))?;
                pts.push(point3(p)? * s);
            }
            loops.push((bound.is_a("IfcFaceOuterBound"), ids, pts));
        }
        if loops.is_empty() {
            return Ok(());
        }
        // Several outer bounds (invalid, but written): each a face of its own with the inner
        // bounds inside it, as IfcOpenShell meshes them.
        let first_outer = loops.iter().position(|l| l.0);
        let normal = first_outer.and_then(|i| newell_normal(&loops[i].2).try_normalize());
        if let (Some(normal), true) = (normal, loops.iter().filter(|l| l.0).count() > 1) {
            let u = normal.any_orthonormal_vector();
            let v = normal.cross(u);
            let flat = |p: &DVec3| DVec2::new(p.dot(u), p.dot(v));
            let (outers, inner): (Vec<FaceLoop>, Vec<FaceLoop>) =
                loops.into_iter().partition(|l| l.0);
            let mut inner: Vec<Option<FaceLoop>> = inner.into_iter().map(Some).collect();
            for outer in outers {
                let ring: Vec<DVec2> = outer.2.iter().map(flat).collect();
                let holes: Vec<FaceLoop> = inner
                    .iter_mut()
                    .filter(|h| {
                        h.as_ref()
                            .is_some_and(|h| crate::polygon::contains(&ring, flat(&h.2[0])))
                    })
                    .filter_map(Option::take)
                    .collect();
                self.polygon(outer, holes);
            }
            return Ok(());
        }
        // The outer bound; when none is marked, the loop enclosing the most area.
        let outer = loops.iter().position(|l| l.0).unwrap_or_else(|| {
            (0..loops.len())
                .max_by(|&a, &b| {
                    let area = |i: usize| newell_normal(&loops[i].2).length();
                    area(a).total_cmp(&area(b))
                })
                .unwrap_or(0)
        });
        let outer_loop = loops.swap_remove(outer);
        self.polygon(outer_loop, loops);
        Ok(())
    }

    /// Adds one face's polygon: its outer loop and the loops that are its holes.
    fn polygon(&mut self, outer_loop: FaceLoop, loops: Vec<FaceLoop>) {
        let holes: Vec<Vec<DVec3>> = loops.iter().map(|l| l.2.clone()).collect();
        let Some((added, tris)) = triangulate_3d_resolving(&outer_loop.2, &holes) else {
            return;
        };
        let ids: Vec<EntityId> = std::iter::once(&outer_loop)
            .chain(loops.iter())
            .flat_map(|l| l.1.iter().copied())
            .collect();
        let pts: Vec<DVec3> = std::iter::once(&outer_loop)
            .chain(loops.iter())
            .flat_map(|l| l.2.iter().copied())
            .collect();
        let mut index: Vec<u32> = ids
            .iter()
            .zip(&pts)
            .map(|(id, p)| {
                *self.vertices.entry(*id).or_insert_with(|| {
                    self.mesh.positions.push(*p);
                    self.mesh.positions.len() as u32 - 1
                })
            })
            .collect();
        // Where bounds cross: the crossing points, this face's own.
        for p in added {
            self.mesh.positions.push(p);
            index.push(self.mesh.positions.len() as u32 - 1);
        }
        self.mesh.triangles.extend(
            tris.iter()
                .map(|t| t.map(|i| index[i as usize]))
                .filter(|t| t[0] != t[1] && t[1] != t[2] && t[0] != t[2]),
        );
    }
}

/// True when some face of the surface model `item` is bounded by an `IfcEdgeLoop`.
fn has_edge_loop(item: Entity<'_>) -> bool {
    [item.get_refs("FbsmFaces"), item.get_refs("SbsmBoundary")]
        .concat()
        .iter()
        .flat_map(|shell| shell.get_refs("CfsFaces"))
        .flat_map(|face| face.get_refs("Bounds"))
        .any(|b| b.get_ref("Bound").is_some_and(|lp| lp.is_a("IfcEdgeLoop")))
}

/// One bound of a face: whether it is the outer one, its points' `#id`s and the points.
type FaceLoop = (bool, Vec<EntityId>, Vec<DVec3>);

/// The mesh of an `IfcFacetedBrep` (outer shell and, for `...WithVoids`, the void shells),
/// an `IfcShellBasedSurfaceModel` or an `IfcFaceBasedSurfaceModel` (faces on surfaces or
/// bounded by edge loops by [`crate::advanced_brep::surface_model`]), in metres; true when
/// it is a solid (a brep) rather than a surface model.
pub fn face_mesh(item: Entity<'_>, units: &Units) -> Result<(Mesh, bool), GeomError> {
    if !item.is_a("IfcManifoldSolidBrep") && crate::advanced_brep::has_face_surfaces(item) {
        return Ok((crate::advanced_brep::surface_model(item, units)?, false));
    }
    let s = units.metres_per_unit;
    let mut m = FaceMesher::default();
    let solid = if item.is_a("IfcManifoldSolidBrep") {
        if !item.is_a("IfcFacetedBrep") {
            return Err(unsupported(&item, "brep (only faceted breps)"));
        }
        let outer = item
            .get_ref("Outer")
            .ok_or_else(|| missing(&item, "Outer"))?;
        m.shell(outer, s)?;
        for void in item.get_refs("Voids") {
            m.shell(void, s)?;
        }
        true
    } else if item.is_a("IfcFaceBasedSurfaceModel") || item.is_a("IfcShellBasedSurfaceModel") {
        for shell in [item.get_refs("FbsmFaces"), item.get_refs("SbsmBoundary")].concat() {
            if let Err(e) = m.shell(shell, s) {
                // A shell whose first face has poly loops but a later one an edge loop
                // ([`crate::advanced_brep::has_face_surfaces`] looks at the first face only, to
                // stay cheap on big meshes): the advanced mesher takes every kind of bound.
                if has_edge_loop(item) {
                    return Ok((crate::advanced_brep::surface_model(item, units)?, false));
                }
                return Err(e);
            }
        }
        false
    } else {
        return Err(unsupported(&item, "face-based representation item"));
    };
    Ok((m.finish(), solid))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_surface_model_mixing_poly_loops_and_edge_loops_is_meshed_whole() {
        // Two unit squares: at z = 0 bounded by a poly loop (the first face), at z = 1 by an
        // edge loop of four edge curves along polylines.
        let m = crate::test_model::ifc4(
            "#1=IFCCARTESIANPOINT((0.,0.,0.));#2=IFCCARTESIANPOINT((1.,0.,0.));\
             #3=IFCCARTESIANPOINT((1.,1.,0.));#4=IFCCARTESIANPOINT((0.,1.,0.));\
             #5=IFCPOLYLOOP((#1,#2,#3,#4));#6=IFCFACEOUTERBOUND(#5,.T.);#7=IFCFACE((#6));\
             #11=IFCCARTESIANPOINT((0.,0.,1.));#12=IFCCARTESIANPOINT((1.,0.,1.));\
             #13=IFCCARTESIANPOINT((1.,1.,1.));#14=IFCCARTESIANPOINT((0.,1.,1.));\
             #21=IFCVERTEXPOINT(#11);#22=IFCVERTEXPOINT(#12);\
             #23=IFCVERTEXPOINT(#13);#24=IFCVERTEXPOINT(#14);\
             #31=IFCPOLYLINE((#11,#12));#32=IFCPOLYLINE((#12,#13));\
             #33=IFCPOLYLINE((#13,#14));#34=IFCPOLYLINE((#14,#11));\
             #41=IFCEDGECURVE(#21,#22,#31,.T.);#42=IFCEDGECURVE(#22,#23,#32,.T.);\
             #43=IFCEDGECURVE(#23,#24,#33,.T.);#44=IFCEDGECURVE(#24,#21,#34,.T.);\
             #51=IFCORIENTEDEDGE(*,*,#41,.T.);#52=IFCORIENTEDEDGE(*,*,#42,.T.);\
             #53=IFCORIENTEDEDGE(*,*,#43,.T.);#54=IFCORIENTEDEDGE(*,*,#44,.T.);\
             #61=IFCEDGELOOP((#51,#52,#53,#54));#62=IFCFACEOUTERBOUND(#61,.T.);\
             #63=IFCFACE((#62));#70=IFCCONNECTEDFACESET((#7,#63));\
             #71=IFCFACEBASEDSURFACEMODEL((#70));#72=IFCCONNECTEDFACESET((#7));\
             #73=IFCFACEBASEDSURFACEMODEL((#72));",
        );
        let (mesh, solid) = face_mesh(m.entity(EntityId(71)).unwrap(), &Units::SI).unwrap();
        assert!(!solid);
        assert!((mesh.area() - 2.0).abs() < 1e-9, "{}", mesh.area());
        let zs: Vec<f64> = mesh.positions.iter().map(|p| p.z).collect();
        assert!(zs.contains(&0.0) && zs.contains(&1.0));
        // Poly loops alone stay on the faceted path.
        let (mesh, _) = face_mesh(m.entity(EntityId(73)).unwrap(), &Units::SI).unwrap();
        assert!((mesh.area() - 1.0).abs() < 1e-9, "{}", mesh.area());
    }

    #[test]
    fn each_of_several_outer_bounds_is_a_face_with_the_holes_inside_it() {
        // Two 0.3 x 0.8 m rectangles as outer bounds of one face (invalid), a 0.1 x 0.2 m hole
        // in the first: 0.24 - 0.02 + 0.24 m2.
        let m = crate::test_model::ifc4(
            "#1=IFCCARTESIANPOINT((-0.4,-0.4,0.));#2=IFCCARTESIANPOINT((-0.1,-0.4,0.));\
             #3=IFCCARTESIANPOINT((-0.1,0.4,0.));#4=IFCCARTESIANPOINT((-0.4,0.4,0.));\
             #5=IFCPOLYLOOP((#1,#2,#3,#4));\
             #6=IFCCARTESIANPOINT((-0.3,-0.1,0.));#7=IFCCARTESIANPOINT((-0.2,-0.1,0.));\
             #8=IFCCARTESIANPOINT((-0.2,0.1,0.));#9=IFCCARTESIANPOINT((-0.3,0.1,0.));\
             #10=IFCPOLYLOOP((#6,#7,#8,#9));\
             #11=IFCCARTESIANPOINT((0.1,-0.4,0.));#12=IFCCARTESIANPOINT((0.4,-0.4,0.));\
             #13=IFCCARTESIANPOINT((0.4,0.4,0.));#14=IFCCARTESIANPOINT((0.1,0.4,0.));\
             #15=IFCPOLYLOOP((#11,#12,#13,#14));\
             #16=IFCFACEOUTERBOUND(#5,.T.);#17=IFCFACEBOUND(#10,.F.);\
             #18=IFCFACEOUTERBOUND(#15,.T.);#19=IFCFACE((#16,#17,#18));\
             #20=IFCCONNECTEDFACESET((#19));#21=IFCFACEBASEDSURFACEMODEL((#20));",
        );
        let item = m.entity(EntityId(21)).unwrap();
        let (mesh, solid) = face_mesh(item, &Units::SI).unwrap();
        assert!(!solid);
        assert!((mesh.area() - 0.46).abs() < 1e-9, "{}", mesh.area());
        // Nothing of the hole is covered: its centre is off every triangle.
        let centre = DVec3::new(-0.25, 0.0, 0.0);
        let covered = mesh.triangles.iter().any(|t| {
            let [a, b, c] = t.map(|i| mesh.positions[i as usize].truncate());
            let side = |p: DVec2, q: DVec2| (q - p).perp_dot(centre.truncate() - p);
            let s = [side(a, b), side(b, c), side(c, a)];
            s.iter().all(|&x| x > 0.0) || s.iter().all(|&x| x < 0.0)
        });
        assert!(!covered);
    }
}
