//! Speed limits from POI roles: the fraction of the profile's top speed a robot drives in a
//! zone or door. Routes (expected time), the Nav2 speed mask and the route graph's
//! `speed_limit` all use these same numbers.

use poinav_roles::{AccessibilityStatus, CoordinationProtocol, Role};
use serde::Serialize;

use crate::floor::{FloorDoor, FloorZone};

/// A speed fraction out of (0, 1].
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("speed fraction {name} must be in (0, 1], not {value}")]
pub struct SpeedError {
    /// Which fraction.
    pub name: &'static str,
    /// Its value.
    pub value: f64,
}

/// Speed fractions (0 < f <= 1) of the profile's maximum speed per role.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RoleSpeeds {
    /// B-1 Hazard zone: proceed with caution.
    pub hazard: f64,
    /// B-2 Narrow/congested (zones and doors; RESTRICTED doors carry B-2).
    pub narrow: f64,
    /// C-1 zone whose CoordinationProtocol is SPEED_REDUCTION: the paper halves the speed
    /// (5.0 -> 2.5 m/s). Planning assumes the rule is in force (another robot present), the
    /// conservative case; set 1.0 to plan for an empty corridor.
    pub speed_reduction: f64,
    /// C-1 zone with YIELD: robots wait rather than slow down.
    pub yield_protocol: f64,
    /// C-1 zone with PRIORITY_PASS.
    pub priority_pass: f64,
    /// C-1 zone without coordination data.
    pub multi_robot: f64,
}

impl Default for RoleSpeeds {
    fn default() -> Self {
        RoleSpeeds {
            hazard: 0.5,
            narrow: 0.5,
            speed_reduction: 0.5,
            yield_protocol: 1.0,
            priority_pass: 1.0,
            multi_robot: 1.0,
        }
    }
}

impl RoleSpeeds {
    /// Checks every fraction is in (0, 1].
    pub fn validate(&self) -> Result<(), SpeedError> {
        for (name, v) in [
            ("hazard", self.hazard),
            ("narrow", self.narrow),
            ("speed_reduction", self.speed_reduction),
            ("yield_protocol", self.yield_protocol),
            ("priority_pass", self.priority_pass),
            ("multi_robot", self.multi_robot),
        ] {
            if !(v > 0.0 && v <= 1.0) {
                return Err(SpeedError { name, value: v });
            }
        }
        Ok(())
    }

    /// The fraction in a zone and why (`B-1`, `C-1 SPEED_REDUCTION`, ...); 1.0 and empty
    /// when no role slows the robot.
    pub fn zone(&self, zone: &FloorZone) -> (f64, Vec<String>) {
        let mut f: f64 = 1.0;
        let mut why = Vec::new();
        if zone.roles.contains(&Role::Hazard) {
            f = f.min(self.hazard);
            why.push("B-1".to_string());
        }
        if zone.roles.contains(&Role::Narrow) {
            f = f.min(self.narrow);
            why.push("B-2".to_string());
        }
        if zone.roles.contains(&Role::MultiRobotZone) {
            let (g, label) = match zone.coordination.map(|c| c.1) {
                Some(CoordinationProtocol::SpeedReduction) => {
                    (self.speed_reduction, "C-1 SPEED_REDUCTION")
                }
                Some(CoordinationProtocol::Yield) => (self.yield_protocol, "C-1 YIELD"),
                Some(CoordinationProtocol::PriorityPass) => {
                    (self.priority_pass, "C-1 PRIORITY_PASS")
                }
                None => (self.multi_robot, "C-1"),
            };
            f = f.min(g);
            why.push(label.to_string());
        }
        (f, why)
    }

    /// The fraction in a door's passage: B-2 doors (and RESTRICTED ones, which the rules give
    /// B-2) are narrow.
    pub fn door(&self, door: &FloorDoor, status: AccessibilityStatus) -> (f64, Vec<String>) {
        if door.roles.contains(&Role::Narrow) || status == AccessibilityStatus::Restricted {
            (self.narrow, vec!["B-2".to_string()])
        } else {
            (1.0, Vec::new())
        }
    }
}
