//! Algorithm 1 of the paper (SPEC.md §5), per control step and robot: every element a ray hits
//! or looks through is looked up in the POI database by GlobalId, its roles (primary and
//! conditional) select behaviours, and the behaviours shape the controller's command into one
//! navigation action:
//!
//! - keep the profile's clearance: the speed is capped so the robot can stop `margin`
//!   before an A-1 element (or robot) in its path; a side closer than the margin steers away.
//! - estimate the door's clear width from the rays themselves ([`Estimator`]) and apply
//!   rule R5 (below MinClearanceWidth: B-2 + RESTRICTED, else FULL_ACCESS, SENSOR_BASED); pass
//!   at a controlled speed, lower with B-2.
//! - C-1: a robot detected by a ray is tracked (its shared pose gives the centre distance);
//!   closer than the zone's MinInterRobotSeparation the robot takes C-2 and runs the zone's
//!   CoordinationProtocol; an oncoming robot makes both keep to their right-hand wall.
//! - the +90/-90 ray hits on A-3 elements are the trajectory references of wall following.
//! - B-1 zones cap the speed.
//! - Face-off: two robots stopped nose to nose in each other's lane (each waiting for the
//!   other's door, or stopped by A-1 for the other): the one with priority goes, no longer
//!   waiting for the other, and the other gives way ([`crate::give_way`]).

use glam::DVec2;
use poinav_nav::{polygon, DoorIdx, Floor, ObstacleIdx, ZoneIdx};
use poinav_roles::runtime::{Observation, RuntimeChange};
use poinav_roles::{CoordinationProtocol, Role};
use serde::Deserialize;

use crate::controller::{Command, Side, WallPd};
use crate::events::{Event, EventKind};
use crate::geometry::wrap_angle;
use crate::give_way::{face_off, goes_first, has_priority, GiveWay, Waiters, STOPPED_M_S};
use crate::plan::Plan;
use crate::poi_db::{Element, PoiDb, RoleSet};
use crate::robot::Robot;
use crate::sensor::{Reading, FRONT, LEFT, LEFT30, RANGE_M, RIGHT, RIGHT30};
use crate::world::{Target, World};

/// Tunable behaviour constants (scenario table `[behaviour]`); defaults are documented in
/// docs/scenarios.md.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Behaviour {
    /// Speed through an A-2 element, fraction of the top speed.
    pub transition_speed_factor: f64,
    /// Speed through an A-2 element with B-2, fraction of the top speed.
    pub narrow_speed_factor: f64,
    /// Speed in a B-1 zone, fraction of the top speed.
    pub hazard_speed_factor: f64,
    /// SPEED_REDUCTION (and the yielded-to robot): fraction of the top speed (paper: 0.5).
    pub reduction_factor: f64,
    /// Side distance kept from the right-hand wall when robots meet in a C-1 zone, measured
    /// from the robot's centre; default half the width plus twice the margin.
    pub keep_right_m: Option<f64>,
    /// Turn rate per metre a side is closer than the margin, rad/s/m.
    pub side_gain: f64,
    /// Largest angle (degrees) between heading and door axis for a clearance measurement.
    pub max_approach_deg: f64,
}

impl Default for Behaviour {
    fn default() -> Self {
        Behaviour {
            transition_speed_factor: 0.6,
            narrow_speed_factor: 0.3,
            hazard_speed_factor: 0.5,
            reduction_factor: 0.5,
            keep_right_m: None,
            side_gain: 4.0,
            max_approach_deg: 25.0,
        }
    }
}

/// SensorClearance(E) for a door approached head-on, from the ray hits themselves. In the door's
/// frame (depth along the wall normal from the door's centre in the model, offset `u` along the
/// wall; only its position and orientation are used, not its width), every ray hit
/// on an obstacle inside the door's depth band (its passage ring projected on the approach axis,
/// from 5 cm before it to its far side) is a point of the wall around the opening:
///
/// - every wall point bounds the half opening on its side from above: far away the +-30 degree
///   rays hit the face (see [`Estimator::face`]) at `u = d tan 30`;
/// - a ray that then looks through the door crosses the face line inside the opening: its
///   offset there bounds the half opening from below (`width = 2 d tan 30` at the switch);
/// - hits deeper than the face (and short of the far side) are on the jamb's reveal: their
///   offset is the jamb itself.
///
/// Each side's half width is its innermost wall point when that lies on the reveal, else the
/// middle of its bounds once they are at most [`MAX_BRACKET_M`] apart (error at most 2.5 cm);
/// the two halves add up to the estimate. Nothing is reported before both jambs are measured
/// so (a loose bracket far from the door could say 2.4 m for a 0.77 m door and lift its B-2),
/// and again whenever the estimate changes by more than 1 mm.
#[derive(Debug, Clone, PartialEq)]
pub struct Estimator {
    door: DoorIdx,
    origin: DVec2,
    axis: DVec2,
    band: (f64, f64),
    /// Depth of the opening's far side (its ring's deepest point): a hit deeper than the face
    /// is on the jamb's reveal only before it; beyond it lies whatever meets the wall on the
    /// other side (a room's side wall starting at the far face), not the jamb.
    far: f64,
    /// Depth of the opening's near side (its ring's nearest point).
    near: f64,
    /// The nearest in-band hit of the front and +-30 degree rays (infinite before the first);
    /// see [`Estimator::face`].
    face_hit: f64,
    /// Per side (0 left, 1 right): the innermost wall point, |u|.
    inner: [f64; 2],
    /// Per side: the innermost hit on the jamb's reveal (deeper than the face, short of the far
    /// side), |u|: the jamb itself.
    reveal: [f64; 2],
    /// Per side: the largest face-line offset of a ray that looked through the door.
    lower: [f64; 2],
    best: Option<f64>,
}

