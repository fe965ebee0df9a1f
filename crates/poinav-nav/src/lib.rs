//! Navigation on a plain floor model (no IFC types): the [`Floor`] that navigation and
//! simulation share; occupancy grids, the room/door graph, routes and the audit build on it.

mod floor;

pub use floor::{Floor, FloorDoor, FloorObstacle, FloorZone, ObstacleKind};
