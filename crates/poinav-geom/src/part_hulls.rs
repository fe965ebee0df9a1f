//! A conservative section for dense furnishings: the union of the convex hulls, one per
//! connected part, of what a mesh has inside a horizontal slab.
//!
//! Revit and ArchiCAD export chairs, sofas and tables as faceted breps of thousands of
//! triangles, often with nearly vertical faces that leave many edges for the exact section's
//! polygon boolean ([`crate::section`]). For a robot, such a piece is an obstacle to keep clear
//! of, not a shape to thread between: each connected part (a leg, a seat, a table top, welded
//! by vertex position) is drawn as the convex hull of its triangles clipped to the slab, which
//! holds the exact section, so obstacles only grow (a part whose hull has no area, a flat
//! vertical panel, is drawn as a line, [`crate::section_lines`]). The cost is linear in the
//! triangles plus a hull per part.

use glam::DVec2;
use rustc_hash::FxHashMap;

use crate::mesh::Mesh;
use crate::region::{self, Region};
use crate::section::clip;
use crate::section_lines::hull_or_line;

/// Meshes of furnishings with at least this many triangles are drawn from their parts' hulls.
pub const DENSE_TRIANGLES: usize = 1_500;

/// Vertices closer than this are welded when finding parts, metres.
const WELD_M: f64 = 1e-6;

fn find(parent: &mut [u32], mut i: u32) -> u32 {
    while parent[i as usize] != i {
        let p = parent[i as usize];
        parent[i as usize] = parent[p as usize];
        i = p;
    }
    i
}

/// The union of the convex hulls of the connected parts of `mesh` inside the slab
/// `z_min..=z_max`, each hull taken over the part's triangles clipped to the slab; empty when
/// nothing is in the slab.
pub fn part_hulls(mesh: &Mesh, z_min: f64, z_max: f64) -> Vec<Region> {
    // Weld vertices by position, so parts are found whatever the indexing.
    let mut welded: FxHashMap<(i64, i64, i64), u32> = FxHashMap::default();
    let ids: Vec<u32> = mesh
        .positions
        .iter()
        .map(|p| {
            let key = (
                (p.x / WELD_M).round() as i64,
                (p.y / WELD_M).round() as i64,
                (p.z / WELD_M).round() as i64,
            );
            let next = welded.len() as u32;
            *welded.entry(key).or_insert(next)
        })
        .collect();
    let mut parent: Vec<u32> = (0..welded.len() as u32).collect();
    let in_slab = |t: &[u32; 3]| {
        let zs = t.map(|i| mesh.positions[i as usize].z);
        let lo = zs[0].min(zs[1]).min(zs[2]);
        let hi = zs[0].max(zs[1]).max(zs[2]);
        hi >= z_min && lo <= z_max
    };
    let in_band: Vec<&[u32; 3]> = mesh.triangles.iter().filter(|t| in_slab(t)).collect();
    for t in &in_band {
        let a = find(&mut parent, ids[t[0] as usize]);
        for &v in &t[1..] {
            let b = find(&mut parent, ids[v as usize]);
            if a != b {
                parent[b as usize] = a;
            }
        }
    }
    let mut parts: FxHashMap<u32, Vec<DVec2>> = FxHashMap::default();
    let (mut a, mut b) = (Vec::with_capacity(8), Vec::with_capacity(8));
    for t in &in_band {
        let tri = t.map(|i| mesh.positions[i as usize]);
        clip(&tri, z_min, true, &mut a);
        clip(&a, z_max, false, &mut b);
        let root = find(&mut parent, ids[t[0] as usize]);
        parts
            .entry(root)
            .or_default()
            .extend(b.iter().map(|p| p.truncate()));
    }
    // Sorted by part root, so the union sees its inputs in the same order every run.
    let mut roots: Vec<u32> = parts.keys().copied().collect();
    roots.sort_unstable();
    let hulls: Vec<Region> = roots.iter().flat_map(|r| hull_or_line(&parts[r])).collect();
    region::union(&hulls)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::section::tests::cuboid;
    use glam::DVec3;

    fn merged(parts: &[Mesh]) -> Mesh {
        let mut m = Mesh::default();
        for p in parts {
            let base = m.positions.len() as u32;
            m.positions.extend(&p.positions);
            m.triangles
                .extend(p.triangles.iter().map(|t| t.map(|i| i + base)));
        }
        m
    }

    #[test]
    fn a_table_is_four_legs_below_its_top_and_its_top_in_the_band() {
        // Legs 0.05 m square at the corners of a 1 x 0.6 m top at 0.72-0.75 m.
        let leg =
            |x: f64, y: f64| cuboid(DVec3::new(x, y, 0.0), DVec3::new(x + 0.05, y + 0.05, 0.72));
        let table = merged(&[
            leg(0.0, 0.0),
            leg(0.95, 0.0),
            leg(0.0, 0.55),
            leg(0.95, 0.55),
            cuboid(DVec3::new(0.0, 0.0, 0.72), DVec3::new(1.0, 0.6, 0.75)),
        ]);
        // Below the top: four separate legs, not one hull over the whole table.
        let low = part_hulls(&table, 0.05, 0.5);
        assert_eq!(low.len(), 4);
        assert!((region::total_area(&low) - 4.0 * 0.0025).abs() < 1e-6);
        // Up to 1 m the top is in the band: the table's whole outline.
        let high = part_hulls(&table, 0.05, 1.0);
        assert_eq!(high.len(), 1);
        assert!((region::total_area(&high) - 0.6).abs() < 1e-6);
        // Above it, nothing.
        assert!(part_hulls(&table, 0.8, 1.0).is_empty());
        // A flat vertical panel as a part of its own: a line, not nothing.
        let panel = crate::section::tests::sheet(
            glam::DVec2::new(0.0, -1.0),
            glam::DVec2::new(1.0, -1.0),
            0.0,
            0.7,
        );
        let with_panel = merged(&[table, panel]);
        let w = crate::section_lines::LINE_WIDTH_M;
        let low = part_hulls(&with_panel, 0.05, 0.5);
        assert_eq!(low.len(), 5);
        assert!((region::total_area(&low) - 4.0 * 0.0025 - (1.0 + w) * w).abs() < 1e-6);
    }
}
