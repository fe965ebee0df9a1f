//! Expectations: what a scenario must show, each measured from the trace records and events (not
//! from the simulator's internals) and judged pass or fail with the measured values.

use glam::DVec2;
use poinav_nav::Floor;
use poinav_roles::{AccessibilityStatus, Role};
use serde::Deserialize;
use serde_json::{json, Value};

use crate::events::{Event, EventKind};
use crate::geometry::{polygon_gap, Obb};
use crate::neighbours::PointGrid;
use crate::poi_db::PoiDb;
use crate::sensor::RAY_DEG;
use crate::step::RunData;
use crate::trace::{Names, StepRecord};
use crate::world::Target;

fn a3() -> Option<Role> {
    Some(Role::PathGuidance)
}

fn wall_follow() -> Option<String> {
    Some("wall-follow".into())
}

/// One expectation of a scenario file (`[[expect]]`, field `kind`).
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(tag = "kind", rename_all = "kebab-case", deny_unknown_fields)]
pub enum Expect {
    /// The last sensor clearance estimate of `door` is within `tolerance_m` of its real clear
    /// width.
    ClearanceEstimate {
        /// Door Name or GlobalId.
        door: String,
        /// Only this robot's measurements.
        #[serde(default)]
        robot: Option<String>,
        /// Tolerance, metres.
        tolerance_m: f64,
    },
    /// After the last sensor measurement of `door`: this status, with and without these roles.
    DoorStatus {
        /// Door Name or GlobalId.
        door: String,
        /// Expected AccessibilityStatus.
        status: AccessibilityStatus,
        /// Roles that must be present.
        #[serde(default)]
        roles_include: Vec<Role>,
        /// Roles that must be absent.
        #[serde(default)]
        roles_exclude: Vec<Role>,
    },
    /// Whenever the two robots' centres are closer than `distance_m`, both have `role`.
    RoleBelowDistance {
        /// Two robots.
        robots: Vec<String>,
        /// Role (C-2).
        role: Role,
        /// Distance, metres.
        distance_m: f64,
    },
    /// While a robot has `role` (after `settle_s` from its onset), its speed is `speed_m_s`
    /// within `tolerance_m_s`.
    SpeedWhileRole {
        /// Robots.
        robots: Vec<String>,
        /// Role.
        role: Role,
        /// Speed, m/s.
        speed_m_s: f64,
        /// Tolerance, m/s.
        tolerance_m_s: f64,
        /// Time allowed to reach the speed, s.
        #[serde(default)]
        settle_s: f64,
    },
    /// The robots' footprints never touch (and, with `walls`, no robot touches anything).
    NoContact {
        /// Robots (default all).
        #[serde(default)]
        robots: Vec<String>,
        /// Walls count too.
        #[serde(default)]
        walls: bool,
    },
    /// A ray's distance to a reference element stays within tolerance.
    LateralDistance {
        /// Robot.
        robot: String,
        /// Ray angle, degrees (90 or -90).
        ray_deg: f64,
        /// Distance, metres.
        distance_m: f64,
        /// Tolerance, metres.
        tolerance_m: f64,
        /// Ignore the first metres travelled.
        #[serde(default)]
        after_m: f64,
        /// Only hits on elements with this role (default A-3).
        #[serde(default = "a3")]
        role: Option<Role>,
        /// Only steps in this controller mode (default `wall-follow`).
        #[serde(default = "wall_follow")]
        mode: Option<String>,
    },
    /// The robot arrives at the zone's goal (within `within_s`).
    ReachesZone {
        /// Robot.
        robot: String,
        /// Zone Name or LongName.
        zone: String,
        /// Deadline, s.
        #[serde(default)]
        within_s: Option<f64>,
    },
    /// The robot's speed stays within a range.
    SpeedRange {
        /// Robot.
        robot: String,
        /// Highest speed reached must be at least this.
        #[serde(default)]
        reaches_m_s: Option<f64>,
        /// And never above this.
        #[serde(default)]
        at_most_m_s: Option<f64>,
    },
}

