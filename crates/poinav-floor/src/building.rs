//! A building for navigation: its storeys as [`Floor`]s and the stairs, ramps and lifts that
//! connect them ([`VerticalConnection`]), plus the AccessibilityStatus of connections for any
//! robot profile (doors': [`crate::door_status`]) and the status helpers both share.

use glam::DVec2;
use poinav_roles::{
    clear_width_status, clear_width_verdict, slope_status, stairs_status, AccessibilityStatus,
    RobotProfile,
};
use serde::{Deserialize, Serialize};

use crate::floor::Floor;
use crate::id::ElementId;
use crate::level::FloorLevel;

/// Every storey and what connects them.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
pub struct Building {
    /// Storeys, in the order they are given (usually by elevation).
    pub floors: Vec<Floor>,
    /// Stairs, ramps and lifts between storeys.
    pub connections: Vec<VerticalConnection>,
    /// Per storey (as `floors`): its walking level, where that comes from and whether it is
    /// at ground level. Empty (or shorter): every storey missing counts as at ground level
    /// with its elevation from the storey (hand-built buildings, one-storey floors).
    #[serde(default)]
    pub levels: Vec<FloorLevel>,
}

impl Building {
    /// A building of one storey.
    pub fn single(floor: Floor) -> Building {
        Building {
            floors: vec![floor],
            connections: Vec::new(),
            levels: Vec::new(),
        }
    }

    /// True when storey `floor` is at ground level ([`FloorLevel::at_ground`]), where a door
    /// with one side outside is an entrance; storeys without a level are.
    pub fn at_ground(&self, floor: usize) -> bool {
        self.levels.get(floor).is_none_or(|l| l.at_ground)
    }

    /// The index of the storey with this name.
    pub fn floor_index(&self, name: &str) -> Option<usize> {
        self.floors.iter().position(|f| f.name == name)
    }

    /// What limits navigation on this building, one sentence each: a building with nothing to
    /// navigate at all (no spaces, doors or obstacles on any storey: an infrastructure model, or
    /// one without a building), storeys with doors but no spaces (their doors join nothing, so
    /// they have no entrance and no room to route to).
    pub fn diagnostics(&self) -> Vec<String> {
        if self
            .floors
            .iter()
            .all(|f| f.zones.is_empty() && f.doors.is_empty() && f.obstacles.is_empty())
        {
            return vec![format!(
                "nothing to navigate: {} spaces, doors, walls or other obstacles (a model without a building, such as infrastructure, or without geometry); the maps are empty",
                match self.floors.len() {
                    0 => "the model has no storeys, no".to_string(),
                    1 => format!("its one storey `{}` has no", self.floors[0].name),
                    n => format!("none of its {n} storeys has"),
                }
            )];
        }
        self.floors
            .iter()
            .filter(|f| f.zones.is_empty() && !f.doors.is_empty())
            .map(|f| {
                format!(
                    "storey `{}` has {} door{} but no spaces (IfcSpace): its doors join no rooms, so it has no entrance and nothing to route to by name; routes there need points (`x,y@{}`), and only the free space enclosed by walls and doors and a free apron on each side of every open door are mapped",
                    f.name,
                    f.doors.len(),
                    if f.doors.len() == 1 { "" } else { "s" },
                    f.name
                )
            })
            .collect()
    }
}

/// What a vertical connection is.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum ConnectionKind {
    /// Stairs: legged robots only.
    Stair,
    /// A ramp: up to the profile's maximum slope.
    Ramp,
    /// A lift: any robot that fits through its door.
    Lift,
}

impl ConnectionKind {
    /// `stair`, `ramp`, `lift`.
    pub fn label(self) -> &'static str {
        match self {
            ConnectionKind::Stair => "stair",
            ConnectionKind::Ramp => "ramp",
            ConnectionKind::Lift => "lift",
        }
    }
}

/// Where a vertical connection is entered on one storey.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Landing {
    /// Index into [`Building::floors`].
    pub floor: usize,
    /// The point a robot drives to (in free space beside the stair foot, ramp end or lift door).
    pub point: DVec2,
}

