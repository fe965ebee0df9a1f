//! Times `mesh_model` on IFC files: `cargo run --release -p poinav-geom --example mesh_timing -- FILE... [--threads N] [--runs N] [--failures]`.

use std::time::Instant;

use poinav_geom::mesh_model;
use poinav_ifc::Model;

fn main() {
    let mut files = Vec::new();
    let mut threads = 0usize;
    let mut runs = 3usize;
    let mut show_failures = false;
    let mut args = std::env::args().skip(1);
    while let Some(a) = args.next() {
        match a.as_str() {
            "--threads" => {
                threads = args
                    .next()
                    .and_then(|v| v.parse().ok())
                    .expect("--threads N")
            }
            "--runs" => runs = args.next().and_then(|v| v.parse().ok()).expect("--runs N"),
            "--failures" => show_failures = true,
            _ => files.push(a),
        }
    }
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .expect("thread pool");
    for file in files {
        let model = Model::open(&file).expect("readable IFC");
        let mut times = Vec::new();
        let mut last = None;
        for _ in 0..runs.max(1) {
            let start = Instant::now();
            let m = pool.install(|| mesh_model(&model));
            times.push(start.elapsed().as_secs_f64());
            last = Some(m);
        }
        times.sort_by(f64::total_cmp);
        let m = last.expect("one run");
        let tris: usize = m
            .elements
            .iter()
            .chain(&m.spaces)
            .map(|e| e.mesh.triangles.len())
            .sum();
        println!(
            "{file}: {} elements, {} spaces, {} failures, {tris} triangles; median {:.3} s ({} threads)",
            m.elements.len(),
            m.spaces.len(),
            m.failures.len(),
            times[times.len() / 2],
            pool.current_num_threads()
        );
        if show_failures {
            for (id, e) in &m.failures {
                println!("  {id}: {e}");
            }
        }
    }
}
