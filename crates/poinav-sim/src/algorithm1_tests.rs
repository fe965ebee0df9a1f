//! Unit tests of Algorithm 1's decisions, one per branch, on tiny hand-built floors: A-1
//! clearance keeping, the A-2 door clearance estimate and rule R5, C-1/C-2 separation with each
//! protocol and at a single-lane door, the A-3 wall references, and the final command.

use super::*;
use crate::geometry::Obb;
use crate::robot::{Brush, Limits, RobotState};
use crate::test_floor::{door_floor, open_floor, rect, robot, wall, View};
use poinav_roles::{AccessibilityStatus, RobotProfile};
use std::f64::consts::FRAC_PI_2;

/// The paper robot brakes at 0.8 x 20 m/s² in Algorithm 1's stopping distances.
const BRAKE: f64 = 16.0;

fn close(a: f64, b: f64) -> bool {
    (a - b).abs() < 1e-9
}

/// An open floor with one more wall.
fn open_with(id: &str, ring: poinav_nav::Ring) -> Floor {
    let mut f = open_floor(None);
    f.obstacles.push(wall(id, ring));
    f
}

#[test]
fn a1_caps_the_speed_to_stop_a_margin_before_a_wall_ahead() {
    // Wall face at x = 3; the paper robot's half length 0.4, margin 0.1.
    let floor = open_with("ahead", rect(3.0, -2.0, 3.2, 2.0));
    let mut v = View::new(&floor, vec![robot("R", DVec2::ZERO, 0.0, 0)]);
    for (x, cap) in [
        (-3.0, 5.0), // 6 m away: the top speed
        (2.0, 4.0),  // 1 m: 0.5 m to stop in at 16 m/s²
        (2.45, (2.0 * BRAKE * 0.05f64).sqrt()),
        (2.55, 0.0), // inside the margin: stop
    ] {
        v.place(0, DVec2::new(x, 0.0), 0.0);
        let (p, _) = v.perceive(0, &mut Mind::new());
        assert!(
            close(p.speed_cap, cap),
            "x {x}: cap {} != {cap}",
            p.speed_cap
        );
        assert_eq!(p.turn_bias, 0.0);
        assert_eq!(p.roles.has(Role::Avoidance), x > -1.0);
    }
}

#[test]
fn a1_steers_away_from_a_side_closer_than_the_margin() {
    // A side 0.40 m from the centre: 0.05 m of the 0.35 m half width's margin of 0.10 m left.
    for (y0, y1, bias) in [(0.4, 0.6, -0.2), (-0.6, -0.4, 0.2), (0.5, 0.7, 0.0)] {
        let floor = open_with("side", rect(-5.0, y0, 5.0, y1));
        let mut v = View::new(&floor, vec![robot("R", DVec2::ZERO, 0.0, 0)]);
        let (p, _) = v.perceive(0, &mut Mind::new());
        assert!(
            close(p.turn_bias, bias),
            "{y0}: bias {} != {bias}",
            p.turn_bias
        );
    }
}

#[test]
fn a3_references_are_the_side_rays_on_path_guidance_walls_only() {
    let mut floor = open_floor(None);
    floor
        .obstacles
        .push(wall("left", rect(-5.0, 1.2, 5.0, 1.4)));
    floor
        .obstacles
        .push(wall("right", rect(-5.0, -1.0, 5.0, -0.8)));
    let mut v = View::new(&floor, vec![robot("R", DVec2::ZERO, 0.0, 0)]);
    let (p, _) = v.perceive(0, &mut Mind::new());
    assert!(close(p.left_ref.unwrap(), 1.2), "{:?}", p.left_ref);
    assert!(close(p.right_ref.unwrap(), 0.8), "{:?}", p.right_ref);
    assert_eq!(p.turn_bias, 0.0);
    assert!(p.roles.has(Role::PathGuidance));
    // Without A-3 the wall is no reference (but still A-1).
    floor.obstacles[0].roles = vec![Role::Avoidance];
    let mut v = View::new(&floor, vec![robot("R", DVec2::ZERO, 0.0, 0)]);
    let (p, _) = v.perceive(0, &mut Mind::new());
    assert_eq!(p.left_ref, None);
    assert!(close(p.right_ref.unwrap(), 0.8));
}

