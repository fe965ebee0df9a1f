//! Robot Point-of-Interest (POI) semantics for IFC models: the facts rules test, mapping rules as
//! data, classification of every element, and writing the three property sets back into the IFC
//! losslessly. The role taxonomy, robot profiles, the status rules and R5's updates are
//! `poinav-roles`' (it knows no IFC), re-exported here.
//!
//! ```
//! use poinav_poi::{classify, RobotProfile, RuleSet, Role, AccessibilityStatus};
//!
//! let text = "ISO-10303-21;HEADER;FILE_SCHEMA(('IFC4'));ENDSEC;DATA;\n\
//!     #1=IFCDOOR('1YvctVUKr0kugbFTf53O9L',$,'Door',$,$,$,$,$,2.1,0.8,$,$,$);\n\
//!     ENDSEC;END-ISO-10303-21;";
//! let model = poinav_ifc::Model::from_bytes("door.ifc", text.as_bytes().to_vec()).unwrap();
//! let c = classify(&model, &RuleSet::defaults(), &RobotProfile::paper());
//! let door = &c.elements[0];
//! assert_eq!(door.primary, [Role::Transition]);
//! assert_eq!(door.conditional, [Role::Narrow]);
//! assert_eq!(door.accessibility.as_ref().unwrap().status, AccessibilityStatus::Restricted);
//! ```

mod classify;
mod condition;
mod error;
mod facts;
mod rules;
pub mod runtime;
mod write;

pub use classify::{classify, Classification, Classified};
pub use condition::{Condition, ConditionError, Op, Operand};
pub use error::PoiError;
pub use facts::{FactContext, FactValue, Facts, MEASURES};
pub use poinav_ifc::timestamp::{iso8601_utc, now_or_source_date_epoch};
pub use poinav_roles::{
    clear_width_status, slope_status, stairs_status, Accessibility, AccessibilityStatus, AppliesTo,
    Category, Coordination, CoordinationProtocol, Locomotion, PoiRecord, PoiType, ProfileError,
    RobotProfile, Role, ValidationMethod,
};
pub use rules::{AccessibilityKind, ConditionalRole, PropertyTest, Rule, RuleSet};
pub use write::{
    previous_enrichment, pset_names, stored_length, write_enrichment, PsetNames, WriteOptions,
    POINAV_MARKER,
};
