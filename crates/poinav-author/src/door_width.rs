//! Design iteration: change a door's width (OverallWidth, its opening and its leaf geometry)
//! in a copy of the model, leaving every other line as it was.

use poinav_ifc::{units, Arg, Editor, Entity, EntityId, Model};

use crate::error::AuthorError;

/// What a door-width patch changed.
#[derive(Debug, Clone, PartialEq)]
pub struct DoorPatch {
    /// The door.
    pub door: EntityId,
    /// Its GlobalId.
    pub global_id: String,
    /// OverallWidth before, metres (`None` when it had none).
    pub old_width_m: Option<f64>,
    /// OverallWidth after, metres.
    pub new_width_m: f64,
    /// Rectangle profiles resized (or copied and resized when shared with other elements).
    pub profiles: Vec<EntityId>,
    /// What could not be updated (e.g. geometry that is not an extruded rectangle).
    pub warnings: Vec<String>,
}

/// Finds a door by GlobalId, else by Name (which must be unique).
pub fn find_door<'m>(model: &'m Model, name_or_guid: &str) -> Result<Entity<'m>, AuthorError> {
    let doors = model.instances_of("IfcDoor");
    if let Some(d) = doors
        .iter()
        .find(|d| d.global_id().as_deref() == Some(name_or_guid))
    {
        return Ok(*d);
    }
    let named: Vec<_> = doors
        .iter()
        .filter(|d| d.name().as_deref() == Some(name_or_guid))
        .collect();
    match named.as_slice() {
        [] => Err(AuthorError::NoSuchDoor(name_or_guid.to_string())),
        [one] => Ok(**one),
        many => Err(AuthorError::AmbiguousDoor {
            name: name_or_guid.to_string(),
            count: many.len(),
            ids: many
                .iter()
                .map(|d| d.id().to_string())
                .collect::<Vec<_>>()
                .join(", "),
        }),
    }
}

/// Extruded-solid rectangle profiles in `product`'s body (directly, or in boolean operands).
fn rectangle_profiles<'m>(
    product: Entity<'m>,
    warnings: &mut Vec<String>,
) -> Vec<(Entity<'m>, Entity<'m>)> {
    let mut out = Vec::new();
    let Some(shape) = product.get_ref("Representation") else {
        return out;
    };
    for rep in shape.get_refs("Representations") {
        if rep.get_str("RepresentationIdentifier").as_deref() != Some("Body") {
            continue;
        }
        let mut items = rep.get_refs("Items");
        let mut guard = 0;
        while let Some(item) = items.pop() {
            guard += 1;
            if guard > 64 {
                break;
            }
            if item.is_a("IfcExtrudedAreaSolid") {
                match item.get_ref("SweptArea") {
                    Some(p) if p.is_a("IfcRectangleProfileDef") => out.push((item, p)),
                    Some(p) => warnings.push(format!(
                        "{} {}: profile {} ({}) is not a rectangle; not resized",
                        product.type_name(),
                        product.id(),
                        p.id(),
                        p.type_name()
                    )),
                    None => {}
                }
            } else if item.is_a("IfcBooleanResult") {
                items.extend(item.get_ref("FirstOperand"));
            } else {
                warnings.push(format!(
                    "{} {}: body item {} ({}) is not an extrusion; not resized",
                    product.type_name(),
                    product.id(),
                    item.id(),
                    item.type_name()
                ));
            }
        }
    }
    out
}

