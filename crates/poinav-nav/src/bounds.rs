//! Size bounds on rasterising and the door/zone graph, and what was given up on when an element
//! passed one ([`GaveUp`]): its area is left unknown, never free, and it is named, as meshing
//! (`poinav_geom::PRODUCT_TIME_LIMIT`) and sectioning (`SectionBounds`) do. The bounds count
//! work, not time, so the same input gives the same grid on any machine.

use glam::DVec2;
use serde::Serialize;

use crate::floor::Floor;
use crate::graph::SIDE_PROBE_M;
use crate::polygon;
use poinav_floor::ElementId;

/// Most vertices one element's rings may have together (100,000). Sectioning keeps a product
/// to 200,000 mesh edges, and the outline of a real wall, slab, space or door has tens to a
/// few thousand vertices; an element with more is a tessellation artefact, and everything that
/// reads rings afterwards (filling, distances in messages, door frames) is linear in them.
pub const ELEMENT_VERTICES: usize = 100_000;

/// Most edge-row tests filling one element may take (200,000,000): per ring, its vertices
/// times the grid rows its bounding box spans, summed, the cost of the even-odd scanline fill (every edge is
/// tested on every row). Measured in a release build on the shared 2-core machine: 100,000
/// vertices over 2,020 rows (2.0e8 tests) fill in 0.82 s, against 0.04 s for a 1,000-vertex
/// outline over the same rows (2,000,000 tests, a real element across a 100 m storey at 5 cm).
pub const RASTER_WORK: u64 = 200_000_000;

/// Most zone vertices a door's side search may test (100,000): the zones whose bounding boxes
/// come within reach of the door's probes ([`SIDE_PROBE_M`]); each probe tests every vertex of
/// those zones, about 120 probes a door, so at most about 12,000,000 point-edge tests a door.
pub const DOOR_SIDE_VERTICES: usize = 100_000;

/// Most cells the search through one door's passage (whether a robot's centre can cross it,
/// the exact clearance in it) may visit (1,000,000): a door 50 m by 50 m at 5 cm cells, far
/// beyond any real door, so it is only reached by broken geometry.
pub const DOOR_CELLS: usize = 1_000_000;

/// The bounds used ([`crate::GridOptions::bounds`]); the defaults are the constants above.
/// Tests lower them to reach them with small floors.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct StageBounds {
    /// [`ELEMENT_VERTICES`].
    pub element_vertices: usize,
    /// [`RASTER_WORK`].
    pub raster_work: u64,
    /// [`DOOR_SIDE_VERTICES`].
    pub door_side_vertices: usize,
    /// [`DOOR_CELLS`].
    pub door_cells: usize,
}

impl Default for StageBounds {
    fn default() -> Self {
        StageBounds {
            element_vertices: ELEMENT_VERTICES,
            raster_work: RASTER_WORK,
            door_side_vertices: DOOR_SIDE_VERTICES,
            door_cells: DOOR_CELLS,
        }
    }
}

/// Which stage gave up.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Stage {
    /// Filling the element's polygon into the occupancy grid.
    Raster,
    /// Deciding a door's sides or searching its passage.
    Graph,
}

impl Stage {
    /// `raster` or `graph`.
    pub fn label(self) -> &'static str {
        match self {
            Stage::Raster => "raster",
            Stage::Graph => "graph",
        }
    }
}

/// An element a stage gave up on, and what was done instead.
#[derive(Debug, Clone, PartialEq, Eq, PartialOrd, Ord, Serialize)]
pub struct GaveUp {
    /// Storey name.
    pub floor: String,
    /// GlobalId.
    pub element: ElementId,
    /// IFC class (`IfcSpace` for zones, `IfcDoor` or `IfcOpeningElement` for doors).
    pub class: String,
    /// The stage.
    pub stage: Stage,
    /// The bound passed, with the amount: `vertices: 150000 > 100000`.
    pub bound: String,
    /// What the grid or graph did instead: `its bounding box is unknown`.
    pub outcome: String,
}

impl GaveUp {
    /// The message for warnings: `storey Level 1: IfcWall 2Ab..: raster bound passed (vertices:
    /// 150000 > 100000): its bounding box is unknown`.
    pub fn message(&self) -> String {
        format!(
            "storey {}: {} {}: {} bound passed ({}): {}",
            self.floor,
            self.class,
            self.element,
            self.stage.label(),
            self.bound,
            self.outcome
        )
    }

    /// What such warnings are grouped by: the message without the storey, element and amounts.
    pub fn reason(&self) -> String {
        let kind = self.bound.split(':').next().unwrap_or_default();
        format!(
            "{} bound passed ({kind}): {}",
            self.stage.label(),
            self.outcome
        )
    }
}

/// The class doors are reported with.
pub fn door_class(floor: &Floor, k: usize) -> &'static str {
    if floor.doors[k].doorless {
        "IfcOpeningElement"
    } else {
        "IfcDoor"
    }
}

/// Which bound filling an element passes, if any (`vertices: N > M` or `raster work: N > M`),
/// given its rings' vertices and `work`, the sum over its rings of each ring's vertices times
/// the grid rows its bounding box spans.
pub fn raster_bound(vertices: usize, work: u64, bounds: &StageBounds) -> Option<String> {
    if vertices > bounds.element_vertices {
        return Some(format!(
            "vertices: {vertices} > {}",
            bounds.element_vertices
        ));
    }
    (work > bounds.raster_work).then(|| format!("raster work: {work} > {}", bounds.raster_work))
}

/// Per door of `floor`: the bound its side search would pass (`zone vertices near: N > M`),
/// if any. Counts the vertices of every zone whose bounding box comes within reach of the
/// door's probes: the door ring's box grown by [`SIDE_PROBE_M`] and the probes' extra 0.25 m.
/// Linear in the zones' vertices once, then in zones per door.
pub fn door_side_bounds(floor: &Floor, bounds: &StageBounds) -> Vec<Option<String>> {
    let boxes: Vec<Option<(DVec2, DVec2, usize)>> = floor
        .zones
        .iter()
        .map(|z| polygon::bounds(&z.ring).map(|(lo, hi)| (lo, hi, z.ring.len())))
        .collect();
    let reach = DVec2::splat(SIDE_PROBE_M + 0.25);
    floor
        .doors
        .iter()
        .map(|d| {
            let (lo, hi) = polygon::bounds(&d.ring).unwrap_or((d.center, d.center));
            // The frame may be either orientation of the ring: its box covers both.
            let half = (hi - lo).length() / 2.0;
            let mid = (lo + hi) / 2.0;
            let (lo, hi) = (
                mid - DVec2::splat(half) - reach,
                mid + DVec2::splat(half) + reach,
            );
            let near: usize = boxes
                .iter()
                .flatten()
                .filter(|(zlo, zhi, _)| {
                    zlo.x <= hi.x && zlo.y <= hi.y && zhi.x >= lo.x && zhi.y >= lo.y
                })
                .map(|(_, _, n)| n)
                .sum();
            (near > bounds.door_side_vertices)
                .then(|| format!("zone vertices near: {near} > {}", bounds.door_side_vertices))
        })
        .collect()
}
