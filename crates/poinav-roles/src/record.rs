//! One element's POI record as navigation and simulation see it: GlobalId, class and name, POI
//! category and type, roles, accessibility and coordination; what rule R5 changes at run time.

use crate::coordination::Coordination;
use crate::runtime::RolesMut;
use crate::status::Accessibility;
use crate::taxonomy::{Category, PoiType, Role};

/// An element's POI record (the IFC-free part of `poinav_poi::Classified`).
#[derive(Debug, Clone, PartialEq)]
pub struct PoiRecord {
    /// GlobalId.
    pub global_id: String,
    /// Class (`IfcDoor`).
    pub class: String,
    /// Name.
    pub name: Option<String>,
    /// POI_Category.
    pub category: Category,
    /// POI_Type.
    pub poi_type: PoiType,
    /// POI_PrimaryRoles.
    pub primary: Vec<Role>,
    /// POI_ConditionalRoles.
    pub conditional: Vec<Role>,
    /// Pset_RobotAccessibility, for transitions.
    pub accessibility: Option<Accessibility>,
    /// Pset_RobotCoordination, for multi-robot zones.
    pub coordination: Option<Coordination>,
}

impl PoiRecord {
    /// What rule R5 reads and changes of this record.
    pub fn roles_mut(&mut self) -> RolesMut<'_> {
        RolesMut {
            primary: &self.primary,
            conditional: &mut self.conditional,
            accessibility: self.accessibility.as_mut(),
            coordination: self.coordination.as_ref(),
        }
    }
}
