//! Criterion benchmark: sectioning dense closed meshes (UV spheres of 10k, 100k and 1M
//! triangles) by a storey's band, to show that the cost grows linearly with the number of
//! triangles (`mesh_section` once summed every projected triangle with a polygon boolean,
//! which grew much faster).
//!
//! Run with `cargo bench -p poinav-geom --bench section`.

use std::hint::black_box;
use std::time::Duration;

use criterion::{
    criterion_group, criterion_main, BenchmarkId, Criterion, SamplingMode, Throughput,
};
use glam::DVec3;
use poinav_geom::section::{mesh_section, mesh_shadow};
use poinav_geom::Mesh;

/// A UV sphere of radius 0.5 m centred 0.5 m above the floor, with `2 * stacks * slices`
/// triangles, faces outwards.
fn sphere(stacks: usize, slices: usize) -> Mesh {
    let mut m = Mesh::default();
    for i in 0..=stacks {
        let t = std::f64::consts::PI * (i as f64 / stacks as f64 - 0.5);
        for k in 0..slices {
            let a = std::f64::consts::TAU * k as f64 / slices as f64;
            m.positions.push(DVec3::new(
                0.5 * t.cos() * a.cos(),
                0.5 * t.cos() * a.sin(),
                0.5 + 0.5 * t.sin(),
            ));
        }
    }
    let at = |i: usize, k: usize| (i * slices + k % slices) as u32;
    for i in 0..stacks {
        for k in 0..slices {
            m.triangles.push([at(i, k), at(i, k + 1), at(i + 1, k + 1)]);
            m.triangles.push([at(i, k), at(i + 1, k + 1), at(i + 1, k)]);
        }
    }
    m
}

fn section(c: &mut Criterion) {
    let mut group = c.benchmark_group("mesh_section");
    group
        .sample_size(10)
        .warm_up_time(Duration::from_secs(1))
        .measurement_time(Duration::from_secs(5))
        .sampling_mode(SamplingMode::Flat);
    // 10k, 100k and 1M triangles.
    for (stacks, slices) in [(50, 100), (158, 316), (500, 1000)] {
        let mesh = sphere(stacks, slices);
        let n = mesh.triangles.len();
        group.throughput(Throughput::Elements(n as u64));
        group.bench_with_input(BenchmarkId::new("band 0.05-1.0 m", n), &mesh, |b, m| {
            b.iter(|| black_box(mesh_section(m, 0.05, 1.0)))
        });
        group.bench_with_input(BenchmarkId::new("band 0.6-0.9 m", n), &mesh, |b, m| {
            b.iter(|| black_box(mesh_section(m, 0.6, 0.9)))
        });
        group.bench_with_input(BenchmarkId::new("shadow", n), &mesh, |b, m| {
            b.iter(|| black_box(mesh_shadow(m)))
        });
    }
    group.finish();
}

criterion_group!(benches, section);
criterion_main!(benches);
