//! Where the robots start when no scenario says: two robots in the largest zone of the floor
//! (the second in the next largest with room when that one is too small), each at the point
//! farthest from any obstacle, at least 2.5 m apart, each facing
//! the most open direction that does not point at the other robot, so the first key press
//! drives into free space.

use glam::DVec2;
use poinav_nav::polygon::{contains, line_crossing, segment_distance, signed_area};
use poinav_nav::Floor;
use poinav_roles::RobotProfile;
use poinav_sim::controller::{ControllerSpec, KeyScheme};
use poinav_sim::RobotSetup;

use crate::error::ViewerError;

/// Finest lattice spacing of the candidate start points, metres.
const STEP_M: f64 = 0.1;
/// Most candidate points: a huge space gets a coarser lattice, so placement stays quick.
const MAX_POINTS: f64 = 20_000.0;
/// Distance kept between the two default robots, metres.
const APART_M: f64 = 2.5;
/// Headings tried when choosing where a robot faces.
const HEADINGS: usize = 72;
/// Headings within this angle of the other robot are not chosen, degrees.
const AVOID_DEG: f64 = 60.0;
/// Farthest a ray looks when measuring open space, metres.
const RAY_MAX_M: f64 = 20.0;

/// Distance from `p` along the unit direction `d` to the first segment, at most [`RAY_MAX_M`].
fn ray_distance(segments: &[(DVec2, DVec2)], p: DVec2, d: DVec2) -> f64 {
    let mut best = RAY_MAX_M;
    for &(a, b) in segments {
        if let Some((t, u)) = line_crossing(p, d, a, b) {
            if t >= 0.0 && (0.0..=1.0).contains(&u) {
                best = best.min(t);
            }
        }
    }
    best
}

/// The heading (degrees) from `p` with the most free room ahead for a body `width` wide
/// (the shortest of three parallel rays: centre and both sides), leaving out headings within
/// [`AVOID_DEG`] of `other`. Ties go to the lowest heading, so the choice is deterministic.
fn open_heading(segments: &[(DVec2, DVec2)], p: DVec2, width: f64, other: DVec2) -> f64 {
    let towards = (other - p).to_angle().to_degrees();
    let mut best = (f64::MIN, towards + 180.0);
    for k in 0..HEADINGS {
        let deg = k as f64 * 360.0 / HEADINGS as f64;
        let off = (deg - towards + 540.0).rem_euclid(360.0) - 180.0;
        if off.abs() < AVOID_DEG {
            continue;
        }
        let d = DVec2::from_angle(deg.to_radians());
        let side = d.perp() * (width / 2.0);
        let room = [p, p + side, p - side]
            .iter()
            .map(|&q| ray_distance(segments, q, d))
            .fold(f64::MAX, f64::min);
        if room > best.0 + 1e-9 {
            best = (room, deg);
        }
    }
    best.1
}

/// A candidate start point and its room, metres.
type Spot = (f64, DVec2);
/// A wall or outline edge.
type Segment = (DVec2, DVec2);

