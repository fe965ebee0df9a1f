//! `IfcUnitAssignment`: the two units geometry needs, length (metres per unit) and plane angle
//! (radians per unit, for trimming parameters of circles and ellipses).

use poinav_ifc::{units, Model};

/// How lengths and plane angles in the file convert to metres and radians.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Units {
    /// Metres per file length unit (0.001 for millimetres).
    pub metres_per_unit: f64,
    /// Radians per file plane angle unit (pi / 180 for degrees; 1.0 when none is declared).
    pub radians_per_unit: f64,
}

impl Units {
    /// Metres and radians.
    pub const SI: Units = Units {
        metres_per_unit: 1.0,
        radians_per_unit: 1.0,
    };

    /// The units of `model`: length from [`poinav_ifc::units::length_unit`], plane angle from
    /// the project's (else the first) `IfcUnitAssignment`.
    pub fn of(model: &Model) -> Units {
        Units {
            metres_per_unit: units::length_unit(model).metres_per_unit,
            radians_per_unit: plane_angle_unit(model).unwrap_or(1.0),
        }
    }
}

/// Radians per plane angle unit declared in `model`, if one is (see
/// [`poinav_ifc::units::project_unit`]).
pub fn plane_angle_unit(model: &Model) -> Option<f64> {
    units::project_unit(model, "PLANEANGLEUNIT")
        .map(|(r, _)| r)
        .filter(|r| r.is_finite() && *r > 0.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn degrees_from_a_conversion_based_unit() {
        let text = "ISO-10303-21;HEADER;FILE_SCHEMA(('IFC2X3'));ENDSEC;DATA;\n\
            #1=IFCUNITASSIGNMENT((#2,#5));#2=IFCSIUNIT(*,.LENGTHUNIT.,.MILLI.,.METRE.);\
            #3=IFCSIUNIT(*,.PLANEANGLEUNIT.,$,.RADIAN.);#4=IFCMEASUREWITHUNIT(IFCPLANEANGLEMEASURE(0.0174532925199433),#3);\
            #6=IFCDIMENSIONALEXPONENTS(0,0,0,0,0,0,0);#5=IFCCONVERSIONBASEDUNIT(#6,.PLANEANGLEUNIT.,'DEGREE',#4);\n\
            ENDSEC;END-ISO-10303-21;";
        let m = Model::from_bytes("t.ifc", text.as_bytes().to_vec()).unwrap();
        let u = Units::of(&m);
        assert_eq!(u.metres_per_unit, 0.001);
        assert!((u.radians_per_unit - std::f64::consts::PI / 180.0).abs() < 1e-15);
    }
}
