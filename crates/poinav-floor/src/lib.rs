//! The building as robots see it, knowing neither IFC nor geometry (as `geo-types` sits
//! beside `geo`): plain 2D data in metres that navigation (`poinav-nav`), the simulator
//! (`poinav-sim`) and the exporters share, and that the IFC bridge (`poinav-bridge`) fills.
//!
//! - [`floor`]: a [`Floor`] (one storey) of obstacles, doors and zones, tagged with GlobalIds,
//!   classes and POI roles.
//! - [`building`]: a [`Building`] is storeys plus stairs, ramps and lifts
//!   ([`VerticalConnection`]); connection statuses for any profile.
//! - [`door_status`]: a door's status for any profile from its profile-free facts (the width
//!   the classification read, the rule that blocks it, [`Block`], its width in plan).
//! - [`id`]: [`ElementId`], the id of an element (its GlobalId), serialised as the plain string.
//! - [`index`]: typed indices into a floor's zones and doors ([`ZoneIdx`], [`DoorIdx`]), with
//!   `Option` for none.
//! - [`level`]: each storey's walking level and which storeys are at ground level.
//! - [`polygon`]: plane geometry on rings (`poinav-plane`, re-exported; the ring first):
//!   containment, distances, areas, interior points, passage frames; [`Ring`], the type of
//!   every ring on a floor.

pub mod building;
pub mod door_status;
pub mod floor;
pub mod id;
pub mod index;
pub mod level;

/// Plane geometry on rings: `poinav-plane`, re-exported so a floor's users need not name it.
pub use poinav_plane as polygon;
pub use poinav_plane::Ring;

pub use building::{Building, ConnectionKind, Landing, VerticalConnection};
pub use door_status::{classified_status, door_status, door_verdict, Block};
pub use floor::{Floor, FloorDoor, FloorObstacle, FloorZone, ObstacleKind};
pub use id::ElementId;
pub use index::{DoorIdx, ObstacleIdx, ZoneIdx};
pub use level::{Entrance, FloorLevel, LevelSource};
