//! Unit tests of the controllers: route following reaches its waypoints (alone, in a run
//! through a door, and between two doors in one wall), key replay and live keys, the
//! wall-following PD law and wall following in a run.

use super::*;
use crate::events::EventKind;
use crate::step::{Sim, SimOptions, DT};
use crate::test_floor::{door_floor, open_floor, rect, robot, setup, wall};
use poinav_nav::Floor;
use std::f64::consts::FRAC_PI_2;

fn close(a: f64, b: f64) -> bool {
    (a - b).abs() < 1e-9
}

#[test]
fn a_follower_turns_in_place_then_reaches_each_waypoint() {
    let lim = robot("R", DVec2::ZERO, 0.0, 0).limits;
    let wps = vec![
        DVec2::new(2.0, 0.0),
        DVec2::new(2.0, 2.0),
        DVec2::new(0.0, 2.0),
    ];
    let mut f = Follower::new(DVec2::ZERO, wps.clone(), 1.0);
    // Facing +y, the first waypoint 90 degrees to the right: turn in place at the top rate.
    let c = f.command(DVec2::ZERO, FRAC_PI_2, &lim);
    assert_eq!(c.v, 0.0);
    assert!(close(c.omega, -lim.max_turn));
    // Facing it: the cruise speed, no turn.
    let c = f.command(DVec2::ZERO, 0.0, &lim);
    assert_eq!(c, Command { v: 1.0, omega: 0.0 });
    // Driven as commanded (speed and turn limits, 60 Hz): every waypoint is passed within its
    // reach (0.1 m; 0.05 m at the last) and the robot stops there.
    let (mut pos, mut heading, mut v) = (DVec2::ZERO, 0.0f64, 0.0);
    let mut nearest = [f64::INFINITY; 3];
    let mut steps = 0;
    while !f.arrived {
        let c = f.command(pos, heading, &lim);
        v = lim.next_speed(v, c.v, DT);
        heading = wrap_angle(heading + lim.turn(c.omega) * DT);
        pos += DVec2::from_angle(heading) * v * DT;
        for (n, wp) in nearest.iter_mut().zip(&wps) {
            *n = n.min(pos.distance(*wp));
        }
        steps += 1;
        assert!(steps < 1200, "not there after 20 s: {pos}");
    }
    assert!(nearest[0] < 0.1 && nearest[1] < 0.1, "{nearest:?}");
    assert!(pos.distance(wps[2]) < 0.05, "{pos}");
    // 6 m at 1 m/s with two corners: between 6 and 12 s.
    assert!((360..720).contains(&steps), "{steps} steps");
    assert_eq!(f.command(pos, heading, &lim), Command::default());
}

#[test]
fn a_route_through_a_door_arrives_in_the_target_zone() {
    let floor = door_floor(1.0, 0.2);
    let s = setup(
        "R",
        DVec2::new(-2.0, -2.0),
        0.0,
        ControllerSpec::Route {
            to: "hall".into(),
            speed_m_s: Some(1.0),
        },
    );
    let mut sim = Sim::new(&floor, &[s], SimOptions::default()).unwrap();
    while sim.mode(0) != Some(Mode::Arrived) {
        sim.tick(true);
        assert!(sim.steps() < 900, "not there after 15 s");
    }
    let pos = sim.robots()[0].state.pos;
    let data = sim.finish();
    let goal = *data.routes[0].last().unwrap();
    assert!(
        floor.zones[1].ring[0].y < goal.y,
        "goal {goal} not in the hall"
    );
    assert!(pos.distance(goal) < 0.05, "{pos} vs {goal}");
    let arrived = data
        .events
        .iter()
        .filter(|e| matches!(&e.kind, EventKind::Arrived { zone, .. } if zone == "hall"))
        .count();
    assert_eq!(arrived, 1);
    // No contact on the way through the 1 m door.
    assert!(!data
        .events
        .iter()
        .any(|e| matches!(e.kind, EventKind::Contact { .. })));
}

