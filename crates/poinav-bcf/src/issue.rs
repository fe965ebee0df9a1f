//! Which topics an audit gives: one per door passage or vertical connection that is BLOCKED or
//! RESTRICTED for a profile and one per space it cannot reach, with the words a designer reads
//! (title, description, labels) and what the viewpoint looks at.

use glam::DVec2;
use poinav_nav::audit::{DoorAudit, ProfileAudit, SpaceAudit, TransitionAudit};
use poinav_nav::{AuditReport, Building, DoorFrame, ObstacleKind, Ring};
use poinav_poi::AccessibilityStatus;

use crate::guid;

/// What a topic is about.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum IssueKind {
    /// A door or a doorway (an opening without a door).
    Door,
    /// A stair, ramp or lift (its kind label).
    Transition(&'static str),
    /// A space the profile cannot reach.
    Space,
}

impl IssueKind {
    /// `door`, `stair`, `ramp`, `lift`, `space`.
    pub fn label(self) -> &'static str {
        match self {
            IssueKind::Door => "door",
            IssueKind::Transition(k) => k,
            IssueKind::Space => "space",
        }
    }
}

/// Where the viewpoint looks, in the plan of one storey (world metres).
#[derive(Debug, Clone, PartialEq)]
pub enum Focus {
    /// A door: its passage ring, centre and the unit normal across it.
    Door {
        /// Passage ring.
        ring: Ring,
        /// Centre.
        center: DVec2,
        /// Unit normal (direction of travel).
        normal: DVec2,
    },
    /// A stair, ramp or lift seen from its landing: the landing point and what to look at
    /// (the middle of the element's outline on that storey, else a metre beyond the landing).
    Landing {
        /// The landing point.
        landing: DVec2,
        /// What to look at.
        target: DVec2,
        /// The element's outline rings on that storey (may be empty).
        rings: Vec<Ring>,
    },
    /// A space: its outline.
    Space {
        /// Outline ring.
        ring: Ring,
    },
}

/// One topic to write.
#[derive(Debug, Clone, PartialEq)]
pub struct Issue {
    /// Topic GUID (deterministic, [`guid::topic_guid`]).
    pub guid: String,
    /// What it is about.
    pub kind: IssueKind,
    /// Index of the profile in the report.
    pub profile: usize,
    /// Profile name.
    pub profile_name: String,
    /// The element's id (an IFC GlobalId for models read from IFC).
    pub element: String,
    /// The status the topic reports: `BLOCKED`, `RESTRICTED` or `UNREACHABLE`.
    pub status: &'static str,
    /// Title.
    pub title: String,
    /// Description.
    pub description: String,
    /// Labels: the profile, the status and the kind.
    pub labels: Vec<String>,
    /// Priority: `High` for BLOCKED and UNREACHABLE, `Normal` for RESTRICTED.
    pub priority: &'static str,
    /// Storey index the viewpoint and snapshot show (`None`: the element is on no storey
    /// poinav knows; the topic then has no viewpoint).
    pub floor: Option<usize>,
    /// What the viewpoint looks at.
    pub focus: Option<Focus>,
}

/// The status words BCF labels use.
pub const UNREACHABLE: &str = "UNREACHABLE";

/// Every topic of `report` on `building`, in the report's order: per profile its doors, then
/// its stairs, ramps and lifts, then its spaces. A topic whose GUID came already (the same
/// element twice) is left out.
pub fn issues(report: &AuditReport, building: &Building) -> Vec<Issue> {
    let mut out: Vec<Issue> = Vec::new();
    for (pi, p) in report.profiles.iter().enumerate() {
        for d in &p.doors {
            if let Some(status) = failing(d.status) {
                out.push(door_issue(building, pi, p, d, status));
            }
        }
        for t in &p.transitions {
            if let Some(status) = failing(t.status) {
                out.push(transition_issue(building, pi, p, t, status));
            }
        }
        for s in &p.spaces {
            if !s.reachable {
                out.push(space_issue(building, pi, p, s));
            }
        }
    }
    let mut seen = std::collections::BTreeSet::new();
    out.retain(|i| seen.insert(i.guid.clone()));
    out
}

