//! Occupancy grids of one storey: exact polygon fill of the floor's rings at a fixed
//! resolution, doors carved open or closed by their AccessibilityStatus for a profile, free
//! space inside the building and unknown outside it (but for a free apron in front of each open
//! entrance, [`GridOptions::entrance_apron_m`]), and inflation by an exact Euclidean
//! distance transform into a grid a robot's centre can plan on ([`NavGrid`]).
//!
//! Cell `(col, row)` covers `origin + [col, col + 1) x [row, row + 1)` cells of `resolution_m`;
//! row 0 is the lowest y. A cell belongs to a polygon when its centre is inside it (even-odd
//! rule), so axis-aligned edges on cell boundaries are rasterised without error; an obstacle's
//! parts thinner than a cell, which may hold no centre, also occupy every cell their boundary
//! touches ([`crate::thin_cells`]), so no route crosses a glass panel or a fence.

use std::time::Instant;

use glam::DVec2;
use poinav_roles::{AccessibilityStatus, RobotProfile};
use serde::Serialize;

use crate::bounds::{self, GaveUp, Stage, StageBounds};
use crate::building::passable;
use crate::door_frame::DoorFrame;
use crate::door_status::{door_status, door_verdict};
use crate::floor::{Floor, ObstacleKind};
use crate::polygon::{self, PassageFrame};
use crate::thin_cells::{lines_doors, ThinCells};
use crate::zone_index::ZoneIndex;
use crate::NavError;
use crate::Ring;
use poinav_floor::{DoorIdx, ZoneIdx};

/// What a cell is.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize)]
#[serde(rename_all = "kebab-case")]
#[repr(u8)]
pub enum CellState {
    /// Inside the building, nothing there.
    Free = 0,
    /// An obstacle (walls, closed doors, furniture by option, stairs).
    Occupied = 1,
    /// Outside the building, furniture by option, or an element only bounded
    /// ([`ObstacleKind::Unknown`]).
    Unknown = 2,
}

/// How furniture and equipment (A-1 objects, [`ObstacleKind::Furniture`]) enter the grid.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum FurnitureMode {
    /// Occupied: planned around with the profile's clearance.
    #[default]
    Obstacle,
    /// Unknown: left to the robot's sensors (not inflated, not entered).
    Unknown,
}

/// How a storey is rasterised.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct GridOptions {
    /// Cell size in metres (default 0.05).
    pub resolution_m: f64,
    /// Unknown border around the floor's bounds, metres (default 0.5).
    pub padding_m: f64,
    /// Furniture as obstacle or unknown.
    pub furniture: FurnitureMode,
    /// Doors whose status is PENDING_VALIDATION are open (default) or closed.
    pub pending_doors_open: bool,
    /// Doors are open or closed by their status for the profile (default); `false` opens
    /// every door, so only geometry and inflation decide what the robot can pass.
    pub doors_by_status: bool,
    /// Cells enclosed by walls and doors but in no zone are free (default); otherwise only
    /// zones and open doors are free.
    pub fill_enclosed: bool,
    /// Depth in metres of the entrance apron: the unknown cells outside an open exterior door
    /// (a door with a zone on one side only), as wide as its passage and this deep, are free,
    /// so robots can plan to and from the entrance (default 1.0; 0 leaves the outside wholly
    /// unknown). An open door joining no zone (models without spaces) gets one on both sides.
    /// The rest of the outside stays unknown.
    pub entrance_apron_m: f64,
    /// The storey is at ground level (default), so a door with a zone on one side only may be
    /// an entrance and gets an apron; `false` (set per storey by [`crate::Navigator`] from
    /// [`crate::Building::at_ground`]): such a door leads onto a balcony or a drop and gets
    /// none, unless it opens onto the terrain ([`crate::FloorDoor::terrain`]).
    pub at_ground: bool,
    /// Size bounds per element ([`StageBounds`]; the defaults are [`crate::bounds`]'s).
    pub bounds: StageBounds,
    /// How far beyond a storey's own extent (its spaces, doors and walls) and its entrance
    /// aprons a [`crate::Navigator`] keeps obstacles when it rasterises the storey, metres
    /// (default 1.0; [`crate::extent::for_grid`]). [`OccupancyGrid::build`] itself draws the
    /// floor it is given whole.
    pub crop_margin_m: f64,
}

impl Default for GridOptions {
    fn default() -> Self {
        GridOptions {
            resolution_m: 0.05,
            padding_m: 0.5,
            furniture: FurnitureMode::Obstacle,
            pending_doors_open: true,
            doors_by_status: true,
            fill_enclosed: true,
            entrance_apron_m: 1.0,
            at_ground: true,
            bounds: StageBounds::default(),
            crop_margin_m: 1.0,
        }
    }
}

/// Most cells of one storey's grid (400,000,000: 1.6 GB of cell states, zone and door
/// indices and clearances at 5 cm is a 1 km square). Inflation, the enclosed fill and the
/// open-boundary scan are linear in cells, so this bounds them too.
pub const MAX_CELLS: usize = 400_000_000;

