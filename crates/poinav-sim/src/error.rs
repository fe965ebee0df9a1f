//! Errors of scenario loading, set-up and output.

use thiserror::Error;

/// What can go wrong.
#[derive(Debug, Error)]
pub enum SimError {
    /// A scenario file is wrong at a line.
    #[error("{file}:{line}: {message}")]
    Scenario {
        /// File.
        file: String,
        /// Line (1-based).
        line: usize,
        /// What.
        message: String,
    },
    /// A robot cannot be set up on the floor.
    #[error("robot `{robot}`: {message}")]
    Setup {
        /// Robot name.
        robot: String,
        /// What.
        message: String,
    },
    /// Reading or writing a file.
    #[error("{path}: {message}")]
    Io {
        /// Path.
        path: String,
        /// What.
        message: String,
    },
    /// A robot profile could not be read.
    #[error(transparent)]
    Profile(#[from] poinav_roles::ProfileError),
}
