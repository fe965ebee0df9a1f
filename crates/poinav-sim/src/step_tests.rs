//! Unit tests of the step: the fixed 60 Hz clock, the speed limits of a move, no tunnelling
//! through a thin wall at the top speed, sliding, contacts reported once per touch, and a start
//! overlapping a wall refused.

use super::*;
use crate::controller::ControllerSpec;
use crate::test_floor::{open_floor, rect, setup, wall};

/// An open floor with a wall 1 cm thick whose face is at x = `x`, across the robot's path.
fn thin_wall(x: f64) -> Floor {
    let mut f = open_floor(None);
    f.obstacles.push(wall("thin", rect(x, -3.0, x + 0.01, 3.0)));
    f
}

fn idle_at(floor: &Floor, pos: DVec2, heading_deg: f64) -> Sim<'_> {
    let s = setup("R", pos, heading_deg, ControllerSpec::Idle);
    Sim::new(floor, &[s], SimOptions::default()).unwrap()
}

fn contacts(sim: &Sim<'_>) -> Vec<(u64, String, String)> {
    sim.events()
        .iter()
        .filter_map(|e| match &e.kind {
            EventKind::Contact { with, class } => Some((e.step, with.clone(), class.clone())),
            _ => None,
        })
        .collect()
}

#[test]
fn the_clock_runs_at_60_hz() {
    let floor = open_floor(None);
    let mut sim = idle_at(&floor, DVec2::ZERO, 0.0);
    assert_eq!(SimOptions::default().dt, 1.0 / 60.0);
    for _ in 0..90 {
        sim.tick(true);
    }
    assert_eq!(sim.steps(), 90);
    assert!((sim.time() - 1.5).abs() < 1e-12, "{}", sim.time());
    assert_eq!(sim.last_records()[0].step, 89);
    // A tick that does not advance records the step but keeps the clock.
    sim.tick(false);
    assert_eq!(sim.steps(), 90);
    // Idle: not a millimetre moved.
    assert_eq!(sim.robots()[0].state.pos, DVec2::ZERO);
    let data = sim.finish();
    assert_eq!(data.records.len(), 91);
    assert_eq!(data.dt, DT);
}

#[test]
fn a_move_keeps_the_acceleration_and_braking_limits() {
    let floor = open_floor(None);
    let mut sim = idle_at(&floor, DVec2::ZERO, 0.0);
    let full = Command { v: 5.0, omega: 0.0 };
    // 50 N on 5 kg: 10 m/s², so 1/6 m/s after one step, and 1/360 m travelled.
    let m = sim.plan_move(0, full, &mut Scratch::default());
    assert!((m.speed - 10.0 / 60.0).abs() < 1e-12, "{}", m.speed);
    assert!((m.pos.x - 10.0 / 3600.0).abs() < 1e-12, "{}", m.pos.x);
    assert!(m.touched.is_empty());
    // Braking from 5 m/s with 100 N: 20 m/s², 1/3 m/s less per step.
    sim.robots[0].state.speed = 5.0;
    let m = sim.plan_move(0, Command { v: 0.0, omega: 0.0 }, &mut Scratch::default());
    assert!((m.speed - (5.0 - 20.0 / 60.0)).abs() < 1e-12, "{}", m.speed);
    // The turn rate is capped at 100 degrees/s.
    let m = sim.plan_move(0, Command { v: 0.0, omega: 9.0 }, &mut Scratch::default());
    assert!(
        (m.heading - 100f64.to_radians() / 60.0).abs() < 1e-12,
        "{}",
        m.heading
    );
}

#[test]
fn no_tunnelling_through_a_thin_wall_at_the_top_speed() {
    // The robot's front (x = 0.4) is 5 cm before a 1 cm wall; one step at 5 m/s is 8.3 cm.
    let floor = thin_wall(0.45);
    let mut sim = idle_at(&floor, DVec2::ZERO, 0.0);
    sim.robots[0].state.speed = 5.0;
    let full = [Command { v: 5.0, omega: 0.0 }];
    for _ in 0..30 {
        sim.move_all(&full, sim.time());
        sim.step += 1;
        sim.robots[0].state.speed = 5.0;
        let front = sim.robots[0].state.pos.x + 0.4;
        assert!(front <= 0.45, "front at {front}");
        assert!(front > 0.45 - 0.01, "stopped {} m short", 0.45 - front);
        assert_eq!(sim.robots[0].state.pos.y, 0.0);
    }
    // It stopped at the face, and the contact is reported once, at the first step.
    assert!(sim.robots[0].state.actual_speed < 1e-6);
    assert!((sim.robots[0].state.odometer - 0.05).abs() < 0.01);
    assert_eq!(contacts(&sim), [(0, "thin".into(), "IfcWall".into())]);
}

#[test]
fn a_move_into_a_wall_at_an_angle_slides_along_it() {
    // Heading 45 degrees down, the lowest corner 1 mm above a wall along y = -1: driving on, the
    // robot slides along +x at the speed's component along the wall.
    let mut floor = open_floor(None);
    floor
        .obstacles
        .push(wall("floor-wall", rect(-5.0, -1.1, 5.0, -1.0)));
    let reach = 0.75 * std::f64::consts::FRAC_1_SQRT_2;
    let mut sim = idle_at(&floor, DVec2::new(0.0, -1.0 + reach + 0.001), -45.0);
    for _ in 0..20 {
        sim.robots[0].state.speed = 1.0;
        sim.move_all(&[Command { v: 1.0, omega: 0.0 }], 0.0);
    }
    let p = sim.robots[0].state.pos;
    // 20 steps at 1 m/s: 1/3 m along the heading, of which x takes 0.236 m (less the first
    // millimetre's worth of approach along y).
    let along = 20.0 / 60.0 * std::f64::consts::FRAC_1_SQRT_2;
    assert!((p.x - along).abs() < 0.01, "slid to x {}", p.x);
    let lowest = sim.robots[0]
        .footprint()
        .corners()
        .iter()
        .map(|c| c.y)
        .fold(f64::INFINITY, f64::min);
    assert!((-1.0..-1.0 + 0.001).contains(&lowest), "corner at {lowest}");
    assert_eq!(contacts(&sim), [(0, "floor-wall".into(), "IfcWall".into())]);
}

#[test]
fn a_start_overlapping_a_wall_is_refused() {
    let floor = thin_wall(0.3);
    let s = setup("R", DVec2::ZERO, 0.0, ControllerSpec::Idle);
    let err = Sim::new(&floor, &[s], SimOptions::default()).unwrap_err();
    assert!(
        err.to_string().contains("starts overlapping IfcWall thin"),
        "{err}"
    );
}
