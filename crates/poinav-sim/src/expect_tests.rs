//! Unit tests of the expectations: each kind holds on hand-made records and events that show
//! it, fails where it must, and reports the measured numbers.

use super::*;
use crate::controller::{Command, Mode};
use crate::poi_db::{RoleSet, Start};
use crate::robot::Brush;
use crate::sensor::LEFT;
use crate::test_floor::{door_floor, rect, wall};
use crate::world::{Passages, RayHit};

const DT: f64 = 0.1;

fn names(robots: &[&str]) -> Names {
    Names {
        robots: robots.iter().map(|r| r.to_string()).collect(),
        ..Names::default()
    }
}

fn rec(step: u64, robot: u32, pos: DVec2, speed: f64) -> StepRecord {
    let miss = RayHit {
        dist: 5.0,
        target: Target::None,
        passages: Passages::default(),
    };
    StepRecord {
        step,
        robot,
        pos,
        heading: 0.0,
        speed,
        omega: 0.0,
        action: Command::default(),
        rays: [miss; 5],
        roles: RoleSet::default(),
        mode: Mode::Route,
        zone: None,
        brush: Brush::paper(),
    }
}

fn event(t: f64, robot: &str, kind: EventKind) -> Event {
    Event {
        step: (t / DT) as u64,
        t,
        robot: robot.into(),
        kind,
    }
}

fn clearance(t: f64, robot: &str, estimate_m: f64, status: AccessibilityStatus) -> Event {
    let roles = if status == AccessibilityStatus::Restricted {
        vec![Role::Transition, Role::Narrow]
    } else {
        vec![Role::Transition]
    };
    event(
        t,
        robot,
        EventKind::Clearance {
            door: "door".into(),
            name: Some("Door".into()),
            estimate_m,
            required_m: 0.9,
            status,
            roles,
        },
    )
}

/// Judges `e` on `steps` (one record per robot each) and `events` on the door floor (0.80 m).
fn run(e: &Expect, robots: &[&str], steps: &[Vec<StepRecord>], events: &[Event]) -> Judged {
    let mut floor = door_floor(0.8, 0.2);
    // Obstacle 3: a cabinet, A-1 only (no A-3 reference).
    floor
        .obstacles
        .push(wall("cabinet", rect(3.0, -3.0, 3.5, -2.5)));
    floor.obstacles[3].roles = vec![Role::Avoidance];
    e.check(&floor).unwrap();
    let db = PoiDb::new(&floor, Start::Keep, &poinav_roles::RobotProfile::paper());
    let sizes = vec![(0.4, 0.35); robots.len()];
    let mut j = Judge::new(e, 7, &names(robots));
    for s in steps {
        j.observe(s, DT, &sizes, &db);
    }
    j.finish(events, &floor)
}

#[test]
fn clearance_estimate_takes_the_last_estimate_of_the_robot() {
    let e = |tolerance_m, robot: Option<&str>| Expect::ClearanceEstimate {
        door: "Door".into(),
        robot: robot.map(Into::into),
        tolerance_m,
    };
    let status = AccessibilityStatus::Restricted;
    let events = [
        clearance(1.0, "A", 0.95, status),
        clearance(1.5, "A", 0.83, status),
        clearance(2.0, "B", 0.70, status),
    ];
    let j = run(&e(0.05, Some("A")), &["A", "B"], &[], &events);
    assert!(j.pass);
    assert_eq!((j.kind, j.line), ("clearance-estimate", 7));
    assert_eq!(j.measured["estimate_m"], 0.83);
    assert_eq!(j.measured["error_m"], 0.03);
    assert_eq!(j.measured["t"], 1.5);
    assert!(!run(&e(0.02, Some("A")), &["A", "B"], &[], &events).pass);
    // Any robot: B's 0.70 m is the last, 0.10 m off.
    let j = run(&e(0.05, None), &["A", "B"], &[], &events);
    assert!(!j.pass);
    assert_eq!(j.measured["error_m"], -0.1);
    // No estimate at all: fails.
    let j = run(&e(1.0, None), &["A"], &[], &[]);
    assert!(!j.pass);
    assert_eq!(j.measured["estimate_m"], Value::Null);
}

#[test]
fn door_status_is_the_last_sensor_check() {
    let e = |status, include: Vec<Role>, exclude: Vec<Role>| Expect::DoorStatus {
        door: "door".into(),
        status,
        roles_include: include,
        roles_exclude: exclude,
    };
    use AccessibilityStatus::*;
    let events = [
        clearance(1.0, "A", 0.95, FullAccess),
        clearance(2.0, "A", 0.78, Restricted),
    ];
    let j = run(
        &e(Restricted, vec![Role::Narrow], vec![]),
        &["A"],
        &[],
        &events,
    );
    assert!(j.pass);
    assert_eq!(j.measured["roles"], json!(["A-2", "B-2"]));
    assert!(!run(&e(FullAccess, vec![], vec![]), &["A"], &[], &events).pass);
    assert!(
        !run(
            &e(Restricted, vec![], vec![Role::Narrow]),
            &["A"],
            &[],
            &events
        )
        .pass
    );
    assert!(
        run(
            &e(FullAccess, vec![], vec![Role::Narrow]),
            &["A"],
            &[],
            &events[..1]
        )
        .pass
    );
    assert!(!run(&e(PendingValidation, vec![], vec![]), &["A"], &[], &[]).pass);
}

