//! Fuzz target: enriching any readable model gives a file that reads back, keeps every original
//! instance byte for byte, and enriches again to the same bytes.
#![no_main]

use libfuzzer_sys::fuzz_target;
use poinav_ifc::Model;
use poinav_poi::{classify, write_enrichment, RobotProfile, RuleSet, WriteOptions};

fuzz_target!(|data: &[u8]| {
    let Ok(model) = Model::from_bytes("fuzz.ifc", data.to_vec()) else {
        return;
    };
    let rules = RuleSet::defaults();
    let profile = RobotProfile::paper();
    let opts = WriteOptions {
        prefix: "Pset_".into(),
        timestamp: "2026-01-01T00:00:00".into(),
    };
    let Ok(editor) = write_enrichment(&model, &classify(&model, &rules, &profile), &opts) else {
        return;
    };
    let once = editor.to_bytes();
    let reread = Model::from_bytes("once.ifc", once.clone()).expect("enriched output re-reads");
    for e in model.entities() {
        if let Some(w) = reread.entity(e.id()) {
            assert_eq!(w.raw(), e.raw(), "original instance changed");
        }
    }
    let again = write_enrichment(&reread, &classify(&reread, &rules, &profile), &opts)
        .expect("re-enrichment");
    assert_eq!(again.to_bytes(), once, "enrichment is idempotent");
});
