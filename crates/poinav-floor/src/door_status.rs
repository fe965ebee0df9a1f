//! A door's AccessibilityStatus for any robot profile, computed from its profile-free facts
//! (the width the classification read, the rule that blocks it, its geometric clear width) by
//! one function, [`door_status`], for the profile a floor was built for and any other alike
//! ([`door_verdict`]: the same status without the reason, for route searches).

use poinav_roles::{clear_width_status, clear_width_verdict, AccessibilityStatus, RobotProfile};
use serde::{Deserialize, Serialize};

use crate::building::{width_status, width_verdict, worse};
use crate::floor::FloorDoor;

/// A rule that blocks a door for every profile, and why (in IFC: a window, a locked door, a
/// property rule; `poinav-poi`'s `accessibility = "blocked"`).
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
pub struct Block {
    /// The rule's id (`R2-window`, or a user rule's).
    pub rule: String,
    /// Why, in words (`IfcWindow is not passable by a ground robot`).
    pub reason: String,
}

/// The classification's verdict on `door` for `profile` (what its Pset_RobotAccessibility
/// says, and what the simulator's POI database starts with): BLOCKED when a rule blocks it,
/// else the clear-width rule on [`FloorDoor::classified_width_m`] (PENDING_VALIDATION when
/// that is unknown). Navigation uses [`door_status`], which also weighs the geometric width.
pub fn classified_status(
    door: &FloorDoor,
    profile: &RobotProfile,
) -> (AccessibilityStatus, String) {
    match &door.blocked {
        Some(b) => (AccessibilityStatus::Blocked, b.reason.clone()),
        None => clear_width_status(door.classified_width_m, None, profile),
    }
}

/// AccessibilityStatus of `door` for `profile`, with the reason: the clear-width rule on its
/// geometric clear width ([`FloorDoor::clear_width_m`], [`width_status`]), unless the
/// classification's verdict for the same profile ([`classified_status`]) is worse; then that,
/// as `<STATUS> as classified (<the width's reason>)`. So a door a rule blocks is BLOCKED for
/// every profile, and a door whose width the classification could not read is
/// PENDING_VALIDATION for every profile its geometric width does not block.
pub fn door_status(door: &FloorDoor, profile: &RobotProfile) -> (AccessibilityStatus, String) {
    let (by_width, reason) = width_status(door.clear_width_m, profile);
    let status = door_verdict(door, profile);
    if status != by_width {
        return (
            status,
            format!("{} as classified ({reason})", status.label()),
        );
    }
    (by_width, reason)
}

/// [`door_status`] without the reason: what a route search asks of every door it crosses.
pub fn door_verdict(door: &FloorDoor, profile: &RobotProfile) -> AccessibilityStatus {
    let by_width = width_verdict(door.clear_width_m, profile);
    let classified = match &door.blocked {
        Some(_) => AccessibilityStatus::Blocked,
        None => clear_width_verdict(door.classified_width_m, profile),
    };
    if worse(classified, by_width) != by_width {
        classified
    } else {
        by_width
    }
}

#[cfg(test)]
mod tests {
    use glam::DVec2;
    use poinav_roles::AccessibilityStatus::*;

    use super::*;

    /// A door `width` m wide in plan, classified from `classified` m, blocked by `blocked`.
    fn door(width: f64, classified: Option<f64>, blocked: Option<&str>) -> FloorDoor {
        FloorDoor {
            id: "d".into(),
            name: Some("Door".into()),
            ring: Default::default(),
            center: DVec2::ZERO,
            clear_width_m: width,
            classified_width_m: classified,
            blocked: blocked.map(|why| Block {
                rule: "R-locked".into(),
                reason: why.into(),
            }),
            roles: vec![],
            spaces: None,
            doorless: false,
            terrain: false,
        }
    }

    /// The paper's robot: 0.70 m wide, MinClearanceWidth 0.90 m.
    fn paper() -> RobotProfile {
        RobotProfile::paper()
    }

    /// A smaller robot: 0.50 m wide, MinClearanceWidth 0.60 m.
    fn small() -> RobotProfile {
        let mut p = RobotProfile::paper();
        p.name = "small".into();
        p.width_m = 0.5;
        p.min_clearance_width_m = Some(0.6);
        p
    }

    #[test]
    fn a_rule_blocks_the_door_for_every_profile() {
        let d = door(
            1.2,
            Some(1.2),
            Some("IfcWindow is not passable by a ground robot"),
        );
        assert_eq!(
            classified_status(&d, &paper()),
            (
                Blocked,
                "IfcWindow is not passable by a ground robot".into()
            )
        );
        for p in [paper(), small()] {
            let (s, why) = door_status(&d, &p);
            assert_eq!(s, Blocked);
            let need = p.min_clearance_width();
            assert_eq!(
                why,
                format!("BLOCKED as classified (clear width 1.200 m >= required {need:.3} m)")
            );
        }
        // Narrower than the robot: blocked by its width as well, which says why.
        let (s, why) = door_status(&door(0.6, Some(0.6), Some("locked")), &paper());
        assert_eq!(
            (s, why.as_str()),
            (Blocked, "clear width 0.600 m < robot width 0.700 m")
        );
    }

