//! Real-time factor of a crowd on the benchmarks' big open floor, as wall time and as CPU time
//! (the latter still means something on a busy machine):
//! `cargo run --release -p poinav-sim --example crowd_rtf -- ROBOTS SECONDS [TRACE_EVERY|0]
//! [jsonl|bin]`. The trace is rendered (JSON Lines, or the compact records with `bin`) and
//! written to `io::sink` (0: no trace), or to the file `CROWD_TRACE` names (to compare runs).

#[path = "../benches/common/mod.rs"]
mod common;

use std::time::Instant;

use poinav_sim::{Recorder, Sim, SimOptions, TraceFormat, TraceOut, DT};

/// User + system CPU seconds of this process so far (Linux `/proc/self/stat`, 100 ticks/s).
fn cpu_seconds() -> f64 {
    let stat = std::fs::read_to_string("/proc/self/stat").unwrap_or_default();
    let after = stat.rsplit_once(')').map_or("", |(_, r)| r);
    let f: Vec<&str> = after.split_whitespace().collect();
    let ticks = |i: usize| f.get(i).and_then(|v| v.parse::<f64>().ok()).unwrap_or(0.0);
    (ticks(11) + ticks(12)) / 100.0
}

fn main() {
    let mut args: Vec<String> = std::env::args().skip(1).collect();
    let format = match args.last().map(String::as_str) {
        Some("bin") => TraceFormat::Bin,
        _ => TraceFormat::Jsonl,
    };
    args.retain(|a| a != "bin" && a != "jsonl");
    let args: Vec<u64> = args.iter().map(|a| a.parse().expect("numbers")).collect();
    let (n, seconds, every) = match args.as_slice() {
        [n, s] => (*n, *s, 1),
        [n, s, e] => (*n, *s, *e),
        _ => panic!("usage: crowd_rtf ROBOTS SECONDS [TRACE_EVERY|0] [jsonl|bin]"),
    };
    let (floor, setups) = common::open_floor(n as usize);
    let opts = SimOptions {
        record: false,
        ..SimOptions::default()
    };
    let mut sim = Sim::new(&floor, &setups, opts).unwrap();
    let steps = (seconds as f64 / DT).round() as u64;
    let mut sink: Box<dyn std::io::Write + Send> = match std::env::var_os("CROWD_TRACE") {
        Some(path) => Box::new(std::io::BufWriter::new(
            std::fs::File::create(path).expect("CROWD_TRACE is a writable path"),
        )),
        None => Box::new(std::io::sink()),
    };
    let trace = (every > 0).then(|| TraceOut {
        writer: &mut sink,
        every,
        name: "sink".into(),
        format,
    });
    let mut rec = Recorder::new(&sim, steps + 1, Vec::new(), trace);
    let (wall, cpu) = (Instant::now(), cpu_seconds());
    // As `poinav simulate` runs it: the loop on a thread of the pool.
    poinav_sim::on_pool(n as usize, || {
        for k in 0..=steps {
            sim.tick(k < steps);
            rec.after_tick(&sim, DT).unwrap();
        }
        rec.finish().unwrap();
    });
    let (wall, cpu) = (wall.elapsed().as_secs_f64(), cpu_seconds() - cpu);
    println!(
        "{n} robots, {seconds} s, trace every {every} ({format:?}): wall {wall:.3} s = {:.1}x real time; CPU {cpu:.2} s = {:.1}x real time per core; {} threads",
        seconds as f64 / wall,
        seconds as f64 / cpu,
        rayon::current_num_threads()
    );
}
