//! `AuthorError`: why a building could not be written or patched.

use poinav_ifc::EntityId;

/// Errors of the authoring layer.
#[derive(Debug, thiserror::Error)]
pub enum AuthorError {
    /// No door matches the name or GlobalId given.
    #[error("no door is named or has the GlobalId `{0}`")]
    NoSuchDoor(String),
    /// Several doors share the name given.
    #[error("{count} doors are named `{name}` ({ids}); give a GlobalId")]
    AmbiguousDoor {
        name: String,
        count: usize,
        ids: String,
    },
    /// A requested size is not a positive finite number.
    #[error("{what} must be a positive number of metres, not {value}")]
    BadSize { what: &'static str, value: f64 },
    /// The door's instance cannot be read.
    #[error("{0}: {1}")]
    Unreadable(EntityId, String),
    /// An edit was refused.
    #[error(transparent)]
    Edit(#[from] poinav_ifc::EditError),
    /// The template model could not be read (a bug).
    #[error(transparent)]
    Read(#[from] poinav_ifc::ReadError),
}