/// The bound door `d` passes, if any: its side search ([`bounds::door_side_bounds`], given
/// as `sides`), filling its ring, or the cells of the search through its passage (a square
/// around its frame's centre as wide as its diagonal and the reach either side, see
/// [`NavGrid::door_passable`] and the exact clearance through it).
fn door_bound(
    d: &crate::floor::FloorDoor,
    sides: &Option<String>,
    rows: &dyn Fn((DVec2, DVec2)) -> usize,
    limits: &StageBounds,
    res: f64,
) -> Option<(Stage, String)> {
    if let Some(b) = sides {
        return Some((Stage::Graph, b.clone()));
    }
    let bbox = polygon::bounds(&d.ring)?;
    let work = d.ring.len() as u64 * rows(bbox) as u64;
    if let Some(b) = bounds::raster_bound(d.ring.len(), work, limits) {
        return Some((Stage::Raster, b));
    }
    let diag = (bbox.1 - bbox.0).length();
    let side = (diag + 2.0 * (PASSAGE_REACH_M + 3.0 * res)) / res + 3.0;
    let cells = side * side;
    (cells > limits.door_cells as f64).then(|| {
        (
            Stage::Graph,
            format!("passage cells: {} > {}", cells as u64, limits.door_cells),
        )
    })
}

/// One door as the grid saw it.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct GridDoor {
    /// Status for the grid's profile.
    pub status: AccessibilityStatus,
    /// Why.
    pub reason: String,
    /// Carved open (free) or closed (occupied).
    pub open: bool,
    /// The passage's frame (`None` when the door has no usable ring).
    #[serde(skip)]
    pub frame: Option<PassageFrame>,
    /// Half the width of the passage carved for it (the clear width when the lining narrows
    /// the ring), metres; `None` without a frame.
    #[serde(skip)]
    pub passage_half_width_m: Option<f64>,
    /// A door with a zone on one side whose other side is walled in: the cell just beyond its
    /// face is enclosed free space in no zone (a closet or shaft without an IfcSpace, a
    /// courtyard; found only with [`GridOptions::fill_enclosed`]). It gets no apron and is no
    /// entrance.
    pub walled_in: bool,
    /// Rasterising or deciding its sides passed a bound ([`crate::bounds`]): its bounding box
    /// is unknown, it is closed, has no frame, gets no apron and is no entrance.
    pub gave_up: bool,
}

/// A storey rasterised for one robot profile.
#[derive(Debug, Clone, PartialEq)]
pub struct OccupancyGrid {
    /// Cell size, metres.
    pub resolution_m: f64,
    /// World position of the lower-left corner of cell (0, 0).
    pub origin: DVec2,
    /// Columns.
    pub width: usize,
    /// Rows.
    pub height: usize,
    /// Cell states, row-major, row 0 lowest.
    pub cells: Vec<CellState>,
    /// The zone each cell's centre is in (the first), if any.
    pub zone: Vec<Option<ZoneIdx>>,
    /// The door whose passage covers the cell, if any.
    pub door: Vec<Option<DoorIdx>>,
    /// Per door of the floor: status, reason, open or closed.
    pub doors: Vec<GridDoor>,
    /// The elements rasterising gave up on ([`crate::bounds`]): zones, obstacles and doors,
    /// each in floor order.
    pub gave_up: Vec<GaveUp>,
}

/// A raster's frame: columns, rows, lower-left corner, cell size (what [`spans`] and the
/// thin-part painting, [`ThinCells`], draw into).
#[derive(Debug, Clone, Copy)]
pub(crate) struct Frame {
    pub width: usize,
    pub height: usize,
    pub origin: DVec2,
    pub res: f64,
}

fn paint(g: Frame, ring: &[DVec2], mut f: impl FnMut(usize)) {
    spans(g, ring, |row, c0, c1| {
        let base = row * g.width;
        for col in c0..c1 {
            f(base + col);
        }
    });
}

/// The cells of `g` whose centre is inside `ring` (even-odd), as runs: `f(row, c0, c1)` for
/// columns `c0..c1` of `row`, rows upwards.
pub(crate) fn spans(g: Frame, ring: &[DVec2], mut f: impl FnMut(usize, usize, usize)) {
    let Frame {
        width,
        height,
        origin,
        res,
    } = g;
    let Some((lo, hi)) = polygon::bounds(ring) else {
        return;
    };
    if ring.len() < 3 {
        return;
    }
    // Rows whose centre y lies in [lo.y, hi.y].
    let r0 = (((lo.y - origin.y) / res - 0.5).ceil().max(0.0)) as usize;
    let r1 = (((hi.y - origin.y) / res - 0.5).floor()).min(height as f64 - 1.0);
    if r1 < 0.0 {
        return;
    }
    let r1 = r1 as usize;
    let mut xs: Vec<f64> = Vec::new();
    for row in r0..=r1.min(height.saturating_sub(1)) {
        let y = origin.y + (row as f64 + 0.5) * res;
        polygon::crossings_into(ring, y, &mut xs);
        xs.sort_by(f64::total_cmp);
        for span in xs.chunks_exact(2) {
            // Columns whose centre x lies in [x0, x1).
            let c0 = ((span[0] - origin.x) / res - 0.5).ceil().max(0.0);
            let c1 = ((span[1] - origin.x) / res - 0.5).ceil().min(width as f64);
            if c1 <= c0 {
                continue;
            }
            f(row, c0 as usize, c1 as usize);
        }
    }
}