/// Drives robot "R" head-on from (0, -3.5) towards the door of [`door_floor`] at the top
/// speed's step (5 m/s at 60 Hz), perceiving each step and applying each measurement (R5);
/// returns (y, estimate, status after it) per reported estimate and the door's status before.
fn approach(w: f64, step: f64) -> (Vec<(f64, f64, AccessibilityStatus)>, AccessibilityStatus) {
    let floor = door_floor(w, 0.2);
    let mut v = View::new(
        &floor,
        vec![robot("R", DVec2::new(0.0, -3.5), FRAC_PI_2, 0)],
    );
    let status = |v: &View<'_>| {
        let rec = v.db.index(Element::Door(DoorIdx::new(0)));
        v.db.get(rec).accessibility.as_ref().unwrap().status
    };
    let before = status(&v);
    let mut mind = Mind::new();
    let mut out = Vec::new();
    let mut y = -3.5;
    while y < -0.5 {
        v.place(0, DVec2::new(0.0, y), FRAC_PI_2);
        let (_, pending) = v.perceive(0, &mut mind);
        if let Some(pc) = pending {
            v.apply(0, &pc);
            out.push((y, pc.estimate_m, status(&v)));
        }
        y += step;
    }
    (out, before)
}

#[test]
fn a2_reports_only_measured_jambs_and_r5_decides_the_status() {
    for (w, want) in [
        (0.8, AccessibilityStatus::Restricted),
        (1.0, AccessibilityStatus::FullAccess),
    ] {
        let (reports, before) = approach(w, 5.0 / 60.0);
        assert_eq!(before, AccessibilityStatus::PendingValidation);
        assert!(!reports.is_empty(), "{w} m: no estimate");
        // Far from the door the angled rays bound the jambs loosely: no guess is reported.
        let first = reports[0].0;
        assert!(first > -3.0, "{w} m: first estimate at y {first}");
        for &(y, est, status) in &reports {
            assert!((est - w).abs() <= 0.05, "{w} m door read {est} at y {y}");
            assert_eq!(status, want, "{w} m door, estimate {est}");
        }
    }
}

#[test]
fn a2_a_loose_bracket_is_no_estimate() {
    // Readings 0.3 m apart: the angled rays' face points jump 17 cm, so a jamb is bracketed
    // only loosely (the 0.80 m door would read 0.689 m): nothing is reported, the door stays
    // PENDING. The 1.00 m door's reveal is hit 0.8 m before it: the jamb itself, exact.
    let (reports, before) = approach(0.8, 0.3);
    assert_eq!(reports, []);
    assert_eq!(before, AccessibilityStatus::PendingValidation);
    let (reports, _) = approach(1.0, 0.3);
    assert_eq!(reports.len(), 1, "{reports:?}");
    let (y, est, status) = reports[0];
    assert!(close(y, -0.8) && close(est, 1.0), "{reports:?}");
    assert_eq!(status, AccessibilityStatus::FullAccess);
}

#[test]
fn a2_estimator_has_no_estimate_before_evidence() {
    let ring = rect(-0.4, 0.0, 0.4, 0.2);
    let e = Estimator::start(DoorIdx::new(0), DVec2::new(0.0, 0.1), DVec2::Y, &ring);
    assert_eq!(e.estimate(), None);
    // The face is the opening's near side until a ray hits it.
    assert!(close(e.face(), -0.1));
}

#[test]
fn a2_a_door_narrower_than_the_robot_is_never_driven_into() {
    // 0.60 m < the 0.70 m robot: stop a margin before the near side (y = 0). The 0.80 m door
    // is passed at the A-2 speed (3 m/s at the door), at 0.5 m capped by A-1 on its jamb (the
    // 30 degree rays look into the opening and hit the reveal 0.8 m away).
    let narrow = door_floor(0.6, 0.2);
    let wide = door_floor(0.8, 0.2);
    let jamb = (2.0 * BRAKE * (0.8 * 30f64.to_radians().cos() - 0.5)).sqrt();
    for (y, cap_narrow, cap_wide) in [(-1.0, 4.0, 5.0), (-0.5, 0.0, jamb)] {
        for (floor, cap) in [(&narrow, cap_narrow), (&wide, cap_wide)] {
            let mut v = View::new(floor, vec![robot("R", DVec2::new(0.0, y), FRAC_PI_2, 0)]);
            let (p, _) = v.perceive(0, &mut Mind::new());
            let w = floor.doors[0].clear_width_m;
            assert!(
                close(p.speed_cap, cap),
                "{w} m at y {y}: {} != {cap}",
                p.speed_cap
            );
            assert!(p.roles.has(Role::Transition));
        }
    }
}