impl Expect {
    /// Robot names the expectation refers to.
    pub fn robots(&self) -> Vec<&str> {
        match self {
            Expect::ClearanceEstimate { robot, .. } => robot.iter().map(String::as_str).collect(),
            Expect::RoleBelowDistance { robots, .. }
            | Expect::SpeedWhileRole { robots, .. }
            | Expect::NoContact { robots, .. } => robots.iter().map(String::as_str).collect(),
            Expect::LateralDistance { robot, .. }
            | Expect::ReachesZone { robot, .. }
            | Expect::SpeedRange { robot, .. } => vec![robot.as_str()],
            Expect::DoorStatus { .. } => Vec::new(),
        }
    }

    /// The `kind` tag.
    pub fn kind(&self) -> &'static str {
        match self {
            Expect::ClearanceEstimate { .. } => "clearance-estimate",
            Expect::DoorStatus { .. } => "door-status",
            Expect::RoleBelowDistance { .. } => "role-below-distance",
            Expect::SpeedWhileRole { .. } => "speed-while-role",
            Expect::NoContact { .. } => "no-contact",
            Expect::LateralDistance { .. } => "lateral-distance",
            Expect::ReachesZone { .. } => "reaches-zone",
            Expect::SpeedRange { .. } => "speed-range",
        }
    }

    /// Checks names against the floor; the error says what is missing.
    pub fn check(&self, floor: &Floor) -> Result<(), ExpectError> {
        let on = || floor.name.clone();
        match self {
            Expect::ClearanceEstimate { door, .. } | Expect::DoorStatus { door, .. } => {
                door_index(floor, door)
                    .map(|_| ())
                    .ok_or_else(|| ExpectError::NoDoor {
                        door: door.clone(),
                        floor: on(),
                    })
            }
            Expect::ReachesZone { zone, .. } => {
                floor
                    .zone(zone)
                    .map(|_| ())
                    .ok_or_else(|| ExpectError::NoZone {
                        zone: zone.clone(),
                        floor: on(),
                    })
            }
            Expect::RoleBelowDistance { robots, .. } if robots.len() != 2 => {
                Err(ExpectError::NotTwoRobots)
            }
            Expect::LateralDistance { ray_deg, .. } if !RAY_DEG.contains(ray_deg) => {
                Err(ExpectError::NoSuchRay(*ray_deg))
            }
            _ => Ok(()),
        }
    }
}

/// An expectation that names what the floor does not have, or is malformed.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ExpectError {
    /// No door by that name or GlobalId.
    #[error("no door `{door}` on floor `{floor}`")]
    NoDoor {
        /// The door asked for.
        door: String,
        /// The floor's name.
        floor: String,
    },
    /// No zone by that name or GlobalId.
    #[error("no zone `{zone}` on floor `{floor}`")]
    NoZone {
        /// The zone asked for.
        zone: String,
        /// The floor's name.
        floor: String,
    },
    /// `role-below-distance` names other than two robots.
    #[error("role-below-distance needs exactly two robots")]
    NotTwoRobots,
    /// `lateral-distance` on a ray the sensor does not have (the ray asked for).
    #[error("ray_deg must be one of {RAY_DEG:?}")]
    NoSuchRay(f64),
}

/// One judged expectation.
#[derive(Debug, Clone, PartialEq)]
pub struct Judged {
    /// Kind.
    pub kind: &'static str,
    /// Line in the scenario file.
    pub line: usize,
    /// What was expected, in words.
    pub expected: String,
    /// What was measured (JSON).
    pub measured: Value,
    /// Held.
    pub pass: bool,
}

fn door_index(floor: &Floor, door: &str) -> Option<usize> {
    floor
        .doors
        .iter()
        .position(|d| d.id == door || d.name.as_deref() == Some(door))
}

fn round(v: f64) -> Value {
    if v.is_finite() {
        json!((v * 1e6).round() / 1e6 + 0.0)
    } else {
        Value::Null
    }
}

fn robot_index(names: &Names, name: &str) -> usize {
    names
        .robots
        .iter()
        .position(|r| r == name)
        .expect("robot names are checked when the scenario loads")
}