/// The entrance aprons of `floor` ([`GridOptions::entrance_apron_m`]): in front of every
/// exterior door (a zone on one side only) that is open for `profile`, outside, a rectangle as
/// wide as its passage and as deep as the apron; a door that joins no zone at all (a model
/// without spaces) gets one on each side, so its passage can be planned through and checked.
/// Doorways ([`crate::FloorDoor::doorless`]) with a zone on one side only get none, nor do
/// doors of storeys not at ground level ([`GridOptions::at_ground`]) unless they open onto
/// the terrain ([`crate::FloorDoor::terrain`]). Each ring
/// comes with the index of its door.
pub fn entrance_aprons(
    floor: &Floor,
    profile: &RobotProfile,
    options: &GridOptions,
) -> Vec<(DoorIdx, Ring)> {
    let apron = options.entrance_apron_m;
    if !(apron.is_finite() && apron > 0.0) {
        return Vec::new();
    }
    let mut out = Vec::new();
    let undecided = bounds::door_side_bounds(floor, &options.bounds);
    let zones = ZoneIndex::new(floor);
    for (k, d) in floor.doors.iter().enumerate() {
        if undecided[k].is_some() {
            continue;
        }
        if options.doors_by_status
            && !passable(door_verdict(d, profile), options.pending_doors_open)
        {
            continue;
        }
        let Some(f) = floor.door_frame_in(k, &zones) else {
            continue;
        };
        let sides: &[f64] = match crate::graph::door_zones_in(floor, &zones, k) {
            // A doorway with a zone on one side leads into the undescribed, not outside.
            [None, Some(_)] | [Some(_), None]
                if d.doorless || !(options.at_ground || d.terrain) =>
            {
                continue
            }
            [None, Some(_)] => &[-1.0],
            [Some(_), None] => &[1.0],
            [None, None] => &[-1.0, 1.0],
            [Some(_), Some(_)] => continue,
        };
        for side in sides {
            let front = PassageFrame {
                center: f.center + f.normal * *side * (f.half_depth + apron / 2.0),
                half_depth: apron / 2.0,
                ..f
            };
            out.push((DoorIdx::new(k), front.rectangle(f.half_width, apron / 2.0)));
        }
    }
    out
}

/// The index of the cell containing `p` in a grid of `width` x `height` cells of `res` metres
/// whose lower-left corner is `origin`.
fn cell_at(origin: DVec2, res: f64, width: usize, height: usize, p: DVec2) -> Option<usize> {
    let q = (p - origin) / res;
    if q.x < 0.0 || q.y < 0.0 {
        return None;
    }
    let (c, r) = (q.x.floor() as usize, q.y.floor() as usize);
    (c < width && r < height).then_some(r * width + c)
}

impl OccupancyGrid {
    /// Rasterises `floor` for `profile`: zones (and, with `fill_enclosed`, space enclosed by
    /// walls and doors) free, walls, stairs and ramps drawn as obstacles, and furniture
    /// occupied, door passages free when the door's status for `profile` is passable (its
    /// lining, when the clear width is narrower than the ring, occupied) and occupied when not;
    /// everything else unknown.
    pub fn build(
        floor: &Floor,
        profile: &RobotProfile,
        options: &GridOptions,
    ) -> Result<OccupancyGrid, NavError> {
        let res = options.resolution_m;
        if !(res.is_finite() && res > 0.0) {
            return Err(NavError::Invalid(format!(
                "grid resolution must be a positive number of metres, not {res}"
            )));
        }
        // An empty storey is a patch of unknown cells. The entrance aprons are inside.
        let (mut lo, mut hi) = floor.bounds().unwrap_or((DVec2::ZERO, DVec2::ZERO));
        for p in entrance_aprons(floor, profile, options)
            .iter()
            .flat_map(|(_, ring)| ring)
        {
            (lo, hi) = (lo.min(*p), hi.max(*p));
        }
        let pad = options.padding_m.max(0.0);
        // Snap the origin to the resolution so that coordinates on multiples of it fall on cell
        // edges.
        // (Rounded to nanometres, so -14 x 0.05 is -0.7 and not -0.7000000000000001.)
        let origin = (((lo - DVec2::splat(pad)) / res).floor() * res * 1e9).round() / 1e9;
        let far = ((hi + DVec2::splat(pad)) / res).ceil() * res;
        let width = (((far.x - origin.x) / res).round() as usize).max(1);
        let height = (((far.y - origin.y) / res).round() as usize).max(1);
        OccupancyGrid::raster(floor, profile, options, res, origin, width, height)
    }

