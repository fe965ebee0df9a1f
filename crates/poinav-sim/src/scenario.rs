//! Scenario files (TOML, documented in docs/scenarios.md): the building (the paper's test
//! building or an IFC file, with design patches), the robots (profile, start pose, controller),
//! the duration, expectations, and variants that re-run the same scenario on a changed design.
//! Every error names the file and line.

use std::path::{Path, PathBuf};

use poinav_roles::{ProfileError, RobotProfile};
use serde::Deserialize;
use toml::Spanned;

use crate::algorithm1::Behaviour;
use crate::controller::{ControllerSpec, Key};
use crate::error::SimError;
use crate::expect::Expect;
use crate::poi_db::Start;
use crate::step::{RobotSetup, DT};

/// Options of the paper's test building (`poinav demo-building`); unset ones keep defaults
/// (`poinav_bridge::demo_floor::demo_spec` makes the building).
#[derive(Debug, Clone, PartialEq, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DemoParams {
    /// Rooms on each side of the corridor.
    pub rooms_per_side: Option<usize>,
    /// Width of the door into Room 2.
    pub room2_door_width_m: Option<f64>,
    /// Width of every other door.
    pub door_width_m: Option<f64>,
    /// Corridor width.
    pub corridor_width_m: Option<f64>,
}

/// A design change applied before enrichment (`poinav patch door-width`).
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DoorPatchSpec {
    /// Door Name or GlobalId.
    pub door: String,
    /// New width, metres.
    pub width_m: f64,
}

/// Where the floor comes from.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BuildingSpec {
    /// The paper's test building with these options.
    #[serde(default)]
    pub demo: Option<DemoParams>,
    /// An IFC file, relative to the scenario file.
    #[serde(default)]
    pub ifc: Option<String>,
    /// Storey name (default: the first).
    #[serde(default)]
    pub storey: Option<String>,
    /// Design patches applied before enrichment.
    #[serde(default)]
    pub patches: Vec<DoorPatchSpec>,
    /// Profile the enrichment (MinClearanceWidth, statuses) is made for: `paper` or a file.
    #[serde(default = "paper")]
    pub profile: String,
    /// Rule file replacing the default rules.
    #[serde(default)]
    pub rules: Option<String>,
}

fn paper() -> String {
    "paper".into()
}

#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawPose {
    x: f64,
    y: f64,
    #[serde(default)]
    heading_deg: f64,
}

#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawRobot {
    name: String,
    #[serde(default = "paper")]
    profile: String,
    #[serde(default)]
    global_id: Option<String>,
    start: RawPose,
    controller: ControllerSpec,
    #[serde(default)]
    priority: i64,
    #[serde(default)]
    brush: bool,
    #[serde(default = "drive")]
    drive_force_n: f64,
    #[serde(default = "brake")]
    brake_force_n: f64,
}

fn drive() -> f64 {
    50.0
}

fn brake() -> f64 {
    100.0
}

#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawVariant {
    name: String,
    #[serde(default)]
    description: String,
    #[serde(default)]
    patches: Vec<DoorPatchSpec>,
    #[serde(default)]
    expect: Vec<Spanned<Expect>>,
}

#[derive(Debug, Clone, Default, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawPoi {
    #[serde(default)]
    start: Option<String>,
}

#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawScenario {
    name: String,
    #[serde(default)]
    description: String,
    duration_s: f64,
    #[serde(default)]
    hz: Option<f64>,
    building: BuildingSpec,
    #[serde(default)]
    poi: RawPoi,
    #[serde(default)]
    behaviour: Behaviour,
    #[serde(default)]
    robot: Vec<Spanned<RawRobot>>,
    #[serde(default)]
    expect: Vec<Spanned<Expect>>,
    #[serde(default)]
    variant: Vec<Spanned<RawVariant>>,
}

/// One robot with the line it is declared on.
#[derive(Debug, Clone)]
pub struct RobotEntry {
    /// Line of its `[[robot]]` table.
    pub line: usize,
    /// The set-up.
    pub setup: RobotSetup,
}

/// One expectation with its line.
#[derive(Debug, Clone, PartialEq)]
pub struct ExpectEntry {
    /// Line of its table.
    pub line: usize,
    /// What is expected.
    pub expect: Expect,
}

/// A re-run of the scenario on a changed design with its own expectations.
#[derive(Debug, Clone, PartialEq)]
pub struct Variant {
    /// Name (output folder).
    pub name: String,
    /// Free text.
    pub description: String,
    /// Line.
    pub line: usize,
    /// Patches added to the building's.
    pub patches: Vec<DoorPatchSpec>,
    /// Expectations added to the scenario's.
    pub expects: Vec<ExpectEntry>,
}

