//! `IfcCartesianPoint` and `IfcCartesianPointList2D/3D`: coordinates in the file's length unit.

use glam::{DVec2, DVec3};
use poinav_ifc::{Entity, Value};

use crate::error::{degenerate, missing, unsupported, GeomError};

/// The numbers of a coordinate list value, or `None` when one is not a number.
fn numbers(v: &Value<'_>) -> Option<Vec<f64>> {
    v.as_list()?.iter().map(Value::as_f64).collect()
}

fn finite(e: &Entity<'_>, c: &[f64]) -> Result<(), GeomError> {
    if c.iter().all(|x| x.is_finite()) {
        Ok(())
    } else {
        Err(degenerate(e, "coordinate is not a finite number"))
    }
}

/// The coordinates of an `IfcCartesianPoint` (2D points get z = 0), in file units.
pub fn point3(e: Entity<'_>) -> Result<DVec3, GeomError> {
    if !e.is_a("IfcCartesianPoint") {
        return Err(unsupported(&e, "a point must be an IfcCartesianPoint"));
    }
    let c = e
        .get("Coordinates")
        .as_ref()
        .and_then(numbers)
        .filter(|c| (1..=3).contains(&c.len()))
        .ok_or_else(|| missing(&e, "Coordinates"))?;
    finite(&e, &c)?;
    Ok(DVec3::new(
        c[0],
        c.get(1).copied().unwrap_or(0.0),
        c.get(2).copied().unwrap_or(0.0),
    ))
}

/// The x and y coordinates of an `IfcCartesianPoint`, in file units.
pub fn point2(e: Entity<'_>) -> Result<DVec2, GeomError> {
    point3(e).map(|p| p.truncate())
}

/// The points of an `IfcCartesianPointList2D` or `IfcCartesianPointList3D` (2D lists get
/// z = 0), in file units.
pub fn point_list(e: Entity<'_>) -> Result<Vec<DVec3>, GeomError> {
    if !e.is_a("IfcCartesianPointList") {
        return Err(unsupported(&e, "expected an IfcCartesianPointList2D/3D"));
    }
    let list = e.get("CoordList").ok_or_else(|| missing(&e, "CoordList"))?;
    let rows = list.as_list().ok_or_else(|| missing(&e, "CoordList"))?;
    rows.iter()
        .map(|row| {
            let c = numbers(row)
                .filter(|c| (2..=3).contains(&c.len()))
                .ok_or_else(|| missing(&e, "CoordList"))?;
            finite(&e, &c)?;
            Ok(DVec3::new(c[0], c[1], c.get(2).copied().unwrap_or(0.0)))
        })
        .collect()
}
