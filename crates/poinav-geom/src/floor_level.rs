//! What a storey's floor is: the level robots walk on ([`walking_level`], from the floor
//! slabs' tops and the spaces' bottoms where they disagree with the storey's elevation) and
//! the holes in that floor ([`floor_voids`]: stairwells, shafts and other drops, where the
//! floor slabs at that level leave a hole).

use poinav_ifc::Entity;
use serde::{Deserialize, Serialize};

use crate::mesh::ElementMesh;
use crate::region::{self, Region};
use crate::section::mesh_shadow;

/// A walking level within this of the storey's elevation is the elevation (floor finishes,
/// screeds), metres.
pub const LEVEL_AGREEMENT_M: f64 = 0.10;
/// Floor slabs and spaces further than this from the storey's elevation are not its floor
/// (the slab above, a basement's), metres.
pub const LEVEL_SEARCH_M: f64 = 1.5;
/// Slab tops and space bottoms this close together are one level, metres.
const LEVEL_CLUSTER_M: f64 = 0.02;
/// A floor slab is at a level when its top is this close to it, metres.
pub const SLAB_AT_LEVEL_M: f64 = 0.10;
/// Holes narrower than twice this are no drop a robot meets (gaps between slab pieces under a
/// wall), metres.
pub const VOID_MIN_HALF_WIDTH_M: f64 = 0.05;

/// Where a storey's walking level comes from.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum LevelFrom {
    /// The storey's elevation: its floor slabs and spaces agree, or it has none.
    #[default]
    StoreyElevation,
    /// The top of its floor slabs.
    FloorSlabs,
    /// The bottom of its spaces (it has no floor slab near its elevation).
    Spaces,
}

/// True for a floor slab (`IfcSlab` of type `FLOOR` or `BASESLAB`): what a storey stands on.
pub fn is_floor_slab(e: Entity<'_>) -> bool {
    e.is_a("IfcSlab")
        && e.get("PredefinedType")
            .and_then(|v| v.as_enum())
            .is_some_and(|t| t == "FLOOR" || t == "BASESLAB")
}

/// The plan area of a mesh's bounding box, square metres (a weight).
fn box_area(m: &ElementMesh) -> Option<(f64, f64, f64)> {
    let (lo, hi) = m.mesh.bounds()?;
    let d = hi - lo;
    (lo.is_finite() && hi.is_finite()).then_some((lo.z, hi.z, (d.x * d.y).max(1e-6)))
}

/// The level with the most area among `(z, area)` within [`LEVEL_SEARCH_M`] of `elevation`
/// (levels [`LEVEL_CLUSTER_M`] apart are one; on a tie the one nearer the elevation).
fn main_level(elevation: f64, candidates: &[(f64, f64)]) -> Option<f64> {
    let mut near: Vec<(f64, f64)> = candidates
        .iter()
        .copied()
        .filter(|(z, a)| z.is_finite() && a.is_finite() && (z - elevation).abs() <= LEVEL_SEARCH_M)
        .collect();
    near.sort_by(|a, b| a.0.total_cmp(&b.0));
    let mut best: Option<(f64, f64)> = None;
    let mut i = 0;
    while i < near.len() {
        let mut j = i;
        let (mut area, mut zsum) = (0.0, 0.0);
        while j < near.len() && near[j].0 - near[i].0 <= LEVEL_CLUSTER_M {
            area += near[j].1;
            zsum += near[j].0 * near[j].1;
            j += 1;
        }
        let z = zsum / area;
        let better = best.is_none_or(|(bz, ba)| {
            area > ba * (1.0 + 1e-9)
                || (area >= ba * (1.0 - 1e-9) && (z - elevation).abs() < (bz - elevation).abs())
        });
        if better {
            best = Some((z, area));
        }
        i = j;
    }
    best.map(|(z, _)| z)
}