/// A loaded scenario.
#[derive(Debug, Clone)]
pub struct Scenario {
    /// The file as given.
    pub file: String,
    /// Its folder (relative paths start here).
    pub dir: PathBuf,
    /// Name.
    pub name: String,
    /// Free text.
    pub description: String,
    /// Duration, seconds.
    pub duration_s: f64,
    /// Step, seconds.
    pub dt: f64,
    /// The building.
    pub building: BuildingSpec,
    /// How the POI database starts.
    pub start: Start,
    /// Behaviour constants.
    pub behaviour: Behaviour,
    /// Robots.
    pub robots: Vec<RobotEntry>,
    /// Expectations of every variant.
    pub expects: Vec<ExpectEntry>,
    /// Variants (none: one plain run).
    pub variants: Vec<Variant>,
}

fn line_of(text: &str, offset: usize) -> usize {
    text[..offset.min(text.len())]
        .bytes()
        .filter(|&b| b == b'\n')
        .count()
        + 1
}

/// What a scenario file looks like, for messages about files that are not one.
const SCENARIO_SHAPE: &str = "a scenario is a TOML file with `name = \"...\"`, `duration_s = 10.0`, a `[building]` table (`demo = {}` or `ifc = \"model.ifc\"`), `[[robot]]` tables and optional `[[expect]]` tables (docs/scenarios.md; examples in crates/poinav-sim/scenarios/)";

impl Scenario {
    /// Reads a scenario file.
    pub fn load(path: &Path) -> Result<Scenario, SimError> {
        let text = std::fs::read_to_string(path).map_err(|e| SimError::Io {
            path: path.display().to_string(),
            message: e.to_string(),
        })?;
        let dir = path.parent().map(Path::to_path_buf).unwrap_or_default();
        Scenario::from_toml(&text, &path.display().to_string(), &dir)
    }

    /// Reads scenario text; `file` names it in errors, `dir` anchors relative paths.
    pub fn from_toml(text: &str, file: &str, dir: &Path) -> Result<Scenario, SimError> {
        let err = |line: usize, message: String| SimError::Scenario {
            file: file.to_string(),
            line,
            message,
        };
        let raw: RawScenario = toml::from_str(text).map_err(|e| {
            let line = e.span().map_or(1, |s| line_of(text, s.start));
            let message = e.message().trim();
            if text.parse::<toml::Table>().is_err() {
                return err(
                    line,
                    format!("not a scenario file: it is not TOML ({message}); {SCENARIO_SHAPE}"),
                );
            }
            err(line, message.to_string())
        })?;
        let at = |s: &std::ops::Range<usize>| line_of(text, s.start);
        if !(raw.duration_s.is_finite() && raw.duration_s > 0.0) {
            return Err(err(
                1,
                format!("duration_s must be positive, not {}", raw.duration_s),
            ));
        }
        let dt = match raw.hz {
            None => DT,
            Some(hz) if hz.is_finite() && hz >= 1.0 => 1.0 / hz,
            Some(hz) => return Err(err(1, format!("hz must be at least 1, not {hz}"))),
        };
        if raw.building.demo.is_some() == raw.building.ifc.is_some() {
            return Err(err(
                1,
                "[building] needs exactly one of `demo` and `ifc`".into(),
            ));
        }
        let start = match raw.poi.start.as_deref() {
            None | Some("keep") => Start::Keep,
            Some("clear") => Start::Clear,
            Some(other) => {
                return Err(err(
                    1,
                    format!("[poi] start must be `keep` or `clear`, not `{other}`"),
                ))
            }
        };
        let mut robots: Vec<RobotEntry> = Vec::new();
        for r in &raw.robot {
            let line = at(&r.span());
            let r = r.get_ref();
            if robots.iter().any(|e| e.setup.name == r.name) {
                return Err(err(line, format!("robot `{}` is declared twice", r.name)));
            }
            let profile = load_profile(&r.profile, dir).map_err(|e| err(line, e.to_string()))?;
            if let ControllerSpec::Keys { scheme, script } = &r.controller {
                for k in script {
                    Key::parse(*scheme, &k.key)
                        .map_err(|m| err(line, format!("robot `{}`: {m}", r.name)))?;
                }
            }
            for (what, v) in [
                ("drive_force_n", r.drive_force_n),
                ("brake_force_n", r.brake_force_n),
            ] {
                if !(v.is_finite() && v > 0.0) {
                    return Err(err(line, format!("{what} must be positive, not {v}")));
                }
            }
            robots.push(RobotEntry {
                line,
                setup: RobotSetup {
                    name: r.name.clone(),
                    global_id: r.global_id.clone(),
                    profile,
                    start: glam::DVec2::new(r.start.x, r.start.y),
                    heading_deg: r.start.heading_deg,
                    controller: r.controller.clone(),
                    priority: r.priority,
                    brush_on: r.brush,
                    drive_force_n: r.drive_force_n,
                    brake_force_n: r.brake_force_n,
                },
            });
        }
        if robots.is_empty() {
            return Err(err(1, "a scenario needs at least one [[robot]]".into()));
        }
        let names: Vec<&str> = robots.iter().map(|r| r.setup.name.as_str()).collect();
        let entries = |list: &[Spanned<Expect>]| -> Result<Vec<ExpectEntry>, SimError> {
            list.iter()
                .map(|e| {
                    let line = at(&e.span());
                    for r in e.get_ref().robots() {
                        if !names.contains(&r) {
                            return Err(err(line, format!("no robot named `{r}`")));
                        }
                    }
                    Ok(ExpectEntry {
                        line,
                        expect: e.get_ref().clone(),
                    })
                })
                .collect()
        };
        let expects = entries(&raw.expect)?;
        let mut variants: Vec<Variant> = Vec::new();
        for v in &raw.variant {
            let line = at(&v.span());
            let r = v.get_ref();
            if variants.iter().any(|x| x.name == r.name) || r.name.is_empty() {
                return Err(err(
                    line,
                    format!("variant name `{}` is empty or used twice", r.name),
                ));
            }
            variants.push(Variant {
                name: r.name.clone(),
                description: r.description.clone(),
                line,
                patches: r.patches.clone(),
                expects: entries(&r.expect)?,
            });
        }
        Ok(Scenario {
            file: file.to_string(),
            dir: dir.to_path_buf(),
            name: raw.name,
            description: raw.description,
            duration_s: raw.duration_s,
            dt,
            building: raw.building,
            start,
            behaviour: raw.behaviour,
            robots,
            expects,
            variants,
        })
    }

