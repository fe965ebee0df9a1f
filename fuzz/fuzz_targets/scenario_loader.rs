//! Fuzz target: loading any text as a simulation scenario never panics; a loaded scenario
//! answers its variant questions without panicking.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else { return };
    if let Ok(s) = poinav_sim::Scenario::from_toml(text, "fuzz.toml", std::path::Path::new(".")) {
        for name in s.variant_names() {
            let _ = s.variant(Some(name));
        }
        let _ = s.variant(None);
    }
});
