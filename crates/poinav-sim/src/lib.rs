//! Multi-robot simulation on a plain floor model ([`poinav_nav::Floor`], never IFC types):
//! robots with the paper's limits and 5-ray sensors on a fixed 60 Hz step, Algorithm 1 turning
//! POI roles into navigation actions and runtime role/status changes, scenario files with
//! expectations, deterministic JSON Lines traces, summaries and SVG plots.
//!
//! ```no_run
//! use std::path::Path;
//! let scenario = poinav_sim::Scenario::load(Path::new("scenarios/separation.toml"))?;
//! # fn floor() -> poinav_nav::Floor { unimplemented!() }
//! // The floor comes from the building's preparation, `poinav_bridge::prepare`.
//! let floor = floor();
//! let outcome = poinav_sim::run(&scenario, None, &floor)?;
//! poinav_sim::write_outputs(Path::new("out/separation"), &outcome, &floor)?;
//! assert!(outcome.passed());
//! # Ok::<(), poinav_sim::SimError>(())
//! ```

pub mod algorithm1;
pub mod controller;
mod error;
pub mod events;
pub mod expect;
pub mod geometry;
pub mod give_way;
mod key_error;
pub mod neighbours;
pub mod output;
pub mod plan;
pub mod plot;
pub mod poi_db;
pub mod recorder;
pub mod robot;
mod run;
pub mod samples;
pub mod scenario;
pub mod sensor;
pub mod step;
#[cfg(test)]
mod test_floor;
pub mod trace;
pub mod trace_bin;
pub mod world;

pub use error::SimError;
pub use events::{Event, EventKind};
pub use key_error::KeyError;
pub use output::{run_into, run_into_as, write_outputs};
pub use recorder::{Recorder, RobotFigures, TraceFormat, TraceOut};
pub use run::{on_pool, run, run_with, Outcome, KEEP_BUSY_ROBOTS};
pub use scenario::Scenario;
pub use step::{RobotSetup, Sim, SimOptions, DT};

/// The scenarios shipped with the crate (`scenarios/*.toml`): name and file text. The paper's
/// three, and one per other coordination protocol (YIELD, PRIORITY_PASS).
pub const SHIPPED: &[(&str, &str)] = &[
    ("doorway", include_str!("../scenarios/doorway.toml")),
    ("separation", include_str!("../scenarios/separation.toml")),
    (
        "wall-following",
        include_str!("../scenarios/wall-following.toml"),
    ),
    ("yield", include_str!("../scenarios/yield.toml")),
    (
        "priority-pass",
        include_str!("../scenarios/priority-pass.toml"),
    ),
];
