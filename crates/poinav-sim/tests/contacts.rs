//! Contacts without tunnelling: at top speed a robot never passes a 1 cm wall, and robots
//! driven into each other by keys never overlap; every touch is a `contact` event.

use glam::DVec2;
use poinav_nav::{Floor, FloorObstacle, ObstacleKind};
use poinav_poi::RobotProfile;
use poinav_sim::controller::{ControllerSpec, KeyPress, KeyScheme};
use poinav_sim::geometry::{polygon_gap, Obb};
use poinav_sim::{EventKind, RobotSetup, Sim, SimOptions};

fn wall(id: &str, x0: f64, y0: f64, x1: f64, y1: f64) -> FloorObstacle {
    FloorObstacle {
        id: id.into(),
        class: "IfcWall".into(),
        kind: ObstacleKind::Structure,
        rings: vec![poinav_nav::polygon::rect(x0, y0, x1, y1)],
        // No A-1: nothing slows the robots down before they hit.
        roles: vec![],
    }
}

fn driver(name: &str, x: f64, y: f64, heading_deg: f64, keys: &[(f64, &str)]) -> RobotSetup {
    RobotSetup {
        name: name.into(),
        global_id: None,
        profile: RobotProfile::paper(),
        start: DVec2::new(x, y),
        heading_deg,
        controller: ControllerSpec::Keys {
            scheme: KeyScheme::Arrows,
            script: keys
                .iter()
                .map(|(t, k)| KeyPress {
                    t: *t,
                    key: (*k).into(),
                    down: true,
                })
                .collect(),
        },
        priority: 0,
        brush_on: false,
        drive_force_n: 500.0,
        brake_force_n: 500.0,
    }
}

#[test]
fn a_thin_wall_stops_a_robot_at_top_speed_and_robots_never_overlap() {
    let floor = Floor {
        name: "box".into(),
        obstacles: vec![
            wall("thin", 5.0, -3.0, 5.01, 3.0),
            wall("south", -1.0, -3.2, 11.0, -3.0),
            wall("north", -1.0, 3.0, 11.0, 3.2),
        ],
        ..Floor::default()
    };
    let robots = [
        driver("A", 0.0, 0.0, 0.0, &[(0.0, "Up")]),
        driver("B", 0.0, 1.5, 0.0, &[(0.0, "Up"), (0.5, "Left")]),
        driver("C", 3.0, -1.6, 180.0, &[(0.0, "Up"), (0.2, "Right")]),
        driver("D", 0.0, -1.6, 0.0, &[(0.0, "Up")]),
    ];
    let mut sim = Sim::new(&floor, &robots, SimOptions::default()).unwrap();
    for _ in 0..240 {
        sim.tick(true);
    }
    let data = sim.finish();
    let n = robots.len();
    let mut top: f64 = 0.0;
    for step in data.records.chunks(n) {
        let boxes: Vec<Obb> = step
            .iter()
            .map(|r| Obb::new(r.pos, r.heading, 0.4, 0.35))
            .collect();
        for (i, r) in step.iter().enumerate() {
            top = top.max(r.speed);
            // Never through or into the thin wall: every corner stays west of x = 5.
            for c in boxes[i].corners() {
                assert!(
                    c.x <= 5.0 + 1e-6,
                    "robot {i} at step {} reached {c}",
                    r.step
                );
            }
            for j in i + 1..n {
                let gap = polygon_gap(&boxes[i].corners(), &boxes[j].corners());
                assert!(gap > 0.0, "robots {i} and {j} overlap at step {}", r.step);
            }
        }
    }
    assert!(top > 4.9, "robots reached top speed: {top}");
    let contacts: Vec<_> = data
        .events
        .iter()
        .filter_map(|e| match &e.kind {
            EventKind::Contact { with, class } => {
                Some((e.robot.clone(), with.clone(), class.clone()))
            }
            _ => None,
        })
        .collect();
    assert!(
        contacts.iter().any(|c| c.0 == "A" && c.1 == "thin"),
        "{contacts:?}"
    );
    assert!(contacts.iter().any(|c| c.2 == "Robot"), "{contacts:?}");
}
