//! Rule R5, runtime constraints: what a robot's sensors find changes an element's conditional
//! roles and status (B-2 for a narrow passage, C-2 for a robot too close in a multi-robot zone).

use crate::classify::{Accessibility, Classified};
use crate::taxonomy::{AccessibilityStatus, Role, ValidationMethod};

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

fn set_role(c: &mut Classified, role: Role, on: bool, change: &mut RuntimeChange) {
    let has = c.conditional.contains(&role);
    if on && !has {
        c.conditional.push(role);
        c.conditional.sort();
        change.added.push(role);
    } else if !on && has {
        c.conditional.retain(|r| *r != role);
        change.removed.push(role);
    }
}

/// Applies R5 to `c`: a clearance below MinClearanceWidth at an A-2 element adds B-2 and makes it
/// RESTRICTED (ValidationMethod SENSOR_BASED), a clearance at or above it removes B-2 and makes it
/// FULL_ACCESS; a robot closer than MinInterRobotSeparation in a C-1 zone adds C-2 (and a
/// farther one removes it). Elements without the role the observation concerns are unchanged.
pub fn apply(c: &mut Classified, observation: Observation) -> RuntimeChange {
    let mut change = RuntimeChange::default();
    match observation {
        Observation::Clearance { measured_width_m } => {
            if !c.primary.contains(&Role::Transition) {
                return change;
            }
            let Some(a) = c.accessibility.as_ref() else {
                return change;
            };
            let narrow = measured_width_m < a.min_clearance_width_m;
            let old = a.status;
            let new = if narrow {
                AccessibilityStatus::Restricted
            } else {
                AccessibilityStatus::FullAccess
            };
            set_role(c, Role::Narrow, narrow, &mut change);
            let a: &mut Accessibility = c.accessibility.as_mut().expect("checked above");
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
            let Some(k) = c.coordination.as_ref() else {
                return change;
            };
            if !c.primary.contains(&Role::MultiRobotZone) {
                return change;
            }
            let close = distance_m < k.min_separation_m;
            set_role(c, Role::RobotInteraction, close, &mut change);
        }
    }
    change
}
