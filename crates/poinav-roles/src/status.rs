//! The status rules (docs/rules.md): an element's AccessibilityStatus for a robot profile as a
//! pure function of its facts (clear width, stairs, slope), with the reason in words. The
//! classification applies them to IFC elements, navigation to doors and vertical connections.

use crate::profile::RobotProfile;
use crate::taxonomy::{AccessibilityStatus, ValidationMethod};

/// Pset_RobotAccessibility values for one element and profile.
#[derive(Debug, Clone, PartialEq)]
pub struct Accessibility {
    /// Required clear width (the profile's), metres.
    pub min_clearance_width_m: f64,
    /// Required clear height (the profile's), metres.
    pub min_clearance_height_m: f64,
    /// The verdict.
    pub status: AccessibilityStatus,
    /// How it was reached.
    pub method: ValidationMethod,
    /// Why, in words (`clear width 0.785 m < required 0.900 m`).
    pub reason: String,
}

fn fmt_m(v: f64) -> String {
    format!("{v:.3} m")
}

/// The clear-width rule (docs/rules.md): at least the profile's MinClearanceWidth is
/// FULL_ACCESS, at least the robot's width RESTRICTED, narrower BLOCKED, unknown
/// PENDING_VALIDATION; with the reason (`source` says where the width comes from). Navigation
/// applies the same rule to doors and connections for any profile.
pub fn clear_width_status(
    clear_width_m: Option<f64>,
    source: Option<&str>,
    profile: &RobotProfile,
) -> (AccessibilityStatus, String) {
    use AccessibilityStatus::*;
    let status = clear_width_verdict(clear_width_m, profile);
    let Some(w) = clear_width_m else {
        return (status, "clear width unknown".into());
    };
    let need = profile.min_clearance_width();
    let from = source.map(|s| format!(" ({s})")).unwrap_or_default();
    let reason = match status {
        FullAccess => format!("clear width {}{from} >= required {}", fmt_m(w), fmt_m(need)),
        Restricted => format!(
            "clear width {}{from} < required {}, >= robot width {}",
            fmt_m(w),
            fmt_m(need),
            fmt_m(profile.width_m)
        ),
        _ => format!(
            "clear width {}{from} < robot width {}",
            fmt_m(w),
            fmt_m(profile.width_m)
        ),
    };
    (status, reason)
}

/// [`clear_width_status`] without the reason: for searches that only ask whether a robot
/// passes (a route's door edges), where writing the reason's numbers cost far more than the
/// rule.
pub fn clear_width_verdict(
    clear_width_m: Option<f64>,
    profile: &RobotProfile,
) -> AccessibilityStatus {
    use AccessibilityStatus::*;
    match clear_width_m {
        Some(w) if w >= profile.min_clearance_width() => FullAccess,
        Some(w) if w >= profile.width_m => Restricted,
        Some(_) => Blocked,
        None => PendingValidation,
    }
}

/// Stairs: FULL_ACCESS for a profile that climbs them, else BLOCKED; with the reason.
pub fn stairs_status(profile: &RobotProfile) -> (AccessibilityStatus, String) {
    if profile.climbs_stairs() {
        (
            AccessibilityStatus::FullAccess,
            format!("profile {} climbs stairs", profile.name),
        )
    } else {
        (
            AccessibilityStatus::Blocked,
            format!(
                "stairs are not passable for a {} robot",
                format!("{:?}", profile.locomotion).to_lowercase()
            ),
        )
    }
}

/// A ramp: FULL_ACCESS up to the profile's maximum slope, BLOCKED above it, PENDING_VALIDATION
/// when the slope is unknown; with the reason.
pub fn slope_status(
    slope_deg: Option<f64>,
    profile: &RobotProfile,
) -> (AccessibilityStatus, String) {
    match slope_deg {
        Some(s) if s <= profile.max_slope_deg => (
            AccessibilityStatus::FullAccess,
            format!("slope {s:.1} deg <= max {:.1} deg", profile.max_slope_deg),
        ),
        Some(s) => (
            AccessibilityStatus::Blocked,
            format!("slope {s:.1} deg > max {:.1} deg", profile.max_slope_deg),
        ),
        None => (
            AccessibilityStatus::PendingValidation,
            "slope unknown".into(),
        ),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use AccessibilityStatus::*;

    #[test]
    fn the_clear_width_verdict_is_the_status_without_its_reason() {
        let paper = RobotProfile::paper();
        let need = paper.min_clearance_width();
        // Around both thresholds, exactly on them, unknown, not a number.
        let widths = [
            None,
            Some(f64::NAN),
            Some(-1.0),
            Some(0.0),
            Some(paper.width_m - 1e-9),
            Some(paper.width_m),
            Some(0.5 * (paper.width_m + need)),
            Some(need - 1e-9),
            Some(need),
            Some(need + 1e-9),
            Some(2.0),
        ];
        let verdicts: Vec<_> = widths
            .iter()
            .map(|&w| {
                let v = clear_width_verdict(w, &paper);
                assert_eq!(v, clear_width_status(w, Some("lining"), &paper).0, "{w:?}");
                v
            })
            .collect();
        assert_eq!(
            verdicts,
            [
                PendingValidation,
                Blocked,
                Blocked,
                Blocked,
                Blocked,
                Restricted,
                Restricted,
                Restricted,
                FullAccess,
                FullAccess,
                FullAccess
            ]
        );
        assert_eq!(
            clear_width_status(Some(0.8), None, &paper).1,
            "clear width 0.800 m < required 0.900 m, >= robot width 0.700 m"
        );
    }
}
