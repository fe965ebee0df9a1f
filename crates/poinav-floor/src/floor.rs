//! `Floor`: one storey as plain 2D data (metres, world XY) tagged with GlobalIds, classes, POI
//! roles and the profile-free facts door statuses are computed from
//! ([`crate::door_status`]). Navigation and simulation read this, never IFC.

use glam::DVec2;
use poinav_roles::{CoordinationProtocol, Role};
use serde::{Deserialize, Serialize};

use crate::door_status::Block;
use crate::id::ElementId;
use poinav_plane::{PassageFrame, Ring};

/// What an obstacle is, for maps and sensors.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum ObstacleKind {
    /// Walls, columns, railings: always solid.
    Structure,
    /// Furniture and equipment: solid, or unknown in maps by option.
    Furniture,
    /// A door leaf or frame: solid, or a passage when the door is open.
    DoorLeaf,
    /// Stairs and ramps drawn as obstacles for profiles that cannot use them.
    Transition,
    /// An element whose geometry could only be bounded, not read (in IFC: its section reached
    /// a bound): the rings hold it, but what is free inside them is not known. Unknown in
    /// maps, never free; solid to sensors.
    Unknown,
}

/// Something a robot cannot pass through.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct FloorObstacle {
    /// GlobalId of the IFC element (or a made-up id for hand-built floors).
    pub id: ElementId,
    /// IFC class.
    pub class: String,
    /// Kind.
    pub kind: ObstacleKind,
    /// Outline rings, counter-clockwise, world metres (several for split elements).
    pub rings: Vec<Ring>,
    /// POI roles (primary and conditional).
    pub roles: Vec<Role>,
}

/// A passage between zones.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct FloorDoor {
    /// GlobalId.
    pub id: ElementId,
    /// Name.
    pub name: Option<String>,
    /// The passage region (the opening's footprint), world metres.
    pub ring: Ring,
    /// Centre of the passage.
    pub center: DVec2,
    /// Clear width in metres, geometric: the passage's in plan.
    pub clear_width_m: f64,
    /// The clear width the classification's clear-width rule read from the model (in IFC:
    /// OverallWidth less the linings, else OverallWidth, else the opening's footprint; a
    /// doorway's own width), distinct from the geometric [`FloorDoor::clear_width_m`]; `None`
    /// when it read none or no such rule classified the door (its status is then unknown).
    #[serde(default)]
    pub classified_width_m: Option<f64>,
    /// The rule that blocks the door for every profile, and why; `None` when none does.
    #[serde(default)]
    pub blocked: Option<Block>,
    /// POI roles (A-2, and B-2 when narrow).
    pub roles: Vec<Role>,
    /// The ids ([`FloorZone::id`]) of the spaces the door bounds, when the model says so (in
    /// IFC: `IfcRelSpaceBoundary`): one for an entrance, two for an interior door. `None`:
    /// unknown, the sides come from geometry alone (see `poinav_nav::graph::door_zones`).
    #[serde(default)]
    pub spaces: Option<Vec<ElementId>>,
    /// True for an opening without a door (a doorway; in IFC an `IfcOpeningElement` nothing
    /// fills): nothing opens or closes there, only its width decides whether a robot fits.
    #[serde(default)]
    pub doorless: bool,
    /// Its side outside every space opens onto the terrain at its storey's walking level (a
    /// hillside door on a storey that is not at ground level): an entrance all the same
    /// ([`crate::level::Entrance::Terrain`]). Set by the IFC bridge (`poinav_bridge::terrain`)
    /// from the terrain's meshes; `false` on hand-built floors.
    #[serde(default)]
    pub terrain: bool,
}

/// A space (room, corridor) as a region.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct FloorZone {
    /// GlobalId.
    pub id: ElementId,
    /// Name.
    pub name: Option<String>,
    /// LongName.
    pub long_name: Option<String>,
    /// Outline, counter-clockwise, world metres.
    pub ring: Ring,
    /// POI roles (Destination, A-3 + C-1 for corridors, B-1 for hazards).
    pub roles: Vec<Role>,
    /// MinInterRobotSeparation and CoordinationProtocol of a C-1 zone.
    pub coordination: Option<(f64, CoordinationProtocol)>,
}

/// One storey for navigation and simulation.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
pub struct Floor {
    /// Storey name.
    pub name: String,
    /// Storey elevation in metres.
    pub elevation_m: f64,
    /// Obstacles.
    pub obstacles: Vec<FloorObstacle>,
    /// Doors.
    pub doors: Vec<FloorDoor>,
    /// Spaces.
    pub zones: Vec<FloorZone>,
}

impl FloorDoor {
    /// The passage's frame from the ring alone: the width axis along the ring's longest edge,
    /// unless that extent is narrower than the clear width and the other is not. `None` without
    /// a usable ring. `poinav_nav::DoorFrame::door_frame` also looks at the zones on either side.
    pub fn frame(&self) -> Option<PassageFrame> {
        let f = PassageFrame::of(&self.ring)?;
        let w = self.clear_width_m;
        if w.is_finite() && 2.0 * f.half_width < w - 1e-6 && 2.0 * f.half_depth >= w - 1e-6 {
            return Some(f.swapped());
        }
        Some(f)
    }
}

impl Floor {
    /// Bounding box of everything on the floor (min, max); `None` when empty.
    pub fn bounds(&self) -> Option<(DVec2, DVec2)> {
        poinav_plane::bounds_of(
            self.obstacles
                .iter()
                .flat_map(|o| o.rings.iter().flatten())
                .chain(self.zones.iter().flat_map(|z| z.ring.iter()))
                .chain(self.doors.iter().flat_map(|d| d.ring.iter())),
        )
    }

    /// The zone with this name (Name or LongName).
    pub fn zone(&self, name: &str) -> Option<&FloorZone> {
        self.zones
            .iter()
            .find(|z| z.name.as_deref() == Some(name) || z.long_name.as_deref() == Some(name))
    }
}
