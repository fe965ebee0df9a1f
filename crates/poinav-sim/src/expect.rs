//! Expectations: what a scenario must show, each measured from the trace records and events (not
//! from the simulator's internals) and judged pass or fail with the measured values.

use poinav_nav::Floor;
use poinav_poi::{AccessibilityStatus, Role};
use serde::Deserialize;
use serde_json::{json, Value};

use crate::events::EventKind;
use crate::geometry::{polygon_gap, Obb};
use crate::sensor::RAY_DEG;
use crate::step::RunData;
use crate::trace::StepRecord;
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

    /// Checks names against the floor; the message says what is missing.
    pub fn check(&self, floor: &Floor) -> Result<(), String> {
        match self {
            Expect::ClearanceEstimate { door, .. } | Expect::DoorStatus { door, .. } => {
                door_index(floor, door)
                    .map(|_| ())
                    .ok_or_else(|| format!("no door `{door}` on floor `{}`", floor.name))
            }
            Expect::ReachesZone { zone, .. } => floor
                .zone(zone)
                .map(|_| ())
                .ok_or_else(|| format!("no zone `{zone}` on floor `{}`", floor.name)),
            Expect::RoleBelowDistance { robots, .. } if robots.len() != 2 => {
                Err("role-below-distance needs exactly two robots".into())
            }
            Expect::LateralDistance { ray_deg, .. } if !RAY_DEG.contains(ray_deg) => {
                Err(format!("ray_deg must be one of {RAY_DEG:?}"))
            }
            _ => Ok(()),
        }
    }
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

fn robot_index(data: &RunData, name: &str) -> usize {
    data.names
        .robots
        .iter()
        .position(|r| r == name)
        .expect("robot names are checked when the scenario loads")
}

fn of_robot(data: &RunData, i: usize) -> impl Iterator<Item = &StepRecord> {
    data.records.iter().filter(move |r| r.robot as usize == i)
}

fn footprint(data: &RunData, r: &StepRecord) -> Obb {
    let (hl, hw) = data.sizes[r.robot as usize];
    Obb::new(r.pos, r.heading, hl, hw)
}

