//! Finding elements whose geometry is a rigid copy of an earlier element's (the same vertices
//! and triangles in the same order, moved, rotated and possibly mirrored), so that a writer
//! stores the geometry once and places it several times.
//!
//! IFC shares geometry through `IfcMappedItem`s (a chair family placed 300 times), but
//! `poinav-geom` meshes each product in world coordinates; a mapped item's mesh keeps the
//! representation map's vertex and triangle order, so copies are recognised here from the
//! element meshes alone: same material, same triangle list, and every vertex where one
//! orthogonal map of the first element's vertices puts it (within [`TOLERANCE`]). Anything
//! that does not match (booleans with openings, welded corners that differ) simply stays a
//! mesh of its own.

use glam::{DMat3, DVec3};
use rustc_hash::{FxHashMap, FxHasher};
use std::hash::{Hash, Hasher};

/// Largest distance (metres) between a vertex and where the map puts it: 0.1 mm, below what
/// the viewer's quantisation keeps (1/32767 of a mesh's half-size) for anything over 3 m.
pub const TOLERANCE: f64 = 1e-4;

/// Where a copy's vertices are relative to its original's, both in element-local
/// coordinates: `copy = linear * original + offset`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Placement {
    /// Orthogonal (a rotation, or a rotation and a mirror when its determinant is -1); exactly
    /// the identity for a copy that is only moved.
    pub linear: DMat3,
    /// Translation.
    pub offset: DVec3,
}

/// One original: its geometry, the three vertices that fix its frame and an invariant that
/// rules most other shapes out before the vertex-by-vertex check.
#[derive(Debug)]
struct Shape {
    id: usize,
    positions: Vec<[f32; 3]>,
    /// Vertex indices `a`, `b` (farthest from `a`), `c` (farthest from the line `ab`).
    frame: [usize; 3],
    /// Sum of squared distances to vertex `a`: unchanged by rotations and mirrors.
    spread: f64,
    triangles: Vec<[u32; 3]>,
}

/// The originals seen so far, bucketed by material, vertex count and triangle list.
#[derive(Debug, Default)]
pub struct Instances {
    buckets: FxHashMap<u64, Vec<Shape>>,
}

fn v(p: [f32; 3]) -> DVec3 {
    DVec3::from(p.map(f64::from))
}

/// The bucket key: a hash of the material, the vertex count and the triangles (a hash
/// collision only costs a comparison: the triangles are compared in full).
fn key(material: usize, n_positions: usize, triangles: &[[u32; 3]]) -> u64 {
    let mut h = FxHasher::default();
    material.hash(&mut h);
    n_positions.hash(&mut h);
    triangles.hash(&mut h);
    h.finish()
}

fn spread(positions: &[[f32; 3]], a: usize) -> f64 {
    let o = v(positions[a]);
    positions.iter().map(|p| (v(*p) - o).length_squared()).sum()
}

/// The frame vertices of `positions`, `None` when the vertices are (nearly) collinear.
fn frame(positions: &[[f32; 3]]) -> Option<[usize; 3]> {
    let a = v(*positions.first()?);
    let (b, _) = positions
        .iter()
        .enumerate()
        .map(|(i, p)| (i, (v(*p) - a).length_squared()))
        .fold((0, 0.0), |best, x| if x.1 > best.1 { x } else { best });
    let ab = v(positions[b]) - a;
    if ab.length() < 1e-3 {
        return None;
    }
    let (c, area) = positions
        .iter()
        .enumerate()
        .map(|(i, p)| (i, (v(*p) - a).cross(ab).length()))
        .fold((0, 0.0), |best, x| if x.1 > best.1 { x } else { best });
    // The third vertex must stand at least 1 mm off the line `ab`.
    (area / ab.length() >= 1e-3).then_some([0, b, c])
}

/// The orthonormal frame (columns) of the points `a`, `b`, `c`.
fn basis(a: DVec3, b: DVec3, c: DVec3) -> DMat3 {
    let e1 = (b - a).normalize();
    let e2 = ((c - a) - e1 * e1.dot(c - a)).normalize();
    DMat3::from_cols(e1, e2, e1.cross(e2))
}

/// Whether `linear * original + offset` puts every vertex within [`TOLERANCE`] of the copy's.
fn fits(original: &[[f32; 3]], copy: &[[f32; 3]], linear: DMat3, offset: DVec3) -> bool {
    original
        .iter()
        .zip(copy)
        .all(|(o, c)| (linear * v(*o) + offset - v(*c)).length_squared() <= TOLERANCE * TOLERANCE)
}

