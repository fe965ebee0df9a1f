//! Property sets as Python dicts (`Model.psets`): GlobalId -> set name -> property name ->
//! value. The pool reads the products in chunks (`pset_chunks`) while the calling thread,
//! holding the GIL, makes each chunk's dicts as it arrives; each distinct set's dict is built
//! once per call and copied for every further product.

use std::sync::{mpsc, Mutex};

use poinav_ifc::property::{PropertySet, PropertyValue, Scalar, TypedScalar};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyString};
use rustc_hash::FxHashMap;

use crate::convert::{self, Strings};
use crate::pset_chunks::{Chunks, ProductSets, SetRef};

/// Dicts already built in this call, by the set they were built from, with its name as a
/// Python string.
///
/// A property set related to many products (and a type's sets, merged into each occurrence's)
/// belongs to every one of them; on office-a 39 % of the sets are repeats. A repeat's dict is
/// a copy (`PyDict_Copy` copies the key table whole) sharing the value objects, so only sets
/// whose values are immutable in Python (str, int, float, bool, None, tuples of them) are
/// cached: a list or a dict value is made anew for every product, as IfcOpenShell does.
#[derive(Debug, Default)]
struct Built<'a, 'py> {
    sets: FxHashMap<SetRef, (Bound<'py, PyString>, Bound<'py, PyDict>)>,
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
    /// The name and dict of the set at `r`: a copy of the one built before, or a new one.
    fn read(
        &mut self,
        py: Python<'py>,
        r: SetRef,
        set: &'a PropertySet,
        strings: &mut Strings<'a, 'py>,
    ) -> PyResult<(Bound<'py, PyString>, Bound<'py, PyDict>)> {
        if let Some((name, dict)) = self.sets.get(&r) {
            return Ok((name.clone(), dict.copy()?));
        }
        let (name, dict) = self.build(py, set, strings)?;
        if set.properties.iter().all(|p| immutable(&p.value)) {
            // Nothing changes the dict before the call returns.
            self.sets.insert(r, (name.clone(), dict.clone()));
        }
        Ok((name, dict))
    }

    /// The name and a new dict of `set`.
    fn build(
        &mut self,
        py: Python<'py>,
        set: &'a PropertySet,
        strings: &mut Strings<'a, 'py>,
    ) -> PyResult<(Bound<'py, PyString>, Bound<'py, PyDict>)> {
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
        Ok((shape.name.clone(), dict))
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

/// True when the Python value of `v` is immutable (a list or a dict is not).
fn immutable(v: &PropertyValue) -> bool {
    match v {
        PropertyValue::Single(_) | PropertyValue::Bounded(..) | PropertyValue::Other(_) => true,
        PropertyValue::Enumerated(l) | PropertyValue::List(l) => l.is_empty(),
        PropertyValue::Complex(_) => false,
    }
}

/// GlobalId -> set name -> property name -> value (each set also has `id`, the set's `#id`)
/// of every instance of `class` (subtypes included) with a GlobalId, in the model's order.
///
/// The pool reads the chunks of products in order without the GIL; this thread makes each
/// chunk's dicts as soon as it is read, so on two cores the Python objects (made on one
/// thread) cost about their CPU share in wall time, not the whole of it.
pub fn psets<'py>(
    py: Python<'py>,
    model: &poinav_ifc::Model,
    class: &str,
) -> PyResult<Bound<'py, PyDict>> {
    let chunks = py.detach(|| Chunks::new(model, class));
    let out = if rayon::current_thread_index().is_some() {
        // On one of the pool's threads (not from Python): waiting there for the pool could
        // wait for itself. Read first, then convert.
        py.detach(|| chunks.read_all(|_| true));
        dicts(py, &chunks, |_| true)?.unbind()
    } else {
        let (tx, rx) = mpsc::channel();
        // A lock only so that the waiting below may run without the GIL (`detach` needs
        // `Sync`); only this thread takes it.
        let rx = Mutex::new(rx);
        let chunks = &chunks;
        py.detach(|| {
            rayon::in_place_scope(|s| {
                s.spawn(move |_| chunks.read_all(|k| tx.send(k).is_ok()));
                Python::attach(|py| {
                    // Wait without the GIL, and only when the next chunk is not there yet.
                    let rx = || rx.lock().expect("taken by this thread only");
                    let ready = |_| {
                        let next = rx().try_recv(); // (the lock is given back here)
                        match next {
                            Ok(_) => true,
                            Err(mpsc::TryRecvError::Empty) => py.detach(|| rx().recv().is_ok()),
                            Err(mpsc::TryRecvError::Disconnected) => false,
                        }
                    };
                    dicts(py, chunks, ready).map(Bound::unbind)
                })
            })
        })?
    };
    // Freeing the library's values needs neither the GIL nor the caller: on the pool, while
    // the caller goes on (1.4 ms on office-a).
    let owned = chunks.into_owned();
    rayon::spawn(move || drop(owned));
    Ok(out.into_bound(py))
}

/// The dicts of every chunk in order, calling `ready(k)` before chunk `k` (false: it was
/// not read, the reading stopped).
fn dicts<'py>(
    py: Python<'py>,
    chunks: &Chunks<'_>,
    mut ready: impl FnMut(usize) -> bool,
) -> PyResult<Bound<'py, PyDict>> {
    let out = PyDict::new(py);
    let mut strings = Strings::default();
    let mut built = Built::default();
    for k in 0..chunks.len() {
        let products = match ready(k).then(|| chunks.products(k)).flatten() {
            Some(p) => p,
            None => {
                return Err(crate::error::PoinavError::new_err(
                    "reading the property sets stopped",
                ))
            }
        };
        for (gid, sets) in products {
            let d = PyDict::new(py);
            match sets {
                ProductSets::Read(sets) => {
                    for &r in sets {
                        let (name, dict) = built.read(py, r, chunks.set(r), &mut strings)?;
                        d.set_item(name, dict)?;
                    }
                }
                ProductSets::Merged(sets) => {
                    for s in sets {
                        let (name, dict) = built.build(py, s, &mut strings)?;
                        d.set_item(name, dict)?;
                    }
                }
            }
            out.set_item(gid, d)?;
        }
    }
    Ok(out)
}
