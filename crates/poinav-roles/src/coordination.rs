//! Pset_RobotCoordination values of a zone: how many robots, how far apart, which protocol.

use serde::Deserialize;

use crate::taxonomy::{AppliesTo, CoordinationProtocol};

/// Pset_RobotCoordination values a rule assigns.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Coordination {
    /// MaxSimultaneousRobots.
    pub max_robots: i64,
    /// MinInterRobotSeparation in metres.
    pub min_separation_m: f64,
    /// CoordinationProtocol.
    pub protocol: CoordinationProtocol,
    /// AppliesTo.
    #[serde(default = "all_robots")]
    pub applies_to: AppliesTo,
}

fn all_robots() -> AppliesTo {
    AppliesTo::AllRobots
}