#[test]
fn b1_hazard_zone_and_b2_narrow_door_cap_the_speed() {
    // A B-1 zone: half the top speed.
    let mut floor = open_floor(None);
    floor.zones[0].roles.push(Role::Hazard);
    let mut v = View::new(&floor, vec![robot("R", DVec2::ZERO, 0.0, 0)]);
    let (p, _) = v.perceive(0, &mut Mind::new());
    assert!(close(p.speed_cap, 2.5), "{}", p.speed_cap);
    assert!(p.roles.has(Role::Hazard));
    // A door 0.7 m ahead: 0.6 x 5 m/s at the door (plus braking room), 0.3 x 5 m/s with B-2.
    for (roles, at_door) in [
        (vec![Role::Transition], 3.0),
        (vec![Role::Transition, Role::Narrow], 1.5),
    ] {
        let mut floor = door_floor(1.0, 0.2);
        floor.doors[0].roles = roles;
        let mut v = View::new(
            &floor,
            vec![robot("R", DVec2::new(0.0, -0.6), FRAC_PI_2, 0)],
        );
        let (p, _) = v.perceive(0, &mut Mind::new());
        // Centre 0.7 m ahead, less the half length: 0.3 m to brake in (4.31 and 3.44 m/s).
        let cap = (at_door * at_door + 2.0 * BRAKE * 0.3f64).sqrt();
        assert!(close(p.speed_cap, cap), "{} != {cap}", p.speed_cap);
    }
}

#[test]
fn c1_a_zone_carries_c2_while_a_robot_in_it_has_it() {
    let floor = open_floor(Some((2.0, CoordinationProtocol::Yield)));
    let mut v = View::new(
        &floor,
        vec![
            robot("A", DVec2::ZERO, 0.0, 1),
            robot("B", DVec2::new(0.0, 1.0), 0.0, 0),
        ],
    );
    let rec = v.db.index(Element::Zone(ZoneIdx::new(0)));
    assert!(!v.db.roles(rec).has(Role::RobotInteraction));
    let mut minds = vec![Mind::new(), Mind::new()];
    for m in &mut minds {
        m.zone = Some(ZoneIdx::new(0));
        m.c2 = true;
    }
    let nearest = [Some((1, 1.0)), Some((0, 1.0))];
    let coordinate = |v: &mut View<'_>, minds: &[Mind]| {
        let env = Env {
            floor: v.floor,
            nav: &v.nav,
            robots: &v.robots,
            world: &v.world,
            behaviour: &v.behaviour,
            step: 0,
            t: 0.0,
            waiters: None,
        };
        let mut observations = Vec::new();
        let mut sink = Sink {
            events: &mut v.events,
            observations: &mut observations,
        };
        zone_coordination(&env, minds, &nearest, &mut v.db, &mut sink);
        observations
    };
    let obs = coordinate(&mut v, &minds);
    assert!(v.db.roles(rec).has(Role::RobotInteraction));
    assert_eq!(obs.len(), 1);
    assert_eq!(obs[0].1, Observation::RobotDistance { distance_m: 1.0 });
    assert!(matches!(
        &v.events[..],
        [Event {
            kind: EventKind::RoleAdded {
                role: Role::RobotInteraction,
                ..
            },
            ..
        }]
    ));
    // Again: nothing changes, nothing is reported.
    assert!(coordinate(&mut v, &minds).is_empty());
    // Neither has C-2 any more: the zone loses it.
    for m in &mut minds {
        m.c2 = false;
    }
    coordinate(&mut v, &minds);
    assert!(!v.db.roles(rec).has(Role::RobotInteraction));
    assert!(matches!(
        v.events.last().unwrap().kind,
        EventKind::RoleRemoved {
            role: Role::RobotInteraction,
            ..
        }
    ));
}

