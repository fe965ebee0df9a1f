//! Vertex quantisation for `KHR_mesh_quantization`: positions as 16-bit integers times a
//! per-mesh step (the node's scale undoes it), unit normals as normalised 8-bit integers.
//!
//! The step is uniform over the three axes, so a node's scale stays uniform (up to a mirror's
//! sign) and normals need no correction: a mesh whose farthest vertex is 5 m from its pivot
//! keeps every vertex within 0.08 mm.

/// Largest magnitude a quantised position coordinate takes.
pub const POSITION_MAX: f64 = 32767.0;

/// The step (metres per unit) of a mesh whose vertices are `positions`: the largest absolute
/// coordinate maps to [`POSITION_MAX`]; 1 for a mesh with every vertex at its origin.
pub fn position_step(positions: &[[f32; 3]]) -> f64 {
    let max = positions
        .iter()
        .flatten()
        .fold(0.0f64, |m, c| m.max(f64::from(c.abs())));
    if max > 0.0 {
        max / POSITION_MAX
    } else {
        1.0
    }
}

/// A position in steps of `step`.
pub fn position(p: [f32; 3], step: f64) -> [i16; 3] {
    p.map(|c| {
        (f64::from(c) / step)
            .round()
            .clamp(-POSITION_MAX, POSITION_MAX) as i16
    })
}

/// A unit normal as normalised signed bytes (`c / 127` reads back).
pub fn normal(n: [f32; 3]) -> [i8; 3] {
    n.map(|c| (c * 127.0).round().clamp(-127.0, 127.0) as i8)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn positions_keep_a_tenth_of_a_millimetre_at_five_metres() {
        let ps = [[5.0, 0.0, -2.5], [1.234_567, 3.0, 0.1]];
        let step = position_step(&ps);
        assert_eq!(step, 5.0 / 32767.0);
        assert_eq!(position(ps[0], step), [32767, 0, -16384]);
        for p in ps {
            let q = position(p, step);
            for k in 0..3 {
                let back = f64::from(q[k]) * step;
                assert!((back - f64::from(p[k])).abs() <= step / 2.0 + 1e-9);
                assert!((back - f64::from(p[k])).abs() < 0.08e-3);
            }
        }
        assert_eq!(position_step(&[[0.0; 3]]), 1.0);
    }

    #[test]
    fn normals_round_to_the_nearest_byte() {
        assert_eq!(normal([0.0, 1.0, -1.0]), [0, 127, -127]);
        let d = std::f32::consts::FRAC_1_SQRT_2;
        assert_eq!(normal([d, -d, 0.0]), [90, -90, 0]);
    }
}