/// Two robots' records: B at `gaps[k]` metres from A (on +x), with C-2 per `roles[k]`.
fn pair_steps(gaps: &[f64], roles: &[(bool, bool)]) -> Vec<Vec<StepRecord>> {
    gaps.iter()
        .zip(roles)
        .enumerate()
        .map(|(k, (&d, &(ra, rb)))| {
            let mut a = rec(k as u64, 0, DVec2::ZERO, 1.0);
            let mut b = rec(k as u64, 1, DVec2::new(d, 0.0), 1.0);
            if ra {
                a.roles.insert(Role::RobotInteraction);
            }
            if rb {
                b.roles.insert(Role::RobotInteraction);
            }
            vec![a, b]
        })
        .collect()
}

#[test]
fn role_below_distance_needs_the_role_at_every_close_step() {
    let e = Expect::RoleBelowDistance {
        robots: vec!["A".into(), "B".into()],
        role: Role::RobotInteraction,
        distance_m: 2.0,
    };
    let ok = pair_steps(
        &[3.0, 1.9, 1.5, 2.5],
        &[(false, false), (true, true), (true, true), (false, true)],
    );
    let j = run(&e, &["A", "B"], &ok, &[]);
    assert!(j.pass);
    assert_eq!(j.measured["steps_below"], 2);
    assert_eq!(j.measured["first_below_t"], 0.1);
    assert_eq!(j.measured["min_distance_m"], 1.5);
    let missing = pair_steps(&[1.9, 1.5], &[(true, true), (true, false)]);
    let j = run(&e, &["A", "B"], &missing, &[]);
    assert!(!j.pass);
    assert_eq!(j.measured["steps_without_role"], 1);
    // Never closer: nothing shown, no pass.
    let far = pair_steps(&[2.5, 3.0], &[(false, false), (false, false)]);
    assert!(!run(&e, &["A", "B"], &far, &[]).pass);
}

#[test]
fn speed_while_role_skips_the_settling_time() {
    let e = |settle_s| Expect::SpeedWhileRole {
        robots: vec!["A".into()],
        role: Role::RobotInteraction,
        speed_m_s: 2.5,
        tolerance_m_s: 0.05,
        settle_s,
    };
    // Without the role at 5 m/s, then with it: 4.0 at the onset, then 2.52, 2.48.
    let steps: Vec<Vec<StepRecord>> = [(5.0, false), (4.0, true), (2.52, true), (2.48, true)]
        .iter()
        .enumerate()
        .map(|(k, &(v, role))| {
            let mut r = rec(k as u64, 0, DVec2::ZERO, v);
            if role {
                r.roles.insert(Role::RobotInteraction);
            }
            vec![r]
        })
        .collect();
    let j = run(&e(0.1), &["A"], &steps, &[]);
    assert!(j.pass, "{}", j.measured);
    assert_eq!(j.measured[0]["steps_with_role"], 3);
    assert_eq!(j.measured[0]["samples"], 2);
    assert_eq!(j.measured[0]["min_speed"], 2.48);
    assert_eq!(j.measured[0]["max_speed"], 2.52);
    let j = run(&e(0.0), &["A"], &steps, &[]);
    assert!(!j.pass);
    assert_eq!(j.measured[0]["max_speed"], 4.0);
    // Never with the role: no samples, no pass.
    assert!(!run(&e(0.0), &["A"], &steps[..1], &[]).pass);
}

#[test]
fn no_contact_measures_the_gap_and_counts_contacts() {
    let e = |walls| Expect::NoContact {
        robots: Vec::new(),
        walls,
    };
    // Boxes 0.8 m long on the x axis: centres 2.0 m apart leave 1.2 m, then 0.9 m leave 0.1 m.
    let steps = pair_steps(&[2.0, 0.9], &[(false, false), (false, false)]);
    let j = run(&e(true), &["A", "B"], &steps, &[]);
    assert!(j.pass);
    assert_eq!(j.measured["min_gap_m"], 0.1);
    assert_eq!(j.measured["contacts"], 0);
    // Overlapping: fails with no event at all.
    let touching = pair_steps(&[0.7], &[(false, false)]);
    let j = run(&e(false), &["A", "B"], &touching, &[]);
    assert!(!j.pass);
    assert_eq!(j.measured["min_gap_m"], 0.0);
    // A wall contact counts only with `walls`; a robot contact always.
    let wall_touch = |class: &str| {
        event(
            0.5,
            "A",
            EventKind::Contact {
                with: "x".into(),
                class: class.into(),
            },
        )
    };
    assert!(run(&e(false), &["A", "B"], &steps, &[wall_touch("IfcWall")]).pass);
    assert!(!run(&e(true), &["A", "B"], &steps, &[wall_touch("IfcWall")]).pass);
    assert!(!run(&e(false), &["A", "B"], &steps, &[wall_touch("Robot")]).pass);
}

