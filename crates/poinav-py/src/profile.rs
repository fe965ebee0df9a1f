//! Robot profiles and rule sets named from Python: `None` or `"paper"` for the paper's robot,
//! else a profile file (TOML); `None` for the default rules, else a rule file.

use std::path::PathBuf;

use poinav_poi::{RobotProfile, RuleSet};
use pyo3::prelude::*;

use crate::error::to_py;

/// The profile `name`: `None` or `"paper"` is the paper's robot, anything else a file.
pub fn profile(name: Option<&PathBuf>) -> PyResult<RobotProfile> {
    match name {
        None => Ok(RobotProfile::paper()),
        Some(p) if p.as_os_str() == "paper" => Ok(RobotProfile::paper()),
        Some(p) => RobotProfile::load(p).map_err(to_py),
    }
}

/// The profiles named (the paper's robot when none).
pub fn profiles(names: &[PathBuf]) -> PyResult<Vec<RobotProfile>> {
    if names.is_empty() {
        return Ok(vec![RobotProfile::paper()]);
    }
    names.iter().map(|n| profile(Some(n))).collect()
}

/// The default rules, extended (or replaced) by the rule file at `path`.
pub fn rules(path: Option<&PathBuf>) -> PyResult<RuleSet> {
    match path {
        None => Ok(RuleSet::defaults()),
        Some(p) => RuleSet::with_user_file(p).map_err(to_py),
    }
}