impl Estimator {
    fn start(door: DoorIdx, centre: DVec2, axis: DVec2, ring: &[DVec2]) -> Estimator {
        let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
        for p in ring {
            let d = (*p - centre).dot(axis);
            lo = lo.min(d);
            hi = hi.max(d);
        }
        Estimator {
            door,
            origin: centre,
            axis,
            band: (lo - 0.05, hi + 0.05),
            far: hi,
            near: lo,
            face_hit: f64::INFINITY,
            reveal: [f64::INFINITY; 2],
            inner: [f64::INFINITY; 2],
            lower: [f64::NEG_INFINITY; 2],
            best: None,
        }
    }

    /// Adds one reading taken at `pos`; returns a new estimate to report.
    fn update(&mut self, pos: DVec2, reading: &Reading) -> Option<f64> {
        let lat = self.axis.perp();
        for (k, (ray, dir)) in reading.rays.iter().zip(reading.dirs).enumerate() {
            if let Target::Obstacle(_) = ray.target {
                let rel = pos + dir * ray.dist - self.origin;
                let depth = rel.dot(self.axis);
                // Up to the far side only: beyond it the hits are on what meets the wall there.
                if depth >= self.band.0 && depth <= self.far + 0.005 {
                    let u = rel.dot(lat);
                    let side = usize::from(u < 0.0);
                    if k != LEFT && k != RIGHT {
                        self.face_hit = self.face_hit.min(depth);
                    }
                    self.inner[side] = self.inner[side].min(u.abs());
                    if depth > self.face() + 0.01 && depth < self.far - 0.01 {
                        self.reveal[side] = self.reveal[side].min(u.abs());
                    }
                }
            }
            let along = dir.dot(self.axis);
            if dir.dot(lat).abs() > 0.2
                && along > 1e-9
                && ray.passages.contains(self.door.get() as u32)
            {
                // Where the ray crossed the face line, on a side that has a wall point.
                let t = (self.face() - (pos - self.origin).dot(self.axis)) / along;
                let u = (pos + dir * t - self.origin).dot(lat);
                let side = usize::from(u < 0.0);
                if t >= 0.0 && u.abs() < self.inner[side] {
                    self.lower[side] = self.lower[side].max(u.abs());
                }
            }
        }
        // To the millimetre: five rays do not resolve less, and a door of exactly the required
        // width must not read 0.8999 m and lose its FULL_ACCESS to rounding.
        let est = (self.estimate()? * 1000.0).round() / 1000.0;
        if self.best.is_none_or(|b| (est - b).abs() > 0.001) {
            self.best = Some(est);
            return Some(est);
        }
        None
    }

    /// Depth of the wall face: the nearest in-band hit of the front and +-30 degree rays, but
    /// never before the opening's near side (which it is until such a hit). The +-90 degree
    /// rays are left out, and the near side bounds it: a perpendicular wall far to the side,
    /// hit a few centimetres before the face, would otherwise make every face point look like
    /// the reveal.
    pub fn face(&self) -> f64 {
        if self.face_hit.is_finite() {
            self.face_hit.max(self.near)
        } else {
            self.near
        }
    }

    /// The current estimate, once both jambs are measured: each side's innermost wall point is
    /// on the reveal (the jamb itself), or its bracket between the last wall point and the
    /// first look through the door is at most [`MAX_BRACKET_M`] wide. A looser bracket is no
    /// evidence of the width (far from the door the angled rays bound it only loosely), so it
    /// gives no estimate at all rather than a guess.
    pub fn estimate(&self) -> Option<f64> {
        let mut width = 0.0;
        for side in 0..2 {
            let upper = self.inner[side];
            let lower = self.lower[side].min(upper);
            // A hit on the reveal (deeper than the face, short of the far side) is the jamb
            // itself, as long as nothing was seen further in.
            let reveal = self.reveal[side];
            if reveal.is_finite() && reveal <= upper + 0.001 {
                width += reveal;
                continue;
            }
            if !lower.is_finite() || !upper.is_finite() {
                return None;
            }
            width += if upper - lower <= MAX_BRACKET_M {
                0.5 * (lower + upper)
            } else {
                return None;
            };
        }
        Some(width)
    }

    /// True while the robot has not gone past the door's band.
    fn before_exit(&self, pos: DVec2) -> bool {
        (pos - self.origin).dot(self.axis) <= self.band.1 + 0.1
    }
}

/// Widest bracket (metres) of a jamb's position that counts as a measurement: a half width
/// known to 2.5 cm. At 5 m/s and 60 Hz an angled ray's face point moves 4.8 cm per step, so a
/// head-on approach at any cruise speed brackets each jamb tightly enough.
pub const MAX_BRACKET_M: f64 = 0.05;

/// Algorithm 1's memory for one robot.
#[derive(Debug)]
pub struct Mind {
    estimator: Option<Estimator>,
    tracked: Vec<u32>,
    /// The robot's own C-2.
    pub c2: bool,
    /// Current zone.
    pub zone: Option<ZoneIdx>,
    keep: Option<WallPd>,
    /// The single-lane door it is waiting at for another robot, if any.
    door_wait: Option<DoorIdx>,
    /// The robot it waits for (at that door, or stopped by A-1 for it), shared as
    /// [`Robot::waits_for`].
    pub waits_for: Option<(u32, Option<DoorIdx>)>,
    /// Its step aside for a robot with priority after a face-off, if it is giving way.
    pub give_way: Option<GiveWay>,
}

impl Mind {
    /// A robot that has seen nothing yet.
    pub fn new() -> Mind {
        Mind {
            estimator: None,
            tracked: Vec::new(),
            c2: false,
            zone: None,
            keep: None,
            door_wait: None,
            waits_for: None,
            give_way: None,
        }
    }
}

impl Clone for Mind {
    fn clone(&self) -> Mind {
        let Mind {
            estimator,
            tracked,
            c2,
            zone,
            keep,
            door_wait,
            waits_for,
            give_way,
        } = self;
        Mind {
            estimator: estimator.clone(),
            tracked: tracked.clone(),
            c2: *c2,
            zone: *zone,
            keep: keep.clone(),
            door_wait: *door_wait,
            waits_for: *waits_for,
            give_way: *give_way,
        }
    }