    /// Rasterises `floor` into a given frame (cell size, lower-left corner, columns, rows).
    pub fn raster(
        floor: &Floor,
        profile: &RobotProfile,
        options: &GridOptions,
        res: f64,
        origin: DVec2,
        width: usize,
        height: usize,
    ) -> Result<OccupancyGrid, NavError> {
        let n = width
            .checked_mul(height)
            .filter(|n| *n <= MAX_CELLS)
            .ok_or_else(|| {
                NavError::Invalid(format!(
                    "storey {}: a {width} x {height} grid is more than {MAX_CELLS} cells: \
                     raise the resolution",
                    floor.name
                ))
            })?;
        let mut cells = vec![CellState::Unknown; n];
        let mut zone: Vec<Option<ZoneIdx>> = vec![None; n];
        let mut door: Vec<Option<DoorIdx>> = vec![None; n];

        let limits = &options.bounds;
        // Rows of the grid a box spans (cell centres inside it), for the raster work bound.
        let rows = |(lo, hi): (DVec2, DVec2)| {
            let r0 = ((lo.y - origin.y) / res - 0.5).ceil().max(0.0);
            let r1 = ((hi.y - origin.y) / res - 0.5)
                .floor()
                .min(height as f64 - 1.0);
            if r1 >= r0 {
                (r1 - r0) as usize + 1
            } else {
                0
            }
        };
        // Past a bound: the bound and the element's bounding box.
        let past = |rings: &[Ring]| {
            let vertices = rings.iter().map(|r| r.len()).sum();
            let work = rings
                .iter()
                .filter_map(|r| Some(r.len() as u64 * rows(polygon::bounds(r)?) as u64))
                .sum();
            let bbox = polygon::bounds_of(rings.iter().flat_map(|r| r.iter()))?;
            bounds::raster_bound(vertices, work, limits).map(|b| (b, bbox))
        };
        let mut gave_up: Vec<GaveUp> = Vec::new();
        let mut note = |element: &str, class: &str, stage: Stage, bound: String, outcome: &str| {
            gave_up.push(GaveUp {
                floor: floor.name.clone(),
                element: element.into(),
                class: class.to_string(),
                stage,
                bound,
                outcome: outcome.to_string(),
            })
        };
        let obstacle_past: Vec<Option<(String, (DVec2, DVec2))>> =
            floor.obstacles.iter().map(|o| past(&o.rings)).collect();
        let zone_past: Vec<Option<(String, (DVec2, DVec2))>> = floor
            .zones
            .iter()
            .map(|z| past(std::slice::from_ref(&z.ring)))
            .collect();
        let door_sides = bounds::door_side_bounds(floor, limits);
        // Obstacles are painted with their parts thinner than a cell ([`ThinCells`]), but
        // around door passages.
        let raster = Frame {
            width,
            height,
            origin,
            res,
        };
        let mut thin = ThinCells::around_doors(raster, floor.doors.iter().map(|d| &d.ring[..]));

        for (k, z) in floor.zones.iter().enumerate().rev() {
            if zone_past[k].is_some() {
                continue;
            }
            paint(raster, &z.ring, |i| {
                zone[i] = Some(ZoneIdx::new(k));
                cells[i] = CellState::Free;
            });
        }

        let furniture_state = match options.furniture {
            FurnitureMode::Obstacle => CellState::Occupied,
            FurnitureMode::Unknown => CellState::Unknown,
        };
        if options.fill_enclosed {
            // Outside = reachable from the grid's border without crossing obstacles or doors.
            let mut barrier = vec![false; n];
            // Elements given up on are no barrier: what they would enclose is not known.
            for (o, past) in floor.obstacles.iter().zip(&obstacle_past) {
                if past.is_some() {
                    continue;
                }
                let lines_door = lines_doors(&o.class);
                for ring in &o.rings {
                    thin.paint(raster, ring, lines_door, |i| barrier[i] = true);
                }
            }
            for (d, sides) in floor.doors.iter().zip(&door_sides) {
                let vertices = d.ring.len();
                let too_big = polygon::bounds(&d.ring).is_some_and(|b| {
                    bounds::raster_bound(vertices, vertices as u64 * rows(b) as u64, limits)
                        .is_some()
                });
                if sides.is_some() || too_big {
                    continue;
                }
                paint(raster, &d.ring, |i| barrier[i] = true);
            }
            let mut outside = vec![false; n];
            let mut stack: Vec<usize> = Vec::new();
            let border = (0..width)
                .flat_map(|c| [c, (height - 1) * width + c])
                .chain((0..height).flat_map(|r| [r * width, r * width + width - 1]));
            for i in border {
                if !barrier[i] && zone[i].is_none() && !outside[i] {
                    outside[i] = true;
                    stack.push(i);
                }
            }
            while let Some(i) = stack.pop() {
                let (c, r) = (i % width, i / width);
                let mut visit = |j: usize| {
                    if !outside[j] && !barrier[j] && zone[j].is_none() {
                        outside[j] = true;
                        stack.push(j);
                    }
                };
                if c > 0 {
                    visit(i - 1);
                }
                if c + 1 < width {
                    visit(i + 1);
                }
                if r > 0 {
                    visit(i - width);
                }
                if r + 1 < height {
                    visit(i + width);
                }
            }
            for i in 0..n {
                if !outside[i] && !barrier[i] {
                    cells[i] = CellState::Free;
                }
            }
        }
        // A zone given up on is unknown over its bounding box, but for other zones' cells.
        for (k, z) in floor.zones.iter().enumerate() {
            let Some((bound, (lo, hi))) = &zone_past[k] else {
                continue;
            };
            paint(raster, &polygon::rect(lo.x, lo.y, hi.x, hi.y), |i| {
                if zone[i].is_none() && cells[i] == CellState::Free {
                    cells[i] = CellState::Unknown;
                }
            });
            note(
                &z.id,
                "IfcSpace",
                Stage::Raster,
                bound.clone(),
                "left out of the zones; its bounding box is unknown",
            );
        }

        for (oi, o) in floor.obstacles.iter().enumerate() {
            let state = match o.kind {
                ObstacleKind::Furniture => furniture_state,
                ObstacleKind::Unknown => CellState::Unknown,
                ObstacleKind::Structure | ObstacleKind::DoorLeaf | ObstacleKind::Transition => {
                    CellState::Occupied
                }
            };
            let box_ring;
            let rings: &[Ring] = match &obstacle_past[oi] {
                Some((bound, (lo, hi))) => {
                    note(
                        &o.id,
                        &o.class,
                        Stage::Raster,
                        bound.clone(),
                        "its bounding box is unknown",
                    );
                    box_ring = [polygon::rect(lo.x, lo.y, hi.x, hi.y)];
                    &box_ring
                }
                None => &o.rings,
            };
            // Given up on: unknown, whatever it is.
            let state = if obstacle_past[oi].is_some() {
                CellState::Unknown
            } else {
                state
            };
            let lines_door = lines_doors(&o.class);
            for ring in rings {
                thin.paint(raster, ring, lines_door, |i| {
                    // Unknown furniture (or element) does not erase walls under it.
                    if state == CellState::Occupied || cells[i] != CellState::Occupied {
                        cells[i] = state;
                    }
                });
            }
        }

        let mut doors = Vec::with_capacity(floor.doors.len());
        let zones = ZoneIndex::new(floor);
        for (k, d) in floor.doors.iter().enumerate() {
            let (status, reason) = door_status(d, profile);
            let given_up = door_bound(d, &door_sides[k], &rows, limits, res);
            if let Some((stage, bound)) = given_up {
                if let Some((lo, hi)) = polygon::bounds(&d.ring) {
                    paint(raster, &polygon::rect(lo.x, lo.y, hi.x, hi.y), |i| {
                        if cells[i] != CellState::Occupied {
                            cells[i] = CellState::Unknown;
                        }
                    });
                }
                note(
                    &d.id,
                    bounds::door_class(floor, k),
                    stage,
                    bound,
                    "closed, no entrance; its bounding box is unknown",
                );
                doors.push(GridDoor {
                    status,
                    reason,
                    open: false,
                    frame: None,
                    passage_half_width_m: None,
                    walled_in: false,
                    gave_up: true,
                });
                continue;
            }
            let open = !options.doors_by_status || passable(status, options.pending_doors_open);
            let frame = floor.door_frame_in(k, &zones);
            let state = if open {
                CellState::Free
            } else {
                CellState::Occupied
            };
            let mut passage_half_width_m = None;
            if let Some(f) = frame {
                let clear = d.clear_width_m;
                let narrower =
                    clear.is_finite() && clear > 0.0 && clear < 2.0 * f.half_width - 1e-6;
                passage_half_width_m = Some(if narrower { clear / 2.0 } else { f.half_width });
                if narrower {
                    // The lining beside the clear passage is solid.
                    let lining = (2.0 * f.half_width - clear) / 4.0;
                    for side in [-1.0, 1.0] {
                        let ring =
                            f.rectangle_at(side * (f.half_width - lining), lining, f.half_depth);
                        paint(raster, &ring, |i| {
                            cells[i] = CellState::Occupied;
                            door[i] = Some(DoorIdx::new(k));
                        });
                    }
                    let ring = f.rectangle(clear / 2.0, f.half_depth);
                    paint(raster, &ring, |i| {
                        cells[i] = state;
                        door[i] = Some(DoorIdx::new(k));
                    });
                } else {
                    paint(raster, &d.ring, |i| {
                        cells[i] = state;
                        door[i] = Some(DoorIdx::new(k));
                    });
                }
            }
            // Walled in: before any apron is painted, a free cell in no zone and no door is
            // one the enclosed fill made free, so enclosed by walls and doors.
            let side = match crate::graph::door_zones_in(floor, &zones, k) {
                [None, Some(_)] => Some(-1.0),
                [Some(_), None] => Some(1.0),
                _ => None,
            };
            let walled_in = match (frame, side) {
                (Some(f), Some(side)) if !d.doorless => {
                    let p = f.center + f.normal * side * (f.half_depth + 2.0 * res);
                    cell_at(origin, res, width, height, p).is_some_and(|i| {
                        cells[i] == CellState::Free && zone[i].is_none() && door[i].is_none()
                    })
                }
                _ => false,
            };
            doors.push(GridDoor {
                status,
                reason,
                open,
                frame,
                passage_half_width_m,
                walled_in,
                gave_up: false,
            });
        }

        // Entrance aprons: free cells in front of open exterior doors, outside.
        for (k, ring) in entrance_aprons(floor, profile, options) {
            if doors[k.get()].walled_in || doors[k.get()].gave_up {
                continue;
            }
            paint(raster, &ring, |i| {
                if cells[i] == CellState::Unknown {
                    cells[i] = CellState::Free;
                }
            });
        }

        Ok(OccupancyGrid {
            resolution_m: res,
            origin,
            width,
            height,
            cells,
            zone,
            door,
            doors,
            gave_up,
        })
    }

