//! Fast, exact reading of IFC files (ISO 10303-21 / STEP) for IFC2X3, IFC4 and IFC4X3_ADD2,
//! with attribute access by name, subtype tests, inverse relations, units, the spatial
//! hierarchy, property sets, and lossless writing of edited copies.
//!
//! ```
//! use poinav_ifc::Model;
//!
//! let text = "ISO-10303-21;HEADER;FILE_SCHEMA(('IFC4'));ENDSEC;DATA;\n\
//!     #1=IFCDOOR('1YvctVUKr0kugbFTf53O9L',$,'Door',$,$,$,$,$,2.1,0.9,$,$,$);\n\
//!     ENDSEC;END-ISO-10303-21;";
//! let model = Model::from_bytes("door.ifc", text.as_bytes().to_vec()).unwrap();
//! let door = &model.instances_of("IfcDoor")[0];
//! assert!(door.is_a("IfcBuildingElement"));
//! assert_eq!(door.get_f64("OverallWidth"), Some(0.9));
//! assert_eq!(door.name().as_deref(), Some("Door"));
//! ```

mod arg;
mod arg_index;
mod check;
mod diagnostic;
mod editor;
mod entity;
mod error;
mod header;
mod id;
mod lines;
mod model;
pub mod property;
mod scan;
pub mod schema;
pub mod spatial;
pub mod string;
pub mod timestamp;
pub mod units;
pub mod value;

pub use arg::{format_real, Arg, ArgError};
pub use diagnostic::{Diagnostic, DiagnosticKind};
pub use editor::{EditError, Editor, NewProperty, OWNER_APPLICATION_ID};
pub use entity::{AttrError, Entity};
pub use error::{ReadError, ReadErrorKind};
pub use header::Header;
pub use id::EntityId;
pub use model::Model;
pub use poinav_io::{GlobalId, GlobalIdError};
pub use schema::{Schema, TypeId};
pub use value::Value;
