//! Surface colours: `IfcStyledItem` -> (`IfcPresentationStyleAssignment` ->) `IfcSurfaceStyle`
//! -> `IfcSurfaceStyleShading` / `...Rendering`, on a representation item or through the
//! product's material (`IfcRelAssociatesMaterial` -> `IfcMaterial` ->
//! `IfcMaterialDefinitionRepresentation`), as RGBA with alpha = 1 - transparency.

use poinav_ifc::{Entity, EntityId, Value};

/// Deepest nesting of style and material containers followed.
const MAX_DEPTH: usize = 8;

/// The colour of the first surface style found among `styles` (an `IfcStyledItem`'s Styles).
fn colour_of_styles(styles: &[Entity<'_>], depth: usize) -> Option<[f32; 4]> {
    if depth > MAX_DEPTH {
        return None;
    }
    for style in styles {
        if style.is_a("IfcPresentationStyleAssignment") {
            if let Some(c) = colour_of_styles(&style.get_refs("Styles"), depth + 1) {
                return Some(c);
            }
        } else if style.is_a("IfcSurfaceStyle") {
            for element in style.get_refs("Styles") {
                if element.is_a("IfcSurfaceStyleShading") {
                    if let Some(c) = shading_colour(element) {
                        return Some(c);
                    }
                }
            }
        }
    }
    None
}

/// The colour of an `IfcSurfaceStyleShading` (or `...Rendering`): its `SurfaceColour`, or
/// for a rendering with a `DiffuseColour` that colour (or the surface colour times that
/// factor), as IfcOpenShell reads it; alpha from `Transparency`.
fn shading_colour(shading: Entity<'_>) -> Option<[f32; 4]> {
    let surface = shading.get_ref("SurfaceColour")?;
    let rgb = |c: Entity<'_>| -> Option<[f64; 3]> {
        let channel = |name| c.get_f64(name).filter(|v| v.is_finite());
        Some([channel("Red")?, channel("Green")?, channel("Blue")?])
    };
    let mut colour = rgb(surface)?;
    if shading.is_a("IfcSurfaceStyleRendering") {
        match shading.get("DiffuseColour") {
            Some(Value::Ref(id)) => {
                if let Some(c) = shading.model().entity(id).and_then(rgb) {
                    colour = c;
                }
            }
            Some(v) => {
                if let Some(f) = v.as_f64().filter(|f| f.is_finite()) {
                    colour = colour.map(|c| c * f);
                }
            }
            None => {}
        }
    }
    let alpha = 1.0
        - shading
            .get_f64("Transparency")
            .filter(|v| v.is_finite())
            .unwrap_or(0.0)
            .clamp(0.0, 1.0) as f32;
    let [r, g, b] = colour.map(|c| c.clamp(0.0, 1.0) as f32);
    Some([r, g, b, alpha])
}

/// The colour an `IfcStyledItem` gives a representation item, if any.
pub fn item_colour(item: Entity<'_>) -> Option<[f32; 4]> {
    item.inverse("StyledByItem")
        .into_iter()
        .find_map(|styled| colour_of_styles(&styled.get_refs("Styles"), 0))
}

/// The colour of `product`'s material (or its type's), if the material has a styled
/// representation.
pub fn material_colour(product: Entity<'_>) -> Option<[f32; 4]> {
    let types = product
        .inverse("IsTypedBy")
        .into_iter()
        .chain(product.inverse("IsDefinedBy"))
        .filter(|r| r.is_a("IfcRelDefinesByType"))
        .filter_map(|r| r.get_ref("RelatingType"));
    std::iter::once(product)
        .chain(types)
        .flat_map(|o| o.inverse("HasAssociations"))
        .filter(|r| r.is_a("IfcRelAssociatesMaterial"))
        .filter_map(|r| r.get_ref("RelatingMaterial"))
        .find_map(|m| material_select_colour(m, 0))
}

/// The colour of the first material in a material select that has one.
fn material_select_colour(m: Entity<'_>, depth: usize) -> Option<[f32; 4]> {
    if depth > MAX_DEPTH {
        return None;
    }
    if m.is_a("IfcMaterial") {
        return material_definition_colour(m);
    }
    // Usages point at their set; sets list their parts; parts name a material.
    let next: Vec<Entity<'_>> = [
        "ForLayerSet",
        "ForProfileSet",
        "MaterialLayers",
        "MaterialProfiles",
        "MaterialConstituents",
        "Materials",
        "Material",
    ]
    .iter()
    .filter(|a| m.attr_index(a).is_ok())
    .flat_map(|a| m.get_refs(a))
    .collect();
    next.into_iter()
        .find_map(|n| material_select_colour(n, depth + 1))
}

/// The colour of an `IfcMaterial` from its `IfcMaterialDefinitionRepresentation`.
fn material_definition_colour(material: Entity<'_>) -> Option<[f32; 4]> {
    let id: EntityId = material.id();
    let mut reps = material.inverse("HasRepresentation");
    if reps.is_empty() && material.attr_index("HasRepresentation").is_err() {
        // IFC2X3 declares no inverse: look for the representation naming this material.
        reps = material
            .model()
            .instances_of("IfcMaterialDefinitionRepresentation")
            .into_iter()
            .filter(|r| r.get("RepresentedMaterial").and_then(|v| v.as_ref_id()) == Some(id))
            .collect();
    }
    reps.into_iter()
        .flat_map(|r| r.get_refs("Representations"))
        .flat_map(|r| r.get_refs("Items"))
        .filter(|i| i.is_a("IfcStyledItem"))
        .find_map(|i| colour_of_styles(&i.get_refs("Styles"), 0))
}
