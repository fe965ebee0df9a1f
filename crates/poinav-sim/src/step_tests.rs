//! Unit tests of the step: the fixed 60 Hz clock, the speed limits of a move, no tunnelling
//! through a thin wall at the top speed, sliding, contacts reported once per touch, a start
//! overlapping a wall refused, the parallel moves (kept where no moved neighbour came near)
//! equal to planning every move in order, and a standing robot's move (nothing looked at) the
//! same as the full one.

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

#[test]
fn parallel_moves_equal_moves_planned_one_after_the_other() {
    // A dense crowd in a walled hall with columns: robots 1.2 m apart (0.4-0.5 m gaps) under
    // pseudo-random commands, so they push, slide and touch each other and the walls.
    let mut floor = open_floor(None);
    for (id, r) in [
        ("s", rect(-10.2, -5.2, 10.2, -5.0)),
        ("n", rect(-10.2, 5.0, 10.2, 5.2)),
        ("w", rect(-10.2, -5.0, -10.0, 5.0)),
        ("e", rect(10.0, -5.0, 10.2, 5.0)),
        ("c1", rect(-4.3, -0.3, -3.7, 0.3)),
        ("c2", rect(3.7, -0.3, 4.3, 0.3)),
    ] {
        floor.obstacles.push(wall(id, r));
    }
    let mut setups = Vec::new();
    for gy in 0..7 {
        for gx in 0..15 {
            let p = DVec2::new(-8.4 + gx as f64 * 1.2, -3.6 + gy as f64 * 1.2);
            if (p.x.abs() - 4.0).abs() < 1.0 && p.y.abs() < 1.0 {
                continue;
            }
            let name = format!("R{}", setups.len());
            setups.push(setup(
                &name,
                p,
                (gx * 37 + gy * 61) as f64,
                ControllerSpec::Idle,
            ));
        }
    }
    let n = setups.len();
    let mut parallel = Sim::new(&floor, &setups, SimOptions::default()).unwrap();
    let mut sequential = Sim::new(&floor, &setups, SimOptions::default()).unwrap();
    sequential.sequential_moves = true;
    let mut seed = 0x2545_F491_4F6C_DD1Du64;
    let mut cmds = vec![Command { v: 0.0, omega: 0.0 }; n];
    for step in 0..240 {
        if step % 12 == 0 {
            for c in &mut cmds {
                seed ^= seed << 13;
                seed ^= seed >> 7;
                seed ^= seed << 17;
                let (a, b) = (
                    (seed & 0xffff) as f64 / 65535.0,
                    (seed >> 48) as f64 / 65535.0,
                );
                *c = Command {
                    v: -1.0 + 6.0 * a,
                    omega: -3.0 + 6.0 * b,
                };
            }
        }
        for sim in [&mut parallel, &mut sequential] {
            sim.world.refresh_robots();
            sim.move_all(&cmds, sim.time());
            sim.step += 1;
        }
        for (a, b) in parallel.robots.iter().zip(&sequential.robots) {
            let (a, b) = (a.state, b.state);
            let bits = |s: crate::robot::RobotState| {
                [
                    s.pos.x,
                    s.pos.y,
                    s.heading,
                    s.speed,
                    s.actual_speed,
                    s.omega,
                    s.odometer,
                ]
                .map(f64::to_bits)
            };
            assert_eq!(bits(a), bits(b), "step {step}");
        }
    }
    let (a, b) = (contacts(&parallel), contacts(&sequential));
    assert_eq!(a, b);
    let robots = a.iter().filter(|c| c.2 == "Robot").count();
    assert!(
        robots >= 20 && a.len() - robots >= 5,
        "{} contacts, {robots} with robots",
        a.len()
    );
}

#[test]
fn a_standing_robots_move_is_the_full_move_without_looking() {
    // Robots at rest 1.15 m apart (0.4-0.5 m gaps), beside a wall (0.05-0.25 m away), one with
    // the heading -0 (turning it by +0 changes its bits: the full move handles that).
    let mut floor = open_floor(None);
    floor.obstacles.push(wall("w", rect(-3.0, -1.0, 7.0, -0.6)));
    let headings = [0.0, -0.0, 90.0, 179.0, -179.0, 45.0, 180.0, -90.0];
    let setups: Vec<_> = headings
        .iter()
        .enumerate()
        .map(|(k, &h)| {
            let p = DVec2::new(-2.0 + k as f64 * 1.15, 0.0);
            setup(&format!("R{k}"), p, h, ControllerSpec::Idle)
        })
        .collect();
    let sim = Sim::new(&floor, &setups, SimOptions::default()).unwrap();
    let dt = sim.opts.dt;
    let mut fast = 0;
    for (i, robot) in sim.robots.iter().enumerate() {
        for omega in [0.0, -0.0] {
            let mut sc = Scratch::default();
            let full = turn_and_slide(&sim.world, robot, i, (0.0, omega), dt, &mut sc);
            let start = *sim.world.robot(i);
            let Some(m) = standing(&sim.world, robot.state, (0.0, omega), start, dt, &mut sc)
            else {
                assert_eq!(robot.state.heading.to_bits(), (-0.0f64).to_bits());
                continue;
            };
            fast += 1;
            assert!(sc.robots.is_empty(), "robot {i}: looked at nobody");
            let bits = |m: &Move| {
                [
                    m.pos.x,
                    m.pos.y,
                    m.heading,
                    m.omega,
                    m.actual_speed,
                    m.speed,
                    m.travelled,
                ]
                .map(f64::to_bits)
            };
            assert_eq!(bits(&m), bits(&full), "robot {i} omega {omega}");
            assert_eq!(m.footprint, full.footprint, "robot {i}");
            assert_eq!((m.bounds, m.cells), (full.bounds, full.cells), "robot {i}");
            assert!(m.touched.is_empty() && full.touched.is_empty(), "robot {i}");
        }
    }
    assert_eq!(fast, 15, "every case but the -0 heading turned by +0");
}
