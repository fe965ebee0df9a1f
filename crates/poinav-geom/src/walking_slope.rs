//! The slope a robot meets on a ramp, read from its mesh: the steepest upward-facing surface
//! that covers a real part of the walking area.
//!
//! Used when a ramp's property sets give no slope. Upward faces steeper than
//! [`WALKABLE_LIMIT_DEG`] are sides or kerbs, not walking surface. Faces are grouped by slope in
//! [`BIN_DEG`] bins; the answer is the steepest bin holding at least [`MIN_SHARE`] of the
//! walking area, so a chamfer or a sliver of a handrail does not decide it, while a ramp's
//! sloped run next to flat landings does.

use crate::Mesh;

/// Upward faces steeper than this are not walked on (degrees).
pub const WALKABLE_LIMIT_DEG: f64 = 35.0;
/// Width of a slope bin (degrees).
pub const BIN_DEG: f64 = 0.25;
/// Share of the walking area a bin must hold to count.
pub const MIN_SHARE: f64 = 0.10;

/// The steepest walking slope of `mesh` in degrees (0 for a flat top), `None` when the mesh has
/// no upward-facing surface.
pub fn walking_slope_deg(mesh: &Mesh) -> Option<f64> {
    let limit = WALKABLE_LIMIT_DEG.to_radians().cos();
    // Bin -> (area, area × slope).
    let mut bins: std::collections::BTreeMap<i64, (f64, f64)> = std::collections::BTreeMap::new();
    let mut total = 0.0;
    for t in &mesh.triangles {
        let [a, b, c] = t.map(|i| mesh.positions[i as usize]);
        let n = (b - a).cross(c - a);
        let twice_area = n.length();
        if twice_area <= 1e-12 {
            continue;
        }
        let nz = n.z / twice_area;
        if nz < limit {
            continue;
        }
        let slope = nz.clamp(-1.0, 1.0).acos().to_degrees();
        let area = 0.5 * twice_area;
        let bin = bins.entry((slope / BIN_DEG).floor() as i64).or_default();
        bin.0 += area;
        bin.1 += area * slope;
        total += area;
    }
    if total <= 0.0 {
        return None;
    }
    let (bin, (area, moment)) = bins
        .iter()
        .rev()
        .find(|(_, (a, _))| *a >= MIN_SHARE * total)
        .or_else(|| bins.iter().max_by(|x, y| x.1 .0.total_cmp(&y.1 .0)))?;
    // The bin's area-weighted mean slope, to 0.01 degree; a flat top reads 0.
    let deg = if *bin == 0 { 0.0 } else { moment / area };
    Some((deg * 100.0).round() / 100.0)
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec3;

    /// A box of `len` × 1 m whose top rises by `rise` over `len` (a ramp), with a flat landing
    /// of `landing` metres at its top.
    fn ramp(len: f64, rise: f64, landing: f64) -> Mesh {
        let p = |x: f64, y: f64, z: f64| DVec3::new(x, y, z);
        let positions = vec![
            // Bottom.
            p(0.0, 0.0, -0.2),
            p(len + landing, 0.0, -0.2),
            p(len + landing, 1.0, -0.2),
            p(0.0, 1.0, -0.2),
            // Sloped top.
            p(0.0, 0.0, 0.0),
            p(len, 0.0, rise),
            p(len, 1.0, rise),
            p(0.0, 1.0, 0.0),
            // Landing top.
            p(len + landing, 0.0, rise),
            p(len + landing, 1.0, rise),
        ];
        let triangles = vec![
            [0, 2, 1],
            [0, 3, 2],
            [4, 5, 6],
            [4, 6, 7],
            [5, 8, 9],
            [5, 9, 6],
            // One side face (vertical): ignored.
            [0, 1, 8],
        ];
        Mesh {
            positions,
            triangles,
        }
    }

    #[test]
    fn the_sloped_run_decides_not_the_flat_landing() {
        // 1:12 ramp (4.76 degrees) of 6 m with a 1.5 m landing.
        let s = walking_slope_deg(&ramp(6.0, 0.5, 1.5)).unwrap();
        assert!((s - 4.76).abs() <= BIN_DEG, "{s}");
    }

    #[test]
    fn a_flat_slab_reads_zero_and_a_mesh_without_top_none() {
        assert_eq!(walking_slope_deg(&ramp(6.0, 0.0, 1.0)), Some(0.0));
        let mut m = ramp(6.0, 0.5, 1.0);
        m.triangles.retain(|t| t[0] == 0);
        assert_eq!(walking_slope_deg(&m), None);
    }

    #[test]
    fn a_small_steep_chamfer_does_not_decide() {
        // A 10 m landing with a 0.2 m-long steep nosing (about 2 % of the top).
        let s = walking_slope_deg(&ramp(0.2, 0.05, 10.0)).unwrap();
        assert_eq!(s, 0.0);
    }
}
