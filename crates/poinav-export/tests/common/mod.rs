//! Shared helpers for poinav-export's integration tests (from `poinav-testkit`): workspace
//! paths, the corpus, and IfcOpenShell's Python with ifctester.

#![allow(dead_code, unused_imports)]

use std::path::PathBuf;

pub use poinav_testkit::{corpus, root, shared};

/// The Python with IfcOpenShell and ifctester (panics, never skips, when either is missing).
pub fn python() -> PathBuf {
    poinav_testkit::python("ifcopenshell, ifctester.ids")
}

/// Runs a script from `tests/ifcos/` with that Python and parses its JSON output.
pub fn ifcos(script: &str, args: &[&std::ffi::OsStr]) -> serde_json::Value {
    poinav_testkit::ifcos_with(&python(), script, args)
}
