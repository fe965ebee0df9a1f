//! Per product of a model: triangles, closed or not, edges of its section's outline before the
//! polygon boolean, and the time its section takes, for the storey band of the lowest storey
//! the product stands on; the slowest first:
//! `cargo run --release -p poinav-geom --example section_stats -- FILE [COUNT]`.

use std::time::Instant;

use poinav_geom::section::{
    is_closed, mesh_section, mesh_section_within, SectionBounds, SectionLimit,
};
use poinav_geom::{floor_plans_with_meshes, mesh_model, PlanOptions};
use poinav_ifc::Model;

fn main() {
    let mut args = std::env::args().skip(1);
    let path = args.next().expect("an IFC file");
    let count: usize = args.next().and_then(|c| c.parse().ok()).unwrap_or(20);
    let model = Model::open(&path).expect("a readable IFC file");
    let meshes = mesh_model(&model);
    let plans = floor_plans_with_meshes(&model, &meshes, &PlanOptions::default());
    let mut rows = Vec::new();
    for m in &meshes.elements {
        let Some((lo, _)) = m.mesh.bounds() else {
            continue;
        };
        // The band of the highest storey at or below the element's lowest point.
        let band = plans
            .iter()
            .rfind(|p| p.elevation_m <= lo.z + 0.01)
            .or(plans.first())
            .map_or((0.05, 1.0), |p| p.band);
        let none = SectionBounds {
            max_edges: 0,
            ..SectionBounds::unbounded()
        };
        let edges = match mesh_section_within(&m.mesh, band.0, band.1, &none) {
            Err(c) => match c.limit {
                SectionLimit::Edges { edges, .. } => edges,
                SectionLimit::Time { .. } => 0,
            },
            Ok(_) => 0,
        };
        let t = Instant::now();
        let r = mesh_section(&m.mesh, band.0, band.1);
        let s = t.elapsed().as_secs_f64();
        let points: usize = r.iter().flat_map(|r| r.rings()).map(|r| r.len()).sum();
        rows.push((
            s,
            m.product,
            m.class.clone(),
            m.mesh.triangles.len(),
            is_closed(&m.mesh),
            edges,
            points,
        ));
    }
    let total: f64 = rows.iter().map(|r| r.0).sum();
    rows.sort_by(|a, b| b.0.total_cmp(&a.0));
    println!("{} elements, sections {total:.3} s in all", rows.len());
    for (s, id, class, tris, closed, edges, points) in rows.iter().take(count) {
        println!("{s:.4} s {id} {class} {tris} triangles closed {closed} edges {edges} -> {points} points");
    }
}