fn footprint(sizes: &[(f64, f64)], r: &StepRecord) -> Obb {
    let (hl, hw) = sizes[r.robot as usize];
    Obb::new(r.pos, r.heading, hl, hw)
}

/// One robot's figures for `speed-while-role`.
#[derive(Debug, Clone)]
struct SpeedWhile {
    robot: usize,
    lo: f64,
    hi: f64,
    samples: usize,
    onset: Option<f64>,
    steps: usize,
}

/// What an expectation accumulates while the run goes (nothing that grows with its length).
#[derive(Debug, Clone)]
enum State {
    /// Judged from the events at the end.
    Events,
    RoleBelow {
        a: usize,
        b: usize,
        below: usize,
        missing: usize,
        min_d: f64,
        first_below: Option<f64>,
        first_role: Option<f64>,
    },
    SpeedWhile(Vec<SpeedWhile>),
    NoContact {
        idx: Vec<usize>,
        names: Vec<String>,
        min_gap: f64,
        points: Vec<DVec2>,
        grid: PointGrid,
    },
    Lateral {
        robot: usize,
        ray: usize,
        odo: f64,
        prev: Option<DVec2>,
        n: usize,
        lo: f64,
        hi: f64,
        sum: f64,
        sq: f64,
        skipped: usize,
    },
    SpeedRange {
        robot: usize,
        max: f64,
    },
}

/// An expectation measured step by step as the run goes ([`Judge::observe`]) and judged at
/// the end ([`Judge::finish`]): the run's records need not be kept.
#[derive(Debug, Clone)]
pub struct Judge {
    expect: Expect,
    line: usize,
    state: State,
}

impl Judge {
    /// Starts measuring `e` (declared at `line`) for robots named by `names`.
    pub fn new(e: &Expect, line: usize, names: &Names) -> Judge {
        let state = match e {
            Expect::ClearanceEstimate { .. }
            | Expect::DoorStatus { .. }
            | Expect::ReachesZone { .. } => State::Events,
            Expect::RoleBelowDistance { robots, .. } => State::RoleBelow {
                a: robot_index(names, &robots[0]),
                b: robot_index(names, &robots[1]),
                below: 0,
                missing: 0,
                min_d: f64::INFINITY,
                first_below: None,
                first_role: None,
            },
            Expect::SpeedWhileRole { robots, .. } => State::SpeedWhile(
                robots
                    .iter()
                    .map(|name| SpeedWhile {
                        robot: robot_index(names, name),
                        lo: f64::INFINITY,
                        hi: f64::NEG_INFINITY,
                        samples: 0,
                        onset: None,
                        steps: 0,
                    })
                    .collect(),
            ),
            Expect::NoContact { robots, .. } => {
                let idx: Vec<usize> = if robots.is_empty() {
                    (0..names.robots.len()).collect()
                } else {
                    robots.iter().map(|r| robot_index(names, r)).collect()
                };
                State::NoContact {
                    names: idx.iter().map(|&i| names.robots[i].clone()).collect(),
                    idx,
                    min_gap: f64::INFINITY,
                    points: Vec::new(),
                    grid: PointGrid::default(),
                }
            }
            Expect::LateralDistance { robot, ray_deg, .. } => State::Lateral {
                robot: robot_index(names, robot),
                ray: RAY_DEG.iter().position(|d| d == ray_deg).expect("checked"),
                odo: 0.0,
                prev: None,
                n: 0,
                lo: f64::INFINITY,
                hi: f64::NEG_INFINITY,
                sum: 0.0,
                sq: 0.0,
                skipped: 0,
            },
            Expect::SpeedRange { robot, .. } => State::SpeedRange {
                robot: robot_index(names, robot),
                max: 0.0,
            },
        };
        Judge {
            expect: e.clone(),
            line,
            state,
        }
    }

