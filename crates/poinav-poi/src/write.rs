//! Writing the three property sets (SPEC.md §3) into a copy of the IFC through the lossless
//! editor: previous poinav sets are removed first, identical sets are shared between elements,
//! lengths are stored in the file's unit.

use poinav_ifc::{Arg, Editor, EntityId, Model, NewProperty, Schema};

use crate::classify::{Classification, Classified};
use crate::error::PoiError;
use poinav_roles::{
    AccessibilityStatus, AppliesTo, Category, CoordinationProtocol, PoiType, ValidationMethod,
};

/// Description written into every property set poinav adds; re-enrichment removes sets carrying it.
pub const POINAV_MARKER: &str = "poinav POI enrichment";

/// The names of the three sets for a prefix.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct PsetNames {
    /// `<prefix>POI_Classification`.
    pub classification: String,
    /// `<prefix>RobotAccessibility`.
    pub accessibility: String,
    /// `<prefix>RobotCoordination`.
    pub coordination: String,
}

/// Set names with `prefix` (`Pset_` as in the paper, or a non-reserved one such as `POINAV_`).
pub fn pset_names(prefix: &str) -> PsetNames {
    PsetNames {
        classification: format!("{prefix}POI_Classification"),
        accessibility: format!("{prefix}RobotAccessibility"),
        coordination: format!("{prefix}RobotCoordination"),
    }
}

/// How to write.
#[derive(Debug, Clone)]
pub struct WriteOptions {
    /// Set-name prefix, `Pset_` by default.
    pub prefix: String,
    /// LastValidated and the header's FILE_NAME time stamp (ISO 8601).
    pub timestamp: String,
}

/// A length in metres as stored in a file whose unit is `metres_per_unit`, rounded to 1e-9 so
/// `0.9 m` is stored as `900.` in millimetres, not `900.0000000000001`.
pub fn stored_length(metres: f64, metres_per_unit: f64) -> f64 {
    let v = metres / metres_per_unit;
    let r = (v * 1e9).round() / 1e9;
    if r == 0.0 {
        v
    } else {
        r
    }
}

struct Writer<'e, 'm> {
    ed: &'e mut Editor<'m>,
    metres: f64,
    schema: Schema,
    enums: Vec<(&'static str, EntityId)>,
}

impl Writer<'_, '_> {
    fn enumeration(&mut self, name: &'static str, labels: &[&str]) -> Result<EntityId, PoiError> {
        if let Some((_, id)) = self.enums.iter().find(|(n, _)| *n == name) {
            return Ok(*id);
        }
        let id = self
            .ed
            .add_enumeration(name, labels.iter().map(|l| Arg::label(l)).collect())?;
        self.enums.push((name, id));
        Ok(id)
    }

    fn enumerated(
        &mut self,
        enum_name: &'static str,
        labels: &[&str],
        value: &str,
    ) -> Result<NewProperty, PoiError> {
        let reference = self.enumeration(enum_name, labels)?;
        Ok(NewProperty::Enumerated(
            vec![Arg::label(value)],
            Some(reference),
        ))
    }