    /// Reuses `self`'s list of tracked robots (the step copies every robot's mind).
    fn clone_from(&mut self, source: &Mind) {
        let Mind {
            estimator,
            tracked,
            c2,
            zone,
            keep,
            door_wait,
            waits_for,
            give_way,
        } = source;
        self.estimator.clone_from(estimator);
        self.tracked.clone_from(tracked);
        self.c2 = *c2;
        self.zone = *zone;
        self.keep.clone_from(keep);
        self.door_wait = *door_wait;
        self.waits_for = *waits_for;
        self.give_way = *give_way;
    }
}

impl Default for Mind {
    fn default() -> Self {
        Mind::new()
    }
}

/// What Algorithm 1 concluded this step, before the controller's command is shaped.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Perception {
    /// Active roles: of the elements sensed, the zone, and the robot's C-2.
    pub roles: RoleSet,
    /// Speed limit from A-1, A-2/B-2, B-1 and C-1, m/s.
    pub speed_cap: f64,
    /// Turn rate added by A-1 side clearance, rad/s.
    pub turn_bias: f64,
    /// A-3 reference on the +90 ray (distance), when it hits an A-3 element directly.
    pub left_ref: Option<f64>,
    /// A-3 reference on the -90 ray.
    pub right_ref: Option<f64>,
    /// Nearest tracked robot and its centre distance.
    pub nearest: Option<(u32, f64)>,
    /// Keep to the right-hand wall (an oncoming robot in a C-1 zone).
    pub keep_right: bool,
    /// Stop (YIELD to a robot with priority).
    pub stop: bool,
    /// While giving way, too close to the other robot to turn: +1 or -1, the way along its
    /// heading that leads away from it (0: room to turn).
    pub squeeze: f64,
}

/// The run-wide things Algorithm 1 reads.
#[derive(Debug, Clone, Copy)]
pub struct Env<'a> {
    /// The floor.
    pub floor: &'a Floor,
    /// Its graph (door axes).
    pub nav: &'a Plan,
    /// All robots (for tracked robots' poses and priorities).
    pub robots: &'a [Robot],
    /// The step's index: its robot boxes and grid are `robots`' footprints as they are now
    /// (a robot's heading is read from its box's axis, sparing a sine and cosine).
    pub world: &'a World,
    /// Behaviour constants.
    pub behaviour: &'a Behaviour,
    /// Step.
    pub step: u64,
    /// Time.
    pub t: f64,
    /// Who waits for whom, made for this step from `robots` ([`Waiters::rebuild`]); `None`
    /// looks every robot up in the robot grid instead (the same decisions).
    pub waiters: Option<&'a Waiters>,
}

/// Where Algorithm 1 reports.
#[derive(Debug)]
pub struct Sink<'a> {
    /// Events.
    pub events: &'a mut Vec<Event>,
    /// Observations that changed a record, for the write-back: (GlobalId, observation, time).
    pub observations: &'a mut Vec<(String, Observation, f64)>,
}

impl Sink<'_> {
    fn push(&mut self, env: &Env<'_>, robot: &str, kind: EventKind) {
        self.events.push(Event {
            step: env.step,
            t: env.t,
            robot: robot.to_string(),
            kind,
        });
    }

    fn change(&mut self, env: &Env<'_>, robot: &str, db: &PoiDb, rec: usize, c: &RuntimeChange) {
        let r = db.get(rec);
        for &role in &c.added {
            self.push(
                env,
                robot,
                EventKind::RoleAdded {
                    element: r.global_id.clone(),
                    name: r.name.clone(),
                    role,
                },
            );
        }
        for &role in &c.removed {
            self.push(
                env,
                robot,
                EventKind::RoleRemoved {
                    element: r.global_id.clone(),
                    name: r.name.clone(),
                    role,
                },
            );
        }
        if let Some((from, to)) = c.status {
            self.push(
                env,
                robot,
                EventKind::StatusChanged {
                    element: r.global_id.clone(),
                    name: r.name.clone(),
                    from,
                    to,
                },
            );
        }
    }
}

/// A robot waits for a single-lane door while another uses it from the other side, this far from
/// the door's centre (metres): room for the other to come out.
pub const DOOR_HOLD_M: f64 = 1.8;
/// A robot that waited for a door goes on once the other is this far from its centre
/// (metres), on whichever side.
pub const DOOR_CLEAR_M: f64 = 1.3;
/// Robots farther than this from a door's centre (metres) do not contend for it.
pub const DOOR_CONFLICT_M: f64 = 3.0;
/// A robot about to enter a shared (C-1) zone through a single-lane door waits while another
/// robot is in that zone this close to the door's centre (metres): it merges into the
/// corridor's traffic, the corridor does not fill up with robots crossing it.
pub const MERGE_M: f64 = 2.0;

/// True when `p` lies in a zone with a C-1 coordination (a corridor).
fn shared_zone_at(env: &Env<'_>, p: DVec2) -> bool {
    env.floor
        .zones
        .iter()
        .any(|z| z.coordination.is_some() && polygon::contains(&z.ring, p))
}