/// A stair, ramp or lift connecting two or more storeys.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct VerticalConnection {
    /// GlobalId (or a made-up id).
    pub id: ElementId,
    /// Name.
    pub name: Option<String>,
    /// Kind.
    pub kind: ConnectionKind,
    /// Landings, one per storey served (at least two).
    pub landings: Vec<Landing>,
    /// Clear width of the flight, ramp or lift door; `None` when unknown.
    pub clear_width_m: Option<f64>,
    /// Ramp slope in degrees; `None` when unknown (or not a ramp).
    pub slope_deg: Option<f64>,
    /// Travel time between two adjacent landings in seconds (waiting for a lift included);
    /// `None`: estimated from the storey heights (see [`VerticalConnection::travel_time_s`]).
    pub travel_time_s: Option<f64>,
}

/// Assumed climbing speed on stairs (vertical metres per second) when no time is given.
pub const STAIR_VERTICAL_SPEED_M_S: f64 = 0.2;
/// Assumed lift speed (m/s) and the wait for it (s) when no time is given.
pub const LIFT_SPEED_M_S: f64 = 1.0;
/// See [`LIFT_SPEED_M_S`].
pub const LIFT_WAIT_S: f64 = 30.0;

impl VerticalConnection {
    /// The label used in reports: name, else id.
    pub fn label(&self) -> &str {
        self.name.as_deref().unwrap_or(&self.id)
    }

    /// Seconds to travel between storeys `dz` metres apart at a speed fraction of the
    /// profile's maximum (ramps).
    pub fn travel_time_s(&self, dz: f64, profile: &RobotProfile) -> f64 {
        if let Some(t) = self.travel_time_s {
            return t;
        }
        let dz = dz.abs();
        match self.kind {
            ConnectionKind::Stair => dz / STAIR_VERTICAL_SPEED_M_S,
            ConnectionKind::Lift => LIFT_WAIT_S + dz / LIFT_SPEED_M_S,
            ConnectionKind::Ramp => {
                let slope = self.slope_deg.unwrap_or(profile.max_slope_deg).max(0.5);
                let run = dz / slope.to_radians().tan();
                run.hypot(dz) / (0.5 * profile.max_speed_m_s)
            }
        }
    }

    /// AccessibilityStatus of this connection for `profile`, with the reason.
    pub fn status(&self, profile: &RobotProfile) -> (AccessibilityStatus, String) {
        use AccessibilityStatus::*;
        let (kind_status, kind_reason) = match self.kind {
            ConnectionKind::Stair => stairs_status(profile),
            ConnectionKind::Ramp => slope_status(self.slope_deg, profile),
            ConnectionKind::Lift => (FullAccess, "lift".into()),
        };
        if kind_status == Blocked {
            return (kind_status, kind_reason);
        }
        let (width_status, width_reason) = match self.clear_width_m {
            Some(w) => width_status(w, profile),
            None if self.kind == ConnectionKind::Lift => (
                PendingValidation,
                "door width unknown (no door found at the lift): measure it on site or model \
                 the lift's door"
                    .into(),
            ),
            None => return (kind_status, kind_reason),
        };
        let worst = worse(kind_status, width_status);
        (worst, format!("{kind_reason}; {width_reason}"))
    }
}

/// The worse of two statuses (BLOCKED > PENDING_VALIDATION > RESTRICTED > FULL_ACCESS).
pub fn worse(a: AccessibilityStatus, b: AccessibilityStatus) -> AccessibilityStatus {
    fn rank(s: AccessibilityStatus) -> u8 {
        match s {
            AccessibilityStatus::FullAccess => 0,
            AccessibilityStatus::Restricted => 1,
            AccessibilityStatus::PendingValidation => 2,
            AccessibilityStatus::Blocked => 3,
        }
    }
    if rank(a) >= rank(b) {
        a
    } else {
        b
    }
}

