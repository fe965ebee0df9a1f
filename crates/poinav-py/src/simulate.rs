//! `simulate`: one run of a scenario (`poinav simulate`), its summary as a dict, the final POI
//! records the robots read and updated, and the trace as numpy columns (also `read_trace`, of a
//! trace file in either format).

use std::path::{Path, PathBuf};

use poinav_sim::Scenario;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use serde_json::Value;

use crate::convert;
use crate::error::{to_py, PoinavError};

/// The trace's columns: one row per robot per recorded step.
#[derive(Debug, Default)]
struct Columns {
    robots: Vec<String>,
    step: Vec<u64>,
    t: Vec<f64>,
    robot: Vec<u32>,
    xy: Vec<f64>,
    heading_deg: Vec<f64>,
    speed: Vec<f64>,
    omega_deg_s: Vec<f64>,
    rays: Vec<f64>,
}

fn columns(trace: &[u8]) -> Result<Columns, String> {
    let mut c = Columns::default();
    for (n, line) in trace.split(|b| *b == b'\n').enumerate() {
        c.push_line(line, n + 1)?;
    }
    Ok(c)
}

impl Columns {
    /// Adds the row of trace line `n` (1-based; an empty line adds nothing).
    fn push_line(&mut self, line: &[u8], n: usize) -> Result<(), String> {
        if line.is_empty() {
            return Ok(());
        }
        let c = self;
        let v: Value = serde_json::from_slice(line).map_err(|e| format!("trace line {n}: {e}"))?;
        let f = |k: &str| v[k].as_f64().unwrap_or(f64::NAN);
        let name = v["robot"].as_str().unwrap_or_default();
        let r = match c.robots.iter().position(|x| x == name) {
            Some(r) => r,
            None => {
                c.robots.push(name.to_string());
                c.robots.len() - 1
            }
        };
        c.step.push(v["step"].as_u64().unwrap_or_default());
        c.t.push(f("t"));
        c.robot.push(r as u32);
        c.xy.extend([f("x"), f("y")]);
        c.heading_deg.push(f("heading_deg"));
        c.speed.push(f("speed"));
        c.omega_deg_s.push(f("omega_deg_s"));
        let rays = v["rays"].as_array().cloned().unwrap_or_default();
        for k in 0..5 {
            c.rays.push(
                rays.get(k)
                    .and_then(|r| r["d"].as_f64())
                    .unwrap_or(f64::NAN),
            );
        }
        Ok(())
    }

    /// The columns as the dict `simulate` and `read_trace` return.
    fn into_dict(self, py: Python<'_>) -> PyResult<Bound<'_, PyDict>> {
        let t = PyDict::new(py);
        t.set_item("robots", self.robots)?;
        t.set_item("step", numpy::PyArray1::from_vec(py, self.step))?;
        t.set_item("t", numpy::PyArray1::from_vec(py, self.t))?;
        t.set_item("robot", numpy::PyArray1::from_vec(py, self.robot))?;
        t.set_item("xy", convert::array2(py, self.xy, 2)?)?;
        t.set_item(
            "heading_deg",
            numpy::PyArray1::from_vec(py, self.heading_deg),
        )?;
        t.set_item("speed", numpy::PyArray1::from_vec(py, self.speed))?;
        t.set_item(
            "omega_deg_s",
            numpy::PyArray1::from_vec(py, self.omega_deg_s),
        )?;
        t.set_item("ray_m", convert::array2(py, self.rays, 5)?)?;
        Ok(t)
    }
}

/// Reads a trace file `poinav simulate` wrote, `trace.jsonl` or the compact `trace.bin`
/// (`--trace-format bin`), into the numpy columns `simulate` returns as `trace`.
#[pyfunction]
pub fn read_trace<'py>(py: Python<'py>, path: PathBuf) -> PyResult<Bound<'py, PyDict>> {
    let cols = py.detach(|| -> PyResult<Columns> {
        let mut c = Columns::default();
        let lines = poinav_sim::trace_bin::read_file(&path).map_err(to_py)?;
        for (n, line) in lines.enumerate() {
            let line = line.map_err(to_py)?;
            c.push_line(line.as_bytes(), n + 1)
                .map_err(|e| PoinavError::new_err(format!("{}: {e}", path.display())))?;
        }
        Ok(c)
    })?;
    cols.into_dict(py)
}