/// Robots "A" (priority 1) at the origin and "B" (priority 0) 1 m to its left, both heading +x,
/// in a C-1 zone with separation `sep` and `protocol`: each one's speed cap and stop.
fn pair(sep: f64, protocol: CoordinationProtocol) -> [(f64, bool, bool); 2] {
    let floor = open_floor(Some((sep, protocol)));
    let mut v = View::new(
        &floor,
        vec![
            robot("A", DVec2::ZERO, 0.0, 1),
            robot("B", DVec2::new(0.0, 1.0), 0.0, 0),
        ],
    );
    [0, 1].map(|i| {
        let mut mind = Mind::new();
        let (p, _) = v.perceive(i, &mut mind);
        assert_eq!(p.nearest.map(|n| n.0), Some(1 - i as u32));
        assert!(close(p.nearest.unwrap().1, 1.0));
        assert!(!p.keep_right);
        assert_eq!(mind.c2, p.roles.has(Role::RobotInteraction));
        (p.speed_cap, p.stop, mind.c2)
    })
}

#[test]
fn c2_separation_runs_each_protocol() {
    use CoordinationProtocol::*;
    // 1 m apart, separation 2 m: both take C-2; the reduced speed is half of 5 m/s.
    assert_eq!(
        pair(2.0, SpeedReduction),
        [(2.5, false, true), (2.5, false, true)]
    );
    assert_eq!(
        pair(2.0, PriorityPass),
        [(5.0, false, true), (2.5, false, true)]
    );
    assert_eq!(pair(2.0, Yield), [(2.5, false, true), (5.0, true, true)]);
    // Farther than the separation: no C-2, no protocol.
    for protocol in [SpeedReduction, PriorityPass, Yield] {
        assert_eq!(
            pair(0.9, protocol),
            [(5.0, false, false), (5.0, false, false)]
        );
    }
}

#[test]
fn c2_switch_is_reported_with_the_distance() {
    let floor = open_floor(Some((2.0, CoordinationProtocol::Yield)));
    let mut v = View::new(
        &floor,
        vec![
            robot("A", DVec2::ZERO, 0.0, 1),
            robot("B", DVec2::new(0.0, 1.0), 0.0, 0),
        ],
    );
    let mut mind = Mind::new();
    v.perceive(1, &mut mind);
    let on: Vec<_> = v
        .events
        .iter()
        .filter_map(|e| match &e.kind {
            EventKind::RobotRole {
                on,
                other,
                distance_m,
                ..
            } => Some((*on, other.clone(), *distance_m)),
            _ => None,
        })
        .collect();
    assert_eq!(on, [(true, Some("A".to_string()), 1.0)]);
    // Moved away (out of the sensor's reach): C-2 is dropped and reported.
    v.place(0, DVec2::new(0.0, -4.0), 0.0);
    v.place(1, DVec2::new(0.0, 4.5), 0.0);
    let (p, _) = v.perceive(1, &mut mind);
    assert!(!mind.c2 && !p.stop && p.nearest.is_none());
    assert!(matches!(
        v.events.last().unwrap().kind,
        EventKind::RobotRole { on: false, .. }
    ));
}

#[test]
fn c1_oncoming_robots_both_keep_right() {
    let floor = open_floor(Some((1.0, CoordinationProtocol::SpeedReduction)));
    let mut v = View::new(
        &floor,
        vec![
            robot("A", DVec2::ZERO, 0.0, 0),
            robot("B", DVec2::new(3.0, 0.0), std::f64::consts::PI, 0),
        ],
    );
    for i in 0..2 {
        let (p, _) = v.perceive(i, &mut Mind::new());
        assert!(p.keep_right, "robot {i}");
        assert!(!p.stop);
        // 3 m apart: no C-2 at separation 1 m; A-1 caps to stop 0.5 m before the other's box.
        assert!(!p.roles.has(Role::RobotInteraction));
        assert!(close(
            p.speed_cap,
            (2.0 * BRAKE * (3.0 - 0.4 - 0.5f64)).sqrt().min(5.0)
        ));
    }
}

