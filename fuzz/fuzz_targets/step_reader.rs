//! Fuzz target: reading any bytes never panics, and a readable model written back unchanged
//! reproduces the input byte for byte.
#![no_main]

use libfuzzer_sys::fuzz_target;
use poinav_ifc::{property, spatial, units, Editor, Model};

fuzz_target!(|data: &[u8]| {
    let Ok(model) = Model::from_bytes("fuzz.ifc", data.to_vec()) else {
        return;
    };
    for e in model.entities().take(2000) {
        let _ = e.args();
        let _ = e.type_name();
        let _ = e.global_id();
        let _ = spatial::storey_of(e);
        if e.is_a("IfcObject") {
            let _ = property::property_sets(e);
        }
    }
    let unit = units::length_unit(&model);
    let _ = spatial::spatial_structure(&model, &unit);
    assert_eq!(
        Editor::new(&model).to_bytes(),
        data,
        "an unchanged model must be written back as read"
    );
});
