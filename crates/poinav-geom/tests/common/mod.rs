//! Shared helpers for the integration tests (from `poinav-testkit`): workspace paths, the
//! corpus, IfcOpenShell's Python with shapely.

#![allow(dead_code, unused_imports)]

use std::path::PathBuf;

pub use poinav_testkit::{corpus, corpus_file, json_of, root, shared, spawn_ifcos};

/// The Python that has IfcOpenShell and shapely (panics, never skips, when it is missing).
pub fn python() -> PathBuf {
    poinav_testkit::python("ifcopenshell, shapely")
}
