//! Criterion benchmarks: `mesh_model` (every element and space of a model, openings cut) on
//! real IFC files, on one thread and on the default rayon pool.
//!
//! Run with `cargo bench -p poinav-geom --bench meshes`. The corpus is read from `shared/ifc/`
//! beside the repository, or from `$POINAV_SHARED/ifc/`. Sample counts are small so the whole
//! run takes about a minute.

use std::hint::black_box;
use std::time::Duration;

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, SamplingMode};
use poinav_geom::mesh_model;
use poinav_ifc::Model;

/// The files benchmarked: one large merged IFC2X3 model and one mid-sized office.
const FILES: [&str; 2] = ["synthetic-merged-office-duplex-ifc2x3.ifc", "office-a.ifc"];

/// Corpus file `name`, indexed; panics with the path when it is missing.
fn load(name: &str) -> Model {
    let path = poinav_testkit::corpus_file(name);
    Model::open(&path).unwrap_or_else(|e| {
        panic!(
            "cannot read {} ({e}); set POINAV_SHARED to the folder holding ifc/",
            path.display()
        )
    })
}

/// `mesh_model` on a pool of one thread and on the default pool (one thread per core).
fn meshes(c: &mut Criterion) {
    let mut group = c.benchmark_group("mesh_model");
    group
        .sample_size(10)
        .warm_up_time(Duration::from_secs(1))
        .measurement_time(Duration::from_secs(5))
        .sampling_mode(SamplingMode::Flat);
    let one = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .expect("a pool of one thread");
    let default = rayon::ThreadPoolBuilder::new()
        .build()
        .expect("the default pool");
    for name in FILES {
        let model = load(name);
        for (label, pool) in [("1 thread", &one), ("default pool", &default)] {
            group.bench_with_input(BenchmarkId::new(label, name), &model, |b, model| {
                b.iter(|| pool.install(|| black_box(mesh_model(model))))
            });
        }
    }
    group.finish();
}

criterion_group!(benches, meshes);
criterion_main!(benches);
