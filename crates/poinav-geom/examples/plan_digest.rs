//! Prints a digest of the floor plans of IFC files (per item: storey, GlobalId, kind, source,
//! region count, area, bounds; per plan: doors, doorways, problems) and the time each file's
//! plans took, to compare plan outputs before and after a change:
//! `cargo run --release -p poinav-geom --example plan_digest -- FILE...`.

use std::time::Instant;

use poinav_geom::{floor_plans, PlanOptions};
use poinav_ifc::Model;

fn main() {
    for path in std::env::args().skip(1) {
        let model = match Model::open(&path) {
            Ok(m) => m,
            Err(e) => {
                eprintln!("{path}: {e}");
                std::process::exit(2);
            }
        };
        let t = Instant::now();
        let plans = floor_plans(&model, &PlanOptions::default());
        eprintln!("{path}: {:.3} s", t.elapsed().as_secs_f64());
        let name = path.rsplit('/').next().unwrap_or(&path);
        for plan in &plans {
            let storey = plan.storey_name.as_deref().unwrap_or("-");
            println!(
                "{name} | {storey} | doors {} | doorways {} | problems {}",
                plan.doors.len(),
                plan.openings.len(),
                plan.problems.len()
            );
            for item in &plan.items {
                let (lo, hi) = poinav_geom::region::bounds_of(&item.regions)
                    .unwrap_or((glam::DVec2::ZERO, glam::DVec2::ZERO));
                println!(
                    "{name} | {storey} | {} {} | {:?} | {} {:?} | {:?} | {:.6} | {:.4} {:.4} {:.4} {:.4}",
                    item.product,
                    item.global_id,
                    item.kind,
                    item.regions.len(),
                    item.regions.iter().map(|r| r.holes.len()).sum::<usize>(),
                    item.source,
                    item.area(),
                    lo.x,
                    lo.y,
                    hi.x,
                    hi.y
                );
            }
        }
    }
}
