//! Where the robots start when no scenario says: two robots in the largest zone of the floor,
//! each at the point of that zone farthest from any obstacle, at least 2.5 m apart, facing
//! each other.

use glam::DVec2;
use poinav_nav::Floor;
use poinav_poi::RobotProfile;
use poinav_sim::controller::{ControllerSpec, KeyScheme};
use poinav_sim::RobotSetup;

use crate::error::ViewerError;

/// Finest lattice spacing of the candidate start points, metres.
const STEP_M: f64 = 0.1;
/// Most candidate points: a huge space gets a coarser lattice, so placement stays quick.
const MAX_POINTS: f64 = 20_000.0;
/// Distance kept between the two default robots, metres.
const APART_M: f64 = 2.5;

fn inside(ring: &[DVec2], p: DVec2) -> bool {
    let mut c = false;
    let n = ring.len();
    for i in 0..n {
        let (a, b) = (ring[i], ring[(i + 1) % n]);
        if (a.y > p.y) != (b.y > p.y) && p.x < a.x + (p.y - a.y) / (b.y - a.y) * (b.x - a.x) {
            c = !c;
        }
    }
    c
}

fn segment_distance(p: DVec2, a: DVec2, b: DVec2) -> f64 {
    let ab = b - a;
    let t = if ab.length_squared() > 0.0 {
        ((p - a).dot(ab) / ab.length_squared()).clamp(0.0, 1.0)
    } else {
        0.0
    };
    p.distance(a + ab * t)
}

fn ring_area(ring: &[DVec2]) -> f64 {
    let n = ring.len();
    (0..n)
        .map(|i| ring[i].perp_dot(ring[(i + 1) % n]))
        .sum::<f64>()
        .abs()
        / 2.0
}

/// Two robots driven by keys (Robot1: arrow keys, Robot2: W A S D) with `profile`, placed in
/// the floor's largest zone where they have the most room.
pub fn default_robots(
    floor: &Floor,
    profile: &RobotProfile,
) -> Result<Vec<RobotSetup>, ViewerError> {
    let fail = |message: &str| ViewerError::Placement {
        floor: floor.name.clone(),
        message: message.into(),
    };
    let zone = floor
        .zones
        .iter()
        .filter(|z| z.ring.len() >= 3)
        .max_by(|a, b| ring_area(&a.ring).total_cmp(&ring_area(&b.ring)))
        .ok_or_else(|| fail("it has no spaces (IfcSpace)"))?;
    let (lo, hi) = zone.ring.iter().fold(
        (DVec2::splat(f64::MAX), DVec2::splat(f64::MIN)),
        |(lo, hi), p| (lo.min(*p), hi.max(*p)),
    );
    let segments: Vec<(DVec2, DVec2)> = floor
        .obstacles
        .iter()
        .flat_map(|o| o.rings.iter())
        .chain(std::iter::once(&zone.ring))
        .flat_map(|r| (0..r.len()).map(move |i| (r[i], r[(i + 1) % r.len()])))
        .filter(|(a, b)| {
            let m = DVec2::splat(10.0);
            a.min(*b).cmpge(lo - m).all() && a.max(*b).cmple(hi + m).all()
        })
        .collect();
    let in_obstacle = |p: DVec2| {
        floor
            .obstacles
            .iter()
            .any(|o| o.rings.first().is_some_and(|r| inside(r, p)))
    };
    let mut candidates: Vec<(f64, DVec2)> = Vec::new();
    let size = hi - lo;
    if !(size.x.is_finite() && size.y.is_finite()) {
        return Err(fail("its largest space has no finite outline"));
    }
    let step = STEP_M.max((size.x * size.y / MAX_POINTS).sqrt());
    let (nx, ny) = ((size.x / step) as usize, (size.y / step) as usize);
    for j in 0..=ny {
        for i in 0..=nx {
            let p = lo + DVec2::new(i as f64, j as f64) * step;
            if !inside(&zone.ring, p) || in_obstacle(p) {
                continue;
            }
            let d = segments
                .iter()
                .map(|&(a, b)| segment_distance(p, a, b))
                .fold(f64::MAX, f64::min);
            candidates.push((d, p));
        }
    }
    // Most room first; ties by position, so the choice is deterministic.
    candidates.sort_by(|a, b| {
        b.0.total_cmp(&a.0)
            .then(a.1.x.total_cmp(&b.1.x))
            .then(a.1.y.total_cmp(&b.1.y))
    });
    let need = 0.5 * profile.width_m.hypot(profile.length_m) + 0.05;
    let first = candidates
        .first()
        .filter(|c| c.0 > need)
        .ok_or_else(|| fail("its largest space has no spot wide enough for the robot"))?
        .1;
    let second = candidates
        .iter()
        .find(|c| c.0 > need && c.1.distance(first) >= APART_M)
        .ok_or_else(|| fail("its largest space has no room for a second robot"))?
        .1;
    let towards = (second - first).to_angle().to_degrees();
    let robot = |name: &str, start: DVec2, heading_deg: f64, scheme| RobotSetup {
        name: name.into(),
        global_id: None,
        profile: profile.clone(),
        start,
        heading_deg,
        controller: ControllerSpec::Keys {
            scheme,
            script: Vec::new(),
        },
        priority: 0,
        brush_on: false,
        drive_force_n: 50.0,
        brake_force_n: 100.0,
    };
    Ok(vec![
        robot("Robot1", first, towards, KeyScheme::Arrows),
        robot("Robot2", second, towards + 180.0, KeyScheme::Wasd),
    ])
}