/// The doors robot `me` must give way at: each door within [`DOOR_CONFLICT_M`] ahead of it
/// (centre within 50 degrees of its heading), too narrow for two robots side by side, that
/// another robot on its other side (or in it) is coming through, nearer to its centre than
/// `me` (on a tie within 5 cm, the one with priority goes). Robots share their poses (as for
/// C-1), so the two decide from the same facts: exactly one of them waits, never both, never
/// neither. `held` is the door it waited at in the last step: it keeps waiting there even when
/// that door has left its heading's cone (a robot driving along a corridor sees a side door
/// turn away as it nears it). A robot that gives way ([`Robot::giving_way`]), or that `me` has
/// priority over and stands in a face-off with ([`face_off`]), is never waited for: it steps
/// aside and waits itself. A robot about to enter a corridor (a zone with a C-1 coordination)
/// from outside it also waits while another robot is in the corridor within [`MERGE_M`] of
/// the door, not coming through it. Returns the nearest such door, the distance to it and the
/// robot waited for.
///
/// The other robots are looked up in the step's robot grid ([`World::any_robot_near`]) within
/// [`DOOR_CONFLICT_M`] of the door, so a crowd at the doors costs what its neighbourhoods
/// hold, not every robot per robot; the decision is the same as testing every robot
/// ([`door_wait_every_robot`]), since a robot farther than that never counts.
fn door_wait(me: usize, env: &Env<'_>, held: Option<DoorIdx>) -> Option<(DoorIdx, f64, u32)> {
    door_wait_with(me, env, held, |center, f| {
        let r = DVec2::splat(DOOR_CONFLICT_M);
        env.world.any_robot_near(center - r, center + r, &mut |r| {
            f(r);
            false
        });
    })
}

/// `door_wait` (the private fast path) testing every robot (the reference for tests).
pub fn door_wait_every_robot(
    me: usize,
    env: &Env<'_>,
    held: Option<DoorIdx>,
) -> Option<(DoorIdx, f64, u32)> {
    door_wait_with(me, env, held, |_, f| {
        (0..env.robots.len() as u32).for_each(&mut *f)
    })
}

/// [`door_wait`] with `others(center, f)` calling `f` on every robot that may be within
/// [`DOOR_CONFLICT_M`] of `center` (it may also offer farther ones, and one twice); also
/// returns the robot waited for (the lowest index of those that make it wait there).
fn door_wait_with(
    me: usize,
    env: &Env<'_>,
    held: Option<DoorIdx>,
    others: impl Fn(DVec2, &mut dyn FnMut(u32)),
) -> Option<(DoorIdx, f64, u32)> {
    let robot = &env.robots[me];
    let lim = &robot.limits;
    let pos = robot.state.pos;
    let dir = env.world.robot(me).ax;
    let cone = 50f64.to_radians().cos();
    let mut nearest: Option<(DoorIdx, f64, u32)> = None;
    // The doors whose centres lie within reach (the grid of door centres offers them in no
    // particular order: the nearest wins, on a tie the lowest index, as in floor order).
    env.nav.doors_near(pos, DOOR_CONFLICT_M + 1e-6, |d| {
        let door = &env.floor.doors[d];
        let Some(axis) = env.nav.doors[d].axis else {
            return;
        };
        let to = door.center - pos;
        let mine = to.length();
        let in_cone = to.dot(dir) >= cone * mine || held == Some(DoorIdx::new(d));
        if !(1e-9..=DOOR_CONFLICT_M).contains(&mine) || !in_cone {
            return;
        }
        let my_side = -to.dot(axis);
        // About to enter a shared (C-1) zone from outside it through this door, not yet
        // committed to the door.
        let merging = mine > DOOR_HOLD_M - 0.2
            && shared_zone_at(env, door.center - axis * my_side.signum() * 0.5)
            && !shared_zone_at(env, pos);
        let mut who: Option<u32> = None;
        others(door.center, &mut |r32| {
            let r = r32 as usize;
            if r == me || who.is_some_and(|w| w <= r32) {
                return;
            }
            let o = &env.robots[r];
            let side_by_side = 2.0 * (lim.half_width + o.limits.half_width) + 3.0 * lim.margin;
            let rel = o.state.pos - door.center;
            let theirs = rel.length();
            if door.clear_width_m >= side_by_side || theirs > DOOR_CONFLICT_M {
                return;
            }
            let in_door = rel.dot(axis).abs() <= 0.3
                && rel.dot(axis.perp()).abs() <= 0.5 * door.clear_width_m;
            let other_side = rel.dot(axis) * my_side < 0.0 || in_door;
            let coming = in_door || env.world.robot(r).ax.dot(-rel) > 0.0;
            let they_go = theirs + 0.05 < mine
                || ((theirs - mine).abs() <= 0.05 && !has_priority(env.robots, me, r));
            // Once waiting, wait until the other has also cleared the door on this side (it
            // turns there, sweeping its corners).
            let clearing = held == Some(DoorIdx::new(d)) && theirs < DOOR_CLEAR_M;
            // Entering the shared zone, give way to the robots already in it near the door
            // (those coming through it: as above).
            let merge = merging && !coming && theirs <= MERGE_M && rel.dot(axis) * my_side < 0.0;
            // Whether `me` may wait for it at all last (the wait-for chain: the costly part).
            if ((other_side && coming && they_go) || clearing || merge) && waits_for(env, me, r) {
                who = Some(r32);
            }
        });
        if let Some(w) = who {
            if nearest.is_none_or(|n| mine < n.1 || (mine == n.1 && d < n.0.get())) {
                nearest = Some((DoorIdx::new(d), mine, w));
            }
        }
    });
    nearest
}

/// Longest wait-for chain (robots) that [`waits_for`] follows to find a cycle.
const CHAIN: usize = 8;

/// A robot ahead closer than this beyond the margin (metres) stops it: it waits for that one.
const BLOCKED_M: f64 = 0.02;

/// How far (metres, centre to centre along each axis) a robot looks for robots that wait for
/// it: the farthest a door wait or an A-1 stop reaches back in a queue at a door.
const WAITERS_M: f64 = 2.0;

