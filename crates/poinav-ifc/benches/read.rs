//! Criterion benchmarks: indexing real IFC files (`Model::from_bytes`) and querying doors and the spatial structure.
//!
//! Run with `cargo bench -p poinav-ifc --bench read`. The corpus is read from `shared/ifc/`
//! beside the repository, or from `$POINAV_SHARED/ifc/`. Sample counts are kept small so the
//! whole run takes well under a minute.

use std::hint::black_box;
use std::time::Duration;

use criterion::{
    criterion_group, criterion_main, BatchSize, BenchmarkId, Criterion, SamplingMode, Throughput,
};
use poinav_ifc::{spatial, units, Model};

/// The files benchmarked: one large merged IFC2X3 model and one mid-sized office.
const FILES: [&str; 2] = ["synthetic-merged-office-duplex-ifc2x3.ifc", "office-a.ifc"];

/// The bytes of corpus file `name`; panics with the path when it is missing.
fn load(name: &str) -> Vec<u8> {
    let path = poinav_testkit::corpus_file(name);
    std::fs::read(&path).unwrap_or_else(|e| {
        panic!(
            "cannot read {} ({e}); set POINAV_SHARED to the folder holding ifc/",
            path.display()
        )
    })
}

/// `Model::from_bytes` on whole files, reported as bytes per second.
fn index(c: &mut Criterion) {
    let mut group = c.benchmark_group("index");
    group
        .sample_size(10)
        .warm_up_time(Duration::from_secs(1))
        .measurement_time(Duration::from_secs(5))
        .sampling_mode(SamplingMode::Flat);
    for name in FILES {
        let bytes = load(name);
        group.throughput(Throughput::Bytes(bytes.len() as u64));
        group.bench_with_input(BenchmarkId::from_parameter(name), &bytes, |b, bytes| {
            // The copy handed to `from_bytes` is made outside the timed part.
            b.iter_batched(
                || bytes.clone(),
                |bytes| Model::from_bytes(name, bytes).expect("corpus file reads"),
                BatchSize::LargeInput,
            );
        });
    }
    group.finish();
}

/// Queries on an indexed model (type and inverse indexes are built on first use, then cached).
fn query(c: &mut Criterion) {
    let mut group = c.benchmark_group("query");
    group
        .sample_size(20)
        .warm_up_time(Duration::from_secs(1))
        .measurement_time(Duration::from_secs(5));
    for name in FILES {
        let model = Model::from_bytes(name, load(name)).expect("corpus file reads");
        let unit = units::length_unit(&model);
        group.bench_with_input(BenchmarkId::new("door-widths", name), &model, |b, model| {
            b.iter(|| {
                let doors = model.instances_of(black_box("IfcDoor"));
                let widths: Vec<Option<f64>> =
                    doors.iter().map(|d| d.get_f64("OverallWidth")).collect();
                black_box(widths)
            });
        });
        group.bench_with_input(BenchmarkId::new("spatial", name), &model, |b, model| {
            b.iter(|| black_box(spatial::spatial_structure(model, &unit)));
        });
    }
    group.finish();
}

criterion_group!(benches, index, query);
criterion_main!(benches);
