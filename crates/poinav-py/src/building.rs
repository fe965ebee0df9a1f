//! `Building`: a model's storeys as navigation floors for one robot profile (what `poinav
//! route`, `audit` and `export nav2` start from): occupancy grids as numpy arrays, routes and
//! the accessibility audit as dicts.

use std::path::PathBuf;

use poinav_nav::{
    AuditOptions, FurnitureMode, GridOptions, NavError, NavGrid, NavOptions, NoPlace, Place,
};
use poinav_poi::{classify, RobotProfile, RuleSet};
use pyo3::prelude::*;
use serde_json::json;

use crate::convert;
use crate::error::{to_py, NoRouteError, PoinavError};
use crate::navigators::Navigators;

/// A building prepared for navigation.
#[pyclass(frozen, module = "poinav._native")]
#[derive(Debug)]
pub struct Building {
    inner: poinav_nav::Building,
    profile: RobotProfile,
    warnings: Vec<String>,
    meshed: usize,
    /// Prepared navigators: routes after the first rasterise nothing.
    navigators: Navigators,
}

impl Building {
    /// Classifies `model` for `profile` with the default rules, meshes it, cuts the storeys'
    /// floor plans and builds the floors and vertical connections, as the CLI does.
    pub fn new(
        py: Python<'_>,
        model: &poinav_ifc::Model,
        profile: Option<&PathBuf>,
    ) -> PyResult<Building> {
        let profile = crate::profile::profile(profile)?;
        let (inner, warnings, meshed) = py.detach(|| {
            let c = classify(model, &RuleSet::defaults(), &profile);
            let stages = poinav_bridge::Stages::of(model);
            let made = poinav_bridge::building(model, &c, &stages);
            let mut warnings: Vec<String> = made.dropped.iter().map(|d| d.message()).collect();
            let building = made.building;
            let meshes = stages.meshes;
            warnings.extend(building.diagnostics());
            (
                building,
                warnings,
                meshes.elements.len() + meshes.spaces.len(),
            )
        });
        Ok(Building {
            inner,
            profile,
            warnings,
            meshed,
            navigators: Navigators::default(),
        })
    }

    fn floor(&self, storey: &Bound<'_, PyAny>) -> PyResult<usize> {
        if let Ok(i) = storey.extract::<usize>() {
            return (i < self.inner.floors.len()).then_some(i).ok_or_else(|| {
                PoinavError::new_err(format!(
                    "no storey {i}: the building has {}",
                    self.inner.floors.len()
                ))
            });
        }
        let name: String = storey.extract()?;
        self.inner.floor_index(&name).ok_or_else(|| {
            let names: Vec<&str> = self.inner.floors.iter().map(|f| f.name.as_str()).collect();
            PoinavError::new_err(format!(
                "no storey named `{name}`; storeys: {}",
                names.join(", ")
            ))
        })
    }
}

fn nav_options(resolution: f64, furniture: &str, pending_closed: bool) -> PyResult<NavOptions> {
    if !(resolution.is_finite() && (0.005..=1.0).contains(&resolution)) {
        return Err(PoinavError::new_err(format!(
            "resolution must be between 0.005 and 1 m, not {resolution}"
        )));
    }
    let furniture = match furniture {
        "obstacle" => FurnitureMode::Obstacle,
        "unknown" => FurnitureMode::Unknown,
        other => {
            return Err(PoinavError::new_err(format!(
                "furniture must be `obstacle` or `unknown`, not `{other}`"
            )))
        }
    };
    Ok(NavOptions {
        grid: GridOptions {
            resolution_m: resolution,
            furniture,
            pending_doors_open: !pending_closed,
            ..GridOptions::default()
        },
        ..NavOptions::default()
    })
}

fn route_error(e: NavError) -> PyErr {
    match e {
        NavError::Unreachable(_) | NavError::NoRoom(_) => NoRouteError::new_err(e.to_string()),
        e => to_py(e),
    }
}

