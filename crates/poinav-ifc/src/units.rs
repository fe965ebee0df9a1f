//! The project's length unit: SI units with prefixes and conversion-based units (feet, inches).

use crate::entity::Entity;
use crate::model::Model;

/// The length unit lengths are stored in, and its size in metres.
#[derive(Debug, Clone, PartialEq)]
pub struct LengthUnit {
    /// How many metres one unit is (0.001 for millimetres, 0.3048 for feet).
    pub metres_per_unit: f64,
    /// What the file calls it: `METRE`, `MILLI METRE`, `FOOT`, ...
    pub name: String,
    /// False when the file declares no length unit and metres are assumed.
    pub declared: bool,
}

impl LengthUnit {
    /// Metres, assumed when a file declares nothing.
    pub fn assumed_metre() -> LengthUnit {
        LengthUnit {
            metres_per_unit: 1.0,
            name: "METRE".into(),
            declared: false,
        }
    }

    /// Converts a length in this unit to metres.
    pub fn to_metres(&self, value: f64) -> f64 {
        value * self.metres_per_unit
    }

    /// Converts metres to this unit (for writing lengths back into the file).
    pub fn from_metres(&self, metres: f64) -> f64 {
        metres / self.metres_per_unit
    }
}

/// Size of an SI prefix (`.MILLI.` is 1e-3).
pub fn si_prefix(prefix: &str) -> Option<f64> {
    Some(match prefix {
        "EXA" => 1e18,
        "PETA" => 1e15,
        "TERA" => 1e12,
        "GIGA" => 1e9,
        "MEGA" => 1e6,
        "KILO" => 1e3,
        "HECTO" => 1e2,
        "DECA" => 1e1,
        "DECI" => 1e-1,
        "CENTI" => 1e-2,
        "MILLI" => 1e-3,
        "MICRO" => 1e-6,
        "NANO" => 1e-9,
        "PICO" => 1e-12,
        "FEMTO" => 1e-15,
        "ATTO" => 1e-18,
        _ => return None,
    })
}

/// Size of `unit` (an IfcSIUnit or IfcConversionBasedUnit) in SI base units, with its name.
/// `.MILLI. .SQUARE_METRE.` is 1e-6: the prefix applies to the metre before squaring.
fn unit_scale(unit: Entity<'_>, depth: usize) -> Option<(f64, String)> {
    if depth > 8 {
        return None;
    }
    if unit.is_a("IfcSIUnit") {
        let name = unit.get("Name")?.as_enum()?.to_string();
        let power = match name.as_str() {
            "SQUARE_METRE" => 2,
            "CUBIC_METRE" => 3,
            _ => 1,
        };
        return match unit
            .get("Prefix")
            .and_then(|p| p.as_enum().map(str::to_string))
        {
            Some(p) => Some((si_prefix(&p)?.powi(power), format!("{p} {name}"))),
            None => Some((1.0, name)),
        };
    }
    if unit.is_a("IfcConversionBasedUnit") {
        let name = unit.get_str("Name").unwrap_or_else(|| "CONVERSION".into());
        let factor = unit.get_ref("ConversionFactor")?;
        let value = factor.get("ValueComponent")?.as_f64()?;
        let (base, _) = unit_scale(factor.get_ref("UnitComponent")?, depth + 1)?;
        return Some((value * base, name.to_uppercase()));
    }
    None
}

/// The project's unit of type `unit_type` (`LENGTHUNIT`, `AREAUNIT`, `PLANEANGLEUNIT`, ...):
/// its size in SI units (m, m², rad) and name. From `IfcProject.UnitsInContext`, else the
/// first unit assignment; `None` when the file declares no such unit.
pub fn project_unit(model: &Model, unit_type: &str) -> Option<(f64, String)> {
    let from_project = model
        .instances_of("IfcProject")
        .first()
        .and_then(|p| p.get_ref("UnitsInContext"));
    let assignments = from_project
        .into_iter()
        .chain(model.instances_of("IfcUnitAssignment"));
    for assignment in assignments {
        for unit in assignment.get_refs("Units") {
            if unit.get("UnitType").and_then(|v| v.as_enum()) == Some(unit_type) {
                if let Some(found) = unit_scale(unit, 0) {
                    return Some(found);
                }
            }
        }
    }
    None
}

