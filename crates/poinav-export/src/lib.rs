//! Exporters that read poinav's results: the semantic CSV of an enrichment and its IDS,
//! 3D exports of element meshes as binary glTF ([`glb`], or one GLB per storey:
//! [`glb_chunks`]) and binary FBX 7.4 ([`fbx`]), and storey floor plans as SVG drawings
//! ([`plan_svg`]).

pub mod fbx;
pub mod glb;
pub mod glb_chunks;
pub mod ids;
pub mod instances;
pub mod palette;
pub mod plan_svg;
pub mod quantise;
pub mod scene;
pub mod semantic_csv;

pub use scene::SceneInput;

/// Why an export failed.
#[derive(Debug, thiserror::Error)]
pub enum ExportError {
    /// The output could not be written.
    #[error("cannot write {path}: {message}")]
    Write { path: String, message: String },
}
