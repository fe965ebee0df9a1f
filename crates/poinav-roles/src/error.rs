//! `ProfileError` (why a robot profile could not be read, naming the file at fault) and
//! `UnknownLabel` (a text that is no label of a taxonomy enumeration).

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

/// A text that is none of an enumeration's labels (a role, category, status, protocol...).
#[derive(Debug, Clone, PartialEq, Eq, Error)]
#[error("`{text}` is not a {kind}; expected one of {}", expected.join(", "))]
pub struct UnknownLabel {
    /// The text read.
    pub text: String,
    /// The enumeration's name (`Role`, `AccessibilityStatus`, ...).
    pub kind: &'static str,
    /// Its labels, in declaration order.
    pub expected: Vec<&'static str>,
}
