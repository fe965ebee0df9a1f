//! Python exceptions: `PoinavError` for every failure, `IfcError` (with `file`, `line` and
//! `entity_id`) for a file that cannot be read, `NoRouteError` when the answer is no.

use pyo3::create_exception;
use pyo3::exceptions::PyException;
use pyo3::prelude::*;

create_exception!(
    poinav,
    PoinavError,
    PyException,
    "Any error of poinav: bad input, an output that cannot be written."
);
create_exception!(
    poinav,
    IfcError,
    PoinavError,
    "An IFC file that cannot be read; `file`, `line` (1-based) and `entity_id` (the `#id`) say where."
);
create_exception!(
    poinav,
    NoRouteError,
    PoinavError,
    "No route: the place is unreachable for the robot, or it has no room there."
);

/// `IfcError` for a read error, with its attributes set.
pub fn ifc_error(py: Python<'_>, e: &poinav_ifc::ReadError) -> PyErr {
    let err = IfcError::new_err(e.to_string());
    let value = err.value(py);
    // Setting attributes on a fresh exception instance cannot fail but for memory.
    let _ = value.setattr("file", e.file.display().to_string());
    let _ = value.setattr("line", e.line);
    let _ = value.setattr("entity_id", e.id.map(|i| i.0));
    let _ = value.setattr("kind", e.kind.to_string());
    err
}

/// `PoinavError` with the error's text and its causes.
pub fn poinav_error(e: &dyn std::error::Error) -> PyErr {
    let mut text = e.to_string();
    let mut source = e.source();
    while let Some(s) = source {
        let part = s.to_string();
        if !text.ends_with(&part) {
            text.push_str(": ");
            text.push_str(&part);
        }
        source = s.source();
    }
    PoinavError::new_err(text)
}

/// Maps any library error to `PoinavError`.
pub fn to_py<E: std::error::Error>(e: E) -> PyErr {
    poinav_error(&e)
}
