//! Giving way in a face-off: two robots stopped nose to nose, each in the other's lane (at a
//! single-lane door, or crossing a corridor between facing doors, each waiting for the other's
//! door), would wait for each other for ever. Both see the same shared poses and speeds, so they
//! decide alike: the one with priority goes, the other steps aside, off the line the one with
//! priority drives on (sideways, to the side it already leans to; the other side when a wall or
//! robot is there; else back, away from it), waits there until that robot has passed, and then
//! resumes its route.

use glam::DVec2;

use crate::algorithm1::Env;
use crate::controller::Command;
use crate::geometry::wrap_angle;
use crate::robot::Robot;
use crate::world::Target;

/// Robots whose centres are closer than this (metres), each ahead of the other and in its
/// lane, both stopped, stand in a face-off.
pub const FACE_OFF_M: f64 = 1.6;
/// Speed (m/s) below which a robot counts as stopped for a face-off.
pub const STOPPED_M_S: f64 = 0.05;
/// Longest a robot gives way (seconds): then it resumes its route whatever the other did (a
/// robot that could not pass in that time is stuck elsewhere; the two meet again and decide
/// anew from their new poses).
pub const GIVE_WAY_MAX_S: f64 = 8.0;
/// Speed of the step aside, fraction of the top speed.
pub const GIVE_WAY_SPEED_FACTOR: f64 = 0.3;
/// Extra distance (metres) a robot keeps from one giving way to it: room for that one to turn
/// (two paper robots' corners sweep 0.53 m around their centres; A-1 leaves 0.1 m between
/// their boxes).
pub const TURN_ROOM_M: f64 = 0.3;
/// A robot this close to its spot (metres) stands on it.
pub const REACHED_M: f64 = 0.05;

/// True when robot `a` has priority over robot `b` (YIELD, PRIORITY_PASS, a tie at a door):
/// the higher priority, on a tie the lower index.
pub fn has_priority(robots: &[Robot], a: usize, b: usize) -> bool {
    let (pa, pb) = (robots[a].priority, robots[b].priority);
    pa > pb || (pa == pb && a < b)
}

/// True when robot `a` goes first in a face-off or a wait-for cycle with robot `b`: a robot on
/// its way before one that has arrived (that one has nowhere to go), else by priority.
pub fn goes_first(robots: &[Robot], a: usize, b: usize) -> bool {
    match (robots[a].arrived, robots[b].arrived) {
        (false, true) => true,
        (true, false) => false,
        _ => has_priority(robots, a, b),
    }
}

/// True when robots `a` and `b` stand in a face-off: both stopped, centres within
/// [`FACE_OFF_M`], each one's centre ahead of the other's and within its lane (the sum of their
/// half widths and the larger margin off its heading line). Symmetric in `a` and `b`, and read
/// from the shared poses only, so both robots reach the same answer.
pub fn face_off(env: &Env<'_>, a: usize, b: usize) -> bool {
    if a == b {
        return false;
    }
    let (ra, rb) = (&env.robots[a], &env.robots[b]);
    let rel = rb.state.pos - ra.state.pos;
    if rel.length() >= FACE_OFF_M
        || ra.state.speed.abs() >= STOPPED_M_S
        || rb.state.speed.abs() >= STOPPED_M_S
    {
        return false;
    }
    let lane = ra.limits.half_width + rb.limits.half_width + ra.limits.margin.max(rb.limits.margin);
    let in_lane = |dir: DVec2, rel: DVec2| rel.dot(dir) > 0.0 && rel.dot(dir.perp()).abs() < lane;
    in_lane(env.world.robot(a).ax, rel) && in_lane(env.world.robot(b).ax, -rel)
}

/// Per robot, the robots whose published wait ([`Robot::waits_for`]) is for it, ascending, and
/// the largest half width and margin of any robot: made once per step, so that a robot finds
/// who waits for it, and the robots that could stand in a face-off with it, without looking
/// through its whole neighbourhood (in a jammed crowd most robots are stopped and wait).
#[derive(Debug, Clone, Default)]
pub struct Waiters {
    start: Vec<u32>,
    items: Vec<u32>,
    max_half_width: f64,
    max_margin: f64,
}

impl Waiters {
    /// Remade from the robots' published waits (counting, no sort).
    pub fn rebuild(&mut self, robots: &[Robot]) {
        let n = robots.len();
        self.start.clear();
        self.start.resize(n + 1, 0);
        for r in robots {
            if let Some((w, _)) = r.waits_for {
                self.start[w as usize + 1] += 1;
            }
        }
        for i in 0..n {
            self.start[i + 1] += self.start[i];
        }
        self.items.clear();
        self.items.resize(self.start[n] as usize, 0);
        let mut next = self.start[..n].to_vec();
        for (p, r) in robots.iter().enumerate() {
            if let Some((w, _)) = r.waits_for {
                let k = &mut next[w as usize];
                self.items[*k as usize] = p as u32;
                *k += 1;
            }
        }
        self.max_half_width = robots.iter().fold(0.0, |m, r| m.max(r.limits.half_width));
        self.max_margin = robots.iter().fold(0.0, |m, r| m.max(r.limits.margin));
    }

    /// The robots waiting for robot `me`, ascending.
    pub fn of(&self, me: usize) -> &[u32] {
        match (self.start.get(me), self.start.get(me + 1)) {
            (Some(&a), Some(&b)) => &self.items[a as usize..b as usize],
            _ => &[],
        }
    }

