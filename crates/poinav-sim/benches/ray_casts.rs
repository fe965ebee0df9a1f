//! The simulator's ray casts measured against parry2d's: the same 500 rays (100 origins spread
//! over the free space of the paper's test building and of office-a.ifc's "Level 1", the five
//! sensor rays from each at a pseudo-random heading, 5 m range) cast against
//! (a) poinav-sim's world index (`World::cast`: uniform 1 m grid, exact casts; it also collects
//! the door passages each ray crosses, as the sensor needs), (a') the same index built without
//! doors (obstacle edges only, the same work as parry2d's), and (b) parry2d-f64: one `Polyline`
//! of every obstacle edge with its BVH, `cast_local_ray`, and (b') parry2d's BVH walked with
//! poinav-sim's segment test at the leaves. No robots are in the world. Before timing, every
//! ray's distance must agree between all four to 1e-9 m.
//!
//! Run with `cargo bench -p poinav-sim --bench ray_casts`; criterion reports rays per second
//! (time per 1000 rays = 2 x time per iteration).

mod common;

use std::time::Duration;

use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use glam::DVec2;
use parry2d_f64::math::Vector;
use parry2d_f64::query::{Ray, RayCast};
use parry2d_f64::shape::Polyline;
use poinav_nav::Floor;
use poinav_sim::geometry::ray_segment;
use poinav_sim::sensor::{directions, RANGE_M};
use poinav_sim::world::World;
use poinav_sim::SimOptions;

/// Ray origins per building.
const ORIGINS: usize = 100;

/// A deterministic pseudo-random number in [0, 1) (xorshift).
fn rng(seed: &mut u64) -> f64 {
    *seed ^= *seed << 13;
    *seed ^= *seed >> 7;
    *seed ^= *seed << 17;
    (*seed >> 11) as f64 / (1u64 << 53) as f64
}

/// The five sensor rays of [`ORIGINS`] robots spread over `floor`'s free space (0.5 m grid,
/// 0.3 m clear of obstacles), as (origin, unit direction).
fn rays(floor: &Floor) -> Vec<(DVec2, DVec2)> {
    let spots = common::free_spots(floor, 0.5, 0.3);
    let mut seed = 0x9E37_79B9_7F4A_7C15u64;
    common::spread(&spots, ORIGINS)
        .into_iter()
        .flat_map(|o| {
            let heading = rng(&mut seed) * std::f64::consts::TAU;
            directions(heading).map(|d| (o, d))
        })
        .collect()
}

/// One parry2d polyline holding every obstacle edge of `floor` (two vertices per edge).
fn parry_polyline(floor: &Floor) -> Polyline {
    let edges = common::obstacle_edges(floor);
    let mut vertices = Vec::with_capacity(2 * edges.len());
    let mut indices = Vec::with_capacity(edges.len());
    for (a, b) in edges {
        let k = vertices.len() as u32;
        vertices.push(Vector::new(a.x, a.y));
        vertices.push(Vector::new(b.x, b.y));
        indices.push([k, k + 1]);
    }
    Polyline::new(vertices, Some(indices))
}

fn parry_cast(shape: &Polyline, o: DVec2, d: DVec2) -> f64 {
    let ray = Ray::new(Vector::new(o.x, o.y), Vector::new(d.x, d.y));
    shape.cast_local_ray(&ray, RANGE_M, true).unwrap_or(RANGE_M)
}

/// parry2d's BVH of `shape` traversed with poinav-sim's exact segment test as the leaf check
/// (`edges` in the polyline's segment order): separates the tree walk from parry2d's segment
/// test.
fn parry_bvh_cast(shape: &Polyline, edges: &[(DVec2, DVec2)], o: DVec2, d: DVec2) -> f64 {
    let ray = Ray::new(Vector::new(o.x, o.y), Vector::new(d.x, d.y));
    shape
        .bvh()
        .cast_ray(&ray, RANGE_M, |i, best| {
            let (a, b) = edges[i as usize];
            ray_segment(o, d, a, b).filter(|&t| t <= best)
        })
        .map_or(RANGE_M, |hit| hit.1)
}

fn ray_casts(c: &mut Criterion) {
    let cell = SimOptions::default().cell_m;
    let mut group = c.benchmark_group("ray_casts");
    group
        .sample_size(20)
        .warm_up_time(Duration::from_secs(1))
        .measurement_time(Duration::from_secs(3));
    for (name, floor) in [
        ("demo-building", common::demo_floor()),
        ("office-a-level-1", common::office_floor()),
    ] {
        let rays = rays(&floor);
        let world = World::new(&floor, cell, 0.0);
        let no_doors = Floor {
            doors: Vec::new(),
            ..floor.clone()
        };
        let world_no_doors = World::new(&no_doors, cell, 0.0);
        let polyline = parry_polyline(&floor);
        let edges = common::obstacle_edges(&floor);
        assert_eq!(world.segment_count(), polyline.num_segments());
        let mut hits = 0;
        for &(o, d) in &rays {
            let a = world.cast(o, d, RANGE_M, None).dist;
            let a2 = world_no_doors.cast(o, d, RANGE_M, None).dist;
            let b = parry_cast(&polyline, o, d);
            let b2 = parry_bvh_cast(&polyline, &edges, o, d);
            assert!(
                [a2, b, b2].iter().all(|x| (a - x).abs() <= 1e-9),
                "{name}: ray from {o} along {d}: world {a}, world without doors {a2}, \
                 parry2d {b}, parry2d's BVH with poinav's segment test {b2}"
            );
            hits += usize::from(a < RANGE_M);
        }
        eprintln!(
            "{name}: {} obstacle edges, {} door passages, {} rays, {hits} hit within {RANGE_M} m; \
             distances agree to 1e-9 m",
            world.segment_count(),
            floor.doors.len(),
            rays.len(),
        );
        group.throughput(Throughput::Elements(rays.len() as u64));
        let n = rays.len();
        group.bench_function(format!("{name}/poinav-world/{n}-rays"), |bch| {
            bch.iter(|| {
                rays.iter()
                    .map(|&(o, d)| world.cast(o, d, RANGE_M, None).dist)
                    .sum::<f64>()
            })
        });
        group.bench_function(
            format!("{name}/poinav-world-without-doors/{n}-rays"),
            |bch| {
                bch.iter(|| {
                    rays.iter()
                        .map(|&(o, d)| world_no_doors.cast(o, d, RANGE_M, None).dist)
                        .sum::<f64>()
                })
            },
        );
        group.bench_function(format!("{name}/parry2d-polyline/{n}-rays"), |bch| {
            bch.iter(|| {
                rays.iter()
                    .map(|&(o, d)| parry_cast(&polyline, o, d))
                    .sum::<f64>()
            })
        });
        group.bench_function(
            format!("{name}/parry2d-bvh-poinav-segment-test/{n}-rays"),
            |bch| {
                bch.iter(|| {
                    rays.iter()
                        .map(|&(o, d)| parry_bvh_cast(&polyline, &edges, o, d))
                        .sum::<f64>()
                })
            },
        );
    }
    group.finish();
}

criterion_group!(benches, ray_casts);
criterion_main!(benches);