    /// Adds one step: `step[i]` is robot `i`'s record. `sizes` are the robots' half length and
    /// half width; `db` the POI database (obstacle records, the only ones read here, never
    /// change during a run).
    pub fn observe(&mut self, step: &[StepRecord], dt: f64, sizes: &[(f64, f64)], db: &PoiDb) {
        match (&mut self.state, &self.expect) {
            (State::Events, _) => {}
            (
                State::RoleBelow {
                    a,
                    b,
                    below,
                    missing,
                    min_d,
                    first_below,
                    first_role,
                },
                Expect::RoleBelowDistance {
                    role, distance_m, ..
                },
            ) => {
                let (ra, rb) = (&step[*a], &step[*b]);
                let t = ra.step as f64 * dt;
                let d = ra.pos.distance(rb.pos);
                *min_d = min_d.min(d);
                let both = ra.roles.has(*role) && rb.roles.has(*role);
                if both && first_role.is_none() {
                    *first_role = Some(t);
                }
                if d < *distance_m {
                    *below += 1;
                    first_below.get_or_insert(t);
                    if !both {
                        *missing += 1;
                    }
                }
            }
            (State::SpeedWhile(per), Expect::SpeedWhileRole { role, settle_s, .. }) => {
                for s in per {
                    let r = &step[s.robot];
                    let t = r.step as f64 * dt;
                    if !r.roles.has(*role) {
                        s.onset = None;
                        continue;
                    }
                    s.steps += 1;
                    let since = *s.onset.get_or_insert(t);
                    if t - since + 1e-9 < *settle_s {
                        continue;
                    }
                    s.samples += 1;
                    s.lo = s.lo.min(r.speed);
                    s.hi = s.hi.max(r.speed);
                }
            }
            (
                State::NoContact {
                    idx,
                    min_gap,
                    points,
                    grid,
                    ..
                },
                _,
            ) => {
                if idx.len() < 2 {
                    return;
                }
                // Only pairs whose centres are closer than both radii plus the gap so far (at
                // most 10 m) can lower it: the grid visits just those. The minimum does not
                // depend on the order pairs are visited in.
                let boxes: Vec<Obb> = idx.iter().map(|&i| footprint(sizes, &step[i])).collect();
                let r_max = boxes.iter().map(Obb::radius).fold(0.0, f64::max);
                points.clear();
                points.extend(boxes.iter().map(|b| b.c));
                grid.rebuild(points, 2.0 * r_max + min_gap.min(10.0));
                grid.pairs(points, |x, y| {
                    let (pa, pb) = (&boxes[x], &boxes[y]);
                    if pa.c.distance(pb.c) > pa.radius() + pb.radius() + min_gap.min(10.0) {
                        return;
                    }
                    *min_gap = min_gap.min(polygon_gap(&pa.corners(), &pb.corners()));
                });
            }
            (
                State::Lateral {
                    robot,
                    ray,
                    odo,
                    prev,
                    n,
                    lo,
                    hi,
                    sum,
                    sq,
                    skipped,
                },
                Expect::LateralDistance {
                    distance_m,
                    after_m,
                    role,
                    mode,
                    ..
                },
            ) => {
                let r = &step[*robot];
                if let Some(p) = *prev {
                    *odo += r.pos.distance(p);
                }
                *prev = Some(r.pos);
                if *odo < *after_m || mode.as_deref().is_some_and(|m| m != r.mode.label()) {
                    return;
                }
                let hit = &r.rays[*ray];
                let on_reference = match hit.target {
                    Target::Obstacle(o) => {
                        hit.passages.is_empty()
                            && role.is_none_or(|role| {
                                db.roles(db.index(crate::poi_db::Element::Obstacle(
                                    poinav_nav::ObstacleIdx::new(o as usize),
                                )))
                                .has(role)
                            })
                    }
                    _ => false,
                };
                if !on_reference {
                    *skipped += 1;
                    return;
                }
                *n += 1;
                *lo = lo.min(hit.dist);
                *hi = hi.max(hit.dist);
                *sum += hit.dist;
                *sq += (hit.dist - distance_m) * (hit.dist - distance_m);
            }
            (State::SpeedRange { robot, max }, _) => {
                *max = max.max(step[*robot].speed);
            }
            _ => unreachable!("the state matches its expectation"),
        }
    }