/// The robot that robot `me` (stopped by a wait, or arrived: `arrived`, its wait `waits`) gives
/// way to: of the robots within [`WAITERS_M`] waiting for it, the lowest index that tops a
/// wait-for cycle through it (having arrived: any robot still on its way). The robots are those
/// `waiters` lists for it, or without it every robot in the robot grid around it: the same
/// ones, since a robot is listed near by the grid cells its box covers in both.
fn waiter_to_give_way_to(
    env: &Env<'_>,
    me: usize,
    arrived: bool,
    waits: Option<(u32, Option<DoorIdx>)>,
    waiters: Option<&Waiters>,
) -> Option<usize> {
    let pos = env.robots[me].state.pos;
    let reach = DVec2::splat(WAITERS_M);
    let (lo, hi) = (pos - reach, pos + reach);
    let first = waits.map(|w| w.0 as usize);
    let mut top: Option<usize> = None;
    let mut consider = |p: u32| {
        let p = p as usize;
        if top.is_none_or(|t| p < t)
            && env.robots[p].waits_for.is_some_and(|w| w.0 as usize == me)
            && match (arrived, first) {
                (true, _) => !env.robots[p].arrived,
                (false, Some(f)) => cycle_tops(env, me, f, p),
                (false, None) => false,
            }
        {
            top = Some(p);
        }
        false
    };
    match waiters {
        Some(w) => {
            for &p in w.of(me) {
                if env.world.robot_listed_near(p as usize, lo, hi) {
                    consider(p);
                }
            }
        }
        None => {
            env.world.any_robot_near(lo, hi, &mut consider);
        }
    }
    top
}

/// The robot that goes first in a face-off with robot `me` (stopped), the lowest index of
/// those: looked up in the robot grid over `waiters`' [`Waiters::face_off_box`] (the lane ahead
/// of it), or without it over the square of [`crate::give_way::FACE_OFF_M`] around it.
fn face_off_first(env: &Env<'_>, me: usize, waiters: Option<&Waiters>) -> Option<usize> {
    let (lo, hi) = match waiters {
        Some(w) => w.face_off_box(env, me),
        None => {
            let pos = env.robots[me].state.pos;
            let reach = DVec2::splat(crate::give_way::FACE_OFF_M);
            (pos - reach, pos + reach)
        }
    };
    let mut first: Option<usize> = None;
    env.world.any_robot_near(lo, hi, &mut |r| {
        let r = r as usize;
        if first.is_none_or(|f| r < f) && goes_first(env.robots, r, me) && face_off(env, me, r) {
            first = Some(r);
        }
        false
    });
    first
}

/// True when robot `top` (which waits for `me`) has priority over `me` and over every robot
/// on the wait-for chain from `me` (whose first hop is `first`, this step's) back to it.
fn cycle_tops(env: &Env<'_>, me: usize, first: usize, top: usize) -> bool {
    if !goes_first(env.robots, top, me) {
        return false;
    }
    let mut cur = first;
    for _ in 0..CHAIN {
        if cur == top {
            return true;
        }
        if !goes_first(env.robots, top, cur) {
            return false;
        }
        match env.robots[cur].waits_for {
            Some((next, _)) => cur = next as usize,
            None => return false,
        }
    }
    false
}

/// The line robot `o` goes on along: to the door it waits at, else its heading.
fn line_of(env: &Env<'_>, o: usize) -> DVec2 {
    let r = &env.robots[o];
    match r.waits_for {
        Some((_, Some(door))) => {
            let to = env.floor.doors[door.get()].center - r.state.pos;
            to.try_normalize().unwrap_or(env.world.robot(o).ax)
        }
        _ => env.world.robot(o).ax,
    }
}

/// False when robot `me` must not wait for robot `other` at a door even if the door protocol
/// says so: `other` has arrived (it is not coming through) or gives way
/// ([`Robot::giving_way`]), or `me` has priority over it and the two
/// stand in a face-off ([`face_off`]), or `other`'s published wait-for chain
/// ([`Robot::waits_for`]) leads back to `me` and `me` has priority over every robot on it (of
/// a wait-for cycle, the robot with priority goes).
fn waits_for(env: &Env<'_>, me: usize, other: usize) -> bool {
    if env.robots[other].giving_way.is_some() || env.robots[other].arrived {
        return false;
    }
    if goes_first(env.robots, me, other) && face_off(env, me, other) {
        return false;
    }
    let mut cur = other;
    for _ in 0..CHAIN {
        if !goes_first(env.robots, me, cur) {
            return true;
        }
        match env.robots[cur].waits_for {
            Some((next, _)) if next as usize == me => return false,
            Some((next, _)) => cur = next as usize,
            None => return true,
        }
    }
    true
}

/// A clearance measurement Algorithm 1 made for a door, to be applied to the POI database (rule
/// R5) with [`apply_clearance`] in robot order after the robots perceived in parallel.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PendingClearance {
    /// Record index of the door.
    pub rec: usize,
    /// The estimate, metres.
    pub estimate_m: f64,
    /// How many of the robot's events of this step came before the measurement.
    pub events_before: usize,
}

