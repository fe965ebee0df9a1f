//! `Enrichment`: a model classified with the POI rules for one or more robot profiles
//! (`poinav enrich`), its summary, its semantic table and writing the enriched IFC, CSV and
//! IDS. The first profile is the one written.

use std::collections::BTreeMap;
use std::path::PathBuf;
use std::sync::Arc;

use poinav_poi::{classify, AccessibilityStatus, Classification, Classified, Role, WriteOptions};
use pyo3::prelude::*;
use pyo3::types::PyBytes;
use serde_json::{json, Value};

use crate::convert;
use crate::error::to_py;

/// A model classified for robot profiles.
#[pyclass(frozen, module = "poinav._native")]
#[derive(Debug)]
pub struct Enrichment {
    model: Arc<poinav_ifc::Model>,
    classifications: Vec<Classification>,
    options: WriteOptions,
}

impl Enrichment {
    pub fn new(
        py: Python<'_>,
        model: Arc<poinav_ifc::Model>,
        profiles: &[PathBuf],
        rules: Option<&PathBuf>,
        pset_prefix: String,
    ) -> PyResult<Enrichment> {
        let rules = crate::profile::rules(rules)?;
        let profiles = crate::profile::profiles(profiles)?;
        let classifications = py.detach(|| {
            profiles
                .iter()
                .map(|p| classify(&model, &rules, p))
                .collect::<Vec<_>>()
        });
        let timestamp = poinav_poi::iso8601_utc(poinav_poi::now_or_source_date_epoch());
        Ok(Enrichment {
            model,
            classifications,
            options: WriteOptions {
                prefix: pset_prefix,
                timestamp,
            },
        })
    }

    fn metres(&self) -> f64 {
        poinav_ifc::units::length_unit(&self.model).metres_per_unit
    }

    fn summary_json(&self) -> Value {
        let primary = &self.classifications[0];
        let mut rules: BTreeMap<&str, usize> = BTreeMap::new();
        let mut categories: BTreeMap<&str, usize> = BTreeMap::new();
        let mut roles: BTreeMap<&str, usize> = BTreeMap::new();
        let mut conditional: BTreeMap<&str, usize> = BTreeMap::new();
        let mut corridors = Vec::new();
        for e in &primary.elements {
            *rules.entry(&e.rule).or_default() += 1;
            *categories.entry(e.category.label()).or_default() += 1;
            for r in &e.primary {
                *roles.entry(r.label()).or_default() += 1;
            }
            for r in &e.conditional {
                *conditional.entry(r.label()).or_default() += 1;
            }
            if e.primary.contains(&Role::MultiRobotZone) {
                corridors.push(json!({
                    "guid": e.global_id,
                    "name": e.name,
                    "long_name": self.model.entity(e.id).and_then(|s| s.get_str("LongName")),
                    "rule": e.rule,
                }));
            }
        }
        let profiles: Vec<Value> = self
            .classifications
            .iter()
            .map(|c| {
                json!({
                    "name": c.profile.name,
                    "min_clearance_width_m": c.profile.min_clearance_width(),
                    "doors": statuses(c, |e| e.class == "IfcDoor"),
                    "transitions": statuses(c, |e| e.poi_type == poinav_poi::PoiType::TransitionElement),
                    "spaces": statuses(c, |e| e.class == "IfcSpace"),
                })
            })
            .collect();
        json!({
            "schema": self.model.schema().name(),
            "length_unit_m": self.metres(),
            "timestamp": self.options.timestamp,
            "pset_prefix": self.options.prefix,
            "elements": primary.elements.len(),
            "rules": rules,
            "categories": categories,
            "roles": roles,
            "conditional_roles": conditional,
            "corridors": corridors,
            "profiles": profiles,
        })
    }
}

/// Per AccessibilityStatus, how many elements `filter` keeps have it (as the CLI counts).
fn statuses(
    c: &Classification,
    filter: impl Fn(&Classified) -> bool,
) -> BTreeMap<&'static str, usize> {
    let mut m: BTreeMap<&'static str, usize> = AccessibilityStatus::ALL
        .iter()
        .map(|s| (s.label(), 0))
        .collect();
    for e in c.elements.iter().filter(|e| filter(e)) {
        if let Some(a) = &e.accessibility {
            *m.entry(a.status.label()).or_default() += 1;
        }
    }
    m
}

#[pymethods]
impl Enrichment {
    /// What `poinav enrich --json` prints (without the file names and `instances_added`,
    /// which `write` returns): counts per rule, category, role, corridors, and per profile the
    /// doors', transitions' and spaces' AccessibilityStatus counts.
    #[getter]
    fn summary<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        convert::json(py, &self.summary_json())
    }

    /// Names of the profiles, in order (the first is the one written).
    #[getter]
    fn profiles(&self) -> Vec<String> {
        self.classifications
            .iter()
            .map(|c| c.profile.name.clone())
            .collect()
    }

    /// The semantic CSV of the first profile (what `poinav enrich --csv` writes), as bytes.
    fn csv_bytes<'py>(&self, py: Python<'py>) -> Bound<'py, PyBytes> {
        let bytes = poinav_export::semantic_csv::to_csv(
            &self.classifications[0],
            self.metres(),
            &self.options.timestamp,
        );
        PyBytes::new(py, &bytes)
    }

    /// The semantic table (one row per classified element, the CSV's columns) as a pandas
    /// DataFrame; pandas is imported only here.
    fn to_dataframe<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let pandas = py.import("pandas").map_err(|e| {
            pyo3::exceptions::PyImportError::new_err(format!(
                "Enrichment.to_dataframe() needs pandas (pip install pandas): {e}"
            ))
        })?;
        let buffer = py
            .import("io")?
            .call_method1("BytesIO", (self.csv_bytes(py),))?;
        let kwargs = pyo3::types::PyDict::new(py);
        kwargs.set_item("keep_default_na", false)?;
        kwargs.set_item("na_values", vec![""])?;
        pandas.call_method("read_csv", (buffer,), Some(&kwargs))
    }

    /// Writes the enriched IFC to `path` (atomically; never the input file), and the semantic
    /// CSV and the IDS when asked. Returns the summary with `output` and `instances_added`.
    #[pyo3(signature = (path, csv = None, ids = None))]
    fn write<'py>(
        &self,
        py: Python<'py>,
        path: PathBuf,
        csv: Option<PathBuf>,
        ids: Option<PathBuf>,
    ) -> PyResult<Bound<'py, PyAny>> {
        let primary = &self.classifications[0];
        let added = py.detach(|| -> PyResult<usize> {
            let editor =
                poinav_poi::write_enrichment(&self.model, primary, &self.options).map_err(to_py)?;
            editor.write(&path).map_err(to_py)?;
            if let Some(csv) = &csv {
                poinav_export::semantic_csv::write_csv(
                    csv,
                    primary,
                    self.metres(),
                    &self.options.timestamp,
                )
                .map_err(to_py)?;
            }
            if let Some(ids) = &ids {
                poinav_export::ids::write_ids(ids, &self.model, primary, &self.options)
                    .map_err(to_py)?;
            }
            Ok(editor.added_count())
        })?;
        let mut summary = self.summary_json();
        summary["output"] = json!(path.display().to_string());
        summary["instances_added"] = json!(added);
        convert::json(py, &summary)
    }

    fn __repr__(&self) -> String {
        format!(
            "<poinav.Enrichment {} elements, profiles {:?}>",
            self.classifications[0].elements.len(),
            self.profiles()
        )
    }
}
