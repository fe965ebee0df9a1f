//! The section of a triangle mesh by a horizontal slab `z_min <= z <= z_max`: the region of
//! world XY over which the mesh occupies some height inside the slab (what a robot of that
//! height runs into), as polygons with holes.
//!
//! For a closed mesh (a solid) this is exact, not sampled: a vertical line meets the solid
//! inside the slab either because it is inside the solid at `z_min`, or because it crosses
//! the solid's surface inside the slab. So the section is the union of
//! - the slice at `z_min`: the parts of triangles above `z_min`, projected on XY and counted
//!   with their orientation (up-facing +1, down-facing -1); a point is inside the solid where
//!   the count is not zero (a vertical ray leaves a solid once more than it enters it);
//! - the projection of the parts of triangles inside the slab (a table top at 0.75 m, the
//!   underside of a shelf).
//!
//! Several closed parts that overlap (an element made of several solids) are filled once. An
//! open mesh (surfaces that enclose nothing) has no inside: only the second term is used.
//!
//! Booleans on coplanar faces (an opening flush with its wall's face) leave needle-thin
//! faces behind, whose projections would be slivers reaching into door gaps: every part of a
//! section thinner than 2 x [`SLIVER_M`] is removed ([`region::open`]).

use glam::{DVec2, DVec3};
use i_overlay::core::overlay_rule::OverlayRule;

use crate::mesh::Mesh;
use crate::polygon;
use crate::region::{self, overlay_rings, Region};

/// Half the thickness below which parts of a section are dropped as slivers, metres.
pub const SLIVER_M: f64 = 0.001;

/// Projected triangles smaller than this (square metres) are left out: vertical faces.
const MIN_TRIANGLE_AREA: f64 = 1e-10;

/// The section of `mesh` by the slab `z_min..=z_max` (world metres), see the module
/// documentation; empty when the mesh does not reach into the slab.
pub fn mesh_section(mesh: &Mesh, z_min: f64, z_max: f64) -> Vec<Region> {
    let Some((lo, hi)) = mesh.bounds() else {
        return Vec::new();
    };
    if hi.z < z_min || lo.z > z_max || z_min.is_nan() || z_max.is_nan() || z_min > z_max {
        return Vec::new();
    }
    let closed = is_closed(mesh);
    let mut above: Vec<Vec<[f64; 2]>> = Vec::new();
    let mut inside: Vec<Vec<[f64; 2]>> = Vec::new();
    for t in &mesh.triangles {
        let tri = t.map(|i| mesh.positions[i as usize]);
        if closed {
            let part = clip_below(&tri, z_min);
            if let Some(c) = projected(&part, false) {
                above.push(c);
            }
        }
        let part = clip_above(&clip_below(&tri, z_min), z_max);
        if let Some(c) = projected(&part, true) {
            inside.push(c);
        }
    }
    region::open(
        &overlay_rings(&above, &inside, OverlayRule::Union),
        SLIVER_M,
    )
}

/// The projection on XY of every triangle of `mesh` (its whole shadow), whatever its height.
pub fn mesh_shadow(mesh: &Mesh) -> Vec<Region> {
    let rings: Vec<Vec<[f64; 2]>> = mesh
        .triangles
        .iter()
        .filter_map(|t| projected(&t.map(|i| mesh.positions[i as usize]), true))
        .collect();
    region::open(&overlay_rings(&rings, &[], OverlayRule::Subject), SLIVER_M)
}

/// True when the mesh encloses volumes, as far as sections need: its triangles' projections on
/// XY cancel out (up-facing area equals down-facing area, as for any closed surface, whether
/// or not its edges are shared: T-junctions and unwelded vertices are fine). A lone face, or
/// a box without its bottom, is open.
pub fn is_closed(mesh: &Mesh) -> bool {
    let (mut signed, mut total) = (0.0, 0.0);
    let Some(&o) = mesh.positions.first() else {
        return false;
    };
    for t in &mesh.triangles {
        let [a, b, c] = t.map(|i| (mesh.positions[i as usize] - o).truncate());
        let area = (b - a).perp_dot(c - a) / 2.0;
        signed += area;
        total += area.abs();
    }
    total > 0.0 && signed.abs() <= 1e-6 * total
}

/// The part of a convex polygon with `z >= z`.
fn clip_below(poly: &[DVec3], z: f64) -> Vec<DVec3> {
    clip(poly, |p| p.z - z)
}

/// The part of a convex polygon with `z <= z`.
fn clip_above(poly: &[DVec3], z: f64) -> Vec<DVec3> {
    clip(poly, |p| z - p.z)
}

/// Sutherland-Hodgman against one plane: keeps points where `side >= 0`.
fn clip(poly: &[DVec3], side: impl Fn(DVec3) -> f64) -> Vec<DVec3> {
    let n = poly.len();
    let mut out = Vec::with_capacity(n + 1);
    for i in 0..n {
        let (a, b) = (poly[i], poly[(i + 1) % n]);
        let (sa, sb) = (side(a), side(b));
        if sa >= 0.0 {
            out.push(a);
        }
        if (sa >= 0.0) != (sb >= 0.0) {
            let t = sa / (sa - sb);
            out.push(a + (b - a) * t);
        }
    }
    out
}