    fn length(&self, metres: f64) -> NewProperty {
        NewProperty::Single(Arg::typed(
            "IfcPositiveLengthMeasure",
            Arg::Real(stored_length(metres, self.metres)),
        ))
    }
}

fn labels<T: Copy>(all: &[T], label: impl Fn(T) -> &'static str) -> Vec<&'static str> {
    all.iter().map(|&v| label(v)).collect()
}

type Props = Vec<(String, NewProperty)>;

fn classification_props(w: &mut Writer<'_, '_>, c: &Classified) -> Result<Props, PoiError> {
    let mut props = vec![
        (
            "POI_Category".to_string(),
            w.enumerated(
                "PEnum_POI_Category",
                &labels(Category::ALL, Category::label),
                c.category.label(),
            )?,
        ),
        (
            "POI_Type".to_string(),
            w.enumerated(
                "PEnum_POI_Type",
                &labels(PoiType::ALL, PoiType::label),
                c.poi_type.label(),
            )?,
        ),
        (
            "POI_PrimaryRoles".to_string(),
            NewProperty::List(c.primary.iter().map(|r| Arg::label(r.label())).collect()),
        ),
    ];
    // IFC2X3 cannot hold an empty list (ListValues is mandatory, [1:?]): the property is left out.
    if !c.conditional.is_empty() || w.schema != Schema::Ifc2x3 {
        props.push((
            "POI_ConditionalRoles".to_string(),
            NewProperty::List(
                c.conditional
                    .iter()
                    .map(|r| Arg::label(r.label()))
                    .collect(),
            ),
        ));
    }
    Ok(props)
}

fn accessibility_props(
    w: &mut Writer<'_, '_>,
    c: &Classified,
    timestamp: &str,
) -> Result<Option<Props>, PoiError> {
    let Some(a) = &c.accessibility else {
        return Ok(None);
    };
    let date = if w.schema == Schema::Ifc2x3 {
        Arg::label(timestamp)
    } else {
        Arg::typed("IfcDateTime", Arg::Text(timestamp.into()))
    };
    Ok(Some(vec![
        (
            "MinClearanceWidth".to_string(),
            w.length(a.min_clearance_width_m),
        ),
        (
            "MinClearanceHeight".to_string(),
            w.length(a.min_clearance_height_m),
        ),
        (
            "AccessibilityStatus".to_string(),
            w.enumerated(
                "PEnum_AccessibilityStatus",
                &labels(AccessibilityStatus::ALL, AccessibilityStatus::label),
                a.status.label(),
            )?,
        ),
        (
            "ValidationMethod".to_string(),
            w.enumerated(
                "PEnum_ValidationMethod",
                &labels(ValidationMethod::ALL, ValidationMethod::label),
                a.method.label(),
            )?,
        ),
        ("LastValidated".to_string(), NewProperty::Single(date)),
    ]))
}

fn coordination_props(w: &mut Writer<'_, '_>, c: &Classified) -> Result<Option<Props>, PoiError> {
    let Some(k) = &c.coordination else {
        return Ok(None);
    };
    Ok(Some(vec![
        (
            "MaxSimultaneousRobots".to_string(),
            NewProperty::Single(Arg::typed("IfcInteger", Arg::Integer(k.max_robots))),
        ),
        (
            "MinInterRobotSeparation".to_string(),
            w.length(k.min_separation_m),
        ),
        (
            "CoordinationProtocol".to_string(),
            w.enumerated(
                "PEnum_CoordinationProtocol",
                &labels(CoordinationProtocol::ALL, CoordinationProtocol::label),
                k.protocol.label(),
            )?,
        ),
        (
            "AppliesTo".to_string(),
            w.enumerated(
                "PEnum_AppliesTo",
                &labels(AppliesTo::ALL, AppliesTo::label),
                k.applies_to.label(),
            )?,
        ),
    ]))
}

/// Ids of everything an earlier poinav enrichment added: its property sets (found by
/// [`POINAV_MARKER`]), their properties and enumerations, the relations that attach them, and
/// an owner history poinav created.
pub fn previous_enrichment(model: &Model) -> Vec<EntityId> {
    let mut out = Vec::new();
    let mut psets = Vec::new();
    for set in model.instances_of("IfcPropertySet") {
        if set.get_str("Description").as_deref() != Some(POINAV_MARKER) {
            continue;
        }
        psets.push(set.id());
        out.push(set.id());
        for p in set.get_refs("HasProperties") {
            out.push(p.id());
            if let Some(e) = p.get_ref("EnumerationReference") {
                out.push(e.id());
            }
        }
    }
    for rel in model.instances_of("IfcRelDefinesByProperties") {
        let defs = rel
            .get("RelatingPropertyDefinition")
            .map(|v| v.refs())
            .unwrap_or_default();
        if !defs.is_empty() && defs.iter().all(|d| psets.contains(d)) {
            out.push(rel.id());
        }
    }
    for app in model.instances_of("IfcApplication") {
        if app.get_str("ApplicationIdentifier").as_deref() != Some(poinav_ifc::OWNER_APPLICATION_ID)
        {
            continue;
        }
        let chain: Vec<EntityId> = model
            .instances_of("IfcOwnerHistory")
            .into_iter()
            .filter(|h| h.get_ref("OwningApplication") == Some(app))
            .flat_map(|h| {
                let pao = h.get_ref("OwningUser");
                let people = pao
                    .map(|p| [p.get_ref("ThePerson"), p.get_ref("TheOrganization")])
                    .unwrap_or_default();
                std::iter::once(Some(h)).chain([pao]).chain(people)
            })
            .flatten()
            .map(|e| e.id())
            .chain([app.id()])
            .chain(app.get_ref("ApplicationDeveloper").map(|d| d.id()))
            .collect();
        // Only when nothing else uses it: an element added later in a BIM tool may point at it.
        let used_elsewhere = chain.iter().any(|&c| {
            model
                .referrers(c)
                .iter()
                .any(|r| !chain.contains(&r.id()) && !out.contains(&r.id()))
        });
        if !used_elsewhere {
            out.extend(chain);
        }
    }
    out.sort_unstable();
    out.dedup();
    out
}

/// Removes any earlier poinav enrichment and adds the property sets of `c`; returns the
/// editor to write. Identical sets are shared by one IfcRelDefinesByProperties.
pub fn write_enrichment<'m>(
    model: &'m Model,
    c: &Classification,
    opts: &WriteOptions,
) -> Result<Editor<'m>, PoiError> {
    let mut ed = Editor::new(model);
    for id in previous_enrichment(model) {
        ed.remove(id)?;
    }
    ed.set_timestamp(&opts.timestamp);
    let names = pset_names(&opts.prefix);
    let mut w = Writer {
        ed: &mut ed,
        metres: poinav_ifc::units::length_unit(model).metres_per_unit,
        schema: model.schema(),
        enums: Vec::new(),
    };
    // Groups of identical sets, in order of first appearance.
    let mut groups: Vec<(String, String, Props, Vec<EntityId>)> = Vec::new();
    let mut index: std::collections::HashMap<String, usize> = std::collections::HashMap::new();
    for el in &c.elements {
        let mut sets = vec![(
            names.classification.clone(),
            classification_props(&mut w, el)?,
        )];
        if let Some(p) = accessibility_props(&mut w, el, &opts.timestamp)? {
            sets.push((names.accessibility.clone(), p));
        }
        if let Some(p) = coordination_props(&mut w, el)? {
            sets.push((names.coordination.clone(), p));
        }
        for (name, props) in sets {
            let key = format!("{name}|{props:?}");
            match index.get(&key) {
                Some(&i) => groups[i].3.push(el.id),
                None => {
                    index.insert(key.clone(), groups.len());
                    groups.push((key, name, props, vec![el.id]));
                }
            }
        }
    }
    for (key, name, props, objects) in groups {
        w.ed.add_property_set(
            &objects,
            &name,
            Some(POINAV_MARKER),
            props,
            &format!("poinav-enrich/{key}"),
        )?;
    }
    Ok(ed)
}
