//! `IfcTessellatedFaceSet`: `IfcTriangulatedFaceSet` and `IfcPolygonalFaceSet` (faces with
//! holes included), indices into an `IfcCartesianPointList3D`, optionally through `PnIndex`.

use glam::DVec3;
use poinav_ifc::{Entity, Value};

use crate::cartesian_point::point_list;
use crate::error::{degenerate, missing, required_ref, unsupported, GeomError};
use crate::mesh::Mesh;
use crate::triangulation::triangulate_3d_resolving;

/// The mesh of a tessellated face set in metres (`s` metres per file unit), and whether the
/// file says it is closed (`Closed`; `$` counts as closed for triangulated sets, as in IFC).
pub fn face_set_mesh(item: Entity<'_>, s: f64) -> Result<(Mesh, bool), GeomError> {
    let list = required_ref(&item, "Coordinates", "IfcCartesianPointList3D")?;
    let points: Vec<DVec3> = point_list(list)?.into_iter().map(|p| p * s).collect();
    // 1-based indices into PnIndex when given, else into the point list. A list of lists in
    // that place is IFC4's first-release `NormalIndex` (indices into `Normals`, one triple per
    // triangle: buildingSMART's own texture examples write it), not point indices: ignored.
    let pn: Option<Vec<usize>> = item.get("PnIndex").and_then(|v| {
        v.as_list()
            .filter(|l| !l.iter().any(|i| i.as_list().is_some()))
            .map(|l| l.iter().map(|i| index(i).unwrap_or(usize::MAX)).collect())
    });
    let resolve = |i: &Value<'_>| -> Result<u32, GeomError> {
        let i =
            index(i).ok_or_else(|| degenerate(&item, "face index is not a positive integer"))?;
        let i = match &pn {
            Some(pn) => *pn
                .get(i)
                .ok_or_else(|| degenerate(&item, "face index outside PnIndex"))?,
            None => i,
        };
        if i < points.len() {
            Ok(i as u32)
        } else {
            Err(degenerate(&item, "face index outside the point list"))
        }
    };
    let closed = item.get("Closed").and_then(|v| v.as_enum()) != Some("F");
    let mut mesh = Mesh {
        positions: points.clone(),
        triangles: Vec::new(),
    };
    if item.is_a("IfcTriangulatedFaceSet") {
        let faces = item
            .get("CoordIndex")
            .ok_or_else(|| missing(&item, "CoordIndex"))?;
        for f in faces.as_list().unwrap_or_default() {
            let idx = f.as_list().unwrap_or_default();
            if idx.len() != 3 {
                return Err(degenerate(&item, "a triangle needs three indices"));
            }
            let t = [resolve(&idx[0])?, resolve(&idx[1])?, resolve(&idx[2])?];
            if t[0] != t[1] && t[1] != t[2] && t[0] != t[2] {
                mesh.triangles.push(t);
            }
        }
    } else if item.is_a("IfcPolygonalFaceSet") {
        for face in item.get_refs("Faces") {
            let ring = |v: Option<Value<'_>>| -> Result<Vec<u32>, GeomError> {
                v.as_ref()
                    .and_then(|v| v.as_list().map(|l| l.iter().map(&resolve).collect()))
                    .unwrap_or_else(|| Err(missing(&face, "CoordIndex")))
            };
            let outer = ring(face.get("CoordIndex"))?;
            let mut holes = Vec::new();
            if let Some(inner) = face.get("InnerCoordIndices") {
                for h in inner.as_list().unwrap_or_default() {
                    holes.push(ring(Some(h.clone()))?);
                }
            }
            let pos = |r: &[u32]| r.iter().map(|&i| points[i as usize]).collect::<Vec<_>>();
            let hole_pts: Vec<Vec<DVec3>> = holes.iter().map(|h| pos(h)).collect();
            let Some((added, tris)) = triangulate_3d_resolving(&pos(&outer), &hole_pts) else {
                continue;
            };
            let mut all: Vec<u32> = outer
                .iter()
                .chain(holes.iter().flatten())
                .copied()
                .collect();
            // Where bounds cross: the crossing points, this face's own.
            for p in added {
                mesh.positions.push(p);
                all.push(mesh.positions.len() as u32 - 1);
            }
            mesh.triangles.extend(
                tris.iter()
                    .map(|t| t.map(|i| all[i as usize]))
                    .filter(|t| t[0] != t[1] && t[1] != t[2] && t[0] != t[2]),
            );
        }
    } else {
        return Err(unsupported(&item, "tessellated face set"));
    }
    drop_unused_points(&mut mesh);
    Ok((mesh, closed))
}

/// Removes the points no triangle uses (a point list may hold more than this set draws, e.g.
/// under a `PnIndex`), keeping the others in order, so the mesh's bounds are the drawn ones.
fn drop_unused_points(mesh: &mut Mesh) {
    let mut new_index = vec![u32::MAX; mesh.positions.len()];
    for t in &mesh.triangles {
        for &i in t {
            new_index[i as usize] = 0;
        }
    }
    let mut kept = 0u32;
    let mut positions = Vec::with_capacity(mesh.positions.len());
    for (i, p) in mesh.positions.iter().enumerate() {
        if new_index[i] == 0 {
            new_index[i] = kept;
            kept += 1;
            positions.push(*p);
        }
    }
    mesh.positions = positions;
    for t in &mut mesh.triangles {
        *t = t.map(|i| new_index[i as usize]);
    }
}

/// A 1-based index as a 0-based one.
fn index(v: &Value<'_>) -> Option<usize> {
    v.as_i64()
        .and_then(|i| usize::try_from(i).ok())
        .and_then(|i| i.checked_sub(1))
}
