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