    /// Number of cells.
    pub fn len(&self) -> usize {
        self.cells.len()
    }

    /// True for a grid without cells (never built by [`OccupancyGrid::build`]).
    pub fn is_empty(&self) -> bool {
        self.cells.is_empty()
    }

    /// The index of the cell containing `p`, if inside the grid.
    pub fn cell_of(&self, p: DVec2) -> Option<usize> {
        cell_at(self.origin, self.resolution_m, self.width, self.height, p)
    }

    /// World position of a cell's centre.
    pub fn center(&self, i: usize) -> DVec2 {
        let (c, r) = (i % self.width, i / self.width);
        self.origin + DVec2::new(c as f64 + 0.5, r as f64 + 0.5) * self.resolution_m
    }

    /// Counts of free, occupied and unknown cells.
    pub fn counts(&self) -> [usize; 3] {
        let mut n = [0; 3];
        for c in &self.cells {
            n[*c as usize] += 1;
        }
        n
    }
}

/// How the grid is inflated for a robot's centre.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct InflationOptions {
    /// Cells closer than this to an obstacle are not traversable (lethal). Default: half the
    /// profile's width (the inscribed radius, as Nav2's inflation layer): a robot that fits a
    /// door (width <= clear width, RESTRICTED or better) can pass it.
    pub lethal_radius_m: Option<f64>,
    /// Up to this distance a cell costs more the closer it is (Nav2's `inflation_radius`).
    /// Default: the profile's radius (circumscribed) plus its clearance margin.
    pub inflation_radius_m: Option<f64>,
    /// Extra cost per metre at the lethal boundary, as a fraction of free travel (falls off
    /// quadratically to 0 at the inflation radius). Default 0.5.
    pub penalty: f64,
}

