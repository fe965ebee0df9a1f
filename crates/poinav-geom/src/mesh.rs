//! Triangle meshes in world coordinates (metres, Z up as in IFC), one per building element.

use glam::{DAffine3, DVec3};
use poinav_ifc::EntityId;

/// An indexed triangle mesh; triangles are counter-clockwise seen from outside.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Mesh {
    /// Vertex positions, world metres.
    pub positions: Vec<DVec3>,
    /// Triangles as indices into `positions`.
    pub triangles: Vec<[u32; 3]>,
}

impl Mesh {
    /// True when the mesh has no triangle.
    pub fn is_empty(&self) -> bool {
        self.triangles.is_empty()
    }

    /// Total surface area in square metres.
    pub fn area(&self) -> f64 {
        self.triangles
            .iter()
            .map(|t| {
                let [a, b, c] = t.map(|i| self.positions[i as usize]);
                0.5 * (b - a).cross(c - a).length()
            })
            .sum()
    }

    /// Axis-aligned bounding box (min, max), `None` when empty.
    pub fn bounds(&self) -> Option<(DVec3, DVec3)> {
        let first = *self.positions.first()?;
        Some(
            self.positions
                .iter()
                .fold((first, first), |(lo, hi), p| (lo.min(*p), hi.max(*p))),
        )
    }

    /// Appends `other`'s triangles.
    pub fn append(&mut self, other: &Mesh) {
        let base = self.positions.len() as u32;
        self.positions.extend_from_slice(&other.positions);
        self.triangles
            .extend(other.triangles.iter().map(|t| t.map(|i| i + base)));
    }

    /// Maps every vertex through `t`; a mirroring `t` (negative determinant) also reverses
    /// every triangle, so triangles keep facing outwards.
    pub fn transform(&mut self, t: &DAffine3) {
        for p in &mut self.positions {
            *p = t.transform_point3(*p);
        }
        if t.matrix3.determinant() < 0.0 {
            self.flip();
        }
    }

    /// Reverses every triangle (turns the mesh inside out).
    pub fn flip(&mut self) {
        for t in &mut self.triangles {
            t.swap(1, 2);
        }
    }

    /// True when every vertex is a finite point.
    pub fn is_finite(&self) -> bool {
        self.positions.iter().all(|p| p.is_finite())
    }

    /// True when every edge is run as often one way as the other by the triangles sharing it
    /// (edges compared by vertex index): the mesh is a closed surface, its triangles
    /// consistently oriented, as an extrusion, a sweep, a boolean result or a brep whose faces
    /// share their points is. Unwelded vertices, T-junctions, a missing or flipped triangle:
    /// false. Linear in the triangles but for one sort.
    pub fn edges_pair_up(&self) -> bool {
        // Each edge once as (low, high): the runs from low to high, the runs back; a closed
        // surface has the same edges, as often, in both lists.
        let mut up: Vec<u64> = Vec::with_capacity(self.triangles.len() * 3 / 2 + 1);
        let mut down: Vec<u64> = Vec::with_capacity(self.triangles.len() * 3 / 2 + 1);
        for t in &self.triangles {
            for (a, b) in [(t[0], t[1]), (t[1], t[2]), (t[2], t[0])] {
                if a < b {
                    up.push((u64::from(a) << 32) | u64::from(b));
                } else if b < a {
                    down.push((u64::from(b) << 32) | u64::from(a));
                }
            }
        }
        if up.len() != down.len() {
            return false;
        }
        up.sort_unstable();
        down.sort_unstable();
        up == down
    }

    /// Enclosed volume in cubic metres (divergence theorem): positive for a closed mesh whose
    /// triangles face outwards, meaningless for an open one.
    pub fn volume(&self) -> f64 {
        let Some(&o) = self.positions.first() else {
            return 0.0;
        };
        self.triangles
            .iter()
            .map(|t| {
                let [a, b, c] = t.map(|i| self.positions[i as usize] - o);
                a.dot(b.cross(c)) / 6.0
            })
            .sum()
    }
}

/// The mesh of one product, with what exporters and floor plans need to know about it.
#[derive(Debug, Clone, PartialEq)]
pub struct ElementMesh {
    /// The product.
    pub product: EntityId,
    /// Its GlobalId.
    pub global_id: String,
    /// Its IFC class in schema spelling.
    pub class: String,
    /// Its Name.
    pub name: Option<String>,
    /// Its storey, if any.
    pub storey: Option<EntityId>,
    /// The geometry, openings subtracted.
    pub mesh: Mesh,
    /// RGBA from the IFC surface style, when the file gives one.
    pub color: Option<[f32; 4]>,
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::section::tests::cuboid;

    #[test]
    fn a_closed_surface_has_its_edges_pair_up() {
        let a = cuboid(DVec3::ZERO, DVec3::ONE);
        assert!(a.edges_pair_up());
        // Two boxes in one mesh; a mirrored box (turned back outwards); a degenerate triangle.
        let mut two = a.clone();
        two.append(&cuboid(DVec3::splat(2.0), DVec3::splat(3.0)));
        assert!(two.edges_pair_up());
        let mut mirrored = a.clone();
        mirrored.transform(&DAffine3::from_scale(DVec3::new(-1.0, 1.0, 1.0)));
        assert!(mirrored.edges_pair_up());
        let mut degenerate = a.clone();
        degenerate.triangles.push([0, 0, 1]);
        assert!(degenerate.edges_pair_up());
        // A triangle missing, one flipped, one vertex unwelded (a copy at the same point).
        let mut missing = a.clone();
        missing.triangles.pop();
        assert!(!missing.edges_pair_up());
        let mut flipped = a.clone();
        flipped.triangles[3].swap(1, 2);
        assert!(!flipped.edges_pair_up());
        let mut unwelded = a.clone();
        unwelded.positions.push(unwelded.positions[0]);
        let copy = unwelded.positions.len() as u32 - 1;
        let t = unwelded
            .triangles
            .iter()
            .position(|t| t.contains(&0))
            .unwrap();
        unwelded.triangles[t] = unwelded.triangles[t].map(|i| if i == 0 { copy } else { i });
        assert!(!unwelded.edges_pair_up());
        // The same edges, but one of them twice one way and never the other.
        let bowtie = Mesh {
            positions: vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z],
            triangles: vec![[0, 1, 2], [0, 1, 3]],
        };
        assert!(!bowtie.edges_pair_up());
        assert!(Mesh::default().edges_pair_up());
    }
}
