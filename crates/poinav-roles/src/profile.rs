//! Robot profiles: the size and abilities of one robot type, read from TOML files.

use std::path::Path;

use serde::{Deserialize, Serialize};

use crate::error::ProfileError;

/// How a robot moves; decides whether stairs are passable.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Locomotion {
    /// Wheels: no stairs.
    Wheeled,
    /// Tracks: no stairs.
    Tracked,
    /// Legs: stairs are passable.
    Legged,
}

/// One robot type. All lengths in metres, speeds in m/s, angles in degrees.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RobotProfile {
    /// Short name used in reports (`paper-robot`).
    pub name: String,
    /// Free text.
    #[serde(default)]
    pub description: String,
    /// How it moves.
    pub locomotion: Locomotion,
    /// Footprint width (across the direction of travel).
    pub width_m: f64,
    /// Footprint length.
    pub length_m: f64,
    /// Height.
    pub height_m: f64,
    /// Extra distance kept on each side of the footprint.
    pub clearance_margin_m: f64,
    /// Clear width a passage needs to be FULL_ACCESS; default width + 2 x margin.
    #[serde(default)]
    pub min_clearance_width_m: Option<f64>,
    /// Clear height a passage needs; default height + margin.
    #[serde(default)]
    pub min_clearance_height_m: Option<f64>,
    /// Steepest ramp it can climb.
    pub max_slope_deg: f64,
    /// Highest step (threshold) it can cross.
    pub max_step_m: f64,
    /// Top speed.
    pub max_speed_m_s: f64,
    /// Turn rate.
    pub rotation_speed_deg_s: f64,
    /// Mass (for acceleration limits in simulation).
    #[serde(default = "default_mass")]
    pub mass_kg: f64,
}

fn default_mass() -> f64 {
    5.0
}

const PAPER: &str = include_str!("../profiles/paper-robot.toml");

impl RobotProfile {
    /// The paper's robot (SPEC.md §4), shipped as `profiles/paper-robot.toml`.
    pub fn paper() -> RobotProfile {
        RobotProfile::from_toml(PAPER, "profiles/paper-robot.toml")
            .expect("shipped profile is valid")
    }

    /// Reads a profile from TOML text; `origin` names it in errors.
    pub fn from_toml(text: &str, origin: &str) -> Result<RobotProfile, ProfileError> {
        let p: RobotProfile = toml::from_str(text).map_err(|e| ProfileError::Toml {
            file: origin.into(),
            message: e.to_string(),
        })?;
        p.validate(origin)?;
        Ok(p)
    }

    /// Reads a profile file.
    pub fn load(path: &Path) -> Result<RobotProfile, ProfileError> {
        let text = std::fs::read_to_string(path).map_err(|source| ProfileError::Io {
            file: path.display().to_string(),
            source,
        })?;
        RobotProfile::from_toml(&text, &path.display().to_string())
    }

    fn validate(&self, origin: &str) -> Result<(), ProfileError> {
        let positive = [
            ("width_m", self.width_m),
            ("length_m", self.length_m),
            ("height_m", self.height_m),
            ("max_speed_m_s", self.max_speed_m_s),
            ("rotation_speed_deg_s", self.rotation_speed_deg_s),
            ("mass_kg", self.mass_kg),
        ];
        for (name, v) in positive {
            if !(v.is_finite() && v > 0.0) {
                return Err(ProfileError::Invalid {
                    file: origin.into(),
                    message: format!("{name} must be a positive number, not {v}"),
                });
            }
        }
        let non_negative = [
            ("clearance_margin_m", self.clearance_margin_m),
            ("max_slope_deg", self.max_slope_deg),
            ("max_step_m", self.max_step_m),
        ];
        for (name, v) in non_negative {
            if !(v.is_finite() && v >= 0.0) {
                return Err(ProfileError::Invalid {
                    file: origin.into(),
                    message: format!("{name} must be zero or more, not {v}"),
                });
            }
        }
        if self.min_clearance_width() < self.width_m {
            return Err(ProfileError::Invalid {
                file: origin.into(),
                message: format!(
                    "min_clearance_width_m {} is narrower than the robot ({} m)",
                    self.min_clearance_width(),
                    self.width_m
                ),
            });
        }
        Ok(())
    }

    /// Clear width needed for FULL_ACCESS.
    pub fn min_clearance_width(&self) -> f64 {
        self.min_clearance_width_m
            .unwrap_or(self.width_m + 2.0 * self.clearance_margin_m)
    }

    /// Clear height needed for FULL_ACCESS.
    pub fn min_clearance_height(&self) -> f64 {
        self.min_clearance_height_m
            .unwrap_or(self.height_m + self.clearance_margin_m)
    }

    /// Radius of the circle around the footprint (for inflating obstacles).
    pub fn radius(&self) -> f64 {
        0.5 * self.width_m.hypot(self.length_m)
    }

    /// True when stairs are passable.
    pub fn climbs_stairs(&self) -> bool {
        self.locomotion == Locomotion::Legged
    }

    /// A profile variable by name, for rule conditions (`profile.min_clearance_width_m`).
    pub fn variable(&self, name: &str) -> Option<f64> {
        Some(match name {
            "width_m" => self.width_m,
            "length_m" => self.length_m,
            "height_m" => self.height_m,
            "clearance_margin_m" => self.clearance_margin_m,
            "min_clearance_width_m" => self.min_clearance_width(),
            "min_clearance_height_m" => self.min_clearance_height(),
            "max_slope_deg" => self.max_slope_deg,
            "max_step_m" => self.max_step_m,
            "max_speed_m_s" => self.max_speed_m_s,
            "rotation_speed_deg_s" => self.rotation_speed_deg_s,
            "radius_m" => self.radius(),
            _ => return None,
        })
    }

    /// Names accepted by [`RobotProfile::variable`].
    pub const VARIABLES: &'static [&'static str] = &[
        "width_m",
        "length_m",
        "height_m",
        "clearance_margin_m",
        "min_clearance_width_m",
        "min_clearance_height_m",
        "max_slope_deg",
        "max_step_m",
        "max_speed_m_s",
        "rotation_speed_deg_s",
        "radius_m",
    ];
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn paper_profile_has_the_papers_numbers() {
        let p = RobotProfile::paper();
        assert_eq!(p.min_clearance_width(), 0.90);
        assert_eq!(p.max_speed_m_s, 5.0);
        assert_eq!(p.rotation_speed_deg_s, 100.0);
        assert_eq!(p.mass_kg, 5.0);
        assert!(!p.climbs_stairs());
    }

    #[test]
    fn bad_profiles_are_refused_with_the_reason() {
        let bad = PAPER.replace("width_m = 0.70", "width_m = -1");
        assert!(RobotProfile::from_toml(&bad, "x.toml")
            .unwrap_err()
            .to_string()
            .contains("width_m must be a positive"));
        let unknown = format!("{PAPER}\nwheels = 4\n");
        assert!(RobotProfile::from_toml(&unknown, "x.toml")
            .unwrap_err()
            .to_string()
            .contains("wheels"));
        let narrow = PAPER.replace(
            "min_clearance_width_m = 0.90",
            "min_clearance_width_m = 0.5",
        );
        assert!(RobotProfile::from_toml(&narrow, "x.toml").is_err());
    }
}