#[test]
fn lateral_distance_counts_a3_hits_in_wall_follow_after_the_start() {
    let e = |tolerance_m| Expect::LateralDistance {
        robot: "A".into(),
        ray_deg: 90.0,
        distance_m: 0.5,
        tolerance_m,
        after_m: 1.0,
        role: Some(Role::PathGuidance),
        mode: Some("wall-follow".into()),
    };
    // 0.5 m a step along x; the left ray hits obstacle `o` at `d`.
    let hit = |k: u64, o: u32, d: f64, mode: Mode| {
        let mut r = rec(k, 0, DVec2::new(0.5 * k as f64, 0.0), 5.0);
        r.mode = mode;
        r.rays[LEFT] = RayHit {
            dist: d,
            target: Target::Obstacle(o),
            passages: Passages::default(),
        };
        vec![r]
    };
    let wf = Mode::WallFollow;
    let steps = [
        hit(0, 0, 0.9, wf),          // before 1 m: ignored
        hit(1, 0, 0.8, wf),          // 0.5 m: ignored
        hit(2, 0, 0.53, wf),         // 1.0 m
        hit(3, 3, 0.2, wf),          // the cabinet, no A-3: skipped
        hit(4, 0, 0.9, Mode::Route), // not wall following: not counted
        hit(5, 1, 0.48, wf),
    ];
    let j = run(&e(0.05), &["A"], &steps, &[]);
    assert!(j.pass, "{}", j.measured);
    assert_eq!(j.measured["samples"], 2);
    assert_eq!(j.measured["skipped_no_reference"], 1);
    assert_eq!(j.measured["min_m"], 0.48);
    assert_eq!(j.measured["max_m"], 0.53);
    assert_eq!(j.measured["mean_m"], 0.505);
    assert!(!run(&e(0.025), &["A"], &steps, &[]).pass);
    // No reference after the start: fails.
    assert!(!run(&e(1.0), &["A"], &steps[..2], &[]).pass);
}

#[test]
fn reaches_zone_within_its_deadline() {
    let e = |within_s| Expect::ReachesZone {
        robot: "A".into(),
        zone: "hall".into(),
        within_s,
    };
    let arrived = |robot: &str| {
        event(
            4.0,
            robot,
            EventKind::Arrived {
                zone: "hall".into(),
                name: Some("hall".into()),
            },
        )
    };
    let j = run(&e(None), &["A", "B"], &[], &[arrived("A")]);
    assert!(j.pass);
    assert_eq!(j.measured["arrived_t"], 4.0);
    assert!(run(&e(Some(4.0)), &["A"], &[], &[arrived("A")]).pass);
    assert!(!run(&e(Some(3.9)), &["A"], &[], &[arrived("A")]).pass);
    assert!(!run(&e(None), &["A", "B"], &[], &[arrived("B")]).pass);
}

#[test]
fn speed_range_bounds_the_top_speed() {
    let e = |reaches_m_s, at_most_m_s| Expect::SpeedRange {
        robot: "A".into(),
        reaches_m_s,
        at_most_m_s,
    };
    let steps: Vec<Vec<StepRecord>> = [1.0, 4.2, 3.0]
        .iter()
        .enumerate()
        .map(|(k, &v)| vec![rec(k as u64, 0, DVec2::ZERO, v)])
        .collect();
    let j = run(&e(Some(4.2), Some(4.2)), &["A"], &steps, &[]);
    assert!(j.pass);
    assert_eq!(j.measured["max_speed"], 4.2);
    assert!(!run(&e(Some(4.5), None), &["A"], &steps, &[]).pass);
    assert!(!run(&e(None, Some(4.0)), &["A"], &steps, &[]).pass);
}

#[test]
fn check_names_what_is_missing() {
    let floor = door_floor(0.8, 0.2);
    let door = Expect::ClearanceEstimate {
        door: "Gate".into(),
        robot: None,
        tolerance_m: 0.05,
    };
    assert_eq!(
        door.check(&floor).map_err(|e| e.to_string()),
        Err("no door `Gate` on floor `test`".into())
    );
    let zone = Expect::ReachesZone {
        robot: "A".into(),
        zone: "Attic".into(),
        within_s: None,
    };
    assert_eq!(
        zone.check(&floor).map_err(|e| e.to_string()),
        Err("no zone `Attic` on floor `test`".into())
    );
    let one = Expect::RoleBelowDistance {
        robots: vec!["A".into()],
        role: Role::RobotInteraction,
        distance_m: 1.0,
    };
    assert!(one
        .check(&floor)
        .unwrap_err()
        .to_string()
        .contains("exactly two robots"));
    let ray = Expect::LateralDistance {
        robot: "A".into(),
        ray_deg: 45.0,
        distance_m: 0.5,
        tolerance_m: 0.05,
        after_m: 0.0,
        role: None,
        mode: None,
    };
    assert!(ray
        .check(&floor)
        .unwrap_err()
        .to_string()
        .starts_with("ray_deg must be one of"));
}