    /// The box holding the centre of every robot that can stand in a face-off with robot `me`
    /// ([`face_off`]): ahead of it within [`FACE_OFF_M`], inside the widest lane any robot
    /// makes with it.
    pub fn face_off_box(&self, env: &Env<'_>, me: usize) -> (DVec2, DVec2) {
        let r = &env.robots[me];
        let lane = r.limits.half_width + self.max_half_width + r.limits.margin.max(self.max_margin);
        let dir = env.world.robot(me).ax;
        let (side, ahead) = (dir.perp() * lane, dir * FACE_OFF_M);
        let p = r.state.pos;
        let corners = [p - side, p + side, p + ahead - side, p + ahead + side];
        corners
            .iter()
            .fold((DVec2::INFINITY, DVec2::NEG_INFINITY), |(lo, hi), &c| {
                (lo.min(c), hi.max(c))
            })
    }
}

/// A robot's step aside for another robot with priority.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GiveWay {
    /// The robot it gives way to.
    pub other: u32,
    /// Where it waits, off the other's line.
    pub spot: DVec2,
    /// When it started, seconds.
    pub since: f64,
}

impl GiveWay {
    /// The give-way robot `me` starts for `other` (going first), which drives on
    /// along unit `line`: the nearest spot off that line that its rays find free (to its side,
    /// then the other side, then straight back away from `other`); `None` when none is.
    pub fn start(env: &Env<'_>, me: usize, other: usize, line: DVec2) -> Option<GiveWay> {
        let (r, o) = (&env.robots[me], &env.robots[other]);
        let pos = r.state.pos;
        let n = line.perp();
        let lat = (pos - o.state.pos).dot(n);
        // Its side of the other's line; on the line, the other's right.
        let side = if lat.abs() > 0.01 { lat.signum() } else { -1.0 };
        // Turned to drive aside, it spans its half length across the other's line.
        let reach = r.limits.half_length.max(r.limits.half_width);
        let clear = reach + o.limits.half_width + 2.0 * r.limits.margin.max(o.limits.margin);
        let back = (pos - o.state.pos).normalize_or_zero();
        let candidates = [
            (n * side, (clear - lat.abs()).max(0.0)),
            (-n * side, clear + lat.abs()),
            (back, clear),
        ];
        candidates.into_iter().find_map(|(dir, shift)| {
            let spot = pos + dir * shift;

            free(env, me, pos, dir, shift + reach + r.limits.margin).then_some(GiveWay {
                other: other as u32,
                spot,
                since: env.t,
            })
        })
    }

    /// True once robot `me` may resume its route: the other has passed it (it is behind the
    /// other, beyond their half sizes), is out of sensor range, or the step aside has lasted
    /// [`GIVE_WAY_MAX_S`].
    pub fn done(&self, env: &Env<'_>, me: usize) -> bool {
        let o = self.other as usize;
        let (r, ro) = (&env.robots[me], &env.robots[o]);
        let rel = r.state.pos - ro.state.pos;
        let passed = rel.dot(env.world.robot(o).ax)
            < -(ro.limits.half_length + r.limits.half_length.max(r.limits.half_width));
        passed || rel.length() > crate::sensor::RANGE_M || env.t - self.since > GIVE_WAY_MAX_S
    }

    /// True when robot `me` stands on its spot.
    pub fn reached(&self, env: &Env<'_>, me: usize) -> bool {
        env.robots[me].state.pos.distance(self.spot) < REACHED_M
    }

    /// The command that takes `robot` to the spot: turn towards it in place (or, when it lies
    /// behind, away from it, to back up: a robot in a door cannot turn), then drive within
    /// `cap` (A-1 and the zone's caps, not the door wait it gives way from) and stop on it.
    /// Too close to the other robot to turn (`squeeze` +1 or -1, see
    /// [`crate::algorithm1::Perception::squeeze`]), it first drives straight away from it.
    pub fn command(&self, robot: &Robot, cap: f64, squeeze: f64) -> Command {
        let lim = &robot.limits;
        let to = self.spot - robot.state.pos;
        if to.length() < REACHED_M {
            return Command::default();
        }
        let mut err = wrap_angle(to.y.atan2(to.x) - robot.state.heading);
        let back = err.abs() > 100f64.to_radians();
        if back {
            err = wrap_angle(err - std::f64::consts::PI);
        }
        let omega = (5.0 * err).clamp(-lim.max_turn, lim.max_turn);
        let slow = lim.max_speed.min(lim.max_reverse) * GIVE_WAY_SPEED_FACTOR;
        let v = if err.abs() > 15f64.to_radians() {
            if squeeze != 0.0 {
                let v = if squeeze > 0.0 { slow.min(cap) } else { -slow };
                return Command { v, omega: 0.0 };
            }
            0.0
        } else if back {
            -(lim.max_reverse * GIVE_WAY_SPEED_FACTOR).min((1.6 * lim.decel * to.length()).sqrt())
        } else {
            (lim.max_speed * GIVE_WAY_SPEED_FACTOR)
                .min(cap)
                .min((1.6 * lim.decel * to.length()).sqrt())
        };
        Command { v, omega }
    }
}

/// True when the robot's box, driven `dist` from `pos` along `dir`, meets no wall or robot: its
/// centre ray and one along each side of it are free that far.
fn free(env: &Env<'_>, me: usize, pos: DVec2, dir: DVec2, dist: f64) -> bool {
    if dir.length_squared() < 0.5 {
        return false;
    }
    let hw = env.robots[me].limits.half_width;
    [0.0, hw, -hw].into_iter().all(|off| {
        let hit = env
            .world
            .cast(pos + dir.perp() * off, dir, dist, Some(me as u32));
        hit.target == Target::None || hit.dist >= dist
    })
}
