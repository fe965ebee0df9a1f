//! IFC authoring for design iteration: writes the paper's test building ([`demo_building()`]) and
//! applies design changes to existing models losslessly ([`door_width`]).

pub mod demo_building;
pub mod door_width;
mod error;
mod step_builder;

pub use demo_building::{demo_building, DemoBuilding, DoorLayout, Layout, RoomLayout};
pub use door_width::{find_door, patch_door_width, DoorPatch};
pub use error::AuthorError;
