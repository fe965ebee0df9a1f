//! The browser viewer (replacing the paper's Unity VR platform, SPEC.md §4): a local web server
//! that runs the robot simulation live and serves a single-page three.js viewer of the building.
//!
//! The server owns no IFC knowledge: the caller (the `poinav serve` command) hands it a
//! [`Viewer`]: the building as one GLB per storey, one [`ElementInfo`] per element for click-to-inspect,
//! every storey as a plain [`poinav_nav::Floor`] with the robots that drive on it, and the storey
//! shown first; a page can switch the simulated storey. The simulation runs on its own thread at the fixed step of [`poinav_sim::DT`], paced to real time; every step's
//! state (poses, the five rays with what they hit, roles, brush) and the POI events it caused
//! go to every connected page over a WebSocket, and the pages' key presses come back the same
//! way. Assets (three.js from npm, vendored under `web/vendor`) are compiled into the binary,
//! so running the viewer needs no Node and no files beside the binary.
//!
//! ```no_run
//! # async fn demo(viewer: poinav_viewer::Viewer) -> Result<(), poinav_viewer::ViewerError> {
//! let bound = poinav_viewer::bind(poinav_viewer::ServerConfig::default(), viewer).await?;
//! println!("open http://{}/", bound.local_addr());
//! bound.run().await
//! # }
//! ```

mod assets;
mod config;
mod error;
mod live;
mod placement;
mod protocol;
mod server;
mod state;

pub use assets::{asset, Asset, ASSETS};
pub use config::ServerConfig;
pub use error::ViewerError;
pub use live::Live;
pub use placement::default_robots;
pub use protocol::{ClientMessage, ProtocolError};
pub use server::{bind, Bound};
pub use state::{ElementInfo, ModelChunk, ViewStorey, Viewer};
