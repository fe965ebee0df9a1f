//! The frame of a passage ring (a door's opening in plan): the width axis along its longest
//! edge, the depth axis across, the centre and half extents, and rectangles in that frame.

use glam::DVec2;

use crate::ring::Ring;

/// The frame of a passage ring: `axis` along its width (the direction of its longest edge),
/// `normal` across it (the direction of travel), the centre of its extents, and its half
/// width and half depth along those axes.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PassageFrame {
    /// Centre of the ring's extents in the frame.
    pub center: DVec2,
    /// Unit vector along the width.
    pub axis: DVec2,
    /// Unit vector across (axis rotated +90 degrees).
    pub normal: DVec2,
    /// Half the extent along `axis`.
    pub half_width: f64,
    /// Half the extent along `normal`.
    pub half_depth: f64,
}

impl PassageFrame {
    /// The frame of `ring`; `None` for fewer than two distinct points.
    pub fn of(ring: &[DVec2]) -> Option<PassageFrame> {
        let n = ring.len();
        let mut best = (0.0, DVec2::X);
        for i in 0..n {
            let d = ring[(i + 1) % n] - ring[i];
            let len = d.length();
            if len > best.0 + 1e-9 {
                best = (len, d / len);
            }
        }
        if best.0 <= 0.0 {
            return None;
        }
        let mut axis = best.1;
        // A canonical direction, so the same ring gives the same frame whatever its winding.
        if axis.x < -1e-12 || (axis.x.abs() <= 1e-12 && axis.y < 0.0) {
            axis = -axis;
        }
        let normal = axis.perp();
        let (mut u0, mut u1, mut v0, mut v1) = (f64::MAX, f64::MIN, f64::MAX, f64::MIN);
        for p in ring {
            let (u, v) = (p.dot(axis), p.dot(normal));
            u0 = u0.min(u);
            u1 = u1.max(u);
            v0 = v0.min(v);
            v1 = v1.max(v);
        }
        let center = axis * ((u0 + u1) / 2.0) + normal * ((v0 + v1) / 2.0);
        Some(PassageFrame {
            center,
            axis,
            normal,
            half_width: (u1 - u0) / 2.0,
            half_depth: (v1 - v0) / 2.0,
        })
    }

    /// The same rectangle with width and depth exchanged (the width axis along the old
    /// normal, in the canonical direction).
    pub fn swapped(&self) -> PassageFrame {
        let mut axis = self.normal;
        if axis.x < -1e-12 || (axis.x.abs() <= 1e-12 && axis.y < 0.0) {
            axis = -axis;
        }
        PassageFrame {
            center: self.center,
            axis,
            normal: axis.perp(),
            half_width: self.half_depth,
            half_depth: self.half_width,
        }
    }

    /// The rectangle `[-hw, hw] x [-hd, hd]` of this frame, counter-clockwise.
    pub fn rectangle(&self, half_width: f64, half_depth: f64) -> Ring {
        let (u, v) = (self.axis * half_width, self.normal * half_depth);
        let c = self.center;
        Ring::from(vec![c - u - v, c + u - v, c + u + v, c - u + v])
    }

    /// The same rectangle shifted along the axis by `offset`.
    pub fn rectangle_at(&self, offset: f64, half_width: f64, half_depth: f64) -> Ring {
        let shifted = PassageFrame {
            center: self.center + self.axis * offset,
            ..*self
        };
        shifted.rectangle(half_width, half_depth)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn passage_frame_of_a_rotated_rectangle() {
        let f0 = PassageFrame {
            center: DVec2::new(5.0, 3.0),
            axis: DVec2::from_angle(0.5),
            normal: DVec2::from_angle(0.5).perp(),
            half_width: 0.5,
            half_depth: 0.1,
        };
        let f = PassageFrame::of(&f0.rectangle(0.5, 0.1)).unwrap();
        assert!((f.half_width - 0.5).abs() < 1e-9 && (f.half_depth - 0.1).abs() < 1e-9);
        assert!(f.center.distance(f0.center) < 1e-9);
        assert!(f.axis.dot(f0.axis).abs() > 1.0 - 1e-9);
    }
}
