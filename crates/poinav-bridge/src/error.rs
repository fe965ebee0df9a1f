//! `BridgeError`: why a building could not be made from a model or a scenario's building could
//! not be prepared, with the error that caused it as its source.

use thiserror::Error;

/// What can go wrong between a model and its building.
#[derive(Debug, Error)]
pub enum BridgeError {
    /// No storey has the Name or GlobalId asked for.
    #[error("no storey named `{name}`; the model has: {storeys}")]
    NoSuchStorey {
        /// What was asked for.
        name: String,
        /// The storeys there are, by label.
        storeys: String,
    },
    /// The model has no storey at all.
    #[error("the model has no storey to plan")]
    NoStorey,
    /// The test building lacks an element its layout names (a bug, or a patched copy that
    /// renamed it).
    #[error("building: the model has no {class} named `{name}`")]
    MissingElement {
        /// IFC class.
        class: &'static str,
        /// Name.
        name: String,
    },
    /// The scenario names no building.
    #[error("building: no building")]
    NoBuilding,
    /// Generating the test building failed.
    #[error("building: the test building")]
    Generate(#[source] poinav_author::AuthorError),
    /// A design patch failed.
    #[error("building: patch door `{door}`")]
    Patch {
        /// The door asked for.
        door: String,
        /// Why.
        #[source]
        source: poinav_author::AuthorError,
    },
    /// The building's IFC file cannot be read.
    #[error("{path}")]
    Io {
        /// The file.
        path: String,
        /// Why.
        #[source]
        source: std::io::Error,
    },
    /// The building's IFC data is not a readable model.
    #[error("building")]
    Read(#[source] poinav_ifc::ReadError),
    /// The scenario's robot profile.
    #[error(transparent)]
    Profile(#[from] poinav_poi::ProfileError),
    /// Rules or the write-back.
    #[error(transparent)]
    Poi(#[from] poinav_poi::PoiError),
    /// The scenario (its variant or profile).
    #[error(transparent)]
    Sim(#[from] poinav_sim::SimError),
}