/// The length unit of `model`: from `IfcProject.UnitsInContext`, else the first unit assignment.
pub fn length_unit(model: &Model) -> LengthUnit {
    match project_unit(model, "LENGTHUNIT") {
        Some((metres_per_unit, name)) => LengthUnit {
            metres_per_unit,
            name,
            declared: true,
        },
        None => LengthUnit::assumed_metre(),
    }
}

/// Square metres per area unit (the length unit squared when no area unit is declared).
pub fn area_scale(model: &Model) -> f64 {
    project_unit(model, "AREAUNIT")
        .map_or_else(|| length_unit(model).metres_per_unit.powi(2), |(s, _)| s)
}

/// Radians per plane-angle unit (radians when none is declared).
pub fn angle_scale(model: &Model) -> f64 {
    project_unit(model, "PLANEANGLEUNIT").map_or(1.0, |(s, _)| s)
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn model(units: &str) -> Model {
        let text = format!(
            "ISO-10303-21;HEADER;FILE_SCHEMA(('IFC4'));ENDSEC;DATA;\n{units}\n#100=IFCPROJECT('0YvctVUKr0kugbFTf53O9L',$,'P',$,$,$,$,$,#1);\nENDSEC;END-ISO-10303-21;"
        );
        Model::from_bytes("t.ifc", text.into_bytes()).unwrap()
    }

    #[test]
    fn reads_prefixed_si_and_conversion_based_units() {
        let mm = model("#1=IFCUNITASSIGNMENT((#2));#2=IFCSIUNIT(*,.LENGTHUNIT.,.MILLI.,.METRE.);");
        assert_eq!(length_unit(&mm).metres_per_unit, 1e-3);
        let ft = model(
            "#1=IFCUNITASSIGNMENT((#3,#5));#3=IFCSIUNIT(*,.AREAUNIT.,$,.SQUARE_METRE.);#4=IFCSIUNIT(*,.LENGTHUNIT.,$,.METRE.);\
             #6=IFCMEASUREWITHUNIT(IFCRATIOMEASURE(0.3048),#4);#7=IFCDIMENSIONALEXPONENTS(1,0,0,0,0,0,0);\
             #5=IFCCONVERSIONBASEDUNIT(#7,.LENGTHUNIT.,'FOOT',#6);",
        );
        let u = length_unit(&ft);
        assert_eq!(
            (u.metres_per_unit, u.name.as_str(), u.declared),
            (0.3048, "FOOT", true)
        );
        let none = model("#1=IFCUNITASSIGNMENT(());");
        assert!(!length_unit(&none).declared);
        assert_eq!(area_scale(&mm), 1e-6, "no area unit: length unit squared");
        let area = model("#1=IFCUNITASSIGNMENT((#2,#3,#4));#2=IFCSIUNIT(*,.LENGTHUNIT.,.MILLI.,.METRE.);#3=IFCSIUNIT(*,.AREAUNIT.,.CENTI.,.SQUARE_METRE.);#4=IFCSIUNIT(*,.PLANEANGLEUNIT.,$,.RADIAN.);");
        assert!((area_scale(&area) - 1e-4).abs() < 1e-18);
        assert_eq!(angle_scale(&area), 1.0);
    }

    proptest! {
        #[test]
        fn metres_round_trip_through_any_unit(scale in 1e-6f64..1e3, metres in -1e4f64..1e4) {
            let u = LengthUnit { metres_per_unit: scale, name: "X".into(), declared: true };
            let back = u.to_metres(u.from_metres(metres));
            prop_assert!((back - metres).abs() <= 1e-9 * metres.abs().max(1.0));
        }
    }
}
