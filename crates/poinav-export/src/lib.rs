//! Exporters that read poinav's results: the semantic CSV of an enrichment and its IDS.

pub mod ids;
pub mod semantic_csv;

/// Why an export failed.
#[derive(Debug, thiserror::Error)]
pub enum ExportError {
    /// The output could not be written.
    #[error("cannot write {path}: {message}")]
    Write { path: String, message: String },
}
