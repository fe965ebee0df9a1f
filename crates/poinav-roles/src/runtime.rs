//! Rule R5, runtime constraints: what a robot's sensors find changes an element's conditional
//! roles and status (B-2 for a narrow passage, C-2 for a robot too close in a multi-robot zone).

use crate::coordination::Coordination;
use crate::status::Accessibility;
use crate::taxonomy::{AccessibilityStatus, Role, ValidationMethod};

/// What rule R5 reads and changes of an element: its primary roles, its conditional roles, its
/// accessibility (for transitions) and its coordination (for multi-robot zones).
#[derive(Debug)]
pub struct RolesMut<'a> {
    /// POI_PrimaryRoles.
    pub primary: &'a [Role],
    /// POI_ConditionalRoles (kept sorted).
    pub conditional: &'a mut Vec<Role>,
    /// Pset_RobotAccessibility.
    pub accessibility: Option<&'a mut Accessibility>,
    /// Pset_RobotCoordination.
    pub coordination: Option<&'a Coordination>,
}

/// What a robot measured at an element.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Observation {
    /// The clear width of a transition, estimated from the sensor rays.
    Clearance {
        /// Estimated clear width in metres.
        measured_width_m: f64,
    },
    /// Another robot inside a multi-robot zone (C-1), at this distance.
    RobotDistance {
        /// Centre-to-centre distance in metres.
        distance_m: f64,
    },
}

/// What an observation changed.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct RuntimeChange {
    /// Conditional roles added.
    pub added: Vec<Role>,
    /// Conditional roles removed.
    pub removed: Vec<Role>,
    /// AccessibilityStatus before and after, when it changed.
    pub status: Option<(AccessibilityStatus, AccessibilityStatus)>,
}

impl RuntimeChange {
    /// True when nothing changed.
    pub fn is_empty(&self) -> bool {
        self.added.is_empty() && self.removed.is_empty() && self.status.is_none()
    }
}

fn set_role(conditional: &mut Vec<Role>, role: Role, on: bool, change: &mut RuntimeChange) {
    let has = conditional.contains(&role);
    if on && !has {
        conditional.push(role);
        conditional.sort();
        change.added.push(role);
    } else if !on && has {
        conditional.retain(|r| *r != role);
        change.removed.push(role);
    }
}

/// Applies R5 to `c`: a clearance below MinClearanceWidth at an A-2 element adds B-2 and makes it
/// RESTRICTED (ValidationMethod SENSOR_BASED), a clearance at or above it removes B-2 and makes it
/// FULL_ACCESS; a robot closer than MinInterRobotSeparation in a C-1 zone adds C-2 (and a
/// farther one removes it). Elements without the role the observation concerns are unchanged.
pub fn apply(c: RolesMut<'_>, observation: Observation) -> RuntimeChange {
    let mut change = RuntimeChange::default();
    match observation {
        Observation::Clearance { measured_width_m } => {
            if !c.primary.contains(&Role::Transition) {
                return change;
            }
            let Some(a) = c.accessibility else {
                return change;
            };
            let narrow = measured_width_m < a.min_clearance_width_m;
            let old = a.status;
            let new = if narrow {
                AccessibilityStatus::Restricted
            } else {
                AccessibilityStatus::FullAccess
            };
            set_role(c.conditional, Role::Narrow, narrow, &mut change);
            a.status = new;
            a.method = ValidationMethod::SensorBased;
            a.reason = format!(
                "sensor clearance {measured_width_m:.3} m {} required {:.3} m",
                if narrow { "<" } else { ">=" },
                a.min_clearance_width_m
            );
            if old != new {
                change.status = Some((old, new));
            }
        }
        Observation::RobotDistance { distance_m } => {
            let Some(k) = c.coordination else {
                return change;
            };
            if !c.primary.contains(&Role::MultiRobotZone) {
                return change;
            }
            let close = distance_m < k.min_separation_m;
            set_role(c.conditional, Role::RobotInteraction, close, &mut change);
        }
    }
    change
}
