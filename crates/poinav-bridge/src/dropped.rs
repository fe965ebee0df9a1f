//! What the bridge left out of a building, and why: stairs, ramps and lifts that connect no
//! storeys, terrain bodies that could not be meshed.

use poinav_nav::ConnectionKind;

/// What a left-out part would have been.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum DroppedKind {
    /// A stair, ramp or lift.
    Connection(ConnectionKind),
    /// A terrain body (an `IfcSite`'s) that could not be meshed.
    Terrain,
}

impl DroppedKind {
    /// `stair`, `ramp`, `lift`, `terrain`.
    pub fn label(self) -> &'static str {
        match self {
            DroppedKind::Connection(k) => k.label(),
            DroppedKind::Terrain => "terrain",
        }
    }

    /// Why such a part is left out, in general: `it connects no storeys`.
    pub fn why(self) -> &'static str {
        match self {
            DroppedKind::Connection(_) => "it connects no storeys",
            DroppedKind::Terrain => "its body cannot be meshed",
        }
    }
}

/// A part of the model the bridge left out.
#[derive(Debug, Clone, PartialEq)]
pub struct Dropped {
    /// GlobalId.
    pub id: String,
    /// Name.
    pub name: Option<String>,
    /// What it would have been.
    pub kind: DroppedKind,
    /// Why it was left out.
    pub reason: String,
}

impl Dropped {
    /// `stair Stair A (2Xk...) is left out, it connects no storeys: REASON`.
    pub fn message(&self) -> String {
        let name = match &self.name {
            Some(n) => format!("{n} ({})", self.id),
            None => self.id.clone(),
        };
        format!(
            "{} {name} is left out, {}: {}",
            self.kind.label(),
            self.kind.why(),
            self.reason
        )
    }

    /// The message without the part's name, for grouping like ones.
    pub fn group(&self) -> String {
        format!("left out, {}: {}", self.kind.why(), self.reason)
    }
}
