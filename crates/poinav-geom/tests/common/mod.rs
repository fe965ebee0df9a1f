//! Shared helpers for the integration tests (from `poinav-testkit`): workspace paths, the
//! corpus, IfcOpenShell's Python with shapely.

#![allow(dead_code, unused_imports)]

use std::path::PathBuf;

pub use poinav_testkit::{corpus, corpus_file, json_of, root, shared, spawn_ifcos};

/// The Python that has IfcOpenShell and shapely (panics, never skips, when it is missing).
pub fn python() -> PathBuf {
    poinav_testkit::python("ifcopenshell, shapely")
}

/// A box an IfcOpenShell script (or an exact expectation) wrote as `{"min": [x, y, z],
/// "max": [x, y, z]}`, and how far a mesh's box is from it.
#[derive(Debug, Clone, Copy)]
pub struct ReferenceBox {
    /// The lower corner.
    pub lo: [f64; 3],
    /// The upper corner.
    pub hi: [f64; 3],
}

impl ReferenceBox {
    /// The box of `reference`; panics naming `what` when a corner is missing (IfcOpenShell
    /// gave no shape).
    pub fn of(reference: &serde_json::Value, what: &str) -> ReferenceBox {
        let corner = |k: &str| -> [f64; 3] {
            let v = reference[k].as_array().unwrap_or_else(|| {
                panic!("{what}: no {k} (IfcOpenShell gives no shape?): {reference}")
            });
            [0, 1, 2].map(|i| v[i].as_f64().expect("a coordinate"))
        };
        ReferenceBox {
            lo: corner("min"),
            hi: corner("max"),
        }
    }

    /// The largest difference over every coordinate of both corners between this box and
    /// `(lo, hi)`, metres.
    pub fn error(&self, (lo, hi): (glam::DVec3, glam::DVec3)) -> f64 {
        (0..3)
            .map(|i| (lo[i] - self.lo[i]).abs().max((hi[i] - self.hi[i]).abs()))
            .fold(0.0, f64::max)
    }
}