/// Robots "A" at (0, ya) heading +y and "B" at (0, yb) heading -y on either side of the door
/// (centre (0, 0.1)) of a `w` m wide [`door_floor`]: the door each waits at and the caps.
fn at_door(w: f64, ya: f64, yb: f64) -> [(Option<u32>, f64); 2] {
    let floor = door_floor(w, 0.2);
    let mut v = View::new(
        &floor,
        vec![
            robot("A", DVec2::new(0.0, ya), FRAC_PI_2, 0),
            robot("B", DVec2::new(0.0, yb), -FRAC_PI_2, 0),
        ],
    );
    [0, 1].map(|i| {
        let mut mind = Mind::new();
        let (p, _) = v.perceive(i, &mut mind);
        assert_eq!(mind.c2, mind.door_wait.is_some());
        (mind.door_wait.map(|d| d.get() as u32), p.speed_cap)
    })
}

#[test]
fn c2_one_robot_at_a_time_through_a_single_lane_door() {
    // 0.90 m < two paper robots side by side (2 x 0.70 + 3 x 0.10 = 1.70 m): single lane.
    // A 1.6 m from the centre goes; B, 2.4 m away, waits and stops 1.8 m from the centre.
    let hold = (2.0 * BRAKE * (2.4 - DOOR_HOLD_M)).sqrt();
    let [a, b] = at_door(0.9, -1.5, 2.5);
    assert_eq!(a, (None, 5.0));
    assert_eq!(b.0, Some(0));
    assert!(close(b.1, hold), "{} != {hold}", b.1);
    // Swapped: the nearer one is B.
    let [a, b] = at_door(0.9, -2.3, 1.7);
    assert_eq!(a.0, Some(0));
    assert!(close(a.1, hold), "{} != {hold}", a.1);
    assert_eq!(b.0, None);
    // Already at the hold distance: stop.
    let [a, _] = at_door(0.9, -1.7, 1.0);
    assert_eq!(a, (Some(0), 0.0));
    // A door wide enough for both: nobody waits.
    let [a, b] = at_door(2.0, -1.5, 2.5);
    assert_eq!((a.0, b.0), (None, None));
}

#[test]
fn c2_a_robot_that_waited_waits_until_the_other_has_cleared_the_door() {
    // A waited at the 0.90 m door; B came through and leaves on A's side, heading away.
    let floor = door_floor(0.9, 0.2);
    for (b, waits) in [
        (DVec2::new(0.8, -0.5), true),
        (DVec2::new(0.9, -1.1), false),
    ] {
        let mut v = View::new(
            &floor,
            vec![
                robot("A", DVec2::new(0.0, -2.5), FRAC_PI_2, 0),
                robot("B", b, -FRAC_PI_2, 0),
            ],
        );
        let centre = floor.doors[0].center;
        // 1.0 m and 1.5 m from the centre: within and beyond DOOR_CLEAR_M (1.3 m).
        assert!(close(b.distance(centre), if waits { 1.0 } else { 1.5 }));
        let mut held = Mind::new();
        held.door_wait = Some(DoorIdx::new(0));
        v.perceive(0, &mut held);
        assert_eq!(held.door_wait, waits.then_some(DoorIdx::new(0)), "B at {b}");
        // A robot that had not waited does not start to.
        let mut fresh = Mind::new();
        v.perceive(0, &mut fresh);
        assert_eq!(fresh.door_wait, None);
    }
}

fn perception(cap: f64) -> Perception {
    Perception {
        roles: RoleSet::default(),
        speed_cap: cap,
        turn_bias: 0.0,
        left_ref: None,
        right_ref: None,
        nearest: None,
        keep_right: false,
        stop: false,
        squeeze: 0.0,
    }
}

#[test]
fn decide_caps_stops_and_bounds_the_turn() {
    let r = robot("R", DVec2::ZERO, 0.0, 0);
    let beh = Behaviour::default();
    let cmd = |v, omega| Command { v, omega };
    let mut mind = Mind::new();
    let mut d = |p: &Perception, c| decide(p, c, &r, &mut mind, 0.0, false, &beh);
    assert_eq!(d(&perception(1.5), cmd(4.0, 0.0)), cmd(1.5, 0.0));
    assert_eq!(d(&perception(1.5), cmd(1.0, 0.0)), cmd(1.0, 0.0));
    assert_eq!(d(&perception(1.5), cmd(-2.0, 0.0)), cmd(-1.5, 0.0));
    let mut p = perception(5.0);
    p.stop = true;
    assert_eq!(d(&p, cmd(3.0, 0.5)), cmd(0.0, 0.5));
    // The A-1 turn is added, and the sum kept within 100 degrees/s.
    let mut p = perception(5.0);
    p.turn_bias = -0.2;
    assert!(close(d(&p, cmd(1.0, 0.5)).omega, 0.3));
    let max_turn = 100f64.to_radians();
    assert!(close(d(&p, cmd(1.0, 9.0)).omega, max_turn));
    assert!(close(d(&p, cmd(1.0, -9.0)).omega, -max_turn));
}