/// The polygon projected on XY, counter-clockwise when `normalise`, else as it comes (up-facing
/// triangles are counter-clockwise); `None` when it has (almost) no area.
fn projected(poly: &[DVec3], normalise: bool) -> Option<Vec<[f64; 2]>> {
    if poly.len() < 3 {
        return None;
    }
    let flat: Vec<DVec2> = poly.iter().map(|p| p.truncate()).collect();
    let a = polygon::signed_area(&flat);
    if a.abs() < MIN_TRIANGLE_AREA || !a.is_finite() {
        return None;
    }
    let mut c: Vec<[f64; 2]> = flat.iter().map(|p| [p.x, p.y]).collect();
    if normalise && a < 0.0 {
        c.reverse();
    }
    Some(c)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::region::total_area;

    /// A closed box, faces outwards.
    fn cuboid(lo: DVec3, hi: DVec3) -> Mesh {
        let p = |i: u32| {
            DVec3::new(
                if i & 1 == 0 { lo.x } else { hi.x },
                if i & 2 == 0 { lo.y } else { hi.y },
                if i & 4 == 0 { lo.z } else { hi.z },
            )
        };
        let quads = [
            [0, 2, 3, 1],
            [4, 5, 7, 6],
            [0, 1, 5, 4],
            [2, 6, 7, 3],
            [0, 4, 6, 2],
            [1, 3, 7, 5],
        ];
        Mesh {
            positions: (0..8).map(p).collect(),
            triangles: quads
                .iter()
                .flat_map(|q| [[q[0], q[1], q[2]], [q[0], q[2], q[3]]])
                .collect(),
        }
    }

    #[test]
    fn a_wall_a_table_top_and_a_lamp() {
        let wall = cuboid(DVec3::new(0.0, 0.0, 0.0), DVec3::new(5.0, 0.2, 3.0));
        assert!(is_closed(&wall));
        assert!(wall.volume() > 0.0);
        let s = mesh_section(&wall, 0.05, 1.0);
        assert_eq!(s.len(), 1);
        assert!((total_area(&s) - 1.0).abs() < 1e-6, "{}", total_area(&s));
        // Only its top face is inside the slab: the slice at z_min is empty.
        let mut table = cuboid(DVec3::new(0.0, 0.0, 0.72), DVec3::new(1.6, 0.8, 0.75));
        table.append(&cuboid(
            DVec3::new(0.0, 0.0, 0.0),
            DVec3::new(0.05, 0.05, 0.72),
        ));
        let s = mesh_section(&table, 0.05, 1.0);
        assert!((total_area(&s) - 1.28).abs() < 1e-6);
        let lamp = cuboid(DVec3::new(0.0, 0.0, 2.0), DVec3::new(0.3, 0.3, 2.2));
        assert!(mesh_section(&lamp, 0.05, 1.0).is_empty());
        // A slab below the band, and one that reaches into it.
        let floor = cuboid(DVec3::new(0.0, 0.0, -0.3), DVec3::new(4.0, 4.0, 0.0));
        assert!(mesh_section(&floor, 0.05, 1.0).is_empty());
        let step = cuboid(DVec3::new(0.0, 0.0, -0.3), DVec3::new(4.0, 4.0, 0.1));
        assert!((total_area(&mesh_section(&step, 0.05, 1.0)) - 16.0).abs() < 1e-6);
        assert!((total_area(&mesh_shadow(&table)) - 1.28).abs() < 1e-6);
    }

    #[test]
    fn overlapping_solids_fill_once_and_an_open_surface_counts_by_its_faces() {
        let mut two = cuboid(DVec3::ZERO, DVec3::new(2.0, 1.0, 3.0));
        two.append(&cuboid(
            DVec3::new(1.0, 0.0, 0.0),
            DVec3::new(3.0, 1.0, 3.0),
        ));
        let s = mesh_section(&two, 0.05, 1.0);
        assert_eq!(s.len(), 1);
        assert!((total_area(&s) - 3.0).abs() < 1e-6);
        // The top face alone of a tall box: open, and above the slab.
        let mut top = cuboid(DVec3::ZERO, DVec3::new(1.0, 1.0, 3.0));
        top.triangles.truncate(4);
        top.triangles.drain(0..2);
        assert!(!is_closed(&top));
        assert!(mesh_section(&top, 0.05, 1.0).is_empty());
    }

    #[test]
    fn a_wall_with_a_door_hole_cut_through() {
        // Two solids either side of a 0.9 m gap, joined above 2.1 m by a lintel.
        let mut wall = cuboid(DVec3::ZERO, DVec3::new(2.0, 0.2, 3.0));
        wall.append(&cuboid(
            DVec3::new(2.9, 0.0, 0.0),
            DVec3::new(5.0, 0.2, 3.0),
        ));
        wall.append(&cuboid(
            DVec3::new(2.0, 0.0, 2.1),
            DVec3::new(2.9, 0.2, 3.0),
        ));
        let s = mesh_section(&wall, 0.05, 1.0);
        assert_eq!(s.len(), 2);
        assert!((total_area(&s) - 0.82).abs() < 1e-6, "{}", total_area(&s));
        assert!(s.iter().all(|r| !r.contains(DVec2::new(2.45, 0.1))));
    }
}