impl Default for InflationOptions {
    fn default() -> Self {
        InflationOptions {
            lethal_radius_m: None,
            inflation_radius_m: None,
            penalty: 0.5,
        }
    }
}

/// An occupancy grid inflated for one profile: the robot's centre may be on a cell when it is
/// free and at least the lethal radius from every occupied cell.
#[derive(Debug, Clone, PartialEq)]
pub struct NavGrid {
    /// The rasterised storey.
    pub occupancy: OccupancyGrid,
    /// Distance from each cell's centre to the nearest occupied cell's edge, metres
    /// (infinite when the floor has no obstacles).
    pub clearance_m: Vec<f32>,
    /// Lethal radius used.
    pub lethal_radius_m: f64,
    /// Inflation radius used.
    pub inflation_radius_m: f64,
    /// Penalty used.
    pub penalty: f64,
    /// Time spent: rasterising and the distance transform, seconds (informative).
    pub timings_s: (f64, f64),
}

impl NavGrid {
    /// Rasterises and inflates `floor` for `profile`.
    pub fn build(
        floor: &Floor,
        profile: &RobotProfile,
        grid: &GridOptions,
        inflation: &InflationOptions,
    ) -> Result<NavGrid, NavError> {
        let t0 = Instant::now();
        let occupancy = OccupancyGrid::build(floor, profile, grid)?;
        let t1 = Instant::now();
        let mut nav = NavGrid::inflate(occupancy, profile, inflation);
        nav.timings_s = ((t1 - t0).as_secs_f64(), t1.elapsed().as_secs_f64());
        Ok(nav)
    }

    /// Inflates a rasterised grid.
    pub fn inflate(
        occupancy: OccupancyGrid,
        profile: &RobotProfile,
        options: &InflationOptions,
    ) -> NavGrid {
        let d2 = distance_transform(&occupancy);
        let res = occupancy.resolution_m;
        let half = res / 2.0;
        let mut clearance_m: Vec<f32> = d2
            .iter()
            .map(|&d| {
                if d.is_finite() {
                    (d.sqrt() * res - half).max(0.0) as f32
                } else {
                    f32::INFINITY
                }
            })
            .collect();
        door_clearance(&occupancy, &mut clearance_m);
        NavGrid::with_clearance(occupancy, clearance_m, profile, options)
    }

    fn with_clearance(
        occupancy: OccupancyGrid,
        clearance_m: Vec<f32>,
        profile: &RobotProfile,
        options: &InflationOptions,
    ) -> NavGrid {
        let lethal = options.lethal_radius_m.unwrap_or(profile.width_m / 2.0);
        let inflation = options
            .inflation_radius_m
            .unwrap_or(profile.radius() + profile.clearance_margin_m)
            .max(lethal);
        NavGrid {
            occupancy,
            clearance_m,
            lethal_radius_m: lethal,
            inflation_radius_m: inflation,
            penalty: options.penalty.max(0.0),
            timings_s: (0.0, 0.0),
        }
    }

    /// True when the robot's centre may be on cell `i`.
    #[inline]
    pub fn traversable(&self, i: usize) -> bool {
        self.occupancy.cells[i] == CellState::Free
            && f64::from(self.clearance_m[i]) >= self.lethal_radius_m - 1e-9
    }

    /// Cost factor (>= 1) of being on cell `i` for its closeness to obstacles.
    #[inline]
    pub fn inflation_factor(&self, i: usize) -> f64 {
        let d = f64::from(self.clearance_m[i]);
        if d >= self.inflation_radius_m || self.inflation_radius_m <= self.lethal_radius_m {
            return 1.0;
        }
        let t = ((self.inflation_radius_m - d) / (self.inflation_radius_m - self.lethal_radius_m))
            .clamp(0.0, 1.0);
        1.0 + self.penalty * t * t
    }