/// Sets the door's OverallWidth to `width_m` and resizes, in its opening's and its own body,
/// every rectangle profile side equal to the old width (within 1 mm). Profiles used by other
/// instances are copied first. Returns the editor holding the change, and what changed.
pub fn patch_door_width<'m>(
    model: &'m Model,
    name_or_guid: &str,
    width_m: f64,
    timestamp: &str,
) -> Result<(Editor<'m>, DoorPatch), AuthorError> {
    if !(width_m.is_finite() && width_m > 0.0) {
        return Err(AuthorError::BadSize {
            what: "door width",
            value: width_m,
        });
    }
    let door = find_door(model, name_or_guid)?;
    let metres = units::length_unit(model).metres_per_unit;
    let old = door.get_f64("OverallWidth");
    let new = width_m / metres;
    let mut ed = Editor::new(model);
    ed.set_timestamp(timestamp);
    ed.set_attr(door.id(), "OverallWidth", Arg::Real(new))?;
    let mut warnings = Vec::new();
    let mut profiles = Vec::new();
    let Some(old) = old else {
        warnings.push(format!(
            "door {} had no OverallWidth; its geometry is left unchanged",
            door.id()
        ));
        return Ok((
            ed,
            DoorPatch {
                door: door.id(),
                global_id: door.global_id().unwrap_or_default(),
                old_width_m: None,
                new_width_m: width_m,
                profiles,
                warnings,
            },
        ));
    };
    let openings: Vec<Entity<'_>> = door
        .inverse("FillsVoids")
        .iter()
        .filter_map(|r| r.get_ref("RelatingOpeningElement"))
        .collect();
    if openings.is_empty() {
        warnings.push(format!(
            "door {} fills no opening; only the door is resized",
            door.id()
        ));
    }
    let tolerance = 0.001 / metres;
    for product in openings.into_iter().chain([door]) {
        for (solid, profile) in rectangle_profiles(product, &mut warnings) {
            let dims = [
                ("XDim", profile.get_f64("XDim")),
                ("YDim", profile.get_f64("YDim")),
            ];
            let Some((attr, _)) = dims
                .iter()
                .find(|(_, v)| v.is_some_and(|v| (v - old).abs() <= tolerance))
            else {
                warnings.push(format!(
                    "{} {}: no side of profile {} equals the old width; not resized",
                    product.type_name(),
                    product.id(),
                    profile.id()
                ));
                continue;
            };
            let shared = model.referrers(profile.id()).len() > 1;
            let target = if shared {
                // Copy the profile with the new size and point only this solid at it.
                let mut args: Vec<Arg> = Vec::new();
                for (i, v) in profile
                    .args()
                    .map_err(|e| AuthorError::Unreadable(profile.id(), e.to_string()))?
                    .iter()
                    .enumerate()
                {
                    let name = profile
                        .model()
                        .schema()
                        .attribute(profile.type_id().expect("known type"), i)
                        .map(|(a, _)| a.name);
                    args.push(if name == Some(*attr) {
                        Arg::Real(new)
                    } else {
                        to_arg(v)
                    });
                }
                let copy = ed.add(profile.type_name(), args)?;
                ed.set_attr(solid.id(), "SweptArea", Arg::Ref(copy))?;
                copy
            } else {
                ed.set_attr(profile.id(), attr, Arg::Real(new))?;
                profile.id()
            };
            profiles.push(target);
        }
    }
    Ok((
        ed,
        DoorPatch {
            door: door.id(),
            global_id: door.global_id().unwrap_or_default(),
            old_width_m: Some(old * metres),
            new_width_m: width_m,
            profiles,
            warnings,
        },
    ))
}

/// A read value written back as it was.
fn to_arg(v: &poinav_ifc::Value<'_>) -> Arg {
    use poinav_ifc::Value;
    match v {
        Value::Null => Arg::Null,
        Value::Derived => Arg::Derived,
        Value::Integer(i) => Arg::Integer(*i),
        Value::Real(r) => Arg::Real(*r),
        Value::String(_) => Arg::Text(v.as_str().map(|s| s.into_owned()).unwrap_or_default()),
        Value::Binary(_) => Arg::Null,
        Value::Enum(e) => Arg::Enum((*e).to_string()),
        Value::Ref(id) => Arg::Ref(*id),
        Value::List(items) => Arg::List(items.iter().map(to_arg).collect()),
        Value::Typed(t, inner) => Arg::Typed((*t).to_string(), Box::new(to_arg(inner))),
    }
}
