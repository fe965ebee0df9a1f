//! `Model`: an IFC file read once (`poinav_ifc::Model`), with its report, storeys, doors,
//! property sets, element meshes as numpy arrays, enrichment and navigation building.

use std::collections::HashMap;
use std::path::PathBuf;
use std::sync::Arc;

use poinav_geom::ElementMesh;
use poinav_ifc::property::{property_sets, PropertySet};
use poinav_ifc::EntityId;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyString};
use rayon::prelude::*;

use crate::building::Building;
use crate::convert;
use crate::enrichment::Enrichment;
use crate::error::ifc_error;

/// An IFC model read by poinav (IFC2X3, IFC4, IFC4X3_ADD2). Immutable; safe to share
/// between threads.
#[pyclass(frozen, module = "poinav._native")]
#[derive(Debug)]
pub struct Model {
    pub(crate) inner: Arc<poinav_ifc::Model>,
}

/// Reads the IFC file at `path`.
#[pyfunction]
pub fn open_path(py: Python<'_>, path: PathBuf) -> PyResult<Model> {
    py.detach(|| poinav_ifc::Model::open(&path))
        .map(|m| Model { inner: Arc::new(m) })
        .map_err(|e| ifc_error(py, &e))
}

/// Reads an IFC file from its bytes; `name` is what errors call it.
#[pyfunction]
#[pyo3(signature = (data, name = "<bytes>".to_string()))]
pub fn open_bytes(py: Python<'_>, data: Vec<u8>, name: String) -> PyResult<Model> {
    py.detach(|| poinav_ifc::Model::from_bytes(name, data))
        .map(|m| Model { inner: Arc::new(m) })
        .map_err(|e| ifc_error(py, &e))
}

/// The keys of a mesh's dict, made once per call.
struct MeshKeys<'py> {
    id: Bound<'py, PyString>,
    global_id: Bound<'py, PyString>,
    class: Bound<'py, PyString>,
    name: Bound<'py, PyString>,
    storey: Bound<'py, PyString>,
    storey_id: Bound<'py, PyString>,
    vertices: Bound<'py, PyString>,
    triangles: Bound<'py, PyString>,
    color: Bound<'py, PyString>,
}

impl<'py> MeshKeys<'py> {
    fn new(py: Python<'py>) -> Self {
        let k = |s| PyString::intern(py, s);
        MeshKeys {
            id: k("id"),
            global_id: k("global_id"),
            class: k("class"),
            name: k("name"),
            storey: k("storey"),
            storey_id: k("storey_id"),
            vertices: k("vertices"),
            triangles: k("triangles"),
            color: k("color"),
        }
    }
}

/// The property sets of every instance of `class` (subtypes included) with a GlobalId, as the
/// library gives them: `property_sets` of each (the benchmark's library side).
fn all_sets(model: &poinav_ifc::Model, class: &str) -> Vec<(String, Vec<PropertySet>)> {
    let products = model.instances_of(class);
    products
        .par_iter()
        .filter_map(|e| e.global_id().map(|g| (g, property_sets(*e))))
        .collect()
}

/// Benchmark helper: reads `path` and every product's property sets in Rust only (no
/// Python objects); returns the number of property sets. What the wheel adds is the
/// difference to `open(path).psets()`. By default as the library gives them to a Rust caller
/// (`property_sets` of each product); `once=True`: as `Model.psets` reads them for its
/// Python objects (each distinct set once, in the same chunks: `pset_chunks::Chunks`).
#[pyfunction]
#[pyo3(signature = (path, once = false))]
pub fn bench_psets(py: Python<'_>, path: PathBuf, once: bool) -> PyResult<usize> {
    let model = py
        .detach(|| poinav_ifc::Model::open(&path))
        .map_err(|e| ifc_error(py, &e))?;
    Ok(py.detach(|| {
        if once {
            let chunks = crate::pset_chunks::Chunks::new(&model, "IfcProduct");
            chunks.read_all(|_| true);
            chunks.set_count()
        } else {
            all_sets(&model, "IfcProduct")
                .iter()
                .map(|(_, s)| s.len())
                .sum()
        }
    }))
}

/// The Name of each storey the meshes name, by id.
fn storey_names<'a>(
    model: &poinav_ifc::Model,
    meshes: impl Iterator<Item = &'a ElementMesh>,
) -> HashMap<EntityId, Option<String>> {
    let mut names = HashMap::new();
    for s in meshes.filter_map(|m| m.storey) {
        names
            .entry(s)
            .or_insert_with(|| model.entity(s).and_then(|e| e.name()));
    }
    names
}

/// Benchmark helper: meshes the model at `path` in Rust only; returns the triangle count.
#[pyfunction]
pub fn bench_meshes(py: Python<'_>, path: PathBuf) -> PyResult<usize> {
    let model = py
        .detach(|| poinav_ifc::Model::open(&path))
        .map_err(|e| ifc_error(py, &e))?;
    Ok(py.detach(|| {
        poinav_geom::mesh_model(&model)
            .elements
            .iter()
            .map(|e| e.mesh.triangles.len())
            .sum()
    }))
}

#[pymethods]
impl Model {
    /// The file name given when opening.
    #[getter]
    fn file(&self) -> String {
        self.inner.file().display().to_string()
    }