impl Shape {
    /// The placement of `copy` (same triangles, same vertex count) relative to this shape.
    fn place(&self, copy: &[[f32; 3]]) -> Option<Placement> {
        let [a, b, c] = self.frame;
        if (spread(copy, a) - self.spread).abs() > 1e-3 * (1.0 + self.spread) {
            return None;
        }
        let (oa, ca) = (v(self.positions[a]), v(copy[a]));
        // Only moved: the exact identity, the most common case (and the cleanest output).
        if fits(&self.positions, copy, DMat3::IDENTITY, ca - oa) {
            return Some(Placement {
                linear: DMat3::IDENTITY,
                offset: ca - oa,
            });
        }
        let from = basis(oa, v(self.positions[b]), v(self.positions[c]));
        let to = basis(ca, v(copy[b]), v(copy[c]));
        let mirrored = DMat3::from_cols(to.x_axis, to.y_axis, -to.z_axis);
        [to, mirrored].into_iter().find_map(|to| {
            let linear = to * from.transpose();
            let offset = ca - linear * oa;
            fits(&self.positions, copy, linear, offset).then_some(Placement { linear, offset })
        })
    }
}

impl Instances {
    /// The original `copy` is a copy of, with its id and the copy's placement.
    pub fn find(
        &self,
        material: usize,
        positions: &[[f32; 3]],
        triangles: &[[u32; 3]],
    ) -> Option<(usize, Placement)> {
        let bucket = self
            .buckets
            .get(&key(material, positions.len(), triangles))?;
        bucket
            .iter()
            .filter(|s| s.positions.len() == positions.len() && s.triangles == triangles)
            .find_map(|s| Some((s.id, s.place(positions)?)))
    }

    /// Records an original under the caller's `id` (shapes whose vertices are all on one line
    /// are not recorded: no frame fixes their rotation).
    pub fn add(
        &mut self,
        id: usize,
        material: usize,
        positions: Vec<[f32; 3]>,
        triangles: Vec<[u32; 3]>,
    ) {
        let Some(frame) = frame(&positions) else {
            return;
        };
        let shape = Shape {
            id,
            spread: spread(&positions, frame[0]),
            frame,
            triangles,
            positions,
        };
        self.buckets
            .entry(key(material, shape.positions.len(), &shape.triangles))
            .or_default()
            .push(shape);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DQuat;

    /// An L-shaped, asymmetric solid's vertices (a mirror of it is not a rotation of it).
    fn shape() -> Vec<[f32; 3]> {
        vec![
            [0.0, 0.0, 0.0],
            [2.0, 0.0, 0.0],
            [2.0, 0.5, 0.0],
            [0.5, 0.5, 0.0],
            [0.5, 1.5, 0.0],
            [0.0, 1.5, 0.3],
        ]
    }

    fn tris() -> Vec<[u32; 3]> {
        vec![[0, 1, 2], [0, 2, 3], [0, 3, 4], [0, 4, 5]]
    }

    fn map(ps: &[[f32; 3]], m: DMat3, t: DVec3) -> Vec<[f32; 3]> {
        ps.iter()
            .map(|p| (m * v(*p) + t).as_vec3().to_array())
            .collect()
    }

    fn close(a: DMat3, b: DMat3) -> bool {
        (a - b).to_cols_array().iter().all(|x| x.abs() < 1e-6)
    }

    #[test]
    fn finds_moved_rotated_and_mirrored_copies_and_nothing_else() {
        let mut found = Instances::default();
        found.add(7, 0, shape(), tris());
        let t = DVec3::new(3.0, -1.0, 0.25);

        let moved = found.find(0, &map(&shape(), DMat3::IDENTITY, t), &tris());
        let (id, p) = moved.unwrap();
        assert_eq!(id, 7);
        assert_eq!(p.linear, DMat3::IDENTITY);
        assert!((p.offset - t).length() < 1e-6);

        let turn = DMat3::from_quat(DQuat::from_rotation_y(0.7));
        let (_, p) = found.find(0, &map(&shape(), turn, t), &tris()).unwrap();
        assert!(close(p.linear, turn), "{p:?}");
        assert!((p.offset - t).length() < 1e-5);

        let mirror = turn * DMat3::from_diagonal(DVec3::new(-1.0, 1.0, 1.0));
        let (_, p) = found.find(0, &map(&shape(), mirror, t), &tris()).unwrap();
        assert!(close(p.linear, mirror), "{p:?}");
        assert!((p.linear.determinant() + 1.0).abs() < 1e-9);

        // Another material, another triangle list, a stretched copy, a vertex moved by 1 mm.
        assert!(found.find(1, &shape(), &tris()).is_none());
        assert!(found.find(0, &shape(), &tris()[1..]).is_none());
        let stretched = DMat3::from_diagonal(DVec3::new(1.01, 1.0, 1.0));
        assert!(found
            .find(0, &map(&shape(), stretched, t), &tris())
            .is_none());
        let mut bent = shape();
        bent[4][2] += 0.001;
        assert!(found.find(0, &bent, &tris()).is_none());
    }

    #[test]
    fn collinear_shapes_are_not_recorded() {
        let mut found = Instances::default();
        let line = vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [2.0, 0.0, 0.0]];
        found.add(0, 0, line.clone(), vec![[0, 1, 2]]);
        assert!(found.find(0, &line, &[[0, 1, 2]]).is_none());
    }
}