    /// The variant named `name`; `None` asks for the plain run (only when there are no
    /// variants).
    pub fn variant(&self, name: Option<&str>) -> Result<Option<&Variant>, SimError> {
        match name {
            None if self.variants.is_empty() => Ok(None),
            None => Err(self.error(
                1,
                format!("choose a variant: {}", self.variant_names().join(", ")),
            )),
            Some(n) => self
                .variants
                .iter()
                .find(|v| v.name == n)
                .map(Some)
                .ok_or_else(|| {
                    self.error(
                        1,
                        format!(
                            "no variant `{n}` (has: {})",
                            self.variant_names().join(", ")
                        ),
                    )
                }),
        }
    }

    /// Variant names in file order.
    pub fn variant_names(&self) -> Vec<&str> {
        self.variants.iter().map(|v| v.name.as_str()).collect()
    }

    /// An error at `line` of this file.
    pub fn error(&self, line: usize, message: String) -> SimError {
        SimError::Scenario {
            file: self.file.clone(),
            line,
            message,
        }
    }

    /// A path written in the file, resolved against its folder.
    pub fn resolve(&self, p: &str) -> PathBuf {
        self.dir.join(p)
    }
}

/// `paper` or a profile file relative to `dir`.
pub fn load_profile(name: &str, dir: &Path) -> Result<RobotProfile, ProfileError> {
    if name == "paper" {
        return Ok(RobotProfile::paper());
    }
    RobotProfile::load(&dir.join(name))
}

#[cfg(test)]
mod tests {
    use super::*;

    const MINI: &str = r#"name = "mini"
duration_s = 1.0
[building]
demo = {}

[[robot]]
name = "R"
start = { x = 1.0, y = 5.4 }
controller = { kind = "idle" }
"#;

    #[test]
    fn errors_name_file_and_line() {
        let ok = Scenario::from_toml(MINI, "mini.toml", Path::new(".")).unwrap();
        assert_eq!(ok.robots[0].line, 6);
        let bad = MINI.replace("kind = \"idle\"", "kind = \"fly\"");
        let e = Scenario::from_toml(&bad, "mini.toml", Path::new("."))
            .unwrap_err()
            .to_string();
        assert!(e.starts_with("mini.toml:9: "), "{e}");
        let bad = format!(
            "{MINI}\n[[expect]]\nkind = \"reaches-zone\"\nrobot = \"Q\"\nzone = \"Room 1\"\n"
        );
        let e = Scenario::from_toml(&bad, "mini.toml", Path::new("."))
            .unwrap_err()
            .to_string();
        assert!(e.starts_with("mini.toml:11: no robot named `Q`"), "{e}");
        let bad = MINI.replace("controller = { kind = \"idle\" }", "controller = { kind = \"keys\", scheme = \"wasd\", script = [{ t = 0.0, key = \"Up\" }] }");
        let e = Scenario::from_toml(&bad, "mini.toml", Path::new("."))
            .unwrap_err()
            .to_string();
        assert!(e.starts_with("mini.toml:6: robot `R`: key `Up`"), "{e}");
        let bad = MINI.replace("duration_s = 1.0", "duration_s = 1.0\nspeed = 3");
        let e = Scenario::from_toml(&bad, "mini.toml", Path::new("."))
            .unwrap_err()
            .to_string();
        assert!(e.starts_with("mini.toml:3: ") && e.contains("speed"), "{e}");
    }
}