/// Judges `e` on a finished run.
pub fn judge(e: &Expect, line: usize, data: &RunData, floor: &Floor) -> Judged {
    let (expected, measured, pass) = match e {
        Expect::ClearanceEstimate {
            door,
            robot,
            tolerance_m,
        } => {
            let d = door_index(floor, door).expect("checked");
            let real = floor.doors[d].clear_width_m;
            let last = data
                .events
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
        Expect::DoorStatus {
            door,
            status,
            roles_include,
            roles_exclude,
        } => {
            let d = door_index(floor, door).expect("checked");
            let last = data
                .events
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
        Expect::RoleBelowDistance {
            robots,
            role,
            distance_m,
        } => {
            let (a, b) = (robot_index(data, &robots[0]), robot_index(data, &robots[1]));
            let n = data.names.robots.len();
            let (mut below, mut missing, mut min_d) = (0usize, 0usize, f64::INFINITY);
            let (mut first_below, mut first_role): (Option<f64>, Option<f64>) = (None, None);
            for step in data.records.chunks(n) {
                let (ra, rb) = (&step[a], &step[b]);
                let t = ra.step as f64 * data.dt;
                let d = ra.pos.distance(rb.pos);
                min_d = min_d.min(d);
                let both = ra.roles.has(*role) && rb.roles.has(*role);
                if both && first_role.is_none() {
                    first_role = Some(t);
                }
                if d < *distance_m {
                    below += 1;
                    first_below.get_or_insert(t);
                    if !both {
                        missing += 1;
                    }
                }
            }
            (
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
            )
        }
        Expect::SpeedWhileRole {
            robots,
            role,
            speed_m_s,
            tolerance_m_s,
            settle_s,
        } => {
            let mut per = Vec::new();
            let mut pass = true;
            for name in robots {
                let i = robot_index(data, name);
                let (mut lo, mut hi, mut samples, mut onset, mut steps) = (
                    f64::INFINITY,
                    f64::NEG_INFINITY,
                    0usize,
                    None::<f64>,
                    0usize,
                );
                for r in of_robot(data, i) {
                    let t = r.step as f64 * data.dt;
                    if !r.roles.has(*role) {
                        onset = None;
                        continue;
                    }
                    steps += 1;
                    let since = *onset.get_or_insert(t);
                    if t - since + 1e-9 < *settle_s {
                        continue;
                    }
                    samples += 1;
                    lo = lo.min(r.speed);
                    hi = hi.max(r.speed);
                }
                let ok = samples > 0
                    && lo >= speed_m_s - tolerance_m_s
                    && hi <= speed_m_s + tolerance_m_s;
                pass &= ok;
                per.push(json!({
                    "robot": name,
                    "steps_with_role": steps,
                    "samples": samples,
                    "min_speed": round(lo),
                    "max_speed": round(hi),
                    "pass": ok,
                }));
            }
            (
                format!(
                    "speed {speed_m_s} +/- {tolerance_m_s} m/s while {} lasts (after {settle_s} s)",
                    role.label()
                ),
                Value::Array(per),
                pass,
            )
        }
        Expect::NoContact { robots, walls } => {
            let idx: Vec<usize> = if robots.is_empty() {
                (0..data.names.robots.len()).collect()
            } else {
                robots.iter().map(|r| robot_index(data, r)).collect()
            };
            let n = data.names.robots.len();
            let mut min_gap = f64::INFINITY;
            for step in data.records.chunks(n) {
                for (x, &a) in idx.iter().enumerate() {
                    for &b in &idx[x + 1..] {
                        let (pa, pb) = (footprint(data, &step[a]), footprint(data, &step[b]));
                        if pa.c.distance(pb.c) > pa.radius() + pb.radius() + min_gap.min(10.0) {
                            continue;
                        }
                        min_gap = min_gap.min(polygon_gap(&pa.corners(), &pb.corners()));
                    }
                }
            }
            let names: Vec<&str> = idx.iter().map(|&i| data.names.robots[i].as_str()).collect();
            let contacts = data
                .events
                .iter()
                .filter(|ev| names.contains(&ev.robot.as_str()))
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
        Expect::LateralDistance {
            robot,
            ray_deg,
            distance_m,
            tolerance_m,
            after_m,
            role,
            mode,
        } => {
            let i = robot_index(data, robot);
            let k = RAY_DEG.iter().position(|d| d == ray_deg).expect("checked");
            let (mut odo, mut prev) = (0.0, None);
            let (mut n, mut lo, mut hi, mut sum, mut sq, mut skipped) =
                (0usize, f64::INFINITY, f64::NEG_INFINITY, 0.0, 0.0, 0usize);
            for r in of_robot(data, i) {
                if let Some(p) = prev {
                    odo += r.pos.distance(p);
                }
                prev = Some(r.pos);
                if odo < *after_m || mode.as_deref().is_some_and(|m| m != r.mode.label()) {
                    continue;
                }
                let ray = &r.rays[k];
                let on_reference = match ray.target {
                    Target::Obstacle(o) => {
                        ray.passages.is_empty()
                            && role.is_none_or(|role| {
                                data.db
                                    .roles(data.db.index(crate::poi_db::Element::Obstacle(o)))
                                    .has(role)
                            })
                    }
                    _ => false,
                };
                if !on_reference {
                    skipped += 1;
                    continue;
                }
                n += 1;
                lo = lo.min(ray.dist);
                hi = hi.max(ray.dist);
                sum += ray.dist;
                sq += (ray.dist - distance_m) * (ray.dist - distance_m);
            }
            let pass = n > 0 && lo >= distance_m - tolerance_m && hi <= distance_m + tolerance_m;
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
        Expect::ReachesZone {
            robot,
            zone,
            within_s,
        } => {
            let zr = floor.zone(zone).expect("checked");
            let t = data
                .events
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
        Expect::SpeedRange {
            robot,
            reaches_m_s,
            at_most_m_s,
        } => {
            let i = robot_index(data, robot);
            let max = of_robot(data, i).map(|r| r.speed).fold(0.0, f64::max);
            (
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
            )
        }
    };
    Judged {
        kind: e.kind(),
        line,
        expected,
        measured,
        pass,
    }
}