    /// The traversable cell nearest to `p` within `max_m`, preferring `p`'s own cell.
    pub fn nearest_traversable(&self, p: DVec2, max_m: f64) -> Option<usize> {
        let g = &self.occupancy;
        let q = (p - g.origin) / g.resolution_m;
        let (pc, pr) = (q.x.floor() as i64, q.y.floor() as i64);
        let reach = (max_m / g.resolution_m).ceil() as i64;
        let mut best: Option<(f64, usize)> = None;
        for r in (pr - reach)..=(pr + reach) {
            for c in (pc - reach)..=(pc + reach) {
                if r < 0 || c < 0 || r >= g.height as i64 || c >= g.width as i64 {
                    continue;
                }
                let i = r as usize * g.width + c as usize;
                if !self.traversable(i) {
                    continue;
                }
                let d = g.center(i).distance(p);
                if d <= max_m && best.is_none_or(|(bd, bi)| d < bd || (d == bd && i < bi)) {
                    best = Some((d, i));
                }
            }
        }
        best.map(|(_, i)| i)
    }

    /// Whether the robot's centre can cross door `k` of the floor in this grid: a path of
    /// traversable cells inside the door's width from one side of its passage to the other
    /// (to its outer edge when `outside` names the side, -1 or +1 along the frame's normal,
    /// that leads out of the building).
    pub fn door_passable(&self, k: usize, outside: Option<f64>) -> bool {
        let g = &self.occupancy;
        let Some(f) = g.doors.get(k).and_then(|d| d.frame) else {
            return false;
        };
        let res = g.resolution_m;
        let ext = 3.0 * res;
        let reach = f.half_width.hypot(f.half_depth + ext) + res;
        let (lo, hi) = (
            f.center - DVec2::splat(reach),
            f.center + DVec2::splat(reach),
        );
        let c0 = (((lo.x - g.origin.x) / res).floor().max(0.0)) as usize;
        let r0 = (((lo.y - g.origin.y) / res).floor().max(0.0)) as usize;
        let c1 = (((hi.x - g.origin.x) / res).ceil() as usize).min(g.width);
        let r1 = (((hi.y - g.origin.y) / res).ceil() as usize).min(g.height);
        if c1 <= c0 || r1 <= r0 {
            return false;
        }
        let (w, h) = (c1 - c0, r1 - r0);
        // 0 outside the region or blocked, 1 start side, 2 goal side, 3 between.
        let mut kind = vec![0u8; w * h];
        for r in 0..h {
            for c in 0..w {
                let i = (r0 + r) * g.width + c0 + c;
                if !self.traversable(i) {
                    continue;
                }
                let d = g.center(i) - f.center;
                let (u, v) = (d.dot(f.axis), d.dot(f.normal));
                if u.abs() > f.half_width || v.abs() > f.half_depth + ext {
                    continue;
                }
                let start_side = -outside.unwrap_or(1.0);
                let goal_side = -start_side;
                let is_start = v * start_side > f.half_depth;
                let is_goal = if outside.is_some() {
                    v * goal_side >= f.half_depth - res
                } else {
                    v * goal_side > f.half_depth
                };
                kind[r * w + c] = if is_start {
                    1
                } else if is_goal {
                    2
                } else {
                    3
                };
            }
        }
        let mut seen = vec![false; w * h];
        let mut stack: Vec<usize> = (0..w * h).filter(|&i| kind[i] == 1).collect();
        for &i in &stack {
            seen[i] = true;
        }
        while let Some(i) = stack.pop() {
            if kind[i] == 2 {
                return true;
            }
            let (c, r) = ((i % w) as i64, (i / w) as i64);
            for (dc, dr) in NEIGHBOURS {
                let (nc, nr) = (c + dc, r + dr);
                if nc < 0 || nr < 0 || nc >= w as i64 || nr >= h as i64 {
                    continue;
                }
                let j = nr as usize * w + nc as usize;
                if seen[j] || kind[j] == 0 {
                    continue;
                }
                seen[j] = true;
                stack.push(j);
            }
        }
        false
    }
}

/// The 8 neighbour offsets (col, row), axis moves first.
pub const NEIGHBOURS: [(i64, i64); 8] = [
    (1, 0),
    (-1, 0),
    (0, 1),
    (0, -1),
    (1, 1),
    (-1, 1),
    (1, -1),
    (-1, -1),
];

/// How far beyond an open door's own depth its passage is taken to continue through the wall
/// (walls are often thicker than the door's frame), metres.
const PASSAGE_REACH_M: f64 = 0.5;

/// Through an open door the clearance is known exactly: half the passage width less the
/// distance from its axis, within the passage and the wall opening around it. The raster's
/// clearance is measured to cell edges and the jambs are rasterised by cell centres, so it can
/// be short by up to a cell, enough to close a door only a few centimetres wider than the robot.
/// There the exact value is used, but never more than a cell above the raster's, so anything
/// else standing in the way still counts.
fn door_clearance(g: &OccupancyGrid, clearance: &mut [f32]) {
    let res = g.resolution_m;
    for d in g.doors.iter().filter(|d| d.open) {
        let (Some(f), Some(half)) = (d.frame, d.passage_half_width_m) else {
            continue;
        };
        let reach = f.half_depth + PASSAGE_REACH_M;
        let corners = [-1.0, 1.0]
            .map(|a| [-1.0, 1.0].map(|n| f.center + f.axis * (a * half) + f.normal * (n * reach)));
        let (lo, hi) = polygon::bounds_of(corners.iter().flatten()).unwrap_or_default();
        let cell = |p: DVec2| ((p - g.origin) / res).floor();
        let (a, b) = (cell(lo).max(DVec2::ZERO), cell(hi));
        if !(b.x >= 0.0 && b.y >= 0.0) {
            continue;
        }
        let (c1, r1) = (
            (b.x as usize).min(g.width - 1),
            (b.y as usize).min(g.height - 1),
        );
        for r in a.y as usize..=r1 {
            for c in a.x as usize..=c1 {
                let i = r * g.width + c;
                if g.cells[i] != CellState::Free {
                    continue;
                }
                let q = g.center(i) - f.center;
                let (lateral, depth) = (q.dot(f.axis).abs(), q.dot(f.normal).abs());
                if lateral > half || depth > reach {
                    continue;
                }
                let exact = half - lateral;
                let raster = f64::from(clearance[i]);
                if exact > raster {
                    clearance[i] = exact.min(raster + res) as f32;
                }
            }
        }
    }
}

