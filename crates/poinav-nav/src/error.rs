//! Errors of navigation: bad input, unknown places, unreachable goals, output failures.

use std::path::PathBuf;

use crate::route::Unreachable;

/// What went wrong.
#[derive(Debug, thiserror::Error)]
pub enum NavError {
    /// An option or an input value is out of range.
    #[error("{0}")]
    Invalid(String),
    /// No storey, space or point by that name.
    #[error("{0}")]
    NotFound(String),
    /// No route: the reason names the door or transition that blocks it.
    #[error("{0}")]
    Unreachable(Box<Unreachable>),
    /// Writing an output file failed.
    #[error("cannot write {}: {source}", path.display())]
    Write {
        /// The file.
        path: PathBuf,
        /// The cause.
        source: std::io::Error,
    },
}