/// A storey's occupancy grid for a robot profile: `cells` (height, width) uint8, 0 free,
/// 1 occupied, 2 unknown, row 0 the lowest y; cell (row, col) starts at
/// `origin + (col, row) * resolution`; `clearance_m` (float32, same shape): each cell's
/// distance to the nearest occupied cell, metres. `numpy.asarray(grid)` is `cells`.
#[pyclass(frozen, get_all, module = "poinav._native")]
#[derive(Debug)]
pub struct Grid {
    /// The storey's name.
    storey: String,
    /// Cell states.
    cells: Py<PyAny>,
    /// Distance to the nearest occupied cell.
    clearance_m: Py<PyAny>,
    /// Cell size, metres.
    resolution: f64,
    /// World x, y of cell (0, 0)'s lower-left corner.
    origin: (f64, f64),
}

#[pymethods]
impl Grid {
    /// Free cells.
    #[classattr]
    const FREE: u8 = 0;
    /// Occupied cells.
    #[classattr]
    const OCCUPIED: u8 = 1;
    /// Unknown cells.
    #[classattr]
    const UNKNOWN: u8 = 2;

    /// (height, width).
    #[getter]
    fn shape<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        self.cells.bind(py).getattr("shape")
    }

    #[pyo3(signature = (dtype = None, copy = None))]
    fn __array__<'py>(
        &self,
        py: Python<'py>,
        dtype: Option<Bound<'py, PyAny>>,
        copy: Option<bool>,
    ) -> PyResult<Bound<'py, PyAny>> {
        let cells = self.cells.bind(py).clone();
        let _ = copy;
        match dtype {
            Some(d) => cells.call_method1("astype", (d,)),
            None => Ok(cells),
        }
    }

    fn __repr__(&self, py: Python<'_>) -> String {
        let shape = self
            .cells
            .bind(py)
            .getattr("shape")
            .map(|s| s.to_string())
            .unwrap_or_default();
        format!(
            "<poinav.Grid {} {shape} cells of {} m>",
            self.storey, self.resolution
        )
    }
}

#[pymethods]
impl Building {
    /// The profile's name.
    #[getter]
    fn profile(&self) -> String {
        self.profile.name.clone()
    }

