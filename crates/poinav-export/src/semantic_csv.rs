//! The semantic CSV: one row per enriched element with GlobalId, class, name, storey, POI
//! category, type, roles and every property value as stored in the IFC (lengths in file units).

use std::path::Path;

use poinav_poi::{stored_length, Classification};

use crate::ExportError;

/// Column names, in order.
pub const COLUMNS: &[&str] = &[
    "GlobalId",
    "IfcClass",
    "Name",
    "Storey",
    "Rule",
    "POI_Category",
    "POI_Type",
    "POI_PrimaryRoles",
    "POI_ConditionalRoles",
    "MinClearanceWidth",
    "MinClearanceHeight",
    "AccessibilityStatus",
    "ValidationMethod",
    "LastValidated",
    "MaxSimultaneousRobots",
    "MinInterRobotSeparation",
    "CoordinationProtocol",
    "AppliesTo",
    "ClearWidth_m",
    "StatusReason",
];

/// Renders the CSV of `c`; `metres_per_unit` converts lengths to the file's unit as stored,
/// `timestamp` is the LastValidated written. Role lists are joined with `;`.
pub fn to_csv(c: &Classification, metres_per_unit: f64, timestamp: &str) -> Vec<u8> {
    let mut w = csv::Writer::from_writer(Vec::new());
    w.write_record(COLUMNS).expect("writing to memory");
    let num = |v: Option<f64>| v.map(|v| v.to_string()).unwrap_or_default();
    for e in &c.elements {
        let roles =
            |r: &[poinav_poi::Role]| r.iter().map(|r| r.label()).collect::<Vec<_>>().join(";");
        let a = e.accessibility.as_ref();
        let k = e.coordination.as_ref();
        let row = [
            e.global_id.clone(),
            e.class.clone(),
            e.name.clone().unwrap_or_default(),
            e.storey.clone().unwrap_or_default(),
            e.rule.clone(),
            e.category.label().to_string(),
            e.poi_type.label().to_string(),
            roles(&e.primary),
            roles(&e.conditional),
            num(a.map(|a| stored_length(a.min_clearance_width_m, metres_per_unit))),
            num(a.map(|a| stored_length(a.min_clearance_height_m, metres_per_unit))),
            a.map(|a| a.status.label().to_string()).unwrap_or_default(),
            a.map(|a| a.method.label().to_string()).unwrap_or_default(),
            a.map(|_| timestamp.to_string()).unwrap_or_default(),
            k.map(|k| k.max_robots.to_string()).unwrap_or_default(),
            num(k.map(|k| stored_length(k.min_separation_m, metres_per_unit))),
            k.map(|k| k.protocol.label().to_string())
                .unwrap_or_default(),
            k.map(|k| k.applies_to.label().to_string())
                .unwrap_or_default(),
            // Metres to the micrometre: no float noise from unit conversion (0.9144000000000001).
            num(e.facts.clear_width_m.map(|w| (w * 1e6).round() / 1e6)),
            a.map(|a| a.reason.clone()).unwrap_or_default(),
        ];
        w.write_record(&row).expect("writing to memory");
    }
    w.into_inner().expect("flushing to memory")
}

/// Writes the CSV atomically.
pub fn write_csv(
    path: &Path,
    c: &Classification,
    metres_per_unit: f64,
    timestamp: &str,
) -> Result<(), ExportError> {
    poinav_io::write_atomic(path, &to_csv(c, metres_per_unit, timestamp)).map_err(|e| {
        ExportError::Write {
            path: path.display().to_string(),
            message: e.to_string(),
        }
    })
}
