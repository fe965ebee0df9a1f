//! Conversions to Python: JSON values (through the `json` module, so dicts keep their
//! order), property values, and flat buffers to numpy arrays.

use glam::DVec3;
use numpy::ndarray::Array2;
use numpy::IntoPyArray;
use poinav_ifc::property::{Property, PropertyValue, Scalar, TypedScalar};
use rustc_hash::FxHashMap;

use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList, PyString, PyTuple};

/// Python strings made once per distinct text: property and set names repeat across a
/// model's products, and making each anew was most of the conversion's time. (FxHash: the
/// default SipHash was a seventh of what remained.)
#[derive(Debug, Default)]
pub struct Strings<'a, 'py> {
    made: FxHashMap<&'a str, Bound<'py, PyString>>,
}

impl<'a, 'py> Strings<'a, 'py> {
    /// The Python string of `s`.
    pub fn get(&mut self, py: Python<'py>, s: &'a str) -> Bound<'py, PyString> {
        self.made
            .entry(s)
            .or_insert_with(|| PyString::new(py, s))
            .clone()
    }
}

/// A JSON value as Python objects (dicts, lists, str, int, float, bool, None).
pub fn json<'py>(py: Python<'py>, value: &serde_json::Value) -> PyResult<Bound<'py, PyAny>> {
    let text = value.to_string();
    py.import("json")?.call_method1("loads", (text,))
}

/// A serialisable value as Python objects.
pub fn to_python<'py, T: serde::Serialize>(
    py: Python<'py>,
    value: &T,
) -> PyResult<Bound<'py, PyAny>> {
    let v = serde_json::to_value(value).map_err(crate::error::to_py)?;
    json(py, &v)
}

/// An `(n, k)` numpy array of `data` (row-major, `n * k` values).
pub fn array2<'py, T: numpy::Element>(
    py: Python<'py>,
    data: Vec<T>,
    k: usize,
) -> PyResult<Bound<'py, PyAny>> {
    let n = data.len().checked_div(k).unwrap_or(0);
    let a = Array2::from_shape_vec((n, k), data)
        .map_err(|e| crate::error::PoinavError::new_err(e.to_string()))?;
    Ok(a.into_pyarray(py).into_any())
}

/// An `(n, k)` numpy array of `rows`, its memory the vector's (no copy).
pub fn rows<'py, T: numpy::Element, const K: usize>(
    py: Python<'py>,
    rows: Vec<[T; K]>,
) -> PyResult<Bound<'py, PyAny>> {
    let n = rows.len();
    let a = Array2::from_shape_vec((n, K), rows.into_flattened())
        .map_err(|e| crate::error::PoinavError::new_err(e.to_string()))?;
    Ok(a.into_pyarray(py).into_any())
}

/// Vertex positions as rows of three floats, the same memory (no copy), for `rows`.
pub fn position_rows(positions: Vec<DVec3>) -> Vec<[f64; 3]> {
    const {
        assert!(size_of::<DVec3>() == size_of::<[f64; 3]>());
        assert!(align_of::<DVec3>() == align_of::<[f64; 3]>());
    }
    let mut v = std::mem::ManuallyDrop::new(positions);
    // SAFETY: `DVec3` is `#[repr(C)] { x: f64, y: f64, z: f64 }`: the layout of `[f64; 3]`
    // (size and alignment checked above), so the allocation, length and capacity carry over
    // and the vector frees it with the same layout.
    unsafe { Vec::from_raw_parts(v.as_mut_ptr().cast::<[f64; 3]>(), v.len(), v.capacity()) }
}

fn scalar<'a, 'py>(
    py: Python<'py>,
    s: &'a TypedScalar,
    strings: &mut Strings<'a, 'py>,
) -> PyResult<Bound<'py, PyAny>> {
    Ok(match &s.value {
        Scalar::Text(t) | Scalar::Enum(t) => strings.get(py, t).into_any(),
        Scalar::Real(r) => r.into_pyobject(py)?.into_any(),
        Scalar::Integer(i) => i.into_pyobject(py)?.into_any(),
        Scalar::Bool(b) => b.into_pyobject(py)?.to_owned().into_any(),
        Scalar::Logical(Some(b)) => b.into_pyobject(py)?.to_owned().into_any(),
        // IfcOpenShell's spelling of the third logical value.
        Scalar::Logical(None) => "UNKNOWN".into_pyobject(py)?.into_any(),
        Scalar::Ref(id) => id.0.into_pyobject(py)?.into_any(),
    })
}

fn scalars<'a, 'py>(
    py: Python<'py>,
    list: &'a [TypedScalar],
    strings: &mut Strings<'a, 'py>,
) -> PyResult<Bound<'py, PyAny>> {
    let items = list
        .iter()
        .map(|s| scalar(py, s, strings))
        .collect::<PyResult<Vec<_>>>()?;
    Ok(PyList::new(py, items)?.into_any())
}

/// A property's value as IfcOpenShell's `get_psets` gives it: a scalar, a list (enumerated
/// and list values; None when unset), a `(lower, upper)` tuple (bounded), a dict (complex),
/// the `#id` (others).
pub fn property_value<'a, 'py>(
    py: Python<'py>,
    v: &'a PropertyValue,
    strings: &mut Strings<'a, 'py>,
) -> PyResult<Bound<'py, PyAny>> {
    Ok(match v {
        PropertyValue::Single(None) => py.None().into_bound(py),
        PropertyValue::Single(Some(s)) => scalar(py, s, strings)?,
        // IFC lists have at least one item: an empty one was unset (`$`), None as for
        // IfcOpenShell.
        PropertyValue::Enumerated(l) | PropertyValue::List(l) if l.is_empty() => {
            py.None().into_bound(py)
        }
        PropertyValue::Enumerated(l) | PropertyValue::List(l) => scalars(py, l, strings)?,
        PropertyValue::Bounded(lo, hi) => {
            let mut f = |s: &'a Option<TypedScalar>| match s {
                Some(s) => scalar(py, s, strings),
                None => Ok(py.None().into_bound(py)),
            };
            let lo = f(lo)?;
            let hi = f(hi)?;
            PyTuple::new(py, [lo, hi])?.into_any()
        }
        PropertyValue::Complex(props) => properties(py, props, strings)?.into_any(),
        PropertyValue::Other(id) => id.0.into_pyobject(py)?.into_any(),
    })
}

/// Properties as a dict name -> value.
pub fn properties<'a, 'py>(
    py: Python<'py>,
    props: &'a [Property],
    strings: &mut Strings<'a, 'py>,
) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    for p in props {
        let value = property_value(py, &p.value, strings)?;
        d.set_item(strings.get(py, &p.name), value)?;
    }
    Ok(d)
}