#[test]
fn decide_keeps_right_with_a_wall_pd_unless_driven_by_keys() {
    let r = robot("R", DVec2::ZERO, 0.0, 0);
    let beh = Behaviour::default();
    let mut p = perception(5.0);
    p.keep_right = true;
    p.right_ref = Some(1.0);
    let cmd = Command { v: 1.0, omega: 0.0 };
    // Target 0.35 + 2 x 0.10 = 0.55 m; the wall 1 m away on the right: turn right.
    let mut mind = Mind::new();
    let c = decide(&p, cmd, &r, &mut mind, 0.0, false, &beh);
    assert!(c.omega < 0.0, "{}", c.omega);
    assert!(mind.keep.is_some());
    let mut pd = WallPd::new(Side::Right, 0.55);
    let max_turn = 100f64.to_radians();
    let want = pd
        .omega(Some(1.0), 0.0, 0.0, 0.5)
        .clamp(-max_turn, max_turn);
    assert_eq!(c.omega, want);
    // Driven by keys: the command stands.
    let mut mind = Mind::new();
    assert_eq!(decide(&p, cmd, &r, &mut mind, 0.0, true, &beh), cmd);
    assert!(mind.keep.is_none());
}

/// Crowds around every door of the test building (robots of two sizes, any heading, some
/// overlapping, some waiting already): the grid lookup decides as testing every robot.
#[test]
fn door_waits_through_the_grid_equal_those_testing_every_robot() {
    let floor = crate::test_floor::doors_floor();
    assert!(floor.doors.len() >= 6, "{} doors", floor.doors.len());
    let nav = Plan::new(&floor);
    let mut seed = 0x2545_F491_4F6C_DD1Du64;
    let mut rnd = || {
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        (seed >> 11) as f64 / (1u64 << 53) as f64
    };
    let paper = RobotProfile::paper();
    let mut small = RobotProfile::paper();
    small.width_m = 0.3;
    small.length_m = 0.4;
    let behaviour = Behaviour::default();
    let (mut waits, mut held_waits) = (0, 0);
    // Sparse crowds (two robots per door) so that robots near the conflict distance decide.
    for _ in 0..100 {
        let mut robots = Vec::new();
        for k in 0..2 * floor.doors.len() {
            let door = &floor.doors[k % floor.doors.len()];
            let profile = if k % 3 == 0 { &small } else { &paper };
            let at = door.center + DVec2::from_angle(rnd() * std::f64::consts::TAU) * (rnd() * 3.5);
            robots.push(Robot {
                name: format!("R{k}"),
                global_id: format!("id{k}"),
                profile: profile.clone(),
                limits: Limits::new(profile, 50.0, 100.0),
                priority: (k % 2) as i64,
                giving_way: None,
                waits_for: None,
                arrived: false,
                state: RobotState {
                    pos: at,
                    heading: rnd() * std::f64::consts::TAU - std::f64::consts::PI,
                    speed: 0.0,
                    actual_speed: 0.0,
                    omega: 0.0,
                    odometer: 0.0,
                    brush: Brush::paper(),
                },
            });
        }
        let mut world = World::new(&floor, 1.0, 0.2);
        let boxes: Vec<Obb> = robots.iter().map(Robot::footprint).collect();
        world.set_robots(&boxes);
        let env = Env {
            floor: &floor,
            nav: &nav,
            robots: &robots,
            world: &world,
            behaviour: &behaviour,
            step: 0,
            t: 0.0,
            waiters: None,
        };
        for me in 0..robots.len() {
            let held = (me % 4 == 0).then_some(DoorIdx::new(me / 4 % floor.doors.len()));
            let fast = door_wait(me, &env, held);
            assert_eq!(fast, door_wait_every_robot(me, &env, held), "robot {me}");
            waits += usize::from(fast.is_some());
            held_waits += usize::from(held.is_some() && fast.map(|f| f.0) == held);
        }
    }
    // Not trivial: many robots wait, some at the door they held.
    assert!(waits > 80, "{waits} robots wait");
    assert!(held_waits > 10, "{held_waits} keep waiting where they held");
}

