//! Steps per second of the simulator (sensing, Algorithm 1, controllers, motion with contacts)
//! with 2, 20 and 100 robots at 60 Hz, 5 rays each, on the paper's test building and on
//! office-a.ifc's "Level 1" (read from `shared/ifc/` beside the repository, or
//! `$POINAV_SHARED/ifc/`). One iteration is one simulated second (60 steps) of a fresh
//! simulation (set up outside the timed part), so the real-time factor is 1 s / time per
//! iteration. Goals (issue 6): >= 1000x real time for 2 robots, >= 20x for 100.
//!
//! Run with `cargo bench -p poinav-sim --bench steps`; sample counts are small so the whole run
//! takes a few minutes on two cores.

mod common;

use std::time::Duration;

use criterion::{criterion_group, criterion_main, BatchSize, BenchmarkGroup, Criterion};
use glam::DVec2;
use poinav_nav::Floor;
use poinav_poi::RobotProfile;
use poinav_sim::controller::{ControllerSpec, KeyPress, KeyScheme, Side};
use poinav_sim::plan::Plan;
use poinav_sim::{RobotSetup, Sim, SimOptions};

fn setup(i: usize, start: DVec2, controller: ControllerSpec) -> RobotSetup {
    RobotSetup {
        name: format!("Robot{}", i + 1),
        global_id: None,
        profile: RobotProfile::paper(),
        start,
        heading_deg: 0.0,
        controller,
        priority: 0,
        brush_on: true,
        drive_force_n: 50.0,
        brake_force_n: 100.0,
    }
}

/// `n` robots on a grid over the test building's rooms and corridor (1.0 x 0.95 m spacing),
/// each driving to another room.
fn demo_robots(floor: &Floor, n: usize) -> Vec<RobotSetup> {
    let mut spots = Vec::new();
    for z in &floor.zones {
        let Some((lo, hi)) = poinav_nav::polygon::bounds(&z.ring) else {
            continue;
        };
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
    let rooms: Vec<String> = floor
        .zones
        .iter()
        .filter_map(|z| z.name.clone())
        .filter(|n| n.starts_with("Room"))
        .collect();
    common::spread(&spots, n)
        .into_iter()
        .enumerate()
        .map(|(i, start)| {
            setup(
                i,
                start,
                ControllerSpec::Route {
                    to: rooms[(i * 7 + 3) % rooms.len()].clone(),
                    speed_m_s: None,
                },
            )
        })
        .collect()
}

/// A short key script: forward, a turn to the left, later one to the right.
fn key_script(scheme: KeyScheme) -> Vec<KeyPress> {
    let (fwd, left, right) = match scheme {
        KeyScheme::Arrows => ("Up", "Left", "Right"),
        KeyScheme::Wasd => ("W", "A", "D"),
    };
    [
        (0.0, fwd, true),
        (0.3, left, true),
        (0.6, left, false),
        (0.8, right, true),
        (0.95, right, false),
    ]
    .into_iter()
    .map(|(t, key, down)| KeyPress {
        t,
        key: key.into(),
        down,
    })
    .collect()
}

/// `n` robots spread over office-a Level 1's free spots (1.2 m grid, each clear of obstacles
/// and its zone's outline by the robot's half-diagonal plus its margin). In turn: a route to
/// another zone reachable through doors wide enough, wall following (left, right) and key
/// replay (arrows, W A S D). A route robot whose zone has no usable door follows walls.
fn office_robots(floor: &Floor, n: usize) -> Vec<RobotSetup> {
    let p = RobotProfile::paper();
    let half_diagonal = 0.5 * p.width_m.hypot(p.length_m);
    let spots = common::free_spots(floor, 1.2, half_diagonal + p.clearance_margin_m);
    let nav = Plan::new(floor);
    common::spread(&spots, n)
        .into_iter()
        .enumerate()
        .map(|(i, start)| {
            let controller = match i % 3 {
                0 => {
                    let reachable: Vec<&str> = floor
                        .zones
                        .iter()
                        .enumerate()
                        .filter(|(z, zone)| {
                            zone.name.is_some()
                                && nav
                                    .door_path(floor, start, poinav_nav::ZoneIdx::new(*z), &p)
                                    .is_some_and(|d| !d.is_empty())
                        })
                        .filter_map(|(_, zone)| zone.name.as_deref())
                        .collect();
                    if reachable.is_empty() {
                        // A zone without usable doors: follow its walls instead.
                        ControllerSpec::WallFollow {
                            side: Side::Left,
                            distance_m: 0.5,
                            to: None,
                            speed_m_s: None,
                        }
                    } else {
                        ControllerSpec::Route {
                            to: reachable[(i * 7 + 3) % reachable.len()].to_string(),
                            speed_m_s: None,
                        }
                    }
                }
                1 => ControllerSpec::WallFollow {
                    side: if i % 2 == 0 { Side::Left } else { Side::Right },
                    distance_m: 0.5,
                    to: None,
                    speed_m_s: None,
                },
                _ => {
                    let scheme = if i % 2 == 0 {
                        KeyScheme::Arrows
                    } else {
                        KeyScheme::Wasd
                    };
                    ControllerSpec::Keys {
                        scheme,
                        script: key_script(scheme),
                    }
                }
            };
            setup(i, start, controller)
        })
        .collect()
}

/// One simulated second (60 steps) per iteration, each on a fresh simulation.
fn bench_second(
    group: &mut BenchmarkGroup<'_, criterion::measurement::WallTime>,
    id: String,
    floor: &Floor,
    setups: &[RobotSetup],
) {
    let opts = SimOptions {
        record: false,
        ..SimOptions::default()
    };
    // Fails early (outside the timing) when a robot cannot be placed or routed.
    Sim::new(floor, setups, opts.clone()).unwrap();
    group.bench_function(id, |b| {
        b.iter_batched(
            || Sim::new(floor, setups, opts.clone()).unwrap(),
            |mut sim| {
                // As `poinav simulate` runs it: the loop on a thread of the pool.
                poinav_sim::on_pool(setups.len(), || {
                    for _ in 0..60 {
                        sim.tick(true);
                    }
                });
                sim
            },
            BatchSize::PerIteration,
        )
    });
}

fn steps(c: &mut Criterion) {
    let demo = common::demo_floor();
    let office = common::office_floor();
    let mut group = c.benchmark_group("steps");
    group
        .sample_size(10)
        .warm_up_time(Duration::from_secs(1))
        .measurement_time(Duration::from_secs(4));
    for n in [2usize, 20, 100] {
        bench_second(
            &mut group,
            format!("demo-building/{n}-robots/1s-at-60Hz"),
            &demo,
            &demo_robots(&demo, n),
        );
    }
    for n in [2usize, 20, 100] {
        bench_second(
            &mut group,
            format!("office-a-level-1/{n}-robots/1s-at-60Hz"),
            &office,
            &office_robots(&office, n),
        );
    }
    group.finish();
}

criterion_group!(benches, steps);
criterion_main!(benches);