/// Squared Euclidean distance (in cells) from every cell's centre to the nearest occupied
/// cell's centre: Felzenszwalb and Huttenlocher's exact transform, two 1D passes, O(n).
/// Infinite everywhere when nothing is occupied.
pub fn distance_transform(grid: &OccupancyGrid) -> Vec<f64> {
    let (w, h) = (grid.width, grid.height);
    let mut f: Vec<f64> = grid
        .cells
        .iter()
        .map(|c| {
            if *c == CellState::Occupied {
                0.0
            } else {
                f64::INFINITY
            }
        })
        .collect();
    let mut scratch = Scratch::new(w.max(h));
    let mut line = vec![0.0; h];
    for c in 0..w {
        for r in 0..h {
            line[r] = f[r * w + c];
        }
        scratch.transform(&mut line);
        for r in 0..h {
            f[r * w + c] = line[r];
        }
    }
    for r in 0..h {
        scratch.transform(&mut f[r * w..(r + 1) * w]);
    }
    f
}

struct Scratch {
    v: Vec<usize>,
    z: Vec<f64>,
    out: Vec<f64>,
}

impl Scratch {
    fn new(n: usize) -> Scratch {
        Scratch {
            v: vec![0; n],
            z: vec![0.0; n + 1],
            out: vec![0.0; n],
        }
    }

    /// 1D squared distance transform of `f` in place (lower envelope of parabolas).
    fn transform(&mut self, f: &mut [f64]) {
        let n = f.len();
        let (v, z, out) = (&mut self.v, &mut self.z, &mut self.out);
        let mut k: usize = 0;
        let mut any = false;
        for q in 0..n {
            if !f[q].is_finite() {
                continue;
            }
            if !any {
                v[0] = q;
                z[0] = f64::NEG_INFINITY;
                z[1] = f64::INFINITY;
                any = true;
                continue;
            }
            let fq = f[q] + (q * q) as f64;
            let mut s;
            loop {
                let p = v[k];
                s = (fq - (f[p] + (p * p) as f64)) / (2.0 * (q - p) as f64);
                // z[0] is -inf, so this stops at k = 0.
                if s <= z[k] {
                    k -= 1;
                } else {
                    break;
                }
            }
            k += 1;
            v[k] = q;
            z[k] = s;
            z[k + 1] = f64::INFINITY;
        }
        if !any {
            return;
        }
        let mut k = 0;
        for (q, o) in out.iter_mut().enumerate().take(n) {
            while z[k + 1] < q as f64 {
                k += 1;
            }
            let p = v[k];
            let d = q as f64 - p as f64;
            *o = d * d + f[p];
        }
        f.copy_from_slice(&out[..n]);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::floor::FloorObstacle;
    use crate::polygon::rect;

    #[test]
    fn distance_transform_matches_brute_force() {
        let mut floor = Floor::default();
        for (i, (x, y)) in [(0.3, 0.4), (1.2, 0.2), (0.9, 1.3), (1.6, 1.6)]
            .iter()
            .enumerate()
        {
            floor.obstacles.push(FloorObstacle {
                id: format!("o{i}").into(),
                class: "IfcColumn".into(),
                kind: ObstacleKind::Structure,
                rings: vec![rect(*x, *y, x + 0.1, y + 0.15)],
                roles: vec![],
            });
        }
        let g =
            OccupancyGrid::build(&floor, &RobotProfile::paper(), &GridOptions::default()).unwrap();
        let d2 = distance_transform(&g);
        let occ: Vec<usize> = (0..g.len())
            .filter(|&i| g.cells[i] == CellState::Occupied)
            .collect();
        assert!(!occ.is_empty());
        for (i, d) in d2.iter().enumerate() {
            let (c, r) = ((i % g.width) as f64, (i / g.width) as f64);
            let best = occ
                .iter()
                .map(|&j| {
                    let (cj, rj) = ((j % g.width) as f64, (j / g.width) as f64);
                    (c - cj).powi(2) + (r - rj).powi(2)
                })
                .fold(f64::INFINITY, f64::min);
            assert_eq!(*d, best, "cell {i}");
        }
    }

    #[test]
    fn exact_fill_of_aligned_rectangles() {
        let floor = Floor {
            obstacles: vec![FloorObstacle {
                id: "w".into(),
                class: "IfcWall".into(),
                kind: ObstacleKind::Structure,
                rings: vec![rect(0.0, 0.0, 1.0, 0.2)],
                roles: vec![],
            }],
            ..Floor::default()
        };
        let g =
            OccupancyGrid::build(&floor, &RobotProfile::paper(), &GridOptions::default()).unwrap();
        // 1.0 x 0.2 m at 0.05 m: 20 x 4 cells.
        assert_eq!(g.counts()[1], 80);
    }
}
