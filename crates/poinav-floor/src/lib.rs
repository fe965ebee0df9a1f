//! The building as robots see it, knowing neither IFC nor geometry (as `geo-types` sits
//! beside `geo`): plain 2D data in metres that navigation (`poinav-nav`), the simulator
//! (`poinav-sim`) and the exporters share, and that the IFC bridge (`poinav-bridge`) fills.
//!
//! - [`floor`]: a [`Floor`] (one storey) of obstacles, doors and zones, tagged with GlobalIds,
//!   classes and POI roles.
//! - [`building`]: a [`Building`] is storeys plus stairs, ramps and lifts
//!   ([`VerticalConnection`]); door and connection statuses for any profile.
//! - [`index`]: typed indices into a floor's zones and doors ([`ZoneIdx`], [`DoorIdx`]), with
//!   `Option` for none.
//! - [`level`]: each storey's walking level and which storeys are at ground level.
//! - [`polygon`]: plane geometry on rings (`poinav-plane`, re-exported; the ring first):
//!   containment, distances, areas, interior points, passage frames; [`Ring`], the type of
//!   every ring on a floor.

pub mod building;
pub mod floor;
pub mod index;
pub mod level;

/// Plane geometry on rings: `poinav-plane`, re-exported so a floor's users need not name it.
pub use poinav_plane as polygon;
pub use poinav_plane::Ring;

pub use building::{Building, ConnectionKind, Landing, VerticalConnection};
pub use floor::{Floor, FloorDoor, FloorObstacle, FloorZone, ObstacleKind};
pub use index::{DoorIdx, ObstacleIdx, ZoneIdx};
pub use level::{Entrance, FloorLevel, LevelSource};
