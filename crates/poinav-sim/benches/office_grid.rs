//! The navigation grid of one real storey: office-a.ifc Level 1 (from the IFC through the floor
//! plan and the POI classification) rasterised at 0.05 m and inflated for the paper's robot.
//! Issue 5's goal: under 0.5 s. Lives here because poinav-nav must not read IFC.

mod common;

use criterion::{criterion_group, criterion_main, Criterion};
use poinav_nav::{GridOptions, InflationOptions, NavGrid};
use poinav_poi::RobotProfile;

fn office_grid(c: &mut Criterion) {
    let floor = common::office_floor();
    let profile = RobotProfile::paper();
    let grid = GridOptions::default();
    let inflation = InflationOptions::default();
    let built = NavGrid::build(&floor, &profile, &grid, &inflation).unwrap();
    assert!(
        built.occupancy.width * built.occupancy.height > 100_000,
        "a storey-sized grid"
    );
    let mut g = c.benchmark_group("office_grid");
    g.sample_size(10);
    g.bench_function("office-a Level 1, 0.05 m, rasterise + inflate", |b| {
        b.iter(|| NavGrid::build(&floor, &profile, &grid, &inflation).unwrap())
    });
    g.finish();
}

criterion_group!(benches, office_grid);
criterion_main!(benches);
