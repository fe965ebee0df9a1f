//! `/poi/markers`: the storey drawn for RViz and Foxglove in the `map` frame. Namespaces:
//! `walls` (one line list per obstacle kind: `walls`, `furniture`, `door_leaves`,
//! `transitions`, `unknown`), `zones` (each space's outline, coloured by its POI roles:
//! B-1 red, C-1 orange, B-2 yellow, others blue) with `zone_labels` (name and roles),
//! `doors` (each door's passage outline, coloured by its AccessibilityStatus: FULL_ACCESS
//! green, RESTRICTED amber, BLOCKED red, PENDING_VALIDATION grey) with `door_labels`.

use std::collections::BTreeMap;

use glam::DVec2;
use poinav_nav::door_status::classified_status;
use poinav_nav::{Floor, ObstacleKind};
use poinav_roles::{RobotProfile, Role};

use crate::msgs::{Marker, MarkerKind};

/// The colour of a door status label (`FULL_ACCESS`, ...).
pub fn status_color(status: &str) -> [f32; 4] {
    match status {
        "FULL_ACCESS" => [0.13, 0.70, 0.29, 1.0],
        "RESTRICTED" => [0.95, 0.61, 0.07, 1.0],
        "BLOCKED" => [0.86, 0.15, 0.15, 1.0],
        _ => [0.55, 0.55, 0.55, 1.0],
    }
}

fn zone_color(roles: &[Role]) -> [f32; 4] {
    if roles.contains(&Role::Hazard) {
        [0.86, 0.15, 0.15, 0.9]
    } else if roles.contains(&Role::MultiRobotZone) {
        [0.95, 0.50, 0.10, 0.9]
    } else if roles.contains(&Role::Narrow) {
        [0.90, 0.80, 0.10, 0.9]
    } else {
        [0.20, 0.45, 0.85, 0.9]
    }
}

fn closed(ring: &[DVec2], z: f64) -> Vec<[f64; 3]> {
    let mut pts: Vec<[f64; 3]> = ring.iter().map(|p| [p.x, p.y, z]).collect();
    if let Some(&first) = pts.first() {
        pts.push(first);
    }
    pts
}

fn labels(roles: &[Role]) -> String {
    roles
        .iter()
        .map(|r| r.label())
        .collect::<Vec<_>>()
        .join(" ")
}

/// The markers of `floor` with door statuses `status` (by GlobalId; doors not in it have the
/// classification's status for `profile`, `poinav_nav::door_status::classified_status`).
pub fn floor_markers(
    floor: &Floor,
    profile: &RobotProfile,
    status: &BTreeMap<String, String>,
) -> Vec<Marker> {
    let mut out = Vec::new();
    let kinds = [
        (ObstacleKind::Structure, "walls", [0.25, 0.25, 0.25, 1.0]),
        (
            ObstacleKind::Furniture,
            "furniture",
            [0.55, 0.40, 0.25, 1.0],
        ),
        (
            ObstacleKind::DoorLeaf,
            "door_leaves",
            [0.45, 0.45, 0.45, 1.0],
        ),
        (
            ObstacleKind::Transition,
            "transitions",
            [0.50, 0.30, 0.70, 1.0],
        ),
        (ObstacleKind::Unknown, "unknown", [0.70, 0.70, 0.70, 1.0]),
    ];
    for (id, (kind, what, color)) in kinds.into_iter().enumerate() {
        let mut points = Vec::new();
        for o in floor.obstacles.iter().filter(|o| o.kind == kind) {
            for ring in &o.rings {
                for i in 0..ring.len() {
                    let (a, b) = (ring[i], ring[(i + 1) % ring.len()]);
                    points.push([a.x, a.y, 0.0]);
                    points.push([b.x, b.y, 0.0]);
                }
            }
        }
        if points.is_empty() {
            continue;
        }
        out.push(Marker {
            ns: "walls".into(),
            id: id as i32,
            kind: MarkerKind::LineList,
            position: [0.0; 3],
            scale: [0.03, 0.0, 0.0],
            color,
            points,
            text: what.into(),
        });
    }
    for (i, z) in floor.zones.iter().enumerate() {
        let name = z
            .name
            .clone()
            .or_else(|| z.long_name.clone())
            .unwrap_or_else(|| z.id.to_string());
        out.push(Marker {
            ns: "zones".into(),
            id: i as i32,
            kind: MarkerKind::LineStrip,
            position: [0.0; 3],
            scale: [0.04, 0.0, 0.0],
            color: zone_color(&z.roles),
            points: closed(&z.ring, 0.01),
            text: String::new(),
        });
        let c = poinav_nav::polygon::centroid(&z.ring).unwrap_or(DVec2::ZERO);
        out.push(Marker {
            ns: "zone_labels".into(),
            id: i as i32,
            kind: MarkerKind::Text,
            position: [c.x, c.y, 0.3],
            scale: [0.0, 0.0, 0.3],
            color: [0.1, 0.1, 0.1, 1.0],
            points: Vec::new(),
            text: format!("{name}\n{}", labels(&z.roles)),
        });
    }
    for (i, d) in floor.doors.iter().enumerate() {
        let s = status
            .get(d.id.as_str())
            .cloned()
            .unwrap_or_else(|| classified_status(d, profile).0.label().to_string());
        out.push(Marker {
            ns: "doors".into(),
            id: i as i32,
            kind: MarkerKind::LineStrip,
            position: [0.0; 3],
            scale: [0.08, 0.0, 0.0],
            color: status_color(&s),
            points: closed(&d.ring, 0.02),
            text: String::new(),
        });
        out.push(Marker {
            ns: "door_labels".into(),
            id: i as i32,
            kind: MarkerKind::Text,
            position: [d.center.x, d.center.y, 0.5],
            scale: [0.0, 0.0, 0.2],
            color: status_color(&s),
            points: Vec::new(),
            text: format!("{} {s}", d.name.as_deref().unwrap_or(&d.id)),
        });
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn centroid_of_a_square() {
        let sq = [
            DVec2::new(0.0, 0.0),
            DVec2::new(2.0, 0.0),
            DVec2::new(2.0, 2.0),
            DVec2::new(0.0, 2.0),
        ];
        assert_eq!(
            poinav_nav::polygon::centroid(&sq),
            Some(DVec2::new(1.0, 1.0))
        );
        assert_eq!(closed(&sq, 0.0).len(), 5);
        assert_eq!(status_color("BLOCKED"), [0.86, 0.15, 0.15, 1.0]);
    }
}