/// The walking level of a storey at `elevation` whose products are `members` (their meshes):
/// the top of its floor slabs ([`is_floor_slab`]) with the most area, else the bottom of its
/// spaces with the most area when that is above the elevation, when that is more than
/// [`LEVEL_AGREEMENT_M`] from the elevation; else the elevation.
pub fn walking_level<'m>(
    elevation: f64,
    members: impl IntoIterator<Item = (Entity<'m>, &'m ElementMesh)>,
) -> (f64, LevelFrom) {
    let (mut slabs, mut spaces) = (Vec::new(), Vec::new());
    for (e, m) in members {
        let Some((z0, z1, area)) = box_area(m) else {
            continue;
        };
        if is_floor_slab(e) {
            slabs.push((z1, area));
        } else if e.is_a("IfcSpace") {
            spaces.push((z0, area));
        }
    }
    let pick = |z: Option<f64>, from: LevelFrom| {
        z.map(|z| {
            if (z - elevation).abs() <= LEVEL_AGREEMENT_M {
                (elevation, LevelFrom::StoreyElevation)
            } else {
                (z, from)
            }
        })
    };
    // Spaces whose bottom is below the elevation are often drawn from the slab's bottom: only
    // a bottom above it says where the floor is.
    let spaces_level = main_level(elevation, &spaces).filter(|z| *z > elevation);
    pick(main_level(elevation, &slabs), LevelFrom::FloorSlabs)
        .or_else(|| pick(spaces_level, LevelFrom::Spaces))
        .unwrap_or((elevation, LevelFrom::StoreyElevation))
}

/// The holes in the floor at `level`: where the floor slabs ([`is_floor_slab`], of any storey)
/// whose tops are within [`SLAB_AT_LEVEL_M`] of it leave a hole inside their union (a
/// stairwell, a shaft, an atrium), parts narrower than `2 *` [`VOID_MIN_HALF_WIDTH_M`]
/// left out. Each comes with the slab around it (the first, in the order given, whose outline
/// holds the hole's centre). A floor without slabs there has none.
pub fn floor_voids<'m>(
    level: f64,
    slabs: impl IntoIterator<Item = (Entity<'m>, &'m ElementMesh)>,
) -> Vec<(Entity<'m>, Vec<Region>)> {
    let at_level: Vec<(Entity<'m>, Vec<Region>)> = slabs
        .into_iter()
        .filter(|(e, m)| {
            is_floor_slab(*e)
                && box_area(m).is_some_and(|(_, top, _)| (top - level).abs() <= SLAB_AT_LEVEL_M)
        })
        .map(|(e, m)| (e, mesh_shadow(&m.mesh)))
        .collect();
    if at_level.is_empty() {
        return Vec::new();
    }
    let all: Vec<Region> = at_level.iter().flat_map(|(_, r)| r.clone()).collect();
    let holes: Vec<Region> = region::union(&all)
        .into_iter()
        .flat_map(|r| r.holes.into_iter().filter_map(Region::from_ring))
        .collect();
    let holes = region::open(&holes, VOID_MIN_HALF_WIDTH_M);
    let mut out: Vec<(Entity<'m>, Vec<Region>)> = Vec::new();
    for hole in holes {
        let c = hole.centroid();
        let k = at_level
            .iter()
            .position(|(_, rs)| {
                rs.iter()
                    .any(|r| crate::polygon::contains_closed(&r.outer, c))
            })
            .unwrap_or(0);
        let slab = at_level[k].0;
        match out.iter_mut().find(|(e, _)| e.id() == slab.id()) {
            Some((_, rs)) => rs.push(hole),
            None => out.push((slab, vec![hole])),
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_main_level_is_the_one_with_most_area_near_the_elevation() {
        // Slab tops at 0.00 (two pieces) and a small one at -0.60; the storey says -0.60.
        let z = main_level(
            -0.6,
            &[(0.0, 40.0), (0.005, 30.0), (-0.6, 5.0), (2.85, 80.0)],
        );
        assert!((z.unwrap() - 0.00214).abs() < 1e-4, "{z:?}");
        // The slab above (2.85) is too far.
        assert_eq!(main_level(0.0, &[(2.85, 80.0)]), None);
        // A tie goes to the level nearer the elevation.
        assert_eq!(main_level(0.0, &[(0.5, 10.0), (-0.3, 10.0)]), Some(-0.3));
    }
}
