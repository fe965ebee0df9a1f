//! Fuzz target: loading any text as a rule file or a robot profile never panics.
#![no_main]

use libfuzzer_sys::fuzz_target;
use poinav_poi::{RobotProfile, RuleSet};

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    if let Ok((rules, _)) = RuleSet::from_toml(text, "fuzz.toml") {
        let _ = rules.classes();
    }
    let _ = RobotProfile::from_toml(text, "fuzz.toml");
});