fn failing(s: AccessibilityStatus) -> Option<&'static str> {
    match s {
        AccessibilityStatus::Blocked | AccessibilityStatus::Restricted => Some(s.label()),
        _ => None,
    }
}

fn priority(status: &str) -> &'static str {
    if status == "RESTRICTED" {
        "Normal"
    } else {
        "High"
    }
}

fn labels(p: &ProfileAudit, status: &str, kind: IssueKind) -> Vec<String> {
    vec![
        p.profile.clone(),
        status.to_string(),
        kind.label().to_string(),
    ]
}

/// A name for titles: the name, else the id.
fn named<'a>(name: Option<&'a str>, id: &'a str) -> &'a str {
    name.map(str::trim).filter(|n| !n.is_empty()).unwrap_or(id)
}

fn door_issue(
    building: &Building,
    pi: usize,
    p: &ProfileAudit,
    d: &DoorAudit,
    status: &'static str,
) -> Issue {
    let kind = IssueKind::Door;
    let what = if d.doorless { "Doorway" } else { "Door" };
    let name = named(d.name.as_deref(), &d.id);
    let title = format!(
        "{what} {name} on {} is {status} for {}: {:.2} m clear, needs {:.2} m",
        d.floor_name, p.profile, d.clear_width_m, d.required_width_m
    );
    let mut description = format!(
        "{what} {name} ({}) on storey {}: clear width {:.3} m; the robot profile {} ({:.3} m wide) needs {:.3} m (MinClearanceWidth). Status {status}: {}.",
        d.id,
        d.floor_name,
        d.clear_width_m,
        p.profile,
        p.robot_width_m,
        d.required_width_m,
        d.reason
    );
    match d.zones.as_slice() {
        [a, b] if a == b => description.push_str(&format!(" Inside {a}.")),
        zones => description.push_str(&format!(
            " Between {}{}.",
            zones.join(" and "),
            if d.exterior { " (an entrance)" } else { "" }
        )),
    }
    description.push_str(if d.grid_passable {
        " The robot's centre can cross it in the inflated occupancy grid."
    } else {
        " The robot's centre cannot cross it in the inflated occupancy grid."
    });
    let floor = building.floors.get(d.floor).map(|_| d.floor);
    let focus = floor.and_then(|fi| {
        let f = &building.floors[fi];
        let k = f.doors.iter().position(|x| x.id == d.id)?;
        let frame = f.door_frame(k)?;
        Some(Focus::Door {
            ring: f.doors[k].ring.clone(),
            center: frame.center,
            normal: frame.normal,
        })
    });
    Issue {
        guid: guid::topic_guid(&p.profile, &d.id, kind.label()),
        kind,
        profile: pi,
        profile_name: p.profile.clone(),
        element: d.id.to_string(),
        status,
        title,
        description,
        labels: labels(p, status, kind),
        priority: priority(status),
        floor,
        focus,
    }
}

