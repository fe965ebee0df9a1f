//! Steps per second of the simulator (sensing, Algorithm 1, controllers, motion with contacts)
//! with 2, 20 and 100 robots on the paper's test building at 60 Hz, 5 rays each. One iteration
//! is one simulated second (60 steps), so the real-time factor is 1 s / time per iteration.
//! Goals (issue 6): >= 1000x real time for 2 robots, >= 20x for 100.
//! A storey of office-a.ifc joins once poinav-nav converts IFC storeys into floors.

use criterion::{criterion_group, criterion_main, Criterion};
use glam::DVec2;
use poinav_nav::Floor;
use poinav_poi::RobotProfile;
use poinav_sim::controller::ControllerSpec;
use poinav_sim::{RobotSetup, Sim, SimOptions};

fn demo_floor() -> Floor {
    let scenario = poinav_sim::Scenario::from_toml(
        "name = \"bench\"\nduration_s = 1.0\n[building]\ndemo = {}\n[[robot]]\nname = \"R\"\nstart = { x = 1.0, y = 5.4 }\ncontroller = { kind = \"idle\" }\n",
        "bench.toml",
        std::path::Path::new("."),
    )
    .unwrap();
    poinav_sim::prepare(&scenario, None, None).unwrap().floor
}

/// `n` robots on a grid over the rooms and the corridor (1.0 x 0.95 m spacing), each driving
/// to another room.
fn robots(floor: &Floor, n: usize) -> Vec<RobotSetup> {
    let mut spots = Vec::new();
    for z in &floor.zones {
        let (lo, hi) = z
            .ring
            .iter()
            .fold((DVec2::INFINITY, DVec2::NEG_INFINITY), |(lo, hi), p| {
                (lo.min(*p), hi.max(*p))
            });
        let mut y = lo.y + 0.5;
        while y <= hi.y - 0.5 {
            let mut x = lo.x + 0.5;
            while x <= hi.x - 0.5 {
                spots.push(DVec2::new(x, y));
                x += 1.0;
            }
            y += 0.95;
        }
    }
    assert!(spots.len() >= n, "{} places for {n} robots", spots.len());
    let step = spots.len() / n;
    let rooms: Vec<String> = floor
        .zones
        .iter()
        .filter_map(|z| z.name.clone())
        .filter(|n| n.starts_with("Room"))
        .collect();
    (0..n)
        .map(|i| RobotSetup {
            name: format!("Robot{}", i + 1),
            global_id: None,
            profile: RobotProfile::paper(),
            start: spots[i * step],
            heading_deg: 0.0,
            controller: ControllerSpec::Route {
                to: rooms[(i * 7 + 3) % rooms.len()].clone(),
                speed_m_s: None,
            },
            priority: 0,
            brush_on: true,
            drive_force_n: 50.0,
            brake_force_n: 100.0,
        })
        .collect()
}

fn steps(c: &mut Criterion) {
    let floor = demo_floor();
    let mut group = c.benchmark_group("steps");
    for n in [2usize, 20, 100] {
        let setups = robots(&floor, n);
        let opts = SimOptions {
            record: false,
            ..SimOptions::default()
        };
        let mut sim = Sim::new(&floor, &setups, opts).unwrap();
        group.bench_function(format!("demo-building/{n}-robots/1s-at-60Hz"), |b| {
            b.iter(|| {
                for _ in 0..60 {
                    sim.tick(true);
                }
            })
        });
    }
    group.finish();
}

criterion_group!(benches, steps);
criterion_main!(benches);