/// Runs the per-element part of Algorithm 1 for robot `me` on this step's `reading`, reading
/// the POI database only: a clearance measurement is handed back to be applied in order (the
/// events it causes belong after the first `events_before` this call pushed).
pub fn perceive(
    me: usize,
    reading: &Reading,
    env: &Env<'_>,
    db: &PoiDb,
    mind: &mut Mind,
    sink: &mut Sink<'_>,
) -> (Perception, Option<PendingClearance>) {
    let events_at_start = sink.events.len();
    let robot = &env.robots[me];
    let lim = &robot.limits;
    let beh = env.behaviour;
    let pos = robot.state.pos;
    let dir = env.world.robot(me).ax;
    let forward = robot.state.speed >= 0.0;
    let mut roles = RoleSet::default();
    let mut cap = lim.max_speed;
    let mut turn_bias = 0.0;
    let brake = 0.8 * lim.decel;

    // Zone: where the robot is.
    let zone = match mind.zone {
        Some(z) if polygon::contains(&env.floor.zones[z.get()].ring, pos) => Some(z),
        _ => env
            .floor
            .zones
            .iter()
            .position(|z| polygon::contains(&z.ring, pos))
            .map(ZoneIdx::new),
    };
    if zone != mind.zone {
        if let Some(z) = zone {
            let zr = &env.floor.zones[z.get()];
            sink.push(
                env,
                &robot.name,
                EventKind::ZoneEntered {
                    zone: zr.id.to_string(),
                    name: zr.name.clone(),
                },
            );
        }
        mind.zone = zone;
    }
    let zone_rec = zone.map(|z| db.index(Element::Zone(z)));
    if let Some(z) = zone_rec {
        // The zone's C-2 (any robot in it) is not this robot's: that one is added below.
        roles = roles.union(db.roles(z).without(Role::RobotInteraction));
        if db.roles(z).has(Role::Hazard) {
            cap = cap.min(lim.max_speed * beh.hazard_speed_factor);
        }
    }

    // Per element hit: roles, A-1, A-3, robots for C-1.
    let mut left_ref = None;
    let mut right_ref = None;
    // The robot A-1 stops it for (the nearest hit ahead within BLOCKED_M of the margin).
    let mut blocked: Option<(u32, f64)> = None;
    for (k, ray) in reading.rays.iter().enumerate() {
        let (sin, cos) = crate::sensor::ray_sin_cos()[k];
        let avoid = match ray.target {
            Target::None => false,
            Target::Robot(r) => {
                if !mind.tracked.contains(&r) {
                    mind.tracked.push(r);
                }
                true
            }
            Target::Obstacle(o) => {
                let rec = db.index(Element::Obstacle(ObstacleIdx::new(o as usize)));
                let rr = db.roles(rec);
                roles = roles.union(rr);
                if rr.has(Role::PathGuidance) && ray.passages.is_empty() {
                    if k == LEFT {
                        left_ref = Some(ray.dist);
                    } else if k == RIGHT {
                        right_ref = Some(ray.dist);
                    }
                }
                rr.has(Role::Avoidance)
            }
        };
        for &d in ray.passages.doors() {
            roles = roles.union(db.roles(db.index(Element::Door(DoorIdx::new(d as usize)))));
        }
        if !avoid {
            continue;
        }
        // MaintainClearance(E, margin).
        if k == FRONT || k == LEFT30 || k == RIGHT30 {
            let lateral = (ray.dist * sin).abs();
            if forward && lateral <= lim.half_width + lim.margin {
                let mut free = ray.dist * cos - lim.half_length - lim.margin;
                if let Target::Robot(r) = ray.target {
                    // A robot giving way to this one is left room to turn aside.
                    if env.robots[r as usize].giving_way == Some(me as u32) {
                        free -= crate::give_way::TURN_ROOM_M;
                    }
                }
                cap = cap.min((2.0 * brake * free.max(0.0)).sqrt());
                if let Target::Robot(r) = ray.target {
                    if free < BLOCKED_M && blocked.is_none_or(|b| free < b.1) {
                        blocked = Some((r, free));
                    }
                }
            }
        } else {
            let free = ray.dist - lim.half_width;
            if free < lim.margin {
                let away = if k == LEFT { -1.0 } else { 1.0 };
                turn_bias += away * beh.side_gain * (lim.margin - free);
            }
        }
    }

    // doors ahead.
    let mut ahead: Vec<DoorIdx> = Vec::new();
    for k in [FRONT, LEFT30, RIGHT30] {
        for d in reading.rays[k]
            .passages
            .doors()
            .iter()
            .map(|&d| DoorIdx::new(d as usize))
        {
            if !ahead.contains(&d) {
                ahead.push(d);
            }
        }
    }
    if let Some(e) = &mind.estimator {
        if !ahead.contains(&e.door) {
            ahead.push(e.door);
        }
    }
    for &d in &ahead {
        let rec = db.index(Element::Door(d));
        let rr = db.roles(rec);
        if !rr.has(Role::Transition) {
            continue;
        }
        // Only doors the robot is about to pass through: axis along the heading, centre on
        // the robot's path.
        let rel = env.floor.doors[d.get()].center - pos;
        let s = rel.dot(dir);
        let through = env.nav.doors[d.get()]
            .axis
            .is_some_and(|a| a.dot(dir).abs() >= 45f64.to_radians().cos());
        let on_path = rel.dot(dir.perp()).abs()
            <= 0.5 * env.floor.doors[d.get()].clear_width_m + lim.half_width;
        if s < -lim.half_length || !through || !on_path {
            continue;
        }
        let factor = if rr.has(Role::Narrow) {
            beh.narrow_speed_factor
        } else {
            beh.transition_speed_factor
        };
        let v_door = lim.max_speed * factor;
        let gap = (s - lim.half_length).max(0.0);
        cap = cap.min((v_door * v_door + 2.0 * brake * gap).sqrt());
        // A door narrower than the robot (as measured, else as modelled) is not driven into:
        // stop a margin before its near side, whatever the command (keys included).
        let measured = mind
            .estimator
            .as_ref()
            .filter(|e| e.door == d)
            .and_then(Estimator::estimate);
        let width = measured.unwrap_or(env.floor.doors[d.get()].clear_width_m);
        if width < 2.0 * lim.half_width + 0.01 {
            let near = env.floor.doors[d.get()]
                .ring
                .iter()
                .map(|p| (*p - pos).dot(dir))
                .fold(f64::INFINITY, f64::min);
            let free = (near - lim.half_length - lim.margin).max(0.0);
            cap = cap.min((2.0 * brake * free).sqrt());
        }
    }
    let pending = sensor_clearance(me, reading, env, db, mind, &ahead).map(|(rec, estimate_m)| {
        PendingClearance {
            rec,
            estimate_m,
            events_before: sink.events.len() - events_at_start,
        }
    });

    // C-1: the tracked robots still in range, and the nearest of them (by distance, then
    // index), each distance computed once.
    let mut nearest: Option<(u32, f64)> = None;
    mind.tracked.retain(|&r| {
        let d = env.robots[r as usize].state.pos.distance(pos);
        let keep = d <= RANGE_M + env.world.robot_radius(r as usize);
        if keep && nearest.is_none_or(|(nr, nd)| d.total_cmp(&nd).then(r.cmp(&nr)).is_lt()) {
            nearest = Some((r, d));
        }
        keep
    });
    mind.tracked.sort_unstable();
    let mut c2 = false;
    let mut keep_right = false;
    let mut stop = false;
    let coordination = zone.and_then(|z| {
        let zr = &env.floor.zones[z.get()];
        let rec = db.index(Element::Zone(z));
        if db.roles(rec).has(Role::MultiRobotZone) {
            zr.coordination
        } else {
            None
        }
    });
    if let (Some((sep, protocol)), Some((other, d))) = (coordination, nearest) {
        if d < sep {
            c2 = true;
            let priority = has_priority(env.robots, me, other as usize);
            let reduced = lim.max_speed * beh.reduction_factor;
            match protocol {
                CoordinationProtocol::SpeedReduction => cap = cap.min(reduced),
                CoordinationProtocol::PriorityPass => {
                    if !priority {
                        cap = cap.min(reduced);
                    }
                }
                CoordinationProtocol::Yield => {
                    if priority {
                        cap = cap.min(reduced);
                    } else {
                        stop = true;
                    }
                }
            }
        }
        for &r in &mind.tracked {
            let o = &env.robots[r as usize];
            let rel = o.state.pos - pos;
            let o_dir = env.world.robot(r as usize).ax;
            if rel.dot(dir) > 0.0 && o_dir.dot(dir) < -0.5 && rel.length() < RANGE_M {
                keep_right = true;
            }
        }
    }
    // C-2 at a single-lane door (any zone): of two robots about to use one door from its two
    // sides, the nearer one goes and the other waits outside DOOR_HOLD_M.
    let wait = door_wait(me, env, mind.door_wait);
    mind.door_wait = wait.map(|w| w.0);
    mind.waits_for = wait
        .map(|w| (w.2, Some(w.0)))
        .or(blocked.map(|b| (b.0, None)));
    // Giving way: to a robot with priority that waits for this one as this one waits for it
    // (it goes: off the line to its door), or that stands in a face-off with it (the lowest
    // index of those there); once giving way, until that robot has passed.
    if mind.give_way.is_some_and(|g| g.done(env, me)) {
        mind.give_way = None;
    }
    if mind
        .give_way
        .is_some_and(|g| g.reached(env, me) && face_off(env, me, g.other as usize))
    {
        // Still in its way where it stepped to (backed off along its line): further.
        let o = mind.give_way.map_or(0, |g| g.other as usize);
        mind.give_way = GiveWay::start(env, me, o, line_of(env, o));
    }
    // Of a wait-for cycle, out of the way of the robot that goes first in it; having arrived,
    // out of the way of any robot on its way that waits for it.
    let arrived = robot.arrived;
    if mind.give_way.is_none() && (arrived || mind.waits_for.is_some()) {
        let top = waiter_to_give_way_to(env, me, arrived, mind.waits_for, env.waiters);
        debug_assert_eq!(
            top,
            waiter_to_give_way_to(env, me, arrived, mind.waits_for, None),
            "the waiters' index decides as the grid lookup"
        );
        mind.give_way = top.and_then(|p| GiveWay::start(env, me, p, line_of(env, p)));
    }
    if mind.give_way.is_none() && robot.state.speed.abs() < STOPPED_M_S {
        let first = face_off_first(env, me, env.waiters);
        debug_assert_eq!(
            first,
            face_off_first(env, me, None),
            "the face-off box decides as the square around the robot"
        );
        mind.give_way = first.and_then(|o| GiveWay::start(env, me, o, line_of(env, o)));
    }
    let squeeze = mind.give_way.map_or(0.0, |g| {
        let o = g.other as usize;
        let rel = env.robots[o].state.pos - pos;
        let room = env.world.robot_radius(me) + env.world.robot_radius(o) + 0.02;
        match (rel.length() < room, rel.dot(dir) > 0.0) {
            (false, _) => 0.0,
            (true, true) => -1.0,
            (true, false) => 1.0,
        }
    });
    // Waiting at the door stops it outside DOOR_HOLD_M, unless it gives way (then it steps
    // aside, off the other's line).
    if let Some((_, mine, _)) = wait {
        c2 = true;
        if mind.give_way.is_none() {
            cap = cap.min((2.0 * brake * (mine - DOOR_HOLD_M).max(0.0)).sqrt());
        }
    }
    if c2 {
        roles.insert(Role::RobotInteraction);
    }
    if c2 != mind.c2 {
        sink.push(
            env,
            &robot.name,
            EventKind::RobotRole {
                role: Role::RobotInteraction,
                on: c2,
                other: nearest.map(|(r, _)| env.robots[r as usize].name.clone()),
                distance_m: nearest.map_or(f64::INFINITY, |n| n.1),
            },
        );
        mind.c2 = c2;
    }
    (
        Perception {
            roles,
            speed_cap: cap.max(0.0),
            turn_bias,
            left_ref,
            right_ref,
            nearest,
            keep_right,
            stop,
            squeeze,
        },
        pending,
    )
}

