//! The storey's occupancy grid for `/map`: the very grid of its Nav2 map
//! ([`poinav_nav::nav2`]: the storey cropped to its own extent, rasterised for the profile,
//! not inflated, BLOCKED doors closed), its cells turned into ROS occupancy values the way
//! nav2_map_server reads `map.pgm` in trinary mode: free 0, occupied 100, unknown -1.

use glam::DVec2;
use poinav_nav::{Building, CellState, Floor, Nav2Options, NavError, Navigator};
use poinav_roles::RobotProfile;

/// A map ready for `nav_msgs/msg/OccupancyGrid`.
#[derive(Debug, Clone, PartialEq)]
pub struct StoreyMap {
    /// Cell size, metres.
    pub resolution_m: f64,
    /// The lower-left corner of cell (0, 0).
    pub origin: DVec2,
    /// Columns.
    pub width: usize,
    /// Rows.
    pub height: usize,
    /// Row-major from row 0 (lowest y): 0 free, 100 occupied, -1 unknown.
    pub data: Vec<i8>,
}

/// The ROS occupancy value of a cell.
pub fn occupancy(c: CellState) -> i8 {
    match c {
        CellState::Free => 0,
        CellState::Occupied => 100,
        CellState::Unknown => -1,
    }
}

/// The map `poinav export nav2` writes for `floor` (as a one-storey building) and `profile`
/// with `options`.
pub fn storey_map(
    floor: &Floor,
    profile: &RobotProfile,
    options: &Nav2Options,
) -> Result<StoreyMap, NavError> {
    let building = Building::single(floor.clone());
    let nav = Navigator::new(&building, profile, &options.nav)?;
    let g = &nav.floors[0].grid.occupancy;
    Ok(StoreyMap {
        resolution_m: g.resolution_m,
        origin: g.origin,
        width: g.width,
        height: g.height,
        data: g.cells.iter().map(|&c| occupancy(c)).collect(),
    })
}
