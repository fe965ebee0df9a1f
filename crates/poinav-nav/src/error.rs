//! Errors of navigation: bad input, unknown or ambiguous places, places without room for the
//! robot, unreachable goals, output failures.

use std::path::PathBuf;

use crate::route::Unreachable;
use crate::space_name::Ambiguous;

/// What went wrong.
#[derive(Debug, thiserror::Error)]
pub enum NavError {
    /// An option or an input value is out of range.
    #[error("{0}")]
    Invalid(String),
    /// A speed fraction is out of range.
    #[error(transparent)]
    Speed(#[from] crate::speed::SpeedError),
    /// No storey, space or point by that name.
    #[error("{0}")]
    NotFound(String),
    /// A name that fits several spaces: the candidates, each with what selects only it.
    #[error("{0}")]
    Ambiguous(Box<Ambiguous>),
    /// The robot has no room: the place named has no spot where it fits, or no entrance lets
    /// it in (the answer is no, as for [`NavError::Unreachable`]; not a bad input).
    #[error("{0}")]
    NoRoom(String),
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