    /// The schema: `IFC2X3`, `IFC4` or `IFC4X3_ADD2`.
    #[getter]
    fn schema(&self) -> &'static str {
        self.inner.schema().name()
    }

    /// Number of instances.
    fn __len__(&self) -> usize {
        self.inner.len()
    }

    /// Storeys sorted by elevation: dicts with `id`, `guid`, `name`, `elevation_m`.
    #[getter]
    fn storeys<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let v = py.detach(|| crate::inspect::storeys(&self.inner));
        convert::json(py, &serde_json::Value::Array(v))
    }

    /// Doors: dicts with `id`, `guid`, `name`, `storey`, `storey_id`, `overall_width_m`,
    /// `overall_height_m` (metres).
    #[getter]
    fn doors<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let v = py.detach(|| crate::inspect::doors(&self.inner));
        convert::json(py, &serde_json::Value::Array(v))
    }

    /// What `poinav inspect --json` prints, as a dict.
    fn inspect<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let v = py.detach(|| crate::inspect::report(&self.inner));
        convert::json(py, &v)
    }

    /// Number of instances of class `cls`, subtypes included.
    fn count(&self, cls: &str) -> usize {
        self.inner.count_of(cls)
    }

    /// Property sets (type sets merged under the occurrence's, as IfcOpenShell's
    /// `get_psets`) of every instance of class `cls` with a GlobalId: GlobalId -> set name ->
    /// property name -> value (each set also has `id`, the set's `#id`).
    #[pyo3(signature = (cls = "IfcProduct"))]
    fn psets<'py>(&self, py: Python<'py>, cls: &str) -> PyResult<Bound<'py, PyDict>> {
        crate::psets::psets(py, &self.inner, cls)
    }

    /// Element meshes in world metres (openings cut), in file order: dicts with `id`,
    /// `global_id`, `class`, `name`, `storey` (name), `storey_id`, `vertices` (n, 3)
    /// float64, `triangles` (m, 3) uint32, `color` (RGBA or None). `spaces=True` adds the
    /// spaces. Elements whose geometry failed are left out (see `mesh_failures`).
    #[pyo3(signature = (spaces = false))]
    fn meshes<'py>(&self, py: Python<'py>, spaces: bool) -> PyResult<Vec<Bound<'py, PyDict>>> {
        // Meshing in parallel without the GIL; with it, only O(1) work per element: the
        // vectors become the arrays' memory, not copied.
        let (elements, storeys) = py.detach(|| {
            let meshes = poinav_geom::mesh_model(&self.inner);
            let elements: Vec<ElementMesh> = meshes
                .elements
                .into_iter()
                .chain(spaces.then_some(meshes.spaces).into_iter().flatten())
                .collect();
            let storeys = storey_names(&self.inner, elements.iter());
            (elements, storeys)
        });
        let k = MeshKeys::new(py);
        let mut out = Vec::with_capacity(elements.len());
        let mut strings = convert::Strings::default();
        for e in &elements {
            let d = PyDict::new(py);
            d.set_item(&k.id, e.product.0)?;
            d.set_item(&k.global_id, &e.global_id)?;
            d.set_item(&k.class, strings.get(py, &e.class))?;
            d.set_item(&k.name, &e.name)?;
            let storey = e.storey.and_then(|s| storeys.get(&s)?.as_deref());
            d.set_item(&k.storey, storey.map(|n| strings.get(py, n)))?;
            d.set_item(&k.storey_id, e.storey.map(|s| s.0))?;
            d.set_item(&k.vertices, py.None())?;
            d.set_item(&k.triangles, py.None())?;
            d.set_item(&k.color, e.color)?;
            out.push(d);
        }
        drop(strings);
        // The vectors move into the arrays (the loop above borrowed the names).
        for (d, e) in out.iter().zip(elements) {
            let vertices = convert::position_rows(e.mesh.positions);
            d.set_item(&k.vertices, convert::rows(py, vertices)?)?;
            d.set_item(&k.triangles, convert::rows(py, e.mesh.triangles)?)?;
        }
        Ok(out)
    }

    /// Products whose geometry could not be made: dicts with `id` and `reason`.
    fn mesh_failures<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let meshes = py.detach(|| poinav_geom::mesh_model(&self.inner));
        let v: Vec<serde_json::Value> = meshes
            .failures
            .iter()
            .map(|(id, e)| serde_json::json!({"id": id.0, "reason": e.to_string()}))
            .collect();
        convert::json(py, &serde_json::Value::Array(v))
    }

    /// Classifies every element with the POI rules for each profile (`poinav enrich`).
    #[pyo3(signature = (profiles = Vec::new(), rules = None, pset_prefix = "Pset_".to_string()))]
    fn enrich(
        &self,
        py: Python<'_>,
        profiles: Vec<PathBuf>,
        rules: Option<PathBuf>,
        pset_prefix: String,
    ) -> PyResult<Enrichment> {
        Enrichment::new(
            py,
            self.inner.clone(),
            &profiles,
            rules.as_ref(),
            pset_prefix,
        )
    }

    /// The building's storeys as navigation floors for `profile` (`poinav route`, `audit`).
    #[pyo3(signature = (profile = None))]
    fn building(&self, py: Python<'_>, profile: Option<PathBuf>) -> PyResult<Building> {
        Building::new(py, &self.inner, profile.as_ref())
    }

    fn __repr__(&self) -> String {
        format!(
            "<poinav.Model {} ({}, {} instances)>",
            self.inner.file().display(),
            self.inner.schema().name(),
            self.inner.len()
        )
    }
}