/// The clear-width rule of poinav-poi ([`poinav_roles::clear_width_status`], docs/rules.md): at
/// least MinClearanceWidth FULL_ACCESS, at least the robot's width RESTRICTED, else BLOCKED; a
/// width that is not a positive number is unknown (PENDING_VALIDATION).
pub fn width_status(clear_width_m: f64, profile: &RobotProfile) -> (AccessibilityStatus, String) {
    clear_width_status(known_width(clear_width_m), None, profile)
}

/// [`width_status`] without the reason.
pub fn width_verdict(clear_width_m: f64, profile: &RobotProfile) -> AccessibilityStatus {
    clear_width_verdict(known_width(clear_width_m), profile)
}

/// A width that is a positive number, else unknown.
fn known_width(clear_width_m: f64) -> Option<f64> {
    (clear_width_m.is_finite() && clear_width_m > 0.0).then_some(clear_width_m)
}

/// True when a robot may pass a transition with this status (`pending_passable` decides
/// PENDING_VALIDATION).
pub fn passable(status: AccessibilityStatus, pending_passable: bool) -> bool {
    match status {
        AccessibilityStatus::FullAccess | AccessibilityStatus::Restricted => true,
        AccessibilityStatus::Blocked => false,
        AccessibilityStatus::PendingValidation => pending_passable,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::floor::FloorDoor;

    fn door(width: f64) -> FloorDoor {
        FloorDoor {
            id: "d".into(),
            name: Some("Door".into()),
            ring: Default::default(),
            center: DVec2::ZERO,
            clear_width_m: width,
            classified_width_m: Some(width),
            blocked: None,
            roles: vec![],
            spaces: None,
            doorless: false,
            terrain: false,
        }
    }

    #[test]
    fn a_building_with_nothing_to_navigate_says_so() {
        let empty = |name: &str| Floor {
            name: name.into(),
            ..Floor::default()
        };
        let one = Building::single(empty("Default Project"));
        assert_eq!(
            one.diagnostics(),
            ["nothing to navigate: its one storey `Default Project` has no spaces, doors, walls or other obstacles (a model without a building, such as infrastructure, or without geometry); the maps are empty"]
        );
        let none = Building {
            floors: vec![],
            connections: vec![],
            levels: vec![],
        };
        assert!(none.diagnostics()[0]
            .starts_with("nothing to navigate: the model has no storeys, no spaces"));
        let mut two = Building {
            floors: vec![empty("L1"), empty("L2")],
            connections: vec![],
            levels: vec![],
        };
        assert!(two.diagnostics()[0]
            .starts_with("nothing to navigate: none of its 2 storeys has spaces"));
        // One door is something: the storey-without-spaces warning instead.
        two.floors[1].doors.push(door(1.0));
        let d = two.diagnostics();
        assert_eq!(d.len(), 1);
        assert!(
            d[0].starts_with("storey `L2` has 1 door but no spaces"),
            "{d:?}"
        );
    }

    #[test]
    fn connections_by_kind() {
        let paper = RobotProfile::paper();
        let c = |kind, slope| VerticalConnection {
            id: "s".into(),
            name: None,
            kind,
            landings: vec![],
            clear_width_m: Some(1.2),
            slope_deg: slope,
            travel_time_s: None,
        };
        assert_eq!(
            c(ConnectionKind::Stair, None).status(&paper).0,
            AccessibilityStatus::Blocked
        );
        assert_eq!(
            c(ConnectionKind::Ramp, Some(5.0)).status(&paper).0,
            AccessibilityStatus::FullAccess
        );
        assert_eq!(
            c(ConnectionKind::Ramp, Some(8.0)).status(&paper).0,
            AccessibilityStatus::Blocked
        );
        assert_eq!(
            c(ConnectionKind::Lift, None).status(&paper).0,
            AccessibilityStatus::FullAccess
        );
        assert!((c(ConnectionKind::Lift, None).travel_time_s(3.0, &paper) - 33.0).abs() < 1e-9);
    }
}