/// Runs `variant` of the scenario (a file, or TOML text with `text=True`; relative paths are
/// resolved from `base`, default the current folder). Returns a dict: `summary` (as
/// summary.json), `pass`, `poi` (the POI records at the end), `trace` (numpy columns, when
/// `trace`), and `outputs` (files written into `output`, when given). With `stream` (and
/// `output`) the trace is not kept: it goes to `output/trace.jsonl` as the steps are taken
/// (`poinav simulate`'s way; memory does not grow with the run), named by `trace_path`.
#[pyfunction]
#[pyo3(signature = (scenario, variant = None, text = false, base = None, output = None, trace = true, stream = false))]
#[allow(clippy::too_many_arguments)]
pub fn simulate<'py>(
    py: Python<'py>,
    scenario: String,
    variant: Option<String>,
    text: bool,
    base: Option<PathBuf>,
    output: Option<PathBuf>,
    trace: bool,
    stream: bool,
) -> PyResult<Bound<'py, PyDict>> {
    if stream && output.is_none() {
        return Err(PoinavError::new_err(
            "stream=True writes the trace into `output`: pass output=",
        ));
    }
    let scenario = if text {
        let dir = base.unwrap_or_else(|| PathBuf::from("."));
        Scenario::from_toml(&scenario, "<scenario>", &dir)
    } else {
        Scenario::load(Path::new(&scenario))
    }
    .map_err(to_py)?;
    let names = scenario.variant_names();
    if variant.is_none() && !names.is_empty() {
        return Err(PoinavError::new_err(format!(
            "scenario `{}` has variants {}: pass variant=",
            scenario.name,
            names.join(", ")
        )));
    }
    let (outcome, cols, written) = py.detach(|| -> PyResult<_> {
        let building = poinav_bridge::prepare(&scenario, variant.as_deref()).map_err(to_py)?;
        let (outcome, written) = match &output {
            Some(dir) if stream => {
                let every = trace.then_some(1);
                poinav_sim::run_into(dir, &scenario, variant.as_deref(), building.floor(), every)
                    .map_err(to_py)?
            }
            _ => {
                let outcome = if trace {
                    poinav_sim::run(&scenario, variant.as_deref(), building.floor())
                } else {
                    poinav_sim::run_with(&scenario, variant.as_deref(), building.floor(), None)
                }
                .map_err(to_py)?;
                let written = match &output {
                    Some(dir) => {
                        poinav_sim::write_outputs(dir, &outcome, building.floor()).map_err(to_py)?
                    }
                    None => Vec::new(),
                };
                (outcome, written)
            }
        };
        let cols = match &outcome.trace {
            Some(t) => Some(columns(t).map_err(PoinavError::new_err)?),
            None => None,
        };
        Ok((outcome, cols, written))
    })?;
    let d = PyDict::new(py);
    d.set_item("summary", convert::json(py, &outcome.summary())?)?;
    d.set_item("pass", outcome.passed())?;
    let poi: Vec<Value> = outcome
        .data
        .db
        .records()
        .iter()
        .map(|e| {
            serde_json::json!({
                "global_id": e.global_id,
                "class": e.class,
                "name": e.name,
                "primary_roles": e.primary.iter().map(|r| r.label()).collect::<Vec<_>>(),
                "conditional_roles": e.conditional.iter().map(|r| r.label()).collect::<Vec<_>>(),
                "status": e.accessibility.as_ref().map(|a| a.status.label()),
                "method": e.accessibility.as_ref().map(|a| a.method.label()),
            })
        })
        .collect();
    d.set_item("poi", convert::json(py, &Value::Array(poi))?)?;
    if let Some(c) = cols {
        d.set_item("trace", c.into_dict(py)?)?;
    }
    if let (true, true, Some(dir)) = (stream, trace, &output) {
        let path = dir.join(poinav_sim::output::TRACE);
        d.set_item("trace_path", path.display().to_string())?;
    }
    let outputs: Vec<String> = written.iter().map(|p| p.display().to_string()).collect();
    d.set_item("outputs", outputs)?;
    Ok(d)
}
