//! The one bridge from IFC to the building robots navigate: [`building`] turns an opened model
//! and its POI classification into a [`poinav_nav::Building`] (every storey as a floor with
//! roles, statuses and the spaces each door joins, the stairs, ramps and lifts between storeys,
//! doors onto the terrain) and says what it left out and why ([`Dropped`]). Every command uses
//! it: route, audit, export nav2, simulate, serve, demo and the Python package.
//!
//! Scenario preparation ([`prepare`]: the test building or an IFC file, design patches,
//! enrichment, the building) and the write-back of a run's findings into a copy of the IFC
//! ([`write_back`]) live here too, so that `poinav-nav` and `poinav-sim` know no IFC.
//!
//! ```no_run
//! use std::path::Path;
//! let scenario = poinav_sim::Scenario::load(Path::new("scenarios/separation.toml"))?;
//! let prepared = poinav_bridge::prepare(&scenario, None)?;
//! let outcome = poinav_sim::run(&scenario, None, prepared.floor())?;
//! poinav_sim::write_outputs(Path::new("out/separation"), &outcome, prepared.floor())?;
//! assert!(outcome.passed());
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

mod building;
pub mod demo_floor;
mod dropped;
mod error;
mod ifc_floor;
mod prepare;
pub mod terrain;
pub mod vertical;
mod write_back;

pub use building::{building, Bridged, Stages};
pub use dropped::{Dropped, DroppedKind};
pub use error::BridgeError;
pub use ifc_floor::{pick, StoreyKey};
pub use prepare::{prepare, prepare_with_meshes, Prepared, STAMP};
pub use write_back::{apply_findings, write_back};
