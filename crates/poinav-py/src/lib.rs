//! The `poinav._native` Python extension module: the library's calls for Python.
//!
//! The pure-Python package `poinav` (python/poinav) wraps these classes and functions; every
//! long call releases the GIL (`Python::detach`). Errors become `poinav.PoinavError` and its
//! subclasses (`error.rs`), never a crash of the interpreter.

mod building;
mod convert;
mod enrichment;
mod error;
mod inspect;
mod model;
mod navigators;
mod profile;
mod pset_chunks;
mod psets;
mod simulate;

use pyo3::prelude::*;

#[pymodule]
fn _native(m: &Bound<'_, PyModule>) -> PyResult<()> {
    let py = m.py();
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    m.add("PoinavError", py.get_type::<error::PoinavError>())?;
    m.add("IfcError", py.get_type::<error::IfcError>())?;
    m.add("NoRouteError", py.get_type::<error::NoRouteError>())?;
    m.add_class::<model::Model>()?;
    m.add_class::<enrichment::Enrichment>()?;
    m.add_class::<building::Building>()?;
    m.add_class::<building::Grid>()?;
    m.add_function(wrap_pyfunction!(model::open_path, m)?)?;
    m.add_function(wrap_pyfunction!(model::open_bytes, m)?)?;
    m.add_function(wrap_pyfunction!(simulate::simulate, m)?)?;
    m.add_function(wrap_pyfunction!(simulate::read_trace, m)?)?;
    m.add_function(wrap_pyfunction!(model::bench_psets, m)?)?;
    m.add_function(wrap_pyfunction!(model::bench_meshes, m)?)?;
    Ok(())
}
