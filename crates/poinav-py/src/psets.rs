//! Property sets as Python dicts (`Model.psets`): GlobalId -> set name -> property name ->
//! value, each distinct set read once and its dict built once per call, copied for every
//! further product.

use poinav_ifc::property::{
    property_sets, read_set_untyped, set_definitions, PropertySet, PropertyValue, Scalar,
    TypedScalar,
};
use poinav_ifc::{Entity, EntityId};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyString};
use rayon::prelude::*;
use rustc_hash::FxHashMap;

use crate::convert::{self, Strings};

/// Dicts already built in this call, by property set `#id`, with the set they were built from
/// and its name as a Python string.
///
/// A property set related to many products (and a type's sets, merged into each occurrence's)
/// comes back from the library once per product; on office-a 39 % of the sets are repeats.
/// A repeat's dict is a copy (`PyDict_Copy` copies the key table whole) sharing the value
/// objects, so only sets whose values are immutable in Python (str, int, float, bool, None,
/// tuples of them) are cached: a list or a dict value is made anew for every product, as
/// IfcOpenShell does.
#[derive(Debug, Default)]
struct Built<'a, 'py> {
    sets: FxHashMap<EntityId, (&'a PropertySet, Bound<'py, PyString>, Bound<'py, PyDict>)>,
    shapes: FxHashMap<&'a str, Shape<'a, 'py>>,
}

/// The sets of one name built so far: the set name and, by position, the last property's
/// name and text value with their Python strings. Sets of one name mostly list the same
/// properties in the same order and often the same texts, so comparing with the previous
/// set's spares most lookups in `Strings` (hashing every name and text was the largest part
/// of the conversion after the Python objects themselves).
#[derive(Debug)]
struct Shape<'a, 'py> {
    name: Bound<'py, PyString>,
    slots: Vec<Slot<'a, 'py>>,
}

/// One position of a `Shape`.
#[derive(Debug)]
struct Slot<'a, 'py> {
    name: &'a str,
    key: Bound<'py, PyString>,
    text: Option<(&'a str, Bound<'py, PyString>)>,
}

impl<'a, 'py> Built<'a, 'py> {
    /// The name and dict of `set`: a copy of the one built for the same set, or a new one.
    fn dict(
        &mut self,
        py: Python<'py>,
        set: &'a PropertySet,
        strings: &mut Strings<'a, 'py>,
    ) -> PyResult<(Bound<'py, PyString>, Bound<'py, PyDict>)> {
        if let Some((first, name, dict)) = self.sets.get(&set.id) {
            if same_set(first, set) {
                return Ok((name.clone(), dict.copy()?));
            }
        }
        let shape = self
            .shapes
            .entry(set.name.as_str())
            .or_insert_with(|| Shape {
                name: strings.get(py, &set.name),
                slots: Vec::new(),
            });
        let dict = PyDict::new(py);
        for (i, p) in set.properties.iter().enumerate() {
            if shape.slots.len() == i {
                shape.slots.push(Slot {
                    name: &p.name,
                    key: strings.get(py, &p.name),
                    text: None,
                });
            }
            let slot = &mut shape.slots[i];
            if slot.name != p.name {
                *slot = Slot {
                    name: &p.name,
                    key: strings.get(py, &p.name),
                    text: None,
                };
            }
            let value = match text(&p.value) {
                Some(t) => match &slot.text {
                    Some((last, v)) if *last == t => v.clone().into_any(),
                    _ => {
                        let v = strings.get(py, t);
                        slot.text = Some((t, v.clone()));
                        v.into_any()
                    }
                },
                None => convert::property_value(py, &p.value, strings)?,
            };
            dict.set_item(&slot.key, value)?;
        }
        dict.set_item(pyo3::intern!(py, "id"), set.id.0)?;
        let name = shape.name.clone();
        if set.properties.iter().all(|p| immutable(&p.value)) {
            // The first set of an id stays the one compared with (a merged set can differ
            // from another with the same id: same occurrence set, another type). Nothing
            // changes the dict before the call returns.
            self.sets
                .entry(set.id)
                .or_insert((set, name.clone(), dict.clone()));
        }
        Ok((name, dict))
    }
}

/// The text of a single text or enumeration value.
fn text(v: &PropertyValue) -> Option<&str> {
    match v {
        PropertyValue::Single(Some(TypedScalar {
            value: Scalar::Text(t) | Scalar::Enum(t),
            ..
        })) => Some(t),
        _ => None,
    }
}

/// True when `a` and `b` hold the same properties: the library reads a property instance
/// the same way each time, so the same `#id`s in the same order give the same values.
fn same_set(a: &PropertySet, b: &PropertySet) -> bool {
    a.name == b.name
        && a.properties.len() == b.properties.len()
        && a.properties
            .iter()
            .zip(&b.properties)
            .all(|(p, q)| p.id == q.id)
}

/// True when the Python value of `v` is immutable (a list or a dict is not).
fn immutable(v: &PropertyValue) -> bool {
    match v {
        PropertyValue::Single(_) | PropertyValue::Bounded(..) | PropertyValue::Other(_) => true,
        PropertyValue::Enumerated(l) | PropertyValue::List(l) => l.is_empty(),
        PropertyValue::Complex(_) => false,
    }
}

/// The property sets of every instance of a class with a GlobalId, as `property_sets` gives
/// them but without the values' IFC type names (`read_set_untyped`: the dicts do not give
/// them), each distinct IfcPropertySet read once.
///
/// A set related to many products (and a type's sets, which every occurrence of the type
/// gets) would otherwise be read, decoded and freed again for every product: 39 % of
/// office-a's 8,494 sets are repeats. A product whose sets share no name gets them as read;
/// one where a type's set and its own share a name (merged) is read by `property_sets`.
#[derive(Debug, Default)]
pub struct AllSets {
    /// The sets read once.
    read: Vec<PropertySet>,
    /// Per product: its GlobalId and sets.
    products: Vec<(String, ProductSets)>,
}

/// One product's property sets.
#[derive(Debug)]
enum ProductSets {
    /// Sets of `AllSets::read`, by index, in order.
    Read(Vec<usize>),
    /// Merged sets of this product alone.
    Merged(Vec<PropertySet>),
}

impl AllSets {
    /// Reads the sets of every instance of `class` (subtypes included) with a GlobalId, in
    /// parallel, in the model's order.
    pub fn read(model: &poinav_ifc::Model, class: &str) -> Self {
        let defs: Vec<(Entity<'_>, String, Vec<Entity<'_>>)> = model
            .instances_of(class)
            .par_iter()
            .filter_map(|e| {
                let g = e.global_id()?;
                Some((*e, g, set_definitions(*e).map(|(d, _)| d).collect()))
            })
            .collect();
        // Each product's sets as indices into the distinct ones, in first-seen order.
        let mut index = FxHashMap::default();
        let mut distinct: Vec<Entity<'_>> = Vec::new();
        let defs: Vec<(Entity<'_>, String, Vec<usize>)> = defs
            .into_iter()
            .map(|(e, g, d)| {
                let d = d
                    .into_iter()
                    .map(|d| {
                        *index.entry(d.id()).or_insert_with(|| {
                            distinct.push(d);
                            distinct.len() - 1
                        })
                    })
                    .collect();
                (e, g, d)
            })
            .collect();
        // Neither `from_type` nor the values' IFC type names are part of the dicts.
        let read: Vec<PropertySet> = distinct
            .par_iter()
            .map(|d| read_set_untyped(*d, false))
            .collect();
        // Comparing names is little work: on one thread (a parallel pass costs more in
        // rayon's hand-offs on a small model); merged sets are rare.
        let products = defs
            .into_iter()
            .map(|(e, g, d)| {
                let names_differ = d
                    .iter()
                    .enumerate()
                    .all(|(i, &a)| d[..i].iter().all(|&b| read[a].name != read[b].name));
                let sets = if names_differ {
                    ProductSets::Read(d)
                } else {
                    ProductSets::Merged(property_sets(e))
                };
                (g, sets)
            })
            .collect();
        AllSets { read, products }
    }

    /// The number of property sets of all products together.
    pub fn set_count(&self) -> usize {
        self.products
            .iter()
            .map(|(_, s)| match s {
                ProductSets::Read(sets) => sets.len(),
                ProductSets::Merged(sets) => sets.len(),
            })
            .sum()
    }
}

/// GlobalId -> set name -> property name -> value (each set also has `id`, the set's `#id`).
pub fn psets<'py>(py: Python<'py>, all: &AllSets) -> PyResult<Bound<'py, PyDict>> {
    let out = PyDict::new(py);
    let mut strings = Strings::default();
    let mut built = Built::default();
    for (gid, sets) in &all.products {
        let d = PyDict::new(py);
        let mut add = |s| -> PyResult<()> {
            let (name, dict) = built.dict(py, s, &mut strings)?;
            d.set_item(name, dict)
        };
        match sets {
            ProductSets::Read(sets) => sets.iter().try_for_each(|&i| add(&all.read[i]))?,
            ProductSets::Merged(sets) => sets.iter().try_for_each(&mut add)?,
        }
        out.set_item(gid, d)?;
    }
    Ok(out)
}
