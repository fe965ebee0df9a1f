//! Real-time factors of big crowds with the trace on: 100, 1000 and 10,000 robots on a big open
//! floor ([`common::open_floor`]: a hall with columns, one C-1 zone, robots on a 3 m grid
//! driving off in different directions and meeting). One iteration is one simulated second (60
//! steps at 60 Hz) of a fresh simulation, every step recorded as `poinav simulate` records it
//! (trace lines rendered, summary figures, plot samples; the bytes go to `io::sink`, so the
//! disk is not measured), so the real-time factor is 1 s / time per iteration. Also the same
//! second with the compact trace (`trace-bin`, [`poinav_sim::trace_bin`]), with the trace
//! thinned to every 6th step (10 Hz) and without a trace. Goals
//! (issue 15): >= 250x real time for 100 robots, >= 50x for 1000, >= 5x for 10,000.
//!
//! Run with `cargo bench -p poinav-sim --bench crowd` (about five minutes on two cores).

mod common;

use std::time::Duration;

use criterion::{criterion_group, criterion_main, BatchSize, BenchmarkGroup, Criterion};
use poinav_nav::Floor;
use poinav_sim::{Recorder, RobotSetup, Sim, SimOptions, TraceFormat, TraceOut, DT};

/// One simulated second per iteration, recorded with the trace kept every `every` steps.
fn bench_second(
    group: &mut BenchmarkGroup<'_, criterion::measurement::WallTime>,
    id: String,
    floor: &Floor,
    setups: &[RobotSetup],
    every: Option<u64>,
    format: TraceFormat,
) {
    let opts = SimOptions {
        record: false,
        ..SimOptions::default()
    };
    // Fails early (outside the timing) when a robot cannot be placed.
    Sim::new(floor, setups, opts.clone()).unwrap();
    group.bench_function(id, |b| {
        b.iter_batched(
            || Sim::new(floor, setups, opts.clone()).unwrap(),
            |mut sim| {
                let mut sink = std::io::sink();
                let trace = every.map(|every| TraceOut {
                    writer: &mut sink,
                    every,
                    name: "sink".into(),
                    format,
                });
                let mut rec = Recorder::new(&sim, 61, Vec::new(), trace);
                // As `poinav simulate` runs it: the loop on a thread of the pool.
                poinav_sim::on_pool(setups.len(), || {
                    for k in 0..=60 {
                        sim.tick(k < 60);
                        rec.after_tick(&sim, DT).unwrap();
                    }
                    rec.finish().unwrap();
                });
                sim
            },
            BatchSize::PerIteration,
        )
    });
}

fn crowd(c: &mut Criterion) {
    let mut group = c.benchmark_group("crowd");
    group
        .sample_size(10)
        .warm_up_time(Duration::from_secs(1))
        .measurement_time(Duration::from_secs(5));
    for n in [100usize, 1000, 10_000] {
        let (floor, setups) = common::open_floor(n);
        for (label, every, format) in [
            ("trace", Some(1), TraceFormat::Jsonl),
            ("trace-bin", Some(1), TraceFormat::Bin),
            ("trace-every-6", Some(6), TraceFormat::Jsonl),
            ("no-trace", None, TraceFormat::Jsonl),
        ] {
            bench_second(
                &mut group,
                format!("open-floor/{n}-robots/1s-at-60Hz/{label}"),
                &floor,
                &setups,
                every,
                format,
            );
        }
    }
    group.finish();
}

criterion_group!(benches, crowd);
criterion_main!(benches);
