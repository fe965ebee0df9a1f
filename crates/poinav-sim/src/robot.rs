//! A robot: its profile-derived limits (top speed, turn rate, acceleration from drive and brake
//! force over mass), its state (pose, speed, turn rate, odometer) and its brush.

use glam::DVec2;
use poinav_roles::RobotProfile;

use crate::geometry::Obb;

/// Motion limits of one robot, SI units.
#[derive(Debug, Clone, PartialEq)]
pub struct Limits {
    /// Top forward speed, m/s (the profile's).
    pub max_speed: f64,
    /// Top reverse speed, m/s (half the forward speed).
    pub max_reverse: f64,
    /// Turn rate, rad/s (the profile's).
    pub max_turn: f64,
    /// Speeding up: drive force / mass, m/s².
    pub accel: f64,
    /// Slowing down: brake force / mass, m/s².
    pub decel: f64,
    /// Half the footprint length (along the heading).
    pub half_length: f64,
    /// Half the footprint width.
    pub half_width: f64,
    /// Clearance kept from A-1 elements (the profile's margin).
    pub margin: f64,
}

impl Limits {
    /// Limits of `profile` with the given drive and brake forces (newtons).
    pub fn new(profile: &RobotProfile, drive_force_n: f64, brake_force_n: f64) -> Limits {
        Limits {
            max_speed: profile.max_speed_m_s,
            max_reverse: 0.5 * profile.max_speed_m_s,
            max_turn: profile.rotation_speed_deg_s.to_radians(),
            accel: drive_force_n / profile.mass_kg,
            decel: brake_force_n / profile.mass_kg,
            half_length: 0.5 * profile.length_m,
            half_width: 0.5 * profile.width_m,
            margin: profile.clearance_margin_m,
        }
    }

    /// The speed after one step of `dt` towards `target` (clamped to the speed limits), with
    /// the acceleration limit when speeding up and the braking limit when slowing down.
    pub fn next_speed(&self, v: f64, target: f64, dt: f64) -> f64 {
        let target = target.clamp(-self.max_reverse, self.max_speed);
        let dv = target - v;
        let slowing = target.abs() < v.abs() || target * v < 0.0;
        let max_dv = if slowing { self.decel } else { self.accel } * dt;
        v + dv.clamp(-max_dv, max_dv)
    }

    /// The turn rate actually applied for a wanted `omega`.
    pub fn turn(&self, omega: f64) -> f64 {
        omega.clamp(-self.max_turn, self.max_turn)
    }
}

/// The rotating brush (paper §2.4: 500 deg/s, toggled on and off).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Brush {
    /// Running.
    pub on: bool,
    /// Current angle, degrees in [0, 360).
    pub angle_deg: f64,
    /// Rotation speed when on, deg/s.
    pub rate_deg_s: f64,
}

impl Brush {
    /// The paper's brush, off.
    pub fn paper() -> Brush {
        Brush {
            on: false,
            angle_deg: 0.0,
            rate_deg_s: 500.0,
        }
    }

    /// Turns the brush for `dt` seconds when it is on.
    pub fn advance(&mut self, dt: f64) {
        if self.on {
            self.angle_deg = (self.angle_deg + self.rate_deg_s * dt).rem_euclid(360.0);
        }
    }
}

/// Where a robot is and how it moves.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RobotState {
    /// Centre, world metres.
    pub pos: DVec2,
    /// Heading, radians from +X, counter-clockwise.
    pub heading: f64,
    /// Commanded forward speed after the limits, m/s (negative backwards).
    pub speed: f64,
    /// Speed actually travelled in the last step (after contacts), m/s.
    pub actual_speed: f64,
    /// Turn rate applied in the last step, rad/s.
    pub omega: f64,
    /// Distance travelled so far, metres.
    pub odometer: f64,
    /// The brush.
    pub brush: Brush,
}

/// One robot of a run.
#[derive(Debug, Clone)]
pub struct Robot {
    /// Name (`Robot1`).
    pub name: String,
    /// GlobalId other robots' sensors report (derived from the name unless given).
    pub global_id: String,
    /// Its profile.
    pub profile: RobotProfile,
    /// Limits derived from the profile.
    pub limits: Limits,
    /// Coordination priority (higher passes first under YIELD and PRIORITY_PASS).
    pub priority: i64,
    /// State.
    pub state: RobotState,
    /// The robot it is giving way to after a face-off ([`crate::give_way`]), shared with the
    /// others as its pose is (set at the end of each step's decisions): nobody waits for it.
    pub giving_way: Option<u32>,
    /// The robot it waits for, at a single-lane door (and the door) or stopped by A-1 for it,
    /// shared likewise: robots follow these chains to find wait-for cycles.
    pub waits_for: Option<(u32, Option<poinav_nav::DoorIdx>)>,
    /// It has arrived (shared likewise): it gives way to robots still on their way.
    pub arrived: bool,
}

impl Robot {
    /// The footprint at the current pose.
    pub fn footprint(&self) -> Obb {
        self.footprint_at(self.state.pos, self.state.heading)
    }

    /// The footprint at another pose.
    pub fn footprint_at(&self, pos: DVec2, heading: f64) -> Obb {
        Obb::new(
            pos,
            heading,
            self.limits.half_length,
            self.limits.half_width,
        )
    }

    /// Unit heading vector.
    pub fn dir(&self) -> DVec2 {
        DVec2::from_angle(self.state.heading)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn mass_limits_acceleration_and_braking() {
        let l = Limits::new(&RobotProfile::paper(), 50.0, 100.0);
        assert_eq!(l.accel, 10.0);
        assert_eq!(l.decel, 20.0);
        let dt = 1.0 / 60.0;
        assert!((l.next_speed(0.0, 5.0, dt) - 10.0 * dt).abs() < 1e-12);
        assert!((l.next_speed(5.0, 2.5, dt) - (5.0 - 20.0 * dt)).abs() < 1e-12);
        assert_eq!(l.next_speed(4.99, 9.0, dt), 5.0);
        assert!((l.turn(10.0) - 100f64.to_radians()).abs() < 1e-12);
        let mut b = Brush::paper();
        b.advance(1.0);
        assert_eq!(b.angle_deg, 0.0);
        b.on = true;
        b.advance(1.0);
        assert_eq!(b.angle_deg, 140.0);
    }
}
