//! Property sets of an object: its own (IsDefinedBy) merged over its type's (IsTypedBy, or
//! IfcRelDefinesByType in IFC2X3), as IfcOpenShell's `get_psets` does.

use crate::entity::Entity;
use crate::value::Value;
use crate::EntityId;

/// One simple value of a property.
#[derive(Debug, Clone, PartialEq)]
pub enum Scalar {
    /// IfcLabel, IfcText, IfcIdentifier, ...
    Text(String),
    /// Any real measure.
    Real(f64),
    /// IfcInteger, IfcCountMeasure, ...
    Integer(i64),
    /// IfcBoolean.
    Bool(bool),
    /// IfcLogical (`None` is UNKNOWN).
    Logical(Option<bool>),
    /// An untyped enumeration item.
    Enum(String),
    /// A reference to another instance.
    Ref(EntityId),
}

/// A property value with the IFC type it was written with (`IFCLABEL`), when typed.
#[derive(Debug, Clone, PartialEq)]
pub struct TypedScalar {
    /// Upper-case IFC type name as written, e.g. `IFCPOSITIVELENGTHMEASURE`.
    pub ty: Option<String>,
    /// The value.
    pub value: Scalar,
}

/// The value of one property, by property kind.
#[derive(Debug, Clone, PartialEq)]
pub enum PropertyValue {
    /// IfcPropertySingleValue (`None` when `$`).
    Single(Option<TypedScalar>),
    /// IfcPropertyEnumeratedValue.
    Enumerated(Vec<TypedScalar>),
    /// IfcPropertyListValue.
    List(Vec<TypedScalar>),
    /// IfcPropertyBoundedValue: lower, upper.
    Bounded(Option<TypedScalar>, Option<TypedScalar>),
    /// IfcComplexProperty.
    Complex(Vec<Property>),
    /// Any other property kind (table, reference): kept by id.
    Other(EntityId),
}

/// One property.
#[derive(Debug, Clone, PartialEq)]
pub struct Property {
    /// The property instance.
    pub id: EntityId,
    /// Its Name.
    pub name: String,
    /// Its value.
    pub value: PropertyValue,
}

/// One property set with its properties.
#[derive(Debug, Clone, PartialEq)]
pub struct PropertySet {
    /// The IfcPropertySet (for merged sets: the occurrence's, else the type's).
    pub id: EntityId,
    /// Its Name.
    pub name: String,
    /// True when every property came from the type object.
    pub from_type: bool,
    /// Properties in file order (type properties first, overridden in place by the occurrence's).
    pub properties: Vec<Property>,
}

impl PropertySet {
    /// The property called `name`.
    pub fn get(&self, name: &str) -> Option<&PropertyValue> {
        self.properties
            .iter()
            .find(|p| p.name == name)
            .map(|p| &p.value)
    }
}

/// Reads a scalar; its IFC type name is kept (`ty`, one allocation) only when `types`.
fn scalar(v: &Value<'_>, types: bool) -> Option<TypedScalar> {
    let (ty, inner) = match v {
        Value::Typed(t, inner) => (Some(*t), inner.as_ref()),
        other => (None, other),
    };
    let value = match inner {
        Value::String(_) => Scalar::Text(inner.as_str()?.into_owned()),
        Value::Real(r) => Scalar::Real(*r),
        Value::Integer(i) if ty.is_some_and(|t| !is_integer_type(t)) => Scalar::Real(*i as f64),
        Value::Integer(i) => Scalar::Integer(*i),
        Value::Enum(e) => match (ty, *e) {
            (Some("IFCBOOLEAN"), "T") => Scalar::Bool(true),
            (Some("IFCBOOLEAN"), "F") => Scalar::Bool(false),
            (Some("IFCLOGICAL"), "T") => Scalar::Logical(Some(true)),
            (Some("IFCLOGICAL"), "F") => Scalar::Logical(Some(false)),
            (Some("IFCLOGICAL"), _) => Scalar::Logical(None),
            _ => Scalar::Enum(e.to_string()),
        },
        Value::Ref(id) => Scalar::Ref(*id),
        _ => return None,
    };
    Some(TypedScalar {
        ty: ty.filter(|_| types).map(str::to_string),
        value,
    })
}

fn is_integer_type(upper: &str) -> bool {
    matches!(
        upper,
        "IFCINTEGER"
            | "IFCCOUNTMEASURE"
            | "IFCPOSITIVEINTEGER"
            | "IFCDAYINMONTHNUMBER"
            | "IFCMONTHINYEARNUMBER"
            | "IFCTIMESTAMP"
    )
}

fn scalars(v: Option<Value<'_>>, types: bool) -> Vec<TypedScalar> {
    v.and_then(|v| {
        v.as_list()
            .map(|l| l.iter().filter_map(|v| scalar(v, types)).collect())
    })
    .unwrap_or_default()
}

/// Reads one property instance.
pub fn property(p: Entity<'_>, depth: usize) -> Property {
    read_property(p, depth, true)
}

