//! Navigation on a plain floor model (no IFC types): the [`Floor`] that navigation and
//! simulation share, and on it occupancy grids, the room/door graph, routes, the
//! accessibility audit and Nav2 bundles.
//!
//! - [`building`], [`level`], [`polygon`] and [`Floor`] are `poinav-floor`'s, re-exported: a
//!   [`Building`] is storeys plus stairs, ramps and lifts; door and connection statuses for any
//!   profile.
//! - [`grid`]: rasterising a storey ([`OccupancyGrid`]) and inflating it for a robot
//!   ([`NavGrid`]); obstacle parts thinner than a cell occupy every cell they touch
//!   ([`thin_cells`]), but around doors.
//! - [`graph`]: the [`Topology`] of zones, doors and landings.
//! - [`bounds`]: the size bounds of rasterising and the graph; elements past one are unknown
//!   in the grid, never free, and named ([`GaveUp`]).
//! - [`navigator`]: a building prepared for one profile ([`Navigator`]); [`route`] plans on it.
//! - [`space_name`]: which space a GlobalId, Name, LongName or `Name@Storey` selects
//!   ([`SpaceNames::find_space`]); an ambiguous name is an error listing the candidates.
//! - [`audit`](mod@audit): reachability and door statuses per profile, JSON, SVG ([`svg`]) and HTML.
//! - [`nav2`]: map, masks, filter parameters and route graphs for Nav2 ([`route_graph`]:
//!   nav2_route GeoJSON per storey and for the building, with operations).
//!
//! ```
//! use glam::DVec2;
//! use poinav_nav::{Building, Floor, FloorDoor, FloorObstacle, FloorZone, NavOptions, Navigator, ObstacleKind, Place};
//! use poinav_roles::RobotProfile;
//!
//! use poinav_nav::polygon::rect;
//! let zone = |name: &str, ring| FloorZone {
//!     id: name.into(), name: Some(name.into()), long_name: None, ring, roles: vec![], coordination: None,
//! };
//! // Two 4 x 4 m rooms inside outer walls, a 0.2 m wall between them with a 1.0 m door.
//! let wall = |id: &str, rings| FloorObstacle {
//!     id: id.into(), class: "IfcWall".into(), kind: ObstacleKind::Structure, rings, roles: vec![],
//! };
//! let floor = Floor {
//!     name: "Level 1".into(),
//!     elevation_m: 0.0,
//!     obstacles: vec![
//!         wall("outer", vec![rect(-0.2, -0.2, 8.4, 0.0), rect(-0.2, 4.0, 8.4, 4.2),
//!                            rect(-0.2, 0.0, 0.0, 4.0), rect(8.2, 0.0, 8.4, 4.0)]),
//!         wall("middle", vec![rect(4.0, 0.0, 4.2, 1.5), rect(4.0, 2.5, 4.2, 4.0)]),
//!     ],
//!     doors: vec![FloorDoor {
//!         id: "door".into(),
//!         name: Some("Door".into()),
//!         ring: rect(4.0, 1.5, 4.2, 2.5),
//!         center: DVec2::new(4.1, 2.0),
//!         clear_width_m: 1.0,
//!         classified_width_m: Some(1.0),
//!         blocked: None,
//!         roles: vec![],
//!         spaces: None,
//!         doorless: false,
//!         terrain: false,
//!     }],
//!     zones: vec![zone("West", rect(0.0, 0.0, 4.0, 4.0)), zone("East", rect(4.2, 0.0, 8.2, 4.0))],
//! };
//! let building = Building::single(floor);
//! let nav = Navigator::new(&building, &RobotProfile::paper(), &NavOptions::default())?;
//! let route = nav.route(&Place::zone("West"), &Place::zone("East"))?;
//! assert_eq!(route.doors[0].name.as_deref(), Some("Door"));
//! // From the middle of one room to the middle of the other.
//! assert!((route.length_m - 4.2).abs() < 0.05, "{}", route.length_m);
//! # Ok::<(), poinav_nav::NavError>(())
//! ```

pub mod audit;
pub mod bounds;
mod door_frame;
pub use poinav_floor::building;
pub use poinav_floor::door_status;
mod error;
pub mod extent;
use poinav_floor::floor;
pub mod graph;
pub mod grid;
pub use poinav_floor::level;
pub mod nav2;
pub mod navigator;
pub use poinav_floor::polygon;
pub mod progress;
pub mod route;
pub mod route_graph;
pub mod space_name;
pub mod speed;
pub mod svg;
pub mod thin_cells;
pub mod zone_index;

pub use audit::{audit, AuditOptions, AuditReport};
pub use bounds::{GaveUp, StageBounds};
pub use building::{Building, ConnectionKind, Landing, VerticalConnection};
pub use door_frame::DoorFrame;
pub use error::NavError;
pub use floor::{Floor, FloorDoor, FloorObstacle, FloorZone, ObstacleKind};
pub use graph::Topology;
pub use grid::{CellState, FurnitureMode, GridOptions, InflationOptions, NavGrid, OccupancyGrid};
pub use level::{Entrance, FloorLevel, LevelSource};
pub use nav2::{write_bundle, write_bundle_with_progress, Nav2Options};
pub use navigator::{NavOptions, Navigator};
pub use poinav_floor::{DoorIdx, ElementId, ObstacleIdx, Ring, ZoneIdx};
pub use progress::{Phase, Progress};
pub use route::{NoPlace, Place, Route, Unreachable};
pub use space_name::{Ambiguous, SpaceNames, SpaceRef};
pub use speed::{RoleSpeeds, SpeedError};
