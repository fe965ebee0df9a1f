//! Criterion benchmarks of one storey at 0.05 m: rasterising, inflating (exact Euclidean
//! distance transform), both together, preparing the navigator (grid, graph, door checks),
//! a route across the storey, the audit and the Nav2 route graph. The storey is the hand-made
//! 60 x 40 m office of `tests/support` (98 rooms with a desk each, 2 corridors, a hall, 100
//! doors) standing in for a storey of office-a.ifc until the IFC -> Floor converter lands.
//!
//! Run with `cargo bench -p poinav-nav --bench grid`.

use std::hint::black_box;
use std::time::Duration;

use criterion::{criterion_group, criterion_main, Criterion};
use poinav_nav::grid::distance_transform;
use poinav_nav::{
    Building, GridOptions, InflationOptions, NavGrid, NavOptions, Navigator, OccupancyGrid, Place,
};
use poinav_poi::RobotProfile;

#[path = "../tests/support/mod.rs"]
mod support;

fn grid(c: &mut Criterion) {
    let floor = support::office_floor();
    let profile = RobotProfile::paper();
    let options = GridOptions::default();
    let mut group = c.benchmark_group("office_60x40m_0.05m");
    group
        .sample_size(20)
        .measurement_time(Duration::from_secs(5));
    group.bench_function("rasterise", |b| {
        b.iter(|| OccupancyGrid::build(black_box(&floor), &profile, &options).unwrap())
    });
    let occupancy = OccupancyGrid::build(&floor, &profile, &options).unwrap();
    group.bench_function("distance_transform", |b| {
        b.iter(|| distance_transform(black_box(&occupancy)))
    });
    group.bench_function("grid_build_inflated", |b| {
        b.iter(|| {
            NavGrid::build(
                black_box(&floor),
                &profile,
                &options,
                &InflationOptions::default(),
            )
            .unwrap()
        })
    });
    let building = Building::single(floor.clone());
    let nav = Navigator::new(&building, &profile, &NavOptions::default()).unwrap();
    group.bench_function("navigator_new", |b| {
        b.iter(|| Navigator::new(black_box(&building), &profile, &NavOptions::default()).unwrap())
    });
    group.bench_function("route_office_1_to_98", |b| {
        b.iter(|| {
            nav.route(&Place::zone("Office 1"), &Place::zone("Office 98"))
                .unwrap()
        })
    });
    group.bench_function("audit_from_entrances", |b| {
        b.iter(|| poinav_nav::audit::audit_profile(black_box(&nav), None).unwrap())
    });
    group.bench_function("nav2_route_graph", |b| {
        b.iter(|| poinav_nav::nav2::route_graph(black_box(&nav), 0, &Default::default()))
    });
    group.finish();
}

criterion_group!(benches, grid);
criterion_main!(benches);
