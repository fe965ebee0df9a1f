//! Conversions to Python: JSON values (through the `json` module, so dicts keep their
//! order), property values, and flat buffers to numpy arrays.

use numpy::ndarray::Array2;
use numpy::IntoPyArray;
use poinav_ifc::property::{Property, PropertyValue, Scalar, TypedScalar};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList, PyTuple};

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

fn scalar<'py>(py: Python<'py>, s: &TypedScalar) -> PyResult<Bound<'py, PyAny>> {
    Ok(match &s.value {
        Scalar::Text(t) | Scalar::Enum(t) => t.into_pyobject(py)?.into_any(),
        Scalar::Real(r) => r.into_pyobject(py)?.into_any(),
        Scalar::Integer(i) => i.into_pyobject(py)?.into_any(),
        Scalar::Bool(b) => b.into_pyobject(py)?.to_owned().into_any(),
        Scalar::Logical(Some(b)) => b.into_pyobject(py)?.to_owned().into_any(),
        // IfcOpenShell's spelling of the third logical value.
        Scalar::Logical(None) => "UNKNOWN".into_pyobject(py)?.into_any(),
        Scalar::Ref(id) => id.0.into_pyobject(py)?.into_any(),
    })
}

fn scalars<'py>(py: Python<'py>, list: &[TypedScalar]) -> PyResult<Bound<'py, PyAny>> {
    let items = list
        .iter()
        .map(|s| scalar(py, s))
        .collect::<PyResult<Vec<_>>>()?;
    Ok(PyList::new(py, items)?.into_any())
}

/// A property's value as IfcOpenShell's `get_psets` gives it: a scalar, a list (enumerated
/// and list values), a `(lower, upper)` tuple (bounded), a dict (complex), the `#id` (others).
pub fn property_value<'py>(py: Python<'py>, v: &PropertyValue) -> PyResult<Bound<'py, PyAny>> {
    Ok(match v {
        PropertyValue::Single(None) => py.None().into_bound(py),
        PropertyValue::Single(Some(s)) => scalar(py, s)?,
        PropertyValue::Enumerated(l) | PropertyValue::List(l) => scalars(py, l)?,
        PropertyValue::Bounded(lo, hi) => {
            let f = |s: &Option<TypedScalar>| match s {
                Some(s) => scalar(py, s),
                None => Ok(py.None().into_bound(py)),
            };
            PyTuple::new(py, [f(lo)?, f(hi)?])?.into_any()
        }
        PropertyValue::Complex(props) => properties(py, props)?.into_any(),
        PropertyValue::Other(id) => id.0.into_pyobject(py)?.into_any(),
    })
}

/// Properties as a dict name -> value.
pub fn properties<'py>(py: Python<'py>, props: &[Property]) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    for p in props {
        d.set_item(&p.name, property_value(py, &p.value)?)?;
    }
    Ok(d)
}