/// Candidate start points of `zone` with their room (distance to the nearest wall or obstacle
/// edge), most room first, and the wall segments near the zone.
fn spots(floor: &Floor, zone: &poinav_nav::FloorZone) -> (Vec<Spot>, Vec<Segment>) {
    let Some((lo, hi)) = poinav_nav::polygon::bounds(&zone.ring) else {
        return (Vec::new(), Vec::new());
    };
    let size = hi - lo;
    if !(size.x.is_finite() && size.y.is_finite()) {
        return (Vec::new(), Vec::new());
    }
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
            .any(|o| o.rings.first().is_some_and(|r| contains(r, p)))
    };
    let mut candidates: Vec<(f64, DVec2)> = Vec::new();
    let step = STEP_M.max((size.x * size.y / MAX_POINTS).sqrt());
    let (nx, ny) = ((size.x / step) as usize, (size.y / step) as usize);
    for j in 0..=ny {
        for i in 0..=nx {
            let p = lo + DVec2::new(i as f64, j as f64) * step;
            if !contains(&zone.ring, p) || in_obstacle(p) {
                continue;
            }
            let d = segments
                .iter()
                .map(|&(a, b)| segment_distance(a, b, p))
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
    (candidates, segments)
}

/// Two robots driven by keys (Robot1: arrow keys, Robot2: W A S D) with `profile`, placed in
/// the floor's largest zone where they have the most room; when that zone has room for one
/// robot only, the second goes to the next largest zone with room for it.
pub fn default_robots(
    floor: &Floor,
    profile: &RobotProfile,
) -> Result<Vec<RobotSetup>, ViewerError> {
    let fail = |message: &str| ViewerError::Placement {
        floor: floor.name.clone(),
        message: message.into(),
    };
    let mut zones: Vec<&poinav_nav::FloorZone> =
        floor.zones.iter().filter(|z| z.ring.len() >= 3).collect();
    if zones.is_empty() {
        return Err(fail("it has no spaces (IfcSpace)"));
    }
    zones.sort_by(|a, b| {
        signed_area(&b.ring)
            .abs()
            .total_cmp(&signed_area(&a.ring).abs())
    });
    let need = 0.5 * profile.width_m.hypot(profile.length_m) + 0.05;
    let mut first: Option<DVec2> = None;
    let mut second: Option<DVec2> = None;
    let mut segments: Vec<(DVec2, DVec2)> = Vec::new();
    for zone in &zones {
        let (candidates, near) = spots(floor, zone);
        let mut fits = candidates.iter().filter(|c| c.0 > need).map(|c| c.1);
        match first {
            None => {
                let Some(p) = fits.next() else { continue };
                first = Some(p);
                second = fits.find(|q| q.distance(p) >= APART_M);
            }
            Some(p) => second = fits.find(|q| q.distance(p) >= APART_M),
        }
        segments.extend(near);
        if second.is_some() {
            break;
        }
    }
    let first =
        first.ok_or_else(|| fail("none of its spaces has a spot wide enough for the robot"))?;
    let second = second.ok_or_else(|| fail("its spaces have no room for a second robot"))?;
    let width = profile.width_m.max(0.0);
    let heading_first = open_heading(&segments, first, width, second);
    let heading_second = open_heading(&segments, second, width, first);
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
        robot("Robot1", first, heading_first, KeyScheme::Arrows),
        robot("Robot2", second, heading_second, KeyScheme::Wasd),
    ])
}

#[cfg(test)]
mod tests {
    use super::*;

    fn square(lo: DVec2, hi: DVec2) -> Vec<(DVec2, DVec2)> {
        let c = [lo, DVec2::new(hi.x, lo.y), hi, DVec2::new(lo.x, hi.y)];
        (0..4).map(|i| (c[i], c[(i + 1) % 4])).collect()
    }

    #[test]
    fn a_ray_stops_at_the_first_wall() {
        let walls = square(DVec2::ZERO, DVec2::new(10.0, 4.0));
        let d = ray_distance(&walls, DVec2::new(2.0, 2.0), DVec2::X);
        assert!((d - 8.0).abs() < 1e-9, "{d}");
        let up = ray_distance(&walls, DVec2::new(2.0, 2.0), DVec2::Y);
        assert!((up - 2.0).abs() < 1e-9, "{up}");
        assert_eq!(ray_distance(&[], DVec2::ZERO, DVec2::X), RAY_MAX_M);
    }

    #[test]
    fn a_robot_faces_the_long_way_but_not_at_the_other_robot() {
        // A 10 m x 4 m room: from (2, 2) the long way is +x, but the other robot stands there,
        // so the robot faces the most open direction outside 60 degrees of it.
        let walls = square(DVec2::ZERO, DVec2::new(10.0, 4.0));
        let alone = open_heading(&walls, DVec2::new(2.0, 2.0), 0.5, DVec2::new(2.0, -50.0));
        // The long way (towards the far corner at most: about 14 degrees).
        let alone = (alone + 540.0).rem_euclid(360.0) - 180.0;
        assert!(alone.abs() <= 20.0, "{alone}");
        let h = open_heading(&walls, DVec2::new(2.0, 2.0), 0.5, DVec2::new(6.0, 2.0));
        let off = (h + 540.0).rem_euclid(360.0) - 180.0;
        assert!(off.abs() >= AVOID_DEG, "{h}");
        // Whatever it chose, there is more room ahead than a robot length.
        let d = DVec2::from_angle(h.to_radians());
        assert!(ray_distance(&walls, DVec2::new(2.0, 2.0), d) > 1.0, "{h}");
    }
}
