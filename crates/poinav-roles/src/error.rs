//! `ProfileError`: why a robot profile could not be read, naming the file at fault.

use thiserror::Error;

/// Errors of reading a robot profile.
#[derive(Debug, Error)]
pub enum ProfileError {
    /// The file could not be read (the message carries the cause too, for callers that show
    /// one line).
    #[error("{file}: {source}")]
    Io {
        /// The file.
        file: String,
        /// Why.
        #[source]
        source: std::io::Error,
    },
    /// The TOML is malformed (the message carries line and column).
    #[error("{file}: {message}")]
    Toml {
        /// The file (or the text's origin).
        file: String,
        /// What and where.
        message: String,
    },
    /// A value is out of range or inconsistent.
    #[error("{file}: {message}")]
    Invalid {
        /// The file (or the text's origin).
        file: String,
        /// What.
        message: String,
    },
}
