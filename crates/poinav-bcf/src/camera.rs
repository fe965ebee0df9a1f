//! The viewpoint's perspective camera: at eye height ([`EYE_HEIGHT_M`] above the storey's
//! walking level) in front of the door (on the side of a space, up to [`DOOR_DISTANCE_M`]
//! away, nearer when that space is smaller), looking at the door's middle; beyond the landing
//! of a stair, ramp or lift, looking at it; above a space, looking down into it. World
//! coordinates in metres, the model's own frame (IFC placements composed, Z up).

use glam::{DVec2, DVec3};
use poinav_nav::polygon;
use poinav_nav::Floor;

use crate::issue::{rings_bounds, Focus};

/// Eye height above the storey's walking level, metres.
pub const EYE_HEIGHT_M: f64 = 1.6;
/// How far in front of a door the camera stands at most, metres.
pub const DOOR_DISTANCE_M: f64 = 2.5;
/// Height of the point looked at on a door, above the walking level, metres.
pub const DOOR_TARGET_HEIGHT_M: f64 = 1.0;
/// Vertical field of view, degrees (within what BCF 2.1 allows, 45-60).
pub const FIELD_OF_VIEW_DEG: f64 = 60.0;

/// A perspective camera.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Camera {
    /// Where the eye is.
    pub position: DVec3,
    /// Unit direction it looks in.
    pub direction: DVec3,
    /// Unit up vector, perpendicular to `direction`.
    pub up: DVec3,
    /// Vertical field of view, degrees.
    pub field_of_view_deg: f64,
}

impl Camera {
    /// A camera at `eye` looking at `target`, its up vector in the vertical plane.
    pub fn looking_at(eye: DVec3, target: DVec3) -> Camera {
        let direction = (target - eye).try_normalize().unwrap_or(DVec3::X);
        let up = (DVec3::Z - direction * direction.z)
            .try_normalize()
            .unwrap_or(DVec3::Y);
        Camera {
            position: eye,
            direction,
            up,
            field_of_view_deg: FIELD_OF_VIEW_DEG,
        }
    }
}

/// The camera for `focus` on `floor`.
pub fn camera(floor: &Floor, focus: &Focus) -> Camera {
    let z = floor.elevation_m;
    match focus {
        Focus::Door { center, normal, .. } => {
            let eye = door_eye(floor, *center, *normal);
            Camera::looking_at(
                eye.extend(z + EYE_HEIGHT_M),
                center.extend(z + DOOR_TARGET_HEIGHT_M),
            )
        }
        Focus::Landing {
            landing, target, ..
        } => {
            let back = (*landing - *target).try_normalize().unwrap_or(-DVec2::X);
            let eye = *landing + back * 1.5;
            Camera::looking_at(eye.extend(z + EYE_HEIGHT_M), target.extend(z + 0.5))
        }
        Focus::Space { ring } => {
            let (lo, hi) = rings_bounds(std::slice::from_ref(ring)).unwrap_or_default();
            let center = polygon::interior_point(ring).unwrap_or((lo + hi) / 2.0);
            let size = (hi - lo).max_element().max(4.0);
            // From the south, high enough to see the whole room at about 50 degrees down.
            let eye = center - DVec2::Y * size * 0.6;
            Camera::looking_at(eye.extend(z + size * 0.8), center.extend(z))
        }
    }
}

/// Where to stand in front of a door: on the side whose space lets the camera stand
/// furthest from it (as far as [`DOOR_DISTANCE_M`], still in that space; the positive normal
/// on a tie, and [`DOOR_DISTANCE_M`] along it when no space touches the door).
pub fn door_eye(floor: &Floor, center: DVec2, normal: DVec2) -> DVec2 {
    let zone_at = |p: DVec2| {
        floor
            .zones
            .iter()
            .position(|z| polygon::contains(&z.ring, p))
    };
    let near = 0.6;
    let reach = |dir: DVec2| -> Option<f64> {
        let zone = zone_at(center + dir * near)?;
        let steps = ((DOOR_DISTANCE_M - near) / 0.1).round() as usize;
        (0..=steps)
            .map(|k| DOOR_DISTANCE_M - k as f64 * 0.1)
            .find(|&d| zone_at(center + dir * d) == Some(zone))
            .or(Some(near))
    };
    match (reach(normal), reach(-normal)) {
        (Some(a), Some(b)) if b > a + 1e-9 => center - normal * b,
        (Some(a), _) => center + normal * a,
        (None, Some(b)) => center - normal * b,
        (None, None) => center + normal * DOOR_DISTANCE_M,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use poinav_nav::polygon::rect;
    use poinav_nav::FloorZone;

    fn zone(id: &str, ring: poinav_nav::Ring) -> FloorZone {
        FloorZone {
            id: id.into(),
            name: Some(id.into()),
            long_name: None,
            ring,
            roles: vec![],
            coordination: None,
        }
    }

    #[test]
    fn the_camera_stands_in_the_room_at_eye_height_looking_at_the_door() {
        // A door at x = 4 in a wall between a 4 m room (west) and a 1 m closet (east).
        let floor = Floor {
            name: "L1".into(),
            elevation_m: 3.0,
            zones: vec![
                zone("closet", rect(4.1, 0.0, 5.1, 4.0)),
                zone("room", rect(0.0, 0.0, 3.9, 4.0)),
            ],
            ..Floor::default()
        };
        let focus = Focus::Door {
            ring: rect(3.9, 1.5, 4.1, 2.5),
            center: DVec2::new(4.0, 2.0),
            normal: DVec2::X,
        };
        let c = camera(&floor, &focus);
        // The room gives the longer view: 2.5 m into it, 1.6 m above the storey.
        assert!((c.position.x - 1.5).abs() < 1e-9, "{c:?}");
        assert!((c.position.y - 2.0).abs() < 1e-9);
        assert!((c.position.z - 4.6).abs() < 1e-9, "{c:?}");
        // Looking at the door's middle 1.0 m above the floor: 2.5 m across, 0.6 m down.
        let expect = DVec3::new(2.5, 0.0, -0.6).normalize();
        assert!((c.direction - expect).length() < 1e-9, "{c:?}");
        assert!(c.up.dot(c.direction).abs() < 1e-9 && c.up.z > 0.0);
        // With the closet only, the camera stays inside it (1 m deep).
        let floor = Floor {
            zones: vec![floor.zones[0].clone()],
            ..floor
        };
        let c = camera(&floor, &focus);
        assert!((c.position.x - 5.0).abs() < 1e-9, "{c:?}");
        assert!(c.direction.x < -0.8 && c.direction.z < 0.0, "{c:?}");
    }
}
