//! Errors of the BCF writer.

use std::path::PathBuf;

/// Why a BCF file could not be made or written.
#[derive(Debug, thiserror::Error)]
pub enum BcfError {
    /// Rasterising a storey for a snapshot failed.
    #[error("snapshot of storey `{floor}` for {profile}")]
    Grid {
        /// Storey name.
        floor: String,
        /// Profile name.
        profile: String,
        /// Why.
        #[source]
        source: poinav_nav::NavError,
    },
    /// The audit names a profile that was not given (the report and the profiles disagree).
    #[error("the audit has {audited} profiles but {given} were given")]
    Profiles {
        /// Profiles in the report.
        audited: usize,
        /// Profiles given.
        given: usize,
    },
    /// Encoding a snapshot PNG failed.
    #[error("encoding snapshot {name}")]
    Png {
        /// Entry name in the archive.
        name: String,
        /// Why.
        #[source]
        source: png::EncodingError,
    },
    /// Building the zip archive failed.
    #[error("writing zip entry {name}")]
    Zip {
        /// Entry name.
        name: String,
        /// Why.
        #[source]
        source: zip::result::ZipError,
    },
    /// Writing the file failed.
    #[error("cannot write {}", path.display())]
    Write {
        /// Output path.
        path: PathBuf,
        /// Why.
        #[source]
        source: std::io::Error,
    },
}