    #[test]
    fn the_classified_width_restricts_a_door_wider_in_plan() {
        // 1.0 m in plan, 0.8 m between the linings: RESTRICTED for the paper robot (0.70 <=
        // 0.80 < 0.90), FULL_ACCESS for the small one (0.80 >= 0.60).
        let d = door(1.0, Some(0.8), None);
        assert_eq!(classified_status(&d, &paper()).0, Restricted);
        assert_eq!(
            door_status(&d, &paper()),
            (
                Restricted,
                "RESTRICTED as classified (clear width 1.000 m >= required 0.900 m)".into()
            )
        );
        assert_eq!(
            door_status(&d, &small()),
            (FullAccess, "clear width 1.000 m >= required 0.600 m".into())
        );
        // 0.65 m between the linings: BLOCKED for the paper robot, RESTRICTED for the small.
        let d = door(1.0, Some(0.65), None);
        assert_eq!(door_status(&d, &paper()).0, Blocked);
        assert_eq!(door_status(&d, &small()).0, FullAccess);
        assert_eq!(
            door_status(&door(1.0, Some(0.55), None), &small()).0,
            Restricted
        );
    }

    #[test]
    fn the_geometric_width_decides_when_it_is_worse() {
        // Classified 1.0 m, 0.8 m in plan: the plan's width decides, with its own reason.
        let d = door(0.8, Some(1.0), None);
        assert_eq!(classified_status(&d, &paper()).0, FullAccess);
        assert_eq!(
            door_status(&d, &paper()),
            (
                Restricted,
                "clear width 0.800 m < required 0.900 m, >= robot width 0.700 m".into()
            )
        );
        assert_eq!(
            door_status(&door(0.6, Some(1.0), None), &paper()),
            (Blocked, "clear width 0.600 m < robot width 0.700 m".into())
        );
        assert_eq!(
            door_status(&door(0.6, Some(1.0), None), &small()).0,
            FullAccess
        );
        // A doorway is classified by its own width: the same verdict either way.
        let d = door(0.85, Some(0.85), None);
        assert_eq!(door_status(&d, &paper()).0, Restricted);
        assert_eq!(door_status(&d, &small()).0, FullAccess);
    }

    #[test]
    fn an_unknown_width_is_pending_for_every_profile_the_plan_does_not_block() {
        // The classification read no width (or classified no accessibility): PENDING for
        // every profile however wide the plan is, unless the plan is narrower than the robot.
        let d = door(1.0, None, None);
        assert_eq!(
            classified_status(&d, &paper()),
            (PendingValidation, "clear width unknown".into())
        );
        for p in [paper(), small()] {
            let need = p.min_clearance_width();
            assert_eq!(
                door_status(&d, &p),
                (
                    PendingValidation,
                    format!(
                        "PENDING_VALIDATION as classified (clear width 1.000 m >= required {need:.3} m)"
                    )
                )
            );
        }
        let d = door(0.6, None, None);
        assert_eq!(door_status(&d, &paper()).0, Blocked);
        assert_eq!(door_status(&d, &small()).0, PendingValidation);
        // Nor a width in plan: unknown, and said so.
        assert_eq!(
            door_status(&door(f64::NAN, None, None), &paper()),
            (PendingValidation, "clear width unknown".into())
        );
        assert_eq!(
            door_status(&door(0.0, Some(1.0), None), &paper()),
            (PendingValidation, "clear width unknown".into())
        );
    }

    /// The rule before the facts, when a floor carried the verdict `stored` of the profile it
    /// was built for and that profile's MinClearanceWidth `required`.
    fn stored_rule(
        door: &FloorDoor,
        stored: AccessibilityStatus,
        required: f64,
        profile: &RobotProfile,
    ) -> (AccessibilityStatus, String) {
        let (by_width, reason) = width_status(door.clear_width_m, profile);
        let not_by_width =
            stored == Blocked && door.clear_width_m.is_finite() && door.clear_width_m >= required;
        let same_profile = (required - profile.min_clearance_width()).abs() < 1e-9;
        if not_by_width || (same_profile && worse(stored, by_width) != by_width) {
            return (
                stored,
                format!("{} as classified ({reason})", stored.label()),
            );
        }
        (by_width, reason)
    }

    #[test]
    fn for_the_profile_a_floor_was_built_for_nothing_changes() {
        // Every combination of width in plan, width as classified and block: for the build
        // profile the facts give the status and reason the stored verdict gave, byte for byte.
        let widths = [
            f64::NAN,
            -1.0,
            0.0,
            0.4,
            0.5,
            0.55,
            0.6,
            0.65,
            0.7,
            0.8,
            0.9,
            1.2,
        ];
        let mut cases = 0;
        for profile in [paper(), small()] {
            for plan in widths {
                for classified in std::iter::once(None).chain(widths.map(Some)) {
                    for blocked in [None, Some("locked")] {
                        let d = door(plan, classified, blocked);
                        // What the bridge stored: the classification's verdict.
                        let stored = match blocked {
                            Some(_) => Blocked,
                            None => clear_width_status(classified, None, &profile).0,
                        };
                        assert_eq!(classified_status(&d, &profile).0, stored);
                        assert_eq!(door_verdict(&d, &profile), door_status(&d, &profile).0);
                        assert_eq!(
                            door_status(&d, &profile),
                            stored_rule(&d, stored, profile.min_clearance_width(), &profile),
                            "{plan} {classified:?} {blocked:?} {}",
                            profile.name
                        );
                        cases += 1;
                    }
                }
            }
        }
        assert_eq!(cases, 2 * 12 * 13 * 2);
    }
}