/// Room 3 to Room 1 of the test building: both doors are in the corridor's south wall (y =
/// 4.0-4.2). Judged from Room 3's door centre, Room 1's door lay on neither side, its approach
/// point was put inside Room 1 (y = 3.2), and the robot drove at it along the corridor into the
/// wall: stopped by A-1 at (6.15, 4.44) for ever (the door crowd's R11, Room 4 to Room 1).
#[test]
fn a_route_between_doors_in_one_wall_approaches_the_second_from_the_corridor() {
    let floor = crate::test_floor::doors_floor();
    let nav = Plan::new(&floor);
    let s = setup(
        "R",
        DVec2::new(10.4, 1.0),
        90.0,
        ControllerSpec::Route {
            to: "Room 1".into(),
            speed_m_s: None,
        },
    );
    let to = nav.zone_at(&floor, DVec2::new(2.0, 2.0)).unwrap();
    let doors = nav
        .door_path(&floor, s.start, to, &s.profile)
        .expect("a way");
    let lead = 0.9;
    let (wps, _) = nav.waypoints(s.start, &doors, to, lead);
    let y: Vec<f64> = wps.iter().map(|p| (p.y * 1e9).round() / 1e9).collect();
    // Out of Room 3 (4.1 -+ 0.9), along the corridor, into Room 1 (4.1 +- 0.9), its goal.
    assert_eq!(&y[..6], [3.2, 4.1, 5.0, 5.0, 4.1, 3.2]);
    assert_eq!((wps[3].x, wps[4].x), (2.0, 2.0));
    let mut sim = Sim::new(&floor, &[s], SimOptions::default()).unwrap();
    while sim.mode(0) != Some(Mode::Arrived) {
        sim.tick(true);
        // 5.72 s at the default cruise speed.
        assert!(sim.steps() < 420, "not there after 7 s");
    }
    assert!(sim.robots()[0].state.pos.y < 4.0);
}

#[test]
fn keys_parse_in_their_scheme_only() {
    use KeyScheme::*;
    assert_eq!(Key::parse(Arrows, "ArrowUp"), Ok(Key::Forward));
    assert_eq!(Key::parse(Arrows, " down "), Ok(Key::Backward));
    assert_eq!(Key::parse(Wasd, "A"), Ok(Key::Left));
    assert_eq!(Key::parse(Wasd, "d"), Ok(Key::Right));
    assert_eq!(Key::parse(Wasd, "Brush"), Ok(Key::Brush));
    assert_eq!(
        Key::parse(Wasd, "Up").map_err(|e| e.to_string()),
        Err("key `Up` is not one of W, A, S, D, Brush".to_string())
    );
    assert!(Key::parse(Arrows, "w").is_err());
}

fn ctx<'a>(t: f64, lim: &'a Limits, nav: &'a Plan) -> Ctx<'a> {
    Ctx {
        t,
        pos: DVec2::ZERO,
        heading: 0.0,
        speed: 0.0,
        limits: lim,
        left_ref: None,
        right_ref: None,
        nav,
    }
}

#[test]
fn a_key_script_drives_at_the_limits() {
    let floor = open_floor(None);
    let nav = Plan::new(&floor);
    let lim = robot("R", DVec2::ZERO, 0.0, 0).limits;
    let key = |t, k, down, name: &str| (t, k, down, name.to_string());
    let mut c = Controller::keys(vec![
        key(1.0, Key::Forward, false, "Up"),
        key(0.0, Key::Forward, true, "Up"),
        key(0.5, Key::Left, true, "Left"),
        key(1.0, Key::Brush, true, "Brush"),
        key(1.5, Key::Backward, true, "Down"),
    ]);
    assert_eq!(c.mode(), Mode::Keys);
    let mut ev = Vec::new();
    let mut at = |t: f64, ev: &mut Vec<ControlEvent>| c.command(&ctx(t, &lim, &nav), ev);
    assert_eq!(at(0.0, &mut ev), Command { v: 5.0, omega: 0.0 });
    assert_eq!(ev, [ControlEvent::Key("Up".into(), true)]);
    let turn = 100f64.to_radians();
    assert_eq!(
        at(0.5, &mut ev),
        Command {
            v: 5.0,
            omega: turn
        }
    );
    ev.clear();
    // Sorted by time (stable): at 1 s the release, then the brush.
    assert_eq!(
        at(1.0, &mut ev),
        Command {
            v: 0.0,
            omega: turn
        }
    );
    assert_eq!(
        ev,
        [
            ControlEvent::Key("Up".into(), false),
            ControlEvent::Key("Brush".into(), true),
            ControlEvent::BrushToggle
        ]
    );
    // Backward at half the top speed.
    assert_eq!(
        at(1.5, &mut ev),
        Command {
            v: -2.5,
            omega: turn
        }
    );
}

#[test]
fn a_live_key_takes_over_and_repeats_are_ignored() {
    let floor = open_floor(None);
    let nav = Plan::new(&floor);
    let lim = robot("R", DVec2::ZERO, 0.0, 0).limits;
    let mut c = Controller::wall_follow(Side::Left, 0.5, 1.0, None);
    assert_eq!(c.mode(), Mode::WallFollow);
    assert!(c.press(2.0, Key::Forward, true, "W"));
    assert_eq!((c.mode(), c.target), (Mode::Keys, None));
    // Auto-repeat of a held key, a release of a key not held, a brush release: ignored.
    assert!(!c.press(2.1, Key::Forward, true, "W"));
    assert!(!c.press(2.1, Key::Left, false, "A"));
    assert!(!c.press(2.1, Key::Brush, false, "Brush"));
    let mut ev = Vec::new();
    let cmd = c.command(&ctx(2.0, &lim, &nav), &mut ev);
    assert_eq!(cmd, Command { v: 5.0, omega: 0.0 });
    assert_eq!(ev, [ControlEvent::Key("W".into(), true)]);
    assert!(c.press(3.0, Key::Forward, false, "W"));
    assert_eq!(
        c.command(&ctx(3.0, &lim, &nav), &mut ev),
        Command::default()
    );
}

