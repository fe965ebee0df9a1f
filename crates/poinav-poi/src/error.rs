//! `PoiError`: why rules, profiles or enrichment failed, naming the file (and rule) at fault.

/// Errors of the POI layer.
#[derive(Debug, thiserror::Error)]
pub enum PoiError {
    /// A file could not be read (the message names the cause too, for one-line callers).
    #[error("{file}: {source}")]
    Io {
        file: String,
        #[source]
        source: std::io::Error,
    },
    /// A TOML file is malformed (the cause carries line and column).
    #[error("{file}: {source}")]
    Toml {
        file: String,
        #[source]
        source: Box<toml::de::Error>,
    },
    /// A value in a file is out of range or inconsistent.
    #[error("{file}: {message}")]
    Invalid { file: String, message: String },
    /// A rule is malformed.
    #[error("{file}: rule `{rule}`: {message}")]
    Rule {
        file: String,
        rule: String,
        message: String,
    },
    /// A rule's condition (`when`, `when_any`, a conditional role's `when`) cannot be read.
    #[error("{file}: rule `{rule}`: condition `{condition}`")]
    Condition {
        file: String,
        rule: String,
        condition: String,
        #[source]
        source: crate::condition::ConditionError,
    },
    /// A robot profile could not be read.
    #[error(transparent)]
    Profile(#[from] poinav_roles::ProfileError),
    /// Writing the enriched model failed.
    #[error(transparent)]
    Edit(#[from] poinav_ifc::EditError),
}
