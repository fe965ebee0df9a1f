//! The POI role taxonomy (SPEC.md §1) and the enumerated values of the three property sets (§3).

use std::fmt;
use std::str::FromStr;

use serde::{Deserialize, Serialize};

use crate::error::UnknownLabel;

macro_rules! labelled_enum {
    ($(#[$meta:meta])* $name:ident { $($(#[$vmeta:meta])* $variant:ident => $label:literal),+ $(,)? }) => {
        $(#[$meta])*
        #[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
        pub enum $name {
            $($(#[$vmeta])* #[serde(rename = $label)] $variant),+
        }

        impl $name {
            /// Every value, in declaration order.
            pub const ALL: &'static [$name] = &[$($name::$variant),+];

            /// The label written into IFC and CSV.
            pub fn label(self) -> &'static str {
                match self {
                    $($name::$variant => $label),+
                }
            }
        }

        impl fmt::Display for $name {
            fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                f.write_str(self.label())
            }
        }

        impl FromStr for $name {
            type Err = UnknownLabel;
            fn from_str(s: &str) -> Result<Self, UnknownLabel> {
                $name::ALL.iter().copied().find(|v| v.label().eq_ignore_ascii_case(s.trim())).ok_or_else(|| {
                    UnknownLabel {
                        text: s.to_string(),
                        kind: stringify!($name),
                        expected: $name::ALL.iter().map(|v| v.label()).collect(),
                    }
                })
            }
        }
    };
}

labelled_enum! {
    /// A POI role (paper Table 2, plus `Destination` from Table 3).
    Role {
        /// A-1 Avoidance: keep clearance from the element.
        Avoidance => "A-1",
        /// A-2 Transition: verify clearance, control passage speed.
        Transition => "A-2",
        /// A-3 Path guidance: use the element as a trajectory reference.
        PathGuidance => "A-3",
        /// B-1 Hazard zone: proceed with caution.
        Hazard => "B-1",
        /// B-2 Narrow/congested: reduce speed.
        Narrow => "B-2",
        /// C-1 Multi-robot zone: apply the zone's coordination protocol.
        MultiRobotZone => "C-1",
        /// C-2 Robot-robot interaction: keep separation, adjust speed.
        RobotInteraction => "C-2",
        /// A room that is a task target.
        Destination => "Destination",
    }
}

impl Role {
    /// The role's name (`Avoidance`, `Narrow/Congested`, ...).
    pub fn name(self) -> &'static str {
        match self {
            Role::Avoidance => "Avoidance",
            Role::Transition => "Transition",
            Role::PathGuidance => "Path Guidance",
            Role::Hazard => "Hazard Zone",
            Role::Narrow => "Narrow/Congested",
            Role::MultiRobotZone => "Multi-Robot Zone",
            Role::RobotInteraction => "Robot-Robot Interaction",
            Role::Destination => "Destination",
        }
    }

    /// The taxonomy category (`A-Mobility`, `B-Safety`, `C-Coordination`; `Task` for Destination).
    pub fn group(self) -> &'static str {
        match self {
            Role::Avoidance | Role::Transition | Role::PathGuidance => "A-Mobility",
            Role::Hazard | Role::Narrow => "B-Safety",
            Role::MultiRobotZone | Role::RobotInteraction => "C-Coordination",
            Role::Destination => "Task",
        }
    }
}

labelled_enum! {
    /// POI_Category of Pset_POI_Classification.
    Category {
        /// Walls, doors, slabs, ...
        Structural => "Structural",
        /// Spaces.
        Functional => "Functional",
        /// Furniture and equipment.
        ObjectBased => "Object-based",
    }
}

labelled_enum! {
    /// POI_Type of Pset_POI_Classification. The paper names the first three; the last two are
    /// poinav's for rule R4 and the floor-slab rule (SPEC.md leaves them to us).
    PoiType {
        /// R1.
        BoundaryElement => "Boundary Element",
        /// R2.
        TransitionElement => "Transition Element",
        /// R3.
        SpaceType => "Space Type",
        /// R4: furniture and equipment fixed in place.
        FixedObject => "Fixed Object",
        /// Floor slabs (paper Table 3, "surface reference").
        FloorSurface => "Floor Surface",
    }
}

labelled_enum! {
    /// AccessibilityStatus of Pset_RobotAccessibility.
    AccessibilityStatus {
        /// Passable at the profile's required clearance.
        FullAccess => "FULL_ACCESS",
        /// Passable with care: narrower than required, wider than the robot.
        Restricted => "RESTRICTED",
        /// Not passable for the profile.
        Blocked => "BLOCKED",
        /// Not enough information to decide.
        PendingValidation => "PENDING_VALIDATION",
    }
}

labelled_enum! {
    /// ValidationMethod of Pset_RobotAccessibility.
    ValidationMethod {
        /// Measured by a robot's sensors (simulation write-back).
        SensorBased => "SENSOR_BASED",
        /// Derived from the model's dimensions and geometry.
        GeometricAnalysis => "GEOMETRIC_ANALYSIS",
        /// Set by a person.
        Manual => "MANUAL",
    }
}

labelled_enum! {
    /// CoordinationProtocol of Pset_RobotCoordination.
    CoordinationProtocol {
        /// One robot waits for the other.
        Yield => "YIELD",
        /// A robot with priority passes first.
        PriorityPass => "PRIORITY_PASS",
        /// Both robots slow down (5.0 -> 2.5 m/s in the paper).
        SpeedReduction => "SPEED_REDUCTION",
    }
}

labelled_enum! {
    /// AppliesTo of Pset_RobotCoordination.
    AppliesTo {
        /// Every robot.
        AllRobots => "ALL_ROBOTS",
        /// Only some robot types.
        SpecificTypes => "SPECIFIC_TYPES",
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn labels_parse_back_and_match_the_spec() {
        let codes: Vec<&str> = Role::ALL.iter().map(|r| r.label()).collect();
        assert_eq!(
            codes,
            [
                "A-1",
                "A-2",
                "A-3",
                "B-1",
                "B-2",
                "C-1",
                "C-2",
                "Destination"
            ]
        );
        for r in Role::ALL {
            assert_eq!(r.label().parse::<Role>().unwrap(), *r);
        }
        assert_eq!(
            "object-based".parse::<Category>().unwrap(),
            Category::ObjectBased
        );
        let e = "A-9".parse::<Role>().unwrap_err();
        assert_eq!((e.text.as_str(), e.kind), ("A-9", "Role"));
        assert!(
            e.to_string()
                .starts_with("`A-9` is not a Role; expected one of A-1, A-2, "),
            "{e}"
        );
        assert_eq!(AccessibilityStatus::ALL.len(), 4);
        assert_eq!(Role::Narrow.group(), "B-Safety");
    }
}
