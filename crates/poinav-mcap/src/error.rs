//! Why a recording could not be written.

use std::path::PathBuf;

/// An error writing a recording.
#[derive(Debug, thiserror::Error)]
pub enum McapError {
    /// Reading the trace or writing the file failed.
    #[error("{path}: {source}")]
    Io {
        /// The file.
        path: PathBuf,
        /// Why.
        source: std::io::Error,
    },
    /// The MCAP writer refused.
    #[error("{path}: MCAP: {source}")]
    Mcap {
        /// The file.
        path: PathBuf,
        /// Why.
        source: mcap::McapError,
    },
    /// A trace line is not what `poinav simulate` writes.
    #[error("{name}:{line}: {message}")]
    Trace {
        /// The trace's name (a path).
        name: String,
        /// Line number, from 1.
        line: u64,
        /// What is wrong.
        message: String,
    },
    /// The storey's map could not be made.
    #[error("the storey's map: {0}")]
    Map(#[from] poinav_nav::NavError),
}
