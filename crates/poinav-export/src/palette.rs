//! Default colours for elements whose IFC file gives no surface style: one sRGB RGBA colour per
//! IFC class, so that walls, slabs, doors and windows are told apart in any viewer.
//!
//! Colours here and in [`poinav_geom::ElementMesh::color`] are sRGB display values, as IFC
//! stores them (`IfcColourRgb`); [`srgb_to_linear`] converts them for glTF, whose
//! `baseColorFactor` is linear.

/// The colour of classes the table does not name: a light neutral grey.
pub const DEFAULT_COLOR: [f32; 4] = [0.78, 0.78, 0.78, 1.0];

/// (class, sRGB RGBA). Matched case-insensitively; `…StandardCase`, `…ElementedCase` and the
/// IFC4X3 `…Part` spellings fall back to their base class (see [`class_color`]).
const TABLE: &[(&str, [f32; 4])] = &[
    ("IfcWall", [0.85, 0.83, 0.78, 1.0]),
    ("IfcCurtainWall", [0.55, 0.70, 0.80, 0.5]),
    ("IfcSlab", [0.62, 0.62, 0.60, 1.0]),
    ("IfcRoof", [0.60, 0.32, 0.25, 1.0]),
    ("IfcCovering", [0.90, 0.88, 0.82, 1.0]),
    ("IfcDoor", [0.60, 0.42, 0.25, 1.0]),
    ("IfcWindow", [0.55, 0.75, 0.90, 0.4]),
    ("IfcPlate", [0.60, 0.75, 0.85, 0.6]),
    ("IfcColumn", [0.70, 0.70, 0.72, 1.0]),
    ("IfcBeam", [0.66, 0.66, 0.70, 1.0]),
    ("IfcMember", [0.55, 0.57, 0.60, 1.0]),
    ("IfcFooting", [0.50, 0.50, 0.48, 1.0]),
    ("IfcPile", [0.50, 0.50, 0.48, 1.0]),
    ("IfcStair", [0.80, 0.60, 0.35, 1.0]),
    ("IfcStairFlight", [0.80, 0.60, 0.35, 1.0]),
    ("IfcRamp", [0.75, 0.65, 0.40, 1.0]),
    ("IfcRampFlight", [0.75, 0.65, 0.40, 1.0]),
    ("IfcRailing", [0.35, 0.35, 0.38, 1.0]),
    ("IfcFurnishingElement", [0.45, 0.55, 0.35, 1.0]),
    ("IfcFurniture", [0.45, 0.55, 0.35, 1.0]),
    ("IfcSystemFurnitureElement", [0.45, 0.55, 0.35, 1.0]),
    ("IfcSpace", [0.40, 0.65, 0.95, 0.25]),
    ("IfcOpeningElement", [0.95, 0.40, 0.40, 0.3]),
    ("IfcBuildingElementProxy", [0.70, 0.55, 0.75, 1.0]),
    ("IfcBuildingElementPart", [0.70, 0.55, 0.75, 1.0]),
    ("IfcFlowTerminal", [0.85, 0.85, 0.90, 1.0]),
    ("IfcSanitaryTerminal", [0.92, 0.92, 0.95, 1.0]),
    ("IfcFlowSegment", [0.45, 0.60, 0.70, 1.0]),
    ("IfcFlowFitting", [0.45, 0.60, 0.70, 1.0]),
    ("IfcDistributionElement", [0.45, 0.60, 0.70, 1.0]),
    ("IfcTransportElement", [0.40, 0.40, 0.45, 1.0]),
];

/// The palette colour (sRGB RGBA) of IFC class `class`, or [`DEFAULT_COLOR`].
pub fn class_color(class: &str) -> [f32; 4] {
    let find = |name: &str| {
        TABLE
            .iter()
            .find(|(c, _)| c.eq_ignore_ascii_case(name))
            .map(|(_, rgba)| *rgba)
    };
    if let Some(rgba) = find(class) {
        return rgba;
    }
    let lower = class.to_ascii_lowercase();
    for suffix in ["standardcase", "elementedcase", "part"] {
        if let Some(base) = lower.strip_suffix(suffix) {
            if let Some(rgba) = find(base) {
                return rgba;
            }
        }
    }
    DEFAULT_COLOR
}

/// An element's colour: its surface style's when valid (every component finite; clamped to
/// [0, 1]), else its class's.
pub fn element_color(style: Option<[f32; 4]>, class: &str) -> [f32; 4] {
    match style {
        Some(c) if c.iter().all(|v| v.is_finite()) => c.map(|v| v.clamp(0.0, 1.0)),
        _ => class_color(class),
    }
}

/// One sRGB component (0..1) as linear light (the IEC 61966-2-1 transfer function).
pub fn srgb_to_linear(c: f32) -> f32 {
    if c <= 0.040_45 {
        c / 12.92
    } else {
        ((c + 0.055) / 1.055).powf(2.4)
    }
}

/// `#RRGGBB`, or `#RRGGBBAA` when not opaque: the name of a colour's material.
pub fn hex_name(rgba: [f32; 4]) -> String {
    let b = rgba.map(|v| (v.clamp(0.0, 1.0) * 255.0).round() as u8);
    if b[3] == 255 {
        format!("#{:02X}{:02X}{:02X}", b[0], b[1], b[2])
    } else {
        format!("#{:02X}{:02X}{:02X}{:02X}", b[0], b[1], b[2], b[3])
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn classes_and_their_variants_share_a_colour() {
        assert_eq!(class_color("IfcWall"), class_color("IfcWallStandardCase"));
        assert_eq!(class_color("IFCWALL"), class_color("IfcWall"));
        assert_eq!(class_color("IfcSlabElementedCase"), class_color("IfcSlab"));
        assert_ne!(class_color("IfcWall"), class_color("IfcDoor"));
        assert_eq!(class_color("IfcSomethingNew"), DEFAULT_COLOR);
        assert!(class_color("IfcWindow")[3] < 1.0);
    }

    #[test]
    fn styles_win_over_the_palette_and_are_clamped() {
        assert_eq!(
            element_color(Some([0.1, 0.2, 0.3, 1.0]), "IfcWall"),
            [0.1, 0.2, 0.3, 1.0]
        );
        assert_eq!(
            element_color(Some([1.5, -0.2, 0.3, 1.0]), "IfcWall"),
            [1.0, 0.0, 0.3, 1.0]
        );
        assert_eq!(
            element_color(Some([f32::NAN, 0.0, 0.0, 1.0]), "IfcDoor"),
            class_color("IfcDoor")
        );
        assert_eq!(element_color(None, "IfcDoor"), class_color("IfcDoor"));
    }

    #[test]
    fn srgb_conversion_and_names() {
        assert_eq!(srgb_to_linear(0.0), 0.0);
        assert!((srgb_to_linear(1.0) - 1.0).abs() < 1e-6);
        assert!((srgb_to_linear(0.5) - 0.214).abs() < 1e-3);
        assert_eq!(hex_name([1.0, 0.0, 0.5, 1.0]), "#FF0080");
        assert_eq!(hex_name([1.0, 0.0, 0.5, 0.5]), "#FF008080");
    }
}
