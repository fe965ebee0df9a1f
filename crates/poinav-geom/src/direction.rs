//! `IfcDirection`: a unit vector from direction ratios (2D ratios get z = 0).

use glam::DVec3;
use poinav_ifc::{Entity, Value};

use crate::error::{degenerate, missing, unsupported, GeomError};

/// Directions shorter than this are treated as zero.
pub const MIN_LENGTH: f64 = 1e-12;

/// The normalised `DirectionRatios` of an `IfcDirection`.
pub fn direction(e: Entity<'_>) -> Result<DVec3, GeomError> {
    if !e.is_a("IfcDirection") {
        return Err(unsupported(&e, "a direction must be an IfcDirection"));
    }
    let r: Vec<f64> = e
        .get("DirectionRatios")
        .and_then(|v| {
            v.as_list()
                .and_then(|l| l.iter().map(Value::as_f64).collect())
        })
        .filter(|r: &Vec<f64>| (2..=3).contains(&r.len()))
        .ok_or_else(|| missing(&e, "DirectionRatios"))?;
    let v = DVec3::new(r[0], r[1], r.get(2).copied().unwrap_or(0.0));
    let len = v.length();
    if !len.is_finite() || len < MIN_LENGTH {
        return Err(degenerate(&e, "direction has zero or non-finite length"));
    }
    Ok(v / len)
}

/// The direction in attribute `attribute` of `e`, or `default` when it is `$`.
pub(crate) fn optional_direction(
    e: &Entity<'_>,
    attribute: &'static str,
    default: DVec3,
) -> Result<DVec3, GeomError> {
    match e.get(attribute) {
        None => Ok(default),
        Some(_) => direction(e.get_ref(attribute).ok_or_else(|| missing(e, attribute))?),
    }
}