fn transition_issue(
    building: &Building,
    pi: usize,
    p: &ProfileAudit,
    t: &TransitionAudit,
    status: &'static str,
) -> Issue {
    let kind = IssueKind::Transition(t.kind);
    let name = named(t.name.as_deref(), &t.id);
    let title = format!(
        "{} {name} is {status} for {}",
        capitalised(t.kind),
        p.profile
    );
    let mut description = format!(
        "{} {name} ({}) between storeys {}: status {status} for the robot profile {} ({:.3} m wide, needs {:.3} m clear): {}.",
        capitalised(t.kind),
        t.id,
        t.floors.join(", "),
        p.profile,
        p.robot_width_m,
        p.required_width_m,
        t.reason
    );
    if let Some(w) = t.clear_width_m {
        description.push_str(&format!(" Clear width {w:.3} m."));
    }
    if let Some(s) = t.slope_deg {
        description.push_str(&format!(" Slope {s:.1} degrees."));
    }
    // Seen from its lowest landing.
    let connection = building.connections.iter().find(|c| c.id == t.id);
    let landing = connection.and_then(|c| {
        c.landings
            .iter()
            .filter(|l| l.floor < building.floors.len())
            .min_by(|a, b| {
                let z = |f: usize| building.floors[f].elevation_m;
                z(a.floor)
                    .total_cmp(&z(b.floor))
                    .then(a.floor.cmp(&b.floor))
            })
    });
    let floor = landing.map(|l| l.floor);
    let focus = landing.map(|l| {
        let f = &building.floors[l.floor];
        let mut rings: Vec<Ring> = f
            .obstacles
            .iter()
            .filter(|o| o.id == t.id)
            .flat_map(|o| o.rings.iter().cloned())
            .chain(
                f.zones
                    .iter()
                    .filter(|z| z.id == t.id)
                    .map(|z| z.ring.clone()),
            )
            .collect();
        if rings.is_empty() {
            // Its parts (flights, landings) carry their own ids: the stair and ramp
            // outlines the landing touches.
            rings = f
                .obstacles
                .iter()
                .filter(|o| o.kind == ObstacleKind::Transition)
                .filter(|o| {
                    o.rings
                        .iter()
                        .any(|r| poinav_nav::polygon::area_distance(r, l.point) < 1.0)
                })
                .flat_map(|o| o.rings.iter().cloned())
                .collect();
        }
        let target = rings_center(&rings).unwrap_or(l.point + DVec2::X);
        Focus::Landing {
            landing: l.point,
            target,
            rings,
        }
    });
    Issue {
        guid: guid::topic_guid(&p.profile, &t.id, kind.label()),
        kind,
        profile: pi,
        profile_name: p.profile.clone(),
        element: t.id.to_string(),
        status,
        title,
        description,
        labels: labels(p, status, kind),
        priority: priority(status),
        floor,
        focus,
    }
}

fn space_issue(building: &Building, pi: usize, p: &ProfileAudit, s: &SpaceAudit) -> Issue {
    let kind = IssueKind::Space;
    let name = named(s.name.as_deref(), &s.id);
    let title = format!(
        "Space {name} on {} is unreachable for {}",
        s.floor_name, p.profile
    );
    let mut description = format!(
        "Space {name} ({}) on storey {} cannot be reached by the robot profile {} ({:.3} m wide, needs {:.3} m clear) from {}: {}.",
        s.id,
        s.floor_name,
        p.profile,
        p.robot_width_m,
        p.required_width_m,
        if p.starts.is_empty() {
            "anywhere (no entrance found)".to_string()
        } else {
            p.starts.join(", ")
        },
        s.reason
    );
    if !s.blocked_by.is_empty() {
        let names: Vec<String> = s.blocked_by.iter().map(|b| b.to_string()).collect();
        description.push_str(&format!(" In the way: {}.", names.join("; ")));
    }
    let floor = building.floors.get(s.floor).map(|_| s.floor);
    let focus = floor.and_then(|fi| {
        let z = building.floors[fi].zones.iter().find(|z| z.id == s.id)?;
        Some(Focus::Space {
            ring: z.ring.clone(),
        })
    });
    Issue {
        guid: guid::topic_guid(&p.profile, &s.id, kind.label()),
        kind,
        profile: pi,
        profile_name: p.profile.clone(),
        element: s.id.to_string(),
        status: UNREACHABLE,
        title,
        description,
        labels: labels(p, UNREACHABLE, kind),
        priority: priority(UNREACHABLE),
        floor,
        focus,
    }
}

fn capitalised(word: &str) -> String {
    let mut c = word.chars();
    match c.next() {
        Some(f) => f.to_uppercase().chain(c).collect(),
        None => String::new(),
    }
}

/// The middle of the bounding box of `rings`.
pub fn rings_center(rings: &[Ring]) -> Option<DVec2> {
    let (lo, hi) = rings_bounds(rings)?;
    Some((lo + hi) / 2.0)
}

/// The bounding box of `rings`.
pub fn rings_bounds(rings: &[Ring]) -> Option<(DVec2, DVec2)> {
    poinav_nav::polygon::bounds_of(rings.iter().flatten())
}
