//! The range sensor (SPEC.md §4): five rays at 0, +30, -30, +90 and -90 degrees from the
//! heading, 5 m range, cast from the robot's centre; each reports the distance, what it hit
//! (building element or robot) and the door passages it looked through.

use glam::DVec2;

use crate::world::{RayHit, World};

/// Ray angles from the heading, degrees, in the order readings use.
pub const RAY_DEG: [f64; 5] = [0.0, 30.0, -30.0, 90.0, -90.0];

/// Index of the 0 degree ray.
pub const FRONT: usize = 0;
/// Index of the +30 degree ray.
pub const LEFT30: usize = 1;
/// Index of the -30 degree ray.
pub const RIGHT30: usize = 2;
/// Index of the +90 degree ray (left).
pub const LEFT: usize = 3;
/// Index of the -90 degree ray (right).
pub const RIGHT: usize = 4;

/// Sine and cosine of each ray's angle from the heading, in [`RAY_DEG`] order (computed once,
/// the same bits as computing them where they are used).
pub fn ray_sin_cos() -> &'static [(f64, f64); 5] {
    static SIN_COS: std::sync::LazyLock<[(f64, f64); 5]> =
        std::sync::LazyLock::new(|| RAY_DEG.map(|d| (d.to_radians().sin(), d.to_radians().cos())));
    &SIN_COS
}

/// The paper's sensor range, metres.
pub const RANGE_M: f64 = 5.0;

/// Unit directions of the five rays for a heading.
pub fn directions(heading: f64) -> [DVec2; 5] {
    RAY_DEG.map(|d| DVec2::from_angle(heading + d.to_radians()))
}

/// One robot's reading in one step.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Reading {
    /// The five rays, in [`RAY_DEG`] order.
    pub rays: [RayHit; 5],
    /// Their unit directions.
    pub dirs: [DVec2; 5],
}

impl Reading {
    /// A reading of nothing (five rays of zero length, no directions): a slot's value before
    /// the rays are cast into it.
    pub const NONE: Reading = Reading {
        rays: [RayHit::NONE; 5],
        dirs: [DVec2::ZERO; 5],
    };
}

/// Casts the five rays of robot `me` from `pos` at `heading`.
pub fn sense(world: &World, me: usize, pos: DVec2, heading: f64, range: f64) -> Reading {
    sense_along(world, me, pos, directions(heading), range)
}

/// Casts the five rays of robot `me` from `pos` along `dirs` ([`directions`] of its heading,
/// kept while the heading stays the same); the origin's cell is found once for the five.
pub fn sense_along(world: &World, me: usize, pos: DVec2, dirs: [DVec2; 5], range: f64) -> Reading {
    let skip = Some(me as u32);
    let rays = match world.origin(pos) {
        Some(origin) => world.cast_each(&origin, &dirs, range, skip),
        None => dirs.map(|d| world.cast(pos, d, range, skip)),
    };
    Reading { rays, dirs }
}