    /// Storeys: dicts with `name`, `elevation_m`, and how many `zones` (spaces), `doors` and
    /// `obstacles` each has.
    #[getter]
    fn storeys<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let v: Vec<serde_json::Value> = self
            .inner
            .floors
            .iter()
            .map(|f| {
                json!({
                    "name": f.name,
                    "elevation_m": f.elevation_m,
                    "zones": f.zones.len(),
                    "doors": f.doors.len(),
                    "obstacles": f.obstacles.len(),
                })
            })
            .collect();
        convert::json(py, &serde_json::Value::Array(v))
    }

    /// Stairs, ramps and lifts between storeys, as dicts.
    #[getter]
    fn connections<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        convert::to_python(py, &self.inner.connections)
    }

    /// What limits navigation (connections left out, storeys without spaces, ...).
    #[getter]
    fn warnings(&self) -> Vec<String> {
        self.warnings.clone()
    }

    /// Elements and spaces meshed (0: the model gave no geometry at all).
    #[getter]
    fn meshed(&self) -> usize {
        self.meshed
    }

    /// How many times the storeys were rasterised for routes: once per set of options
    /// (`resolution`, `furniture`, `pending_closed`), the last four kept; later routes and
    /// grids with the same options reuse them.
    #[getter]
    fn navigators_built(&self) -> usize {
        self.navigators.built()
    }

    /// The occupancy grid of `storey` (its name or index) for the profile (see `Grid`).
    #[pyo3(signature = (storey, resolution = 0.05, furniture = "obstacle", pending_closed = false))]
    fn grid<'py>(
        &self,
        py: Python<'py>,
        storey: &Bound<'py, PyAny>,
        resolution: f64,
        furniture: &str,
        pending_closed: bool,
    ) -> PyResult<Grid> {
        let fi = self.floor(storey)?;
        let options = nav_options(resolution, furniture, pending_closed)?;
        let grid = py
            .detach(|| {
                // A route with these options made this grid already.
                let kept = self
                    .navigators
                    .with_kept(&self.inner, &options, |nav| nav.floors[fi].grid.clone());
                match kept {
                    Some(grid) => Ok(grid),
                    None => {
                        let g = GridOptions {
                            at_ground: self.inner.at_ground(fi),
                            ..options.grid.clone()
                        };
                        NavGrid::build(
                            &self.inner.floors[fi],
                            &self.profile,
                            &g,
                            &options.inflation,
                        )
                    }
                }
            })
            .map_err(to_py)?;
        let o = &grid.occupancy;
        let cells: Vec<u8> = o.cells.iter().map(|c| *c as u8).collect();
        let width = o.width.max(1);
        Ok(Grid {
            storey: self.inner.floors[fi].name.clone(),
            cells: convert::array2(py, cells, width)?.unbind(),
            resolution: o.resolution_m,
            origin: (o.origin.x, o.origin.y),
            clearance_m: convert::array2(py, grid.clearance_m, width)?.unbind(),
        })
    }

    /// A route from `a` to `b` (a space's GlobalId, Name or LongName, `Name@Storey`, a point
    /// `x,y@Storey`, or `outside`), as `poinav route --json` prints it. Raises
    /// `NoRouteError` when there is none.
    #[pyo3(signature = (a, b, resolution = 0.05, furniture = "obstacle", pending_closed = false))]
    fn route<'py>(
        &self,
        py: Python<'py>,
        a: &str,
        b: &str,
        resolution: f64,
        furniture: &str,
        pending_closed: bool,
    ) -> PyResult<Bound<'py, PyAny>> {
        let options = nav_options(resolution, furniture, pending_closed)?;
        let from: Place = a
            .parse()
            .map_err(|e: NoPlace| PoinavError::new_err(e.to_string()))?;
        let to: Place = b
            .parse()
            .map_err(|e: NoPlace| PoinavError::new_err(e.to_string()))?;
        let route = py.detach(|| {
            self.navigators
                .with(&self.inner, &self.profile, &options, |nav| {
                    nav.route(&from, &to)
                })
                .and_then(|r| r)
        });
        let mut v = serde_json::to_value(route.map_err(route_error)?).map_err(to_py)?;
        v["warnings"] = json!(self.warnings);
        convert::json(py, &v)
    }

    /// The accessibility audit for `profiles` (default: the building's profile), as
    /// `poinav audit --json` prints it; `start` a space to measure reachability from.
    #[pyo3(signature = (profiles = Vec::new(), start = None, resolution = 0.05, furniture = "obstacle", pending_closed = false))]
    fn audit<'py>(
        &self,
        py: Python<'py>,
        profiles: Vec<PathBuf>,
        start: Option<String>,
        resolution: f64,
        furniture: &str,
        pending_closed: bool,
    ) -> PyResult<Bound<'py, PyAny>> {
        let nav = nav_options(resolution, furniture, pending_closed)?;
        let profiles = if profiles.is_empty() {
            vec![self.profile.clone()]
        } else {
            crate::profile::profiles(&profiles)?
        };
        let mut report = py
            .detach(|| poinav_nav::audit(&self.inner, &profiles, &AuditOptions { nav, start }))
            .map_err(to_py)?;
        let dropped: Vec<String> = self
            .warnings
            .iter()
            .filter(|w| !report.warnings.contains(w))
            .cloned()
            .collect();
        report.warnings.splice(0..0, dropped);
        convert::json(py, &report.to_json())
    }

    fn __repr__(&self) -> String {
        format!(
            "<poinav.Building {} storeys for {}>",
            self.inner.floors.len(),
            self.profile.name
        )
    }
}
