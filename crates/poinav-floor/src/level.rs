//! Where each storey's walking level comes from ([`FloorLevel`]) and which storeys are at
//! ground level, where a door with one side outside is an entrance ([`ground_levels`]); on
//! other storeys only a door that opens onto the terrain is ([`Entrance`]).

use serde::{Deserialize, Serialize};

/// How far a storey's walking level may be from the ground storey's and still be at ground
/// level (a raised ground floor, a split level), metres.
pub const GROUND_TOLERANCE_M: f64 = 1.2;

/// What a storey's walking level was taken from.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum LevelSource {
    /// The storey's own elevation (its placement, else `Elevation`): the floor slabs and
    /// spaces agree with it, or there are none.
    #[default]
    StoreyElevation,
    /// The top of the storey's floor slabs, which disagrees with its elevation.
    FloorSlabs,
    /// The bottom of the storey's spaces, which disagrees with its elevation (no floor slabs).
    Spaces,
}

impl LevelSource {
    /// `storey-elevation`, `floor-slabs`, `spaces`.
    pub fn label(self) -> &'static str {
        match self {
            LevelSource::StoreyElevation => "storey-elevation",
            LevelSource::FloorSlabs => "floor-slabs",
            LevelSource::Spaces => "spaces",
        }
    }
}

/// How an entrance (a door with a space on one side only whose other side is outside) is
/// reached from outside.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Entrance {
    /// On a storey at ground level ([`FloorLevel::at_ground`]).
    Ground,
    /// On a storey not at ground level (above or below), but its outside opens onto the
    /// terrain at that storey's walking level (a hillside door, [`crate::FloorDoor::terrain`]).
    Terrain,
}

impl Entrance {
    /// `ground`, `terrain`.
    pub fn label(self) -> &'static str {
        match self {
            Entrance::Ground => "ground",
            Entrance::Terrain => "terrain",
        }
    }
}

/// One storey's level: what the model says and what robots walk on.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct FloorLevel {
    /// The storey's elevation as the model gives it, world metres.
    pub storey_elevation_m: f64,
    /// The level robots walk on (the floor's `elevation_m`), world metres.
    pub walking_level_m: f64,
    /// Where the walking level comes from.
    pub from: LevelSource,
    /// The storey is at ground level: a door with a space on one side only whose other side
    /// is outside is an entrance there; on other storeys it leads onto a balcony, a terrace,
    /// a light well or a drop, never into the building from outside, unless it opens onto
    /// the terrain ([`Entrance::Terrain`]).
    pub at_ground: bool,
}

/// Marks the storeys at ground level among `levels` (their walking levels and whether the
/// storey has anything to navigate): the ground storey is the one with spaces or doors whose
/// walking level is nearest the model's zero (IFC's ±0.00 is the ground floor) when one is
/// within [`GROUND_TOLERANCE_M`] of it, else the lowest one with spaces or doors; every storey
/// within [`GROUND_TOLERANCE_M`] of its level is at ground level.
pub fn ground_levels(levels: &[(f64, bool)]) -> Vec<bool> {
    let used = || levels.iter().filter(|(_, u)| *u).map(|(z, _)| *z);
    let near_zero = used()
        .filter(|z| z.abs() <= GROUND_TOLERANCE_M)
        .min_by(|a, b| a.abs().total_cmp(&b.abs()));
    let ground = near_zero.or_else(|| used().min_by(f64::total_cmp));
    levels
        .iter()
        .map(|(z, _)| ground.is_none_or(|g| (z - g).abs() <= GROUND_TOLERANCE_M))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_ground_storey_is_nearest_zero_else_the_lowest_used() {
        // Basement, ground floor, two upper floors.
        let g = ground_levels(&[(-2.8, true), (0.0, true), (2.85, true), (5.7, true)]);
        assert_eq!(g, [false, true, false, false]);
        // A raised ground floor and an empty storey at zero.
        let g = ground_levels(&[(0.0, false), (0.9, true), (3.9, true)]);
        assert_eq!(g, [true, true, false]);
        // Absolute elevations (above sea level): the lowest used storey.
        let g = ground_levels(&[(312.0, true), (315.0, true)]);
        assert_eq!(g, [true, false]);
        assert_eq!(ground_levels(&[(4.0, false)]), [true]);
    }
}
