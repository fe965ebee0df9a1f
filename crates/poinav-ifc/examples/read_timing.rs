//! Prints how long each stage of reading a file takes: `cargo run --release --example read_timing FILE`.

use std::time::Instant;

fn main() {
    let path = std::env::args().nth(1).expect("usage: read_timing FILE");
    let t = Instant::now();
    let bytes = std::fs::read(&path).expect("readable file");
    let read = t.elapsed();
    let t = Instant::now();
    let model = poinav_ifc::Model::from_bytes(&path, bytes).expect("valid IFC");
    let index = t.elapsed();
    let t = Instant::now();
    let unit = poinav_ifc::units::length_unit(&model);
    let s = poinav_ifc::spatial::spatial_structure(&model, &unit);
    let doors: usize = model
        .instances_of("IfcDoor")
        .iter()
        .filter(|d| poinav_ifc::spatial::storey_of(**d).is_some())
        .count();
    let rest = t.elapsed();
    let mb = model.bytes().len() as f64 / 1e6;
    println!(
        "{path}: {} instances, read {:.1} ms, index+check {:.1} ms ({:.0} MB/s), units+spatial+{doors} door storeys ({} storeys) {:.1} ms",
        model.len(),
        read.as_secs_f64() * 1e3,
        index.as_secs_f64() * 1e3,
        mb / index.as_secs_f64(),
        s.storeys.len(),
        rest.as_secs_f64() * 1e3
    );
}