/// The A-2 branch: starts and feeds the door clearance estimate; returns the door's record and
/// a new estimate to report.
fn sensor_clearance(
    me: usize,
    reading: &Reading,
    env: &Env<'_>,
    db: &PoiDb,
    mind: &mut Mind,
    ahead: &[DoorIdx],
) -> Option<(usize, f64)> {
    let robot = &env.robots[me];
    let pos = robot.state.pos;
    let dir = env.world.robot(me).ax;
    let max_off = env.behaviour.max_approach_deg.to_radians();
    if let Some(e) = &mind.estimator {
        let aligned = e.axis.dot(dir) >= max_off.cos();
        if !aligned || !e.before_exit(pos) {
            mind.estimator = None;
        }
    }
    if mind.estimator.is_none() {
        for &d in ahead {
            let rec = db.index(Element::Door(d));
            if !db.roles(rec).has(Role::Transition) {
                continue;
            }
            let Some(axis) = env.nav.doors[d.get()].axis else {
                continue;
            };
            let to = env.floor.doors[d.get()].center - pos;
            let off = wrap_angle(to.y.atan2(to.x) - robot.state.heading).abs();
            if axis.dot(dir).abs() >= max_off.cos()
                && off <= 20f64.to_radians()
                && to.length() <= RANGE_M
            {
                let axis = if axis.dot(dir) >= 0.0 { axis } else { -axis };
                let door = &env.floor.doors[d.get()];
                mind.estimator = Some(Estimator::start(d, door.center, axis, &door.ring));
                break;
            }
        }
    }
    let e = mind.estimator.as_mut()?;
    let estimate = e.update(pos, reading)?;
    Some((db.index(Element::Door(e.door)), estimate))
}

