//! Live driving (the browser viewer): keys pressed while the simulation runs take effect at the
//! next step, take a robot over from its route, ignore auto-repeat, toggle the brush, and give
//! exactly the run a scripted key replay gives.

use glam::DVec2;
use poinav_nav::Floor;
use poinav_poi::RobotProfile;
use poinav_sim::controller::{ControllerSpec, Key, KeyPress, KeyScheme, Mode};
use poinav_sim::{EventKind, RobotSetup, Sim, SimOptions};

fn robot(controller: ControllerSpec) -> RobotSetup {
    RobotSetup {
        name: "Robot1".into(),
        global_id: None,
        profile: RobotProfile::paper(),
        start: DVec2::ZERO,
        heading_deg: 0.0,
        controller,
        priority: 0,
        brush_on: false,
        drive_force_n: 50.0,
        brake_force_n: 100.0,
    }
}

fn keys(script: Vec<KeyPress>) -> ControllerSpec {
    ControllerSpec::Keys {
        scheme: KeyScheme::Arrows,
        script,
    }
}

#[test]
fn live_presses_equal_a_scripted_replay() {
    let floor = Floor::default();
    let scripted = keys(vec![
        KeyPress {
            t: 0.5,
            key: "Up".into(),
            down: true,
        },
        KeyPress {
            t: 1.0,
            key: "Left".into(),
            down: true,
        },
        KeyPress {
            t: 1.5,
            key: "Left".into(),
            down: false,
        },
        KeyPress {
            t: 2.0,
            key: "Up".into(),
            down: false,
        },
    ]);
    let mut a = Sim::new(&floor, &[robot(scripted)], SimOptions::default()).unwrap();
    let mut b = Sim::new(&floor, &[robot(keys(vec![]))], SimOptions::default()).unwrap();
    let live = [
        (30, Key::Forward, true, "Up"),
        (60, Key::Left, true, "Left"),
        (90, Key::Left, false, "Left"),
        (120, Key::Forward, false, "Up"),
    ];
    for step in 0..180u64 {
        for &(at, key, down, name) in &live {
            if at == step {
                assert!(b.press(0, key, down, name));
            }
        }
        a.tick(true);
        b.tick(true);
    }
    let (ra, rb) = (a.robots()[0].state, b.robots()[0].state);
    assert_eq!(ra.pos, rb.pos);
    assert_eq!(ra.heading, rb.heading);
    assert!(ra.odometer > 3.0, "drove {} m", ra.odometer);
    assert_eq!(a.finish().events, b.finish().events);
}

#[test]
fn a_press_takes_over_a_route_and_repeats_are_ignored() {
    let floor = Floor::default();
    let mut sim = Sim::new(
        &floor,
        &[robot(ControllerSpec::Idle)],
        SimOptions::default(),
    )
    .unwrap();
    assert_eq!(sim.mode(0), Some(Mode::Idle));
    assert!(sim.press(0, Key::Forward, true, "ArrowUp"));
    assert!(
        !sim.press(0, Key::Forward, true, "ArrowUp"),
        "auto-repeat must be ignored"
    );
    assert!(!sim.press(1, Key::Forward, true, "ArrowUp"), "no robot 1");
    for _ in 0..30 {
        sim.tick(true);
    }
    assert_eq!(sim.mode(0), Some(Mode::Keys));
    let x = sim.robots()[0].state.pos.x;
    assert!(x > 0.3, "moved {x} m in 0.5 s");
    assert!(sim.press(0, Key::Forward, false, "ArrowUp"));
    assert!(!sim.press(0, Key::Forward, false, "ArrowUp"));
    assert!(sim.press(0, Key::Brush, true, "Brush"));
    for _ in 0..60 {
        sim.tick(true);
    }
    let r = sim.robots()[0].state;
    assert!(r.brush.on);
    assert!(r.speed.abs() < 1e-9, "released: stops, speed {}", r.speed);
    let events = sim.take_events();
    let keys: Vec<(String, bool)> = events
        .iter()
        .filter_map(|e| match &e.kind {
            EventKind::Key { key, down } => Some((key.clone(), *down)),
            _ => None,
        })
        .collect();
    assert_eq!(
        keys,
        [
            ("ArrowUp".to_string(), true),
            ("ArrowUp".to_string(), false),
            ("Brush".to_string(), true)
        ]
    );
    assert!(events
        .iter()
        .any(|e| e.kind == EventKind::Brush { on: true }));
    assert!(sim.take_events().is_empty(), "taken events are gone");
    assert_eq!(sim.readings().len(), 1);
}
