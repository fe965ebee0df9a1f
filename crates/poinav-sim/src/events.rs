//! Events: what changed during a run (conditional roles and statuses from rule R5, sensor
//! clearance measurements, a robot's own C-2, contacts, zones entered, targets reached, keys and
//! brush), each stamped with step, time and robot, rendered as deterministic JSON.

use poinav_roles::{AccessibilityStatus, Role};

use crate::trace::Json;

/// What happened.
#[derive(Debug, Clone, PartialEq)]
pub enum EventKind {
    /// A conditional role was added to an element's record (R5).
    RoleAdded {
        /// GlobalId.
        element: String,
        /// Name.
        name: Option<String>,
        /// Role.
        role: Role,
    },
    /// A conditional role was removed from an element's record.
    RoleRemoved {
        /// GlobalId.
        element: String,
        /// Name.
        name: Option<String>,
        /// Role.
        role: Role,
    },
    /// An AccessibilityStatus changed.
    StatusChanged {
        /// GlobalId.
        element: String,
        /// Name.
        name: Option<String>,
        /// Before.
        from: AccessibilityStatus,
        /// After.
        to: AccessibilityStatus,
    },
    /// A robot's sensors measured a door's clear width.
    Clearance {
        /// GlobalId of the door.
        door: String,
        /// Name.
        name: Option<String>,
        /// The estimate, metres.
        estimate_m: f64,
        /// MinClearanceWidth, metres.
        required_m: f64,
        /// Status after R5.
        status: AccessibilityStatus,
        /// Primary and conditional roles after R5.
        roles: Vec<Role>,
    },
    /// The robot's own role switched (C-2 while another robot is closer than the zone's
    /// MinInterRobotSeparation).
    RobotRole {
        /// Role.
        role: Role,
        /// On or off.
        on: bool,
        /// The nearest tracked robot.
        other: Option<String>,
        /// Its centre distance, metres.
        distance_m: f64,
    },
    /// The robot touched something.
    Contact {
        /// GlobalId (or robot name) of what it touched.
        with: String,
        /// IFC class, or `Robot`.
        class: String,
    },
    /// The robot's centre entered a zone.
    ZoneEntered {
        /// GlobalId.
        zone: String,
        /// Name.
        name: Option<String>,
    },
    /// The robot reached its target zone's goal.
    Arrived {
        /// GlobalId.
        zone: String,
        /// Name.
        name: Option<String>,
    },
    /// A scripted key.
    Key {
        /// Key name as scripted.
        key: String,
        /// Down or up.
        down: bool,
    },
    /// The brush was switched.
    Brush {
        /// Now running.
        on: bool,
    },
}

/// One event.
#[derive(Debug, Clone, PartialEq)]
pub struct Event {
    /// Step number.
    pub step: u64,
    /// Time, seconds.
    pub t: f64,
    /// Robot name.
    pub robot: String,
    /// What.
    pub kind: EventKind,
}

impl EventKind {
    /// The `kind` tag in JSON.
    pub fn tag(&self) -> &'static str {
        match self {
            EventKind::RoleAdded { .. } => "role-added",
            EventKind::RoleRemoved { .. } => "role-removed",
            EventKind::StatusChanged { .. } => "status-changed",
            EventKind::Clearance { .. } => "clearance",
            EventKind::RobotRole { .. } => "robot-role",
            EventKind::Contact { .. } => "contact",
            EventKind::ZoneEntered { .. } => "zone-entered",
            EventKind::Arrived { .. } => "arrived",
            EventKind::Key { .. } => "key",
            EventKind::Brush { .. } => "brush",
        }
    }

    /// The fields after `kind`, written into `j` (an open object).
    pub fn write_fields(&self, j: &mut Json) {
        match self {
            EventKind::RoleAdded {
                element,
                name,
                role,
            }
            | EventKind::RoleRemoved {
                element,
                name,
                role,
            } => {
                j.key("element").str(element);
                j.key("name").opt_str(name.as_deref());
                j.key("role").str(role.label());
            }
            EventKind::StatusChanged {
                element,
                name,
                from,
                to,
            } => {
                j.key("element").str(element);
                j.key("name").opt_str(name.as_deref());
                j.key("from").str(from.label());
                j.key("to").str(to.label());
            }
            EventKind::Clearance {
                door,
                name,
                estimate_m,
                required_m,
                status,
                roles,
            } => {
                j.key("door").str(door);
                j.key("name").opt_str(name.as_deref());
                j.key("estimate_m").num(*estimate_m, 6);
                j.key("required_m").num(*required_m, 6);
                j.key("status").str(status.label());
                j.key("method").str("SENSOR_BASED");
                j.key("roles").begin_array();
                for r in roles {
                    j.str(r.label());
                }
                j.end_array();
            }
            EventKind::RobotRole {
                role,
                on,
                other,
                distance_m,
            } => {
                j.key("role").str(role.label());
                j.key("on").bool(*on);
                j.key("other").opt_str(other.as_deref());
                j.key("distance_m").num(*distance_m, 6);
            }
            EventKind::Contact { with, class } => {
                j.key("with").str(with);
                j.key("class").str(class);
            }
            EventKind::ZoneEntered { zone, name } | EventKind::Arrived { zone, name } => {
                j.key("zone").str(zone);
                j.key("name").opt_str(name.as_deref());
            }
            EventKind::Key { key, down } => {
                j.key("key").str(key);
                j.key("down").bool(*down);
            }
            EventKind::Brush { on } => {
                j.key("on").bool(*on);
            }
        }
    }
}

impl Event {
    /// The event as one JSON object.
    pub fn to_json(&self) -> String {
        let mut j = Json::default();
        j.begin_object();
        j.key("step").int(self.step as i64);
        j.key("t").num(self.t, 6);
        j.key("robot").str(&self.robot);
        j.key("kind").str(self.kind.tag());
        self.kind.write_fields(&mut j);
        j.end_object();
        j.finish()
    }
}
