//! Robot roles without IFC: the POI role taxonomy and the enumerated values of the three
//! property sets, robot profiles (TOML), the status rules (pure functions of an element's facts
//! and a profile: clear width, stairs, slope), the coordination values of a zone and rule R5's
//! runtime updates from sensor observations. Navigation and simulation depend on this crate;
//! `poinav-poi` (which reads IFC) re-exports it.
//!
//! ```
//! use poinav_roles::{clear_width_status, AccessibilityStatus, RobotProfile};
//!
//! let paper = RobotProfile::paper();
//! let (status, why) = clear_width_status(Some(0.785), Some("door lining"), &paper);
//! assert_eq!(status, AccessibilityStatus::Restricted);
//! assert!(why.starts_with("clear width 0.785 m (door lining) < required"), "{why}");
//! ```

mod coordination;
mod error;
mod profile;
mod record;
pub mod runtime;
mod status;
mod taxonomy;

pub use coordination::Coordination;
pub use error::{ProfileError, UnknownLabel};
pub use profile::{Locomotion, RobotProfile};
pub use record::PoiRecord;
pub use status::{
    clear_width_status, clear_width_verdict, slope_status, stairs_status, Accessibility,
};
pub use taxonomy::{
    AccessibilityStatus, AppliesTo, Category, CoordinationProtocol, PoiType, Role, ValidationMethod,
};