/// Applies robot `me`'s clearance measurement to the POI database (rule R5) and reports it: the
/// measurement, the observation for the write-back and the role and status changes. True when
/// a record's roles or status changed.
pub fn apply_clearance(
    me: usize,
    pending: &PendingClearance,
    env: &Env<'_>,
    db: &mut PoiDb,
    sink: &mut Sink<'_>,
) -> bool {
    let robot = &env.robots[me];
    let (rec, estimate) = (pending.rec, pending.estimate_m);
    let observation = Observation::Clearance {
        measured_width_m: estimate,
    };
    let change = db.apply(rec, observation);
    let r = db.get(rec);
    let a = r.accessibility.as_ref();
    let mut roles: Vec<Role> = r.primary.iter().chain(&r.conditional).copied().collect();
    roles.sort();
    roles.dedup();
    let kind = EventKind::Clearance {
        door: r.global_id.clone(),
        name: r.name.clone(),
        estimate_m: estimate,
        required_m: a.map_or(f64::NAN, |a| a.min_clearance_width_m),
        status: a.map_or(poinav_roles::AccessibilityStatus::PendingValidation, |a| {
            a.status
        }),
        roles,
    };
    sink.observations
        .push((r.global_id.clone(), observation, env.t));
    sink.push(env, &robot.name, kind);
    sink.change(env, &robot.name, db, rec, &change);
    !change.is_empty()
}

/// C-1 at the zone level: a zone's record carries C-2 while some robot in it has C-2 (R5 with
/// the smallest distance any of them measured), and loses it when none has.
pub fn zone_coordination(
    env: &Env<'_>,
    minds: &[Mind],
    nearest: &[Option<(u32, f64)>],
    db: &mut PoiDb,
    sink: &mut Sink<'_>,
) {
    // Per zone, in one pass over the robots: the first robot in it and the closest C-2 distance.
    let zones = env.floor.zones.len();
    let mut closest: Vec<Option<(f64, usize)>> = vec![None; zones];
    let mut present: Vec<Option<usize>> = vec![None; zones];
    for (i, m) in minds.iter().enumerate() {
        let Some(z) = m.zone.map(ZoneIdx::get).filter(|&z| z < zones) else {
            continue;
        };
        present[z].get_or_insert(i);
        if let (true, Some((_, d))) = (m.c2, nearest[i]) {
            if closest[z].is_none_or(|(c, _)| d < c) {
                closest[z] = Some((d, i));
            }
        }
    }
    for (z, zone) in env.floor.zones.iter().enumerate() {
        if zone.coordination.is_none() {
            continue;
        }
        let rec = db.index(Element::Zone(ZoneIdx::new(z)));
        let (closest, present) = (closest[z], present[z]);
        let has = db.roles(rec).has(Role::RobotInteraction);
        let (distance, who) = match (closest, has) {
            (Some((d, i)), _) => (d, i),
            (None, true) => (f64::INFINITY, present.unwrap_or(0)),
            (None, false) => continue,
        };
        let observation = Observation::RobotDistance {
            distance_m: distance,
        };
        let change = db.apply(rec, observation);
        if !change.is_empty() {
            let name = env.robots[who].name.clone();
            sink.observations
                .push((db.get(rec).global_id.clone(), observation, env.t));
            sink.change(env, &name, db, rec, &change);
        }
    }
}

/// ComputeNavigationAction: the controller's command within the speed cap, steered by A-1 side
/// clearance, and along the right-hand wall while robots meet (unless driven by keys); while
/// the robot gives way, the step aside instead (within the cap, whatever the protocol's stop).
pub fn decide(
    p: &Perception,
    cmd: Command,
    robot: &Robot,
    mind: &mut Mind,
    t: f64,
    manual: bool,
    beh: &Behaviour,
) -> Command {
    let lim = &robot.limits;
    if let (Some(g), false) = (mind.give_way, manual) {
        mind.keep = None;
        return g.command(robot, p.speed_cap, p.squeeze);
    }
    let mut v = if cmd.v >= 0.0 {
        cmd.v.min(p.speed_cap)
    } else {
        cmd.v.max(-p.speed_cap)
    };
    if p.stop {
        v = 0.0;
    }
    let mut omega = cmd.omega;
    if p.keep_right && !manual {
        let target = beh
            .keep_right_m
            .unwrap_or(lim.half_width + 2.0 * lim.margin);
        let pd = mind
            .keep
            .get_or_insert_with(|| WallPd::new(Side::Right, target));
        // Only while driving: a robot turning in place (to line up with a door) turns as its
        // controller says, or the two would hold it swinging on the spot.
        if p.right_ref.is_some() && cmd.v > 0.0 {
            omega = pd.omega(
                p.right_ref,
                t,
                robot.state.heading,
                robot.state.speed.max(0.5),
            );
        }
    } else {
        mind.keep = None;
    }
    // A-1's side steering while driving only: added to a turn in place (lining up with a
    // door, a jamb close beside) it can cancel the turn and hold the robot still for ever.
    if cmd.v != 0.0 {
        omega += p.turn_bias;
    }
    Command {
        v,
        omega: omega.clamp(-lim.max_turn, lim.max_turn),
    }
}

#[cfg(test)]
#[path = "algorithm1_tests.rs"]
mod tests;
