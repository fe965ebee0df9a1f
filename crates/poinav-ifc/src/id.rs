//! `EntityId`: the `#id` of a STEP instance.

use std::fmt;

/// The `#id` of an instance in a STEP file (`#42` is `EntityId(42)`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct EntityId(pub u64);

impl fmt::Display for EntityId {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "#{}", self.0)
    }
}