    /// Judges the expectation on what was observed and the run's `events`.
    pub fn finish(self, events: &[Event], floor: &Floor) -> Judged {
        let (expected, measured, pass) = match (&self.expect, self.state) {
            (
                Expect::ClearanceEstimate {
                    door,
                    robot,
                    tolerance_m,
                },
                _,
            ) => {
                let d = door_index(floor, door).expect("checked");
                let real = floor.doors[d].clear_width_m;
                let last = events
                    .iter()
                    .rev()
                    .filter(|ev| robot.as_ref().is_none_or(|r| &ev.robot == r))
                    .filter_map(|ev| match &ev.kind {
                        EventKind::Clearance {
                            door: id,
                            estimate_m,
                            ..
                        } if *id == floor.doors[d].id => Some((ev.t, *estimate_m)),
                        _ => None,
                    })
                    .next();
                let pass = last.is_some_and(|(_, est)| (est - real).abs() <= *tolerance_m);
                (
                    format!("sensor clearance estimate of `{door}` within {tolerance_m} m of its clear width"),
                    json!({
                        "real_width_m": round(real),
                        "estimate_m": last.map(|l| round(l.1)),
                        "error_m": last.map(|l| round(l.1 - real)),
                        "t": last.map(|l| round(l.0)),
                    }),
                    pass,
                )
            }
            (
                Expect::DoorStatus {
                    door,
                    status,
                    roles_include,
                    roles_exclude,
                },
                _,
            ) => {
                let d = door_index(floor, door).expect("checked");
                let last = events
                    .iter()
                    .rev()
                    .filter_map(|ev| match &ev.kind {
                        EventKind::Clearance {
                            door: id,
                            status,
                            roles,
                            ..
                        } if *id == floor.doors[d].id => Some((*status, roles.clone())),
                        _ => None,
                    })
                    .next();
                let pass = last.as_ref().is_some_and(|(s, roles)| {
                    s == status
                        && roles_include.iter().all(|r| roles.contains(r))
                        && !roles_exclude.iter().any(|r| roles.contains(r))
                });
                (
                    format!(
                        "`{door}` {} after the sensor check, with {:?}, without {:?}",
                        status.label(),
                        roles_include.iter().map(|r| r.label()).collect::<Vec<_>>(),
                        roles_exclude.iter().map(|r| r.label()).collect::<Vec<_>>()
                    ),
                    json!({
                        "status": last.as_ref().map(|l| l.0.label()),
                        "method": last.as_ref().map(|_| "SENSOR_BASED"),
                        "roles": last.as_ref().map(|l| l.1.iter().map(|r| r.label()).collect::<Vec<_>>()),
                    }),
                    pass,
                )
            }
            (
                Expect::RoleBelowDistance {
                    role, distance_m, ..
                },
                State::RoleBelow {
                    below,
                    missing,
                    min_d,
                    first_below,
                    first_role,
                    ..
                },
            ) => (
                format!(
                    "both robots have {} whenever their distance is below {distance_m} m",
                    role.label()
                ),
                json!({
                    "steps_below": below,
                    "steps_without_role": missing,
                    "first_below_t": first_below.map(round),
                    "first_role_t": first_role.map(round),
                    "min_distance_m": round(min_d),
                }),
                below > 0 && missing == 0,
            ),
            (
                Expect::SpeedWhileRole {
                    robots,
                    role,
                    speed_m_s,
                    tolerance_m_s,
                    settle_s,
                },
                State::SpeedWhile(per),
            ) => {
                let mut out = Vec::new();
                let mut pass = true;
                for (name, s) in robots.iter().zip(per) {
                    let ok = s.samples > 0
                        && s.lo >= speed_m_s - tolerance_m_s
                        && s.hi <= speed_m_s + tolerance_m_s;
                    pass &= ok;
                    out.push(json!({
                        "robot": name,
                        "steps_with_role": s.steps,
                        "samples": s.samples,
                        "min_speed": round(s.lo),
                        "max_speed": round(s.hi),
                        "pass": ok,
                    }));
                }
                (
                    format!(
                        "speed {speed_m_s} +/- {tolerance_m_s} m/s while {} lasts (after {settle_s} s)",
                        role.label()
                    ),
                    Value::Array(out),
                    pass,
                )
            }
            (
                Expect::NoContact { walls, .. },
                State::NoContact {
                    idx,
                    names,
                    min_gap,
                    ..
                },
            ) => {
                let contacts = events
                    .iter()
                    .filter(|ev| names.contains(&ev.robot))
                    .filter(|ev| match &ev.kind {
                        EventKind::Contact { class, .. } => *walls || class == "Robot",
                        _ => false,
                    })
                    .count();
                (
                    format!(
                        "no contact between robots{}",
                        if *walls { " or with the building" } else { "" }
                    ),
                    json!({ "min_gap_m": round(min_gap), "contacts": contacts }),
                    contacts == 0 && (min_gap > 0.0 || idx.len() < 2),
                )
            }
            (
                Expect::LateralDistance {
                    ray_deg,
                    distance_m,
                    tolerance_m,
                    after_m,
                    ..
                },
                State::Lateral {
                    n,
                    lo,
                    hi,
                    sum,
                    sq,
                    skipped,
                    ..
                },
            ) => {
                let pass =
                    n > 0 && lo >= distance_m - tolerance_m && hi <= distance_m + tolerance_m;
                (
                    format!(
                        "{ray_deg} degree ray at {distance_m} +/- {tolerance_m} m after {after_m} m"
                    ),
                    json!({
                        "samples": n,
                        "skipped_no_reference": skipped,
                        "min_m": round(lo),
                        "max_m": round(hi),
                        "mean_m": if n > 0 { round(sum / n as f64) } else { Value::Null },
                        "rms_error_m": if n > 0 { round((sq / n as f64).sqrt()) } else { Value::Null },
                    }),
                    pass,
                )
            }
            (
                Expect::ReachesZone {
                    robot,
                    zone,
                    within_s,
                },
                _,
            ) => {
                let zr = floor.zone(zone).expect("checked");
                let t = events
                    .iter()
                    .find(|ev| {
                        &ev.robot == robot
                            && matches!(&ev.kind, EventKind::Arrived { zone: z, .. } if *z == zr.id)
                    })
                    .map(|ev| ev.t);
                (
                    format!(
                        "`{robot}` reaches `{zone}`{}",
                        within_s
                            .map(|s| format!(" within {s} s"))
                            .unwrap_or_default()
                    ),
                    json!({ "arrived_t": t.map(round) }),
                    t.is_some_and(|t| within_s.is_none_or(|w| t <= w)),
                )
            }
            (
                Expect::SpeedRange {
                    robot,
                    reaches_m_s,
                    at_most_m_s,
                },
                State::SpeedRange { max, .. },
            ) => (
                {
                    let mut parts = Vec::new();
                    if let Some(v) = reaches_m_s {
                        parts.push(format!("reaches {v} m/s"));
                    }
                    if let Some(v) = at_most_m_s {
                        parts.push(format!("never exceeds {v} m/s"));
                    }
                    format!("`{robot}` speed {}", parts.join(" and "))
                },
                json!({ "max_speed": round(max) }),
                reaches_m_s.is_none_or(|v| max >= v - 1e-6)
                    && at_most_m_s.is_none_or(|v| max <= v + 1e-9),
            ),
            _ => unreachable!("the state matches its expectation"),
        };
        Judged {
            kind: self.expect.kind(),
            line: self.line,
            expected,
            measured,
            pass,
        }
    }
}

/// Judges `e` on a finished run that kept its records ([`crate::SimOptions::record`]).
pub fn judge(e: &Expect, line: usize, data: &RunData, floor: &Floor) -> Judged {
    let mut j = Judge::new(e, line, &data.names);
    let n = data.names.robots.len().max(1);
    for step in data.records.chunks(n) {
        j.observe(step, data.dt, &data.sizes, &data.db);
    }
    j.finish(&data.events, floor)
}

#[cfg(test)]
#[path = "expect_tests.rs"]
mod tests;
