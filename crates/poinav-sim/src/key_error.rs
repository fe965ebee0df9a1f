//! `KeyError`: a key name that is not one of its scheme's keys.

use crate::controller::KeyScheme;

/// A key name not in its scheme (`Up` for W A S D).
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("key `{name}` is not one of {}", keys(*scheme))]
pub struct KeyError {
    /// The name given.
    pub name: String,
    /// The scheme it was looked up in.
    pub scheme: KeyScheme,
}

fn keys(scheme: KeyScheme) -> &'static str {
    match scheme {
        KeyScheme::Arrows => "Up, Down, Left, Right, Brush",
        KeyScheme::Wasd => "W, A, S, D, Brush",
    }
}