#[test]
fn the_wall_pd_law_turns_towards_a_far_wall_and_holds_when_it_is_lost() {
    // 0.1 m farther than the target on the left at 1 m/s: kp = 16/1, a left turn of 1.6 rad/s.
    let mut left = WallPd::new(Side::Left, 0.5);
    assert!(close(left.omega(Some(0.6), 0.0, 0.0, 1.0), 1.6));
    // 0.1 s later 0.01 m nearer: kd = 8, de/dt = -0.1: 16 x 0.09 - 0.8.
    assert!(close(
        left.omega(Some(0.59), 0.1, 0.0, 1.0),
        16.0 * 0.09 - 0.8
    ));
    // The same on the right turns right; at 2 m/s the gains halve; slow speeds count as 0.5.
    let mut right = WallPd::new(Side::Right, 0.5);
    assert!(close(right.omega(Some(0.6), 0.0, 0.0, 2.0), -0.8));
    let mut slow = WallPd::new(Side::Right, 0.5);
    assert!(close(slow.omega(Some(0.4), 0.0, 0.0, 0.1), 3.2));
    // A jump of more than 0.25 m (a door): the heading of the last reference is held.
    let mut pd = WallPd::new(Side::Left, 0.5);
    pd.omega(Some(0.5), 0.0, 0.3, 1.0);
    assert!(close(pd.omega(Some(1.5), 0.1, 0.2, 1.0), 4.0 * 0.1));
    assert!(close(pd.omega(None, 0.2, 0.3, 1.0), 0.0));
    // Lost for more than 1.5 s: the next wall, however far, is taken.
    pd.omega(None, 1.8, 0.3, 1.0);
    assert!(close(pd.omega(Some(1.5), 1.9, 0.3, 1.0), 16.0));
}

/// An open floor with a wall face along y = -1 from x = -10 to 10.
fn corridor() -> Floor {
    let mut f = open_floor(None);
    f.obstacles
        .push(wall("side", rect(-10.0, -1.2, 10.0, -1.0)));
    f
}

#[test]
fn wall_following_settles_at_its_distance() {
    // Starting 7 cm too far from the wall on the right and 10 cm too near, at rest: 0.6 m after
    // 6 s (to 1 mm), heading along the wall, 5.95 m driven (6 s at 1 m/s less the 0.1 s to
    // get there at 10 m/s²), never touching it. (Not from 10 cm too far: at rest the gains are
    // those of 0.5 m/s, the turn saturates, the side ray's distance grows as the robot turns
    // towards the wall, and it ends facing the wall, stopped by A-1.)
    let floor = corridor();
    for y in [-0.33, -0.5] {
        let s = setup(
            "R",
            DVec2::new(-8.0, y),
            0.0,
            ControllerSpec::WallFollow {
                side: Side::Right,
                distance_m: 0.6,
                to: None,
                speed_m_s: Some(1.0),
            },
        );
        let mut sim = Sim::new(&floor, &[s], SimOptions::default()).unwrap();
        for _ in 0..360 {
            sim.tick(true);
        }
        assert_eq!(sim.mode(0), Some(Mode::WallFollow));
        let st = sim.robots()[0].state;
        assert!((st.pos.y - (-0.4)).abs() < 0.001, "from {y}: {}", st.pos);
        assert!(
            st.heading.abs() < 0.1f64.to_radians(),
            "from {y}: {}",
            st.heading
        );
        assert!(
            (st.pos.x - (-8.0 + 5.95)).abs() < 0.02,
            "from {y}: {}",
            st.pos
        );
        let right = sim.readings()[0].rays[crate::sensor::RIGHT].dist;
        assert!((right - 0.6).abs() < 0.001, "from {y}: {right}");
        assert!(!sim
            .events()
            .iter()
            .any(|e| matches!(e.kind, EventKind::Contact { .. })));
    }
}

/// The trace writer indexes `Mode::ALL` by `mode as usize`.
#[test]
fn mode_all_is_in_declaration_order() {
    for (i, m) in Mode::ALL.iter().enumerate() {
        assert_eq!(*m as usize, i, "{m:?}");
    }
    let labels: Vec<&str> = Mode::ALL.iter().map(|m| m.label()).collect();
    assert_eq!(labels, ["idle", "route", "wall-follow", "keys", "arrived"]);
}
