//! Prints each space's footprint and the doors the facts context finds for it:
//! `cargo run -p poinav-poi --example adjacency FILE`.

fn main() {
    let path = std::env::args().nth(1).expect("usage: adjacency FILE");
    let model = poinav_ifc::Model::open(&path).expect("readable IFC");
    let ctx = poinav_poi::FactContext::new(&model);
    println!(
        "doors from space boundaries: {}",
        ctx.doors_from_space_boundaries()
    );
    let mut cache = poinav_geom::PlacementCache::new(&model);
    for d in model.instances_of("IfcDoor") {
        if let Ok(g) = poinav_geom::door_geometry(&mut cache, d) {
            println!("door {} centre {:.2?}", d.id(), g.center);
        }
    }
    for s in model.instances_of("IfcSpace") {
        let f = ctx.footprint(s.id());
        println!(
            "{} {:?} area {:?} z {:?} doors {:?}",
            s.id(),
            s.get_str("LongName"),
            f.map(|f| f.area()),
            f.map(|f| (f.z_min, f.z_max)),
            ctx.doors_of_space(s.id())
        );
    }
}