/// The door crowd's deadlock (R6 and R18 of `tests/scale.rs`): A left Room 2's door heading for
/// Room 5's across the corridor, B left Room 5's heading for Room 2's; they meet nose to nose
/// at (6.2, 4.9) and (6.2, 5.9), each waiting at the other's door (held, the other within
/// DOOR_CLEAR_M of it) and each within DOOR_HOLD_M of it: before giving way both were capped to
/// 0 for ever. Stopped (a face-off) or still moving (the published wait-for cycle alone), A (it
/// goes first: lower index) no longer waits and B steps aside off A's line to Room 5's door.
#[test]
fn of_two_robots_waiting_for_each_other_one_goes_and_the_other_gives_way() {
    let floor = crate::test_floor::doors_floor();
    let door = |name: &str| {
        let d = floor
            .doors
            .iter()
            .position(|d| d.name.as_deref() == Some(name));
        DoorIdx::new(d.unwrap())
    };
    let (room2, room5) = (door("Door Room 2"), door("Door Room 5"));
    assert_eq!(floor.doors[room2.get()].center, DVec2::new(6.2, 4.1));
    assert!((floor.doors[room5.get()].center - DVec2::new(6.2, 6.7)).length() < 1e-9);
    for speed in [0.0, 0.2] {
        let mut robots = vec![
            robot("A", DVec2::new(6.2, 4.9), FRAC_PI_2, 0),
            robot("B", DVec2::new(6.2, 5.9), -FRAC_PI_2, 0),
        ];
        // As published by the last step: each waits for the other at its door.
        robots[0].waits_for = Some((1, Some(room5)));
        robots[1].waits_for = Some((0, Some(room2)));
        for r in &mut robots {
            r.state.speed = speed;
        }
        let mut v = View::new(&floor, robots);
        let mut a = Mind::new();
        a.door_wait = Some(room5);
        let mut b = Mind::new();
        b.door_wait = Some(room2);
        let (pa, _) = v.perceive(0, &mut a);
        let (pb, _) = v.perceive(1, &mut b);
        // A goes: no door wait, only A-1 (B's box 0.1 m beyond the margin) and the corridor's
        // SPEED_REDUCTION (2.5 m/s) cap it.
        assert_eq!((a.door_wait, a.waits_for, a.give_way), (None, None, None));
        assert!(
            close(pa.speed_cap, (2.0 * BRAKE * 0.1f64).sqrt()),
            "{}",
            pa.speed_cap
        );
        // B still waits at Room 2's door, for A, and gives way: a step aside to A's right,
        // its half length + A's half width + twice the margin (0.95 m) off A's line.
        assert_eq!(b.waits_for, Some((0, Some(room2))), "speed {speed}");
        let g = b.give_way.expect("B gives way");
        assert_eq!(g.other, 0);
        assert!(
            (g.spot - DVec2::new(7.15, 5.9)).length() < 1e-9,
            "{}",
            g.spot
        );
        // Its door wait no longer stops it. Too close to A to turn (centres 1.0 m apart, their
        // corners sweep 0.53 m each), it first backs straight away from A at 0.3 x 2.5 m/s.
        assert!(pb.speed_cap > 0.0);
        assert_eq!(pb.squeeze, -1.0);
        let r = &v.robots[1];
        let cmd = decide(
            &pb,
            Command { v: 2.0, omega: 0.0 },
            r,
            &mut b,
            0.0,
            false,
            &v.behaviour,
        );
        assert_eq!(
            cmd,
            Command {
                v: -0.75,
                omega: 0.0
            }
        );
        // With room to turn, it turns towards the spot (to its left) in place.
        let mut p = pb.clone();
        p.squeeze = 0.0;
        let cmd = decide(
            &p,
            Command { v: 2.0, omega: 0.0 },
            r,
            &mut b,
            0.0,
            false,
            &v.behaviour,
        );
        assert_eq!(cmd.v, 0.0);
        assert!(close(cmd.omega, 100f64.to_radians()), "{}", cmd.omega);
    }
}
