//! ROS 2 recordings of poinav simulations as MCAP files: reads a run's trace
//! (`trace.jsonl`), the storey it ran on ([`poinav_nav::Floor`]) and its Nav2 map, and writes
//! laser scans, odometry, TF, the occupancy grid, POI markers and events as CDR messages with
//! their `ros2msg` schemas, so Foxglove, RViz (through `ros2 bag play`) and rosbag2 tools
//! open them. Knows no IFC and nothing of how the simulator works: only its outputs.
//!
//! ```no_run
//! # fn main() -> Result<(), Box<dyn std::error::Error>> {
//! # let floor: poinav_nav::Floor = unimplemented!();
//! let profile = poinav_roles::RobotProfile::paper();
//! let map = poinav_mcap::storey_map(&floor, &profile, &poinav_nav::Nav2Options::default())?;
//! let scene = poinav_mcap::Scene { floor: &floor, profile: &profile, map: &map, dt: 1.0 / 60.0 };
//! let summary = poinav_mcap::write_recording(
//!     std::path::Path::new("out/trace.jsonl"),
//!     &scene,
//!     std::path::Path::new("out/run.mcap"),
//! )?;
//! println!("{} messages", summary.total());
//! # Ok(()) }
//! ```

pub mod cdr;
mod error;
pub mod map;
pub mod markers;
pub mod msgs;
pub mod record;
pub mod schema;

pub use error::McapError;
pub use map::{storey_map, StoreyMap};
pub use record::{write_recording, write_recording_from, RecordSummary, Scene, START_NS};