/// Reads one property instance, with its scalars' IFC type names when `types`.
fn read_property(p: Entity<'_>, depth: usize, types: bool) -> Property {
    let name = p.name().unwrap_or_default();
    let one = |v: Option<Value<'_>>| v.as_ref().and_then(|v| scalar(v, types));
    let value = if p.is_a("IfcPropertySingleValue") {
        PropertyValue::Single(one(p.get("NominalValue")))
    } else if p.is_a("IfcPropertyEnumeratedValue") {
        PropertyValue::Enumerated(scalars(p.get("EnumerationValues"), types))
    } else if p.is_a("IfcPropertyListValue") {
        PropertyValue::List(scalars(p.get("ListValues"), types))
    } else if p.is_a("IfcPropertyBoundedValue") {
        PropertyValue::Bounded(one(p.get("LowerBoundValue")), one(p.get("UpperBoundValue")))
    } else if p.is_a("IfcComplexProperty") && depth < 8 {
        PropertyValue::Complex(
            p.get_refs("HasProperties")
                .into_iter()
                .map(|c| read_property(c, depth + 1, types))
                .collect(),
        )
    } else {
        PropertyValue::Other(p.id())
    };
    Property {
        id: p.id(),
        name,
        value,
    }
}

/// The property set definitions (IfcPropertySet, IfcElementQuantity, IfcDoorLiningProperties, ...)
/// attached to `e` directly, in file order of their relations.
pub fn own_definitions<'m>(e: Entity<'m>) -> Vec<Entity<'m>> {
    let mut out = Vec::new();
    for rel in e.inverse("IsDefinedBy") {
        if rel.is_a("IfcRelDefinesByProperties") {
            out.extend(rel.get_refs("RelatingPropertyDefinition"));
        }
    }
    out
}

/// The property set definitions of `e`'s type object, if it has one.
pub fn type_definitions<'m>(e: Entity<'m>) -> Vec<Entity<'m>> {
    let rels = e.inverse("IsTypedBy").into_iter().chain(
        e.inverse("IsDefinedBy")
            .into_iter()
            .filter(|r| r.is_a("IfcRelDefinesByType")),
    );
    rels.filter_map(|r| r.get_ref("RelatingType"))
        .flat_map(|t| t.get_refs("HasPropertySets"))
        .collect()
}

/// The type object of `e` (IfcDoorType, IfcWallType, ...), if any.
pub fn type_object<'m>(e: Entity<'m>) -> Option<Entity<'m>> {
    let rels = e.inverse("IsTypedBy").into_iter().chain(
        e.inverse("IsDefinedBy")
            .into_iter()
            .filter(|r| r.is_a("IfcRelDefinesByType")),
    );
    rels.filter_map(|r| r.get_ref("RelatingType")).next()
}

/// The IfcPropertySets that [`property_sets`] merges for `e`, in its order: its type's
/// (`true`), then its own (`false`).
pub fn set_definitions<'m>(e: Entity<'m>) -> impl Iterator<Item = (Entity<'m>, bool)> {
    let from_type = type_definitions(e).into_iter().map(|d| (d, true));
    let own = own_definitions(e).into_iter().map(|d| (d, false));
    from_type
        .chain(own)
        .filter(|(d, _)| d.is_a("IfcPropertySet"))
}

/// One IfcPropertySet as written, not merged with any other.
pub fn read_set(def: Entity<'_>, from_type: bool) -> PropertySet {
    read_set_with(def, from_type, true)
}

/// [`read_set`] without the IFC type names (every `ty` is `None`; one allocation less per
/// value), for readers that give values as IfcOpenShell's `get_psets` does: a text or a
/// number without the type it was written with.
pub fn read_set_untyped(def: Entity<'_>, from_type: bool) -> PropertySet {
    read_set_with(def, from_type, false)
}

fn read_set_with(def: Entity<'_>, from_type: bool, types: bool) -> PropertySet {
    PropertySet {
        id: def.id(),
        name: def.name().unwrap_or_default(),
        from_type,
        properties: def
            .get_refs("HasProperties")
            .into_iter()
            .map(|p| read_property(p, 0, types))
            .collect(),
    }
}

/// All IfcPropertySets of `e`, type sets merged under the occurrence's by set and property name.
/// Where no two of [`set_definitions`] share a name, these are their [`read_set`]s as they are.
pub fn property_sets(e: Entity<'_>) -> Vec<PropertySet> {
    let mut sets: Vec<PropertySet> = Vec::new();
    for (def, is_type) in set_definitions(e) {
        let read = read_set(def, is_type);
        match sets.iter_mut().find(|s| s.name == read.name) {
            Some(set) => {
                if !is_type {
                    set.id = read.id;
                    set.from_type = false;
                }
                for p in read.properties {
                    match set.properties.iter_mut().find(|q| q.name == p.name) {
                        Some(q) => *q = p,
                        None => set.properties.push(p),
                    }
                }
            }
            None => sets.push(read),
        }
    }
    sets
}
