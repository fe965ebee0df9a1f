//! The Nav2 bundle of a building for one robot profile, one folder per storey:
//!
//! - `map.yaml` + `map.pgm` for nav2_map_server (trinary: 0 occupied, 254 free, 205 unknown,
//!   first row = largest y, thresholds 0.65 / 0.196, origin = the lower-left pixel, yaw 0). Not
//!   inflated (Nav2's inflation layer does that); BLOCKED doors are drawn closed; outside the
//!   building unknown but for the free apron in front of each open entrance
//!   ([`crate::GridOptions::entrance_apron_m`]). The free threshold is 0.196, not Nav2's default 0.25, under which 205 would load as free
//!   ([`Nav2Options::free_thresh`]).
//! - `keepout_mask.yaml` + `.pgm`: mask value 100 (black) on BLOCKED doors and on stairs or
//!   ramps the profile cannot use, free elsewhere (trinary).
//! - `speed_mask.yaml` + `.pgm`: mode scale with thresholds 0 and 1 so a pixel decodes to the
//!   mask value `100 - speed percent` of its zone's or door's roles (B-1, B-2, C-1), 0 (no
//!   limit) elsewhere.
//! - `costmap_filter_info.yaml`: parameters of two costmap_filter_info_server nodes, keepout
//!   (type 0, base 0, multiplier 1) and speed (type 1, percent: limit = 100 - mask, base 100,
//!   multiplier -1).
//! - `route_graph.geojson`: the storey's nav2_route graph ([`crate::route_graph`]): Point nodes
//!   (zones, doors, landings and the corners of the grid paths between them, each with its
//!   storey) and MultiLineString edges (id, startid, endid, cost = seconds at the role speeds,
//!   overridable, metadata with speed_limit in percent for AdjustSpeedLimit, abs_speed_limit in
//!   m/s, the roles, zones and doors crossed; an `OpenDoor` TriggerEvent operation on entering
//!   an edge through a door), every edge in both directions, ids unique across nodes and edges.
//!
//! and at the top `route_graph.geojson` (the whole building's graph: every storey's in its own
//! frame plus edges joining storeys through stairs, ramps and lifts, marked with the connection
//! and its travel time; `CallLift` operations on lifts), `README.md` (how to load it, every
//! field of the graphs) and `topology.json` (the building's room/door graph for the profile).
//! Every file is written atomically; the same input gives the same bytes.
//!
//! Only where there is something to navigate: each storey's maps cover its own extent (its
//! spaces, doors and walls, [`crate::extent`]) plus the entrance aprons and
//! [`crate::GridOptions::crop_margin_m`], not whatever else the storey holds (a site, terrain,
//! a roof's overhang), as [`Navigator`] rasterises it; a storey without spaces or doors (a
//! roof, an empty level) gets no folder and is listed in [`BundleSummary::skipped`] with why.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use glam::DVec2;
use poinav_roles::{AccessibilityStatus, RobotProfile};
use serde::Serialize;

use crate::audit::slug;
use crate::building::Building;
use crate::floor::ObstacleKind;
use crate::graph::round6;
use crate::grid::{CellState, OccupancyGrid};
use crate::navigator::{NavOptions, Navigator};
use crate::NavError;

/// How the bundle is made.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Nav2Options {
    /// Grids, inflation, speeds.
    pub nav: NavOptions,
    /// The map frame named in the route graph.
    pub frame: String,
    /// Connect each door or landing of a zone to this many nearest others in the route graph
    /// (besides the zone's own node).
    pub neighbours: usize,
    /// `free_thresh` of `map.yaml` and `keepout_mask.yaml`. Default 0.196 (ROS 1's map_saver
    /// value): with Nav2's own default 0.25, the unknown grey 205 (p = 50 / 255 = 0.196) loads
    /// as free, so the outside of the building would become free space.
    pub free_thresh: f64,
}

impl Default for Nav2Options {
    fn default() -> Self {
        Nav2Options {
            nav: NavOptions::default(),
            frame: "map".into(),
            neighbours: 2,
            free_thresh: 0.196,
        }
    }
}

/// What was written for one storey.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct StoreyBundle {
    /// Storey name.
    pub floor: String,
    /// Folder (relative to the bundle).
    pub folder: String,
    /// Map size in cells.
    pub width: usize,
    /// Rows.
    pub height: usize,
    /// Origin [x, y] of the lower-left pixel.
    pub origin: [f64; 2],
    /// Cells with keepout 100.
    pub keepout_cells: usize,
    /// Cells with a speed limit.
    pub speed_cells: usize,
    /// Route graph nodes and (directed) edges.
    pub graph_nodes: usize,
    /// Directed edges.
    pub graph_edges: usize,
}

pub use crate::extent::SkippedStorey;

/// What was written.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct BundleSummary {
    /// Profile name.
    pub profile: String,
    /// Per storey written.
    pub storeys: Vec<StoreyBundle>,
    /// Storeys left out, with why.
    pub skipped: Vec<SkippedStorey>,
    /// The building-wide route graph (`route_graph.geojson` at the top).
    pub building_graph: crate::route_graph::BuildingGraphCounts,
    /// Every file written.
    pub files: Vec<PathBuf>,
    /// The elements rasterising and the graph gave up on ([`crate::bounds`]): unknown in the
    /// maps, such doors closed and no entrances.
    pub gave_up: Vec<crate::bounds::GaveUp>,
}

/// The binary PGM (P5) of a grid of 8-bit values, first row = largest y.
pub fn pgm(width: usize, height: usize, value: impl Fn(usize) -> u8) -> Vec<u8> {
    let mut out = format!("P5\n{width} {height}\n255\n").into_bytes();
    out.reserve(width * height);
    for row in (0..height).rev() {
        for col in 0..width {
            out.push(value(row * width + col));
        }
    }
    out
}

/// The map_server YAML for an image.
pub fn map_yaml(grid: &OccupancyGrid, image: &str, mode: &str, occupied: f64, free: f64) -> String {
    format!(
        "image: {image}\nmode: {mode}\nresolution: {}\norigin: [{}, {}, 0.0]\nnegate: 0\noccupied_thresh: {occupied:?}\nfree_thresh: {free:?}\n",
        grid.resolution_m,
        round6(grid.origin.x),
        round6(grid.origin.y),
    )
}

/// The PGM grey level that nav2_map_server in scale mode (free_thresh 0, occupied_thresh 1,
/// negate 0) decodes to `value` (0-100): `rint((1 - x / 255) * 100) == value`.
pub fn scale_pixel(value: u8) -> u8 {
    let v = f64::from(value.min(100));
    let guess = (255.0 * (1.0 - v / 100.0)).round() as i32;
    for d in [0, -1, 1, -2, 2] {
        let x = (guess + d).clamp(0, 255);
        if ((1.0 - f64::from(x) / 255.0) * 100.0).round_ties_even() == v {
            return x as u8;
        }
    }
    guess.clamp(0, 255) as u8
}

fn write(files: &mut Vec<PathBuf>, path: PathBuf, bytes: &[u8]) -> Result<(), NavError> {
    poinav_io::write_atomic(&path, bytes).map_err(|source| NavError::Write {
        path: path.clone(),
        source,
    })?;
    files.push(path);
    Ok(())
}

/// Writes the bundle of `building` for `profile` into `dir` (created if missing): each storey
/// cropped to its own extent, storeys with nothing to navigate skipped ([`Navigator`]).
pub fn write_bundle(
    building: &Building,
    profile: &RobotProfile,
    options: &Nav2Options,
    dir: &Path,
) -> Result<BundleSummary, NavError> {
    write_bundle_with_progress(building, profile, options, dir, &crate::progress::none)
}

/// [`write_bundle`], telling `progress` about each storey rasterised and written.
pub fn write_bundle_with_progress(
    building: &Building,
    profile: &RobotProfile,
    options: &Nav2Options,
    dir: &Path,
    progress: crate::progress::Progress<'_>,
) -> Result<BundleSummary, NavError> {
    let nav = Navigator::with_progress(building, profile, &options.nav, progress)?;
    write_navigator_bundle_with_progress(&nav, options, dir, progress)
}

/// Writes the bundle of a prepared building (storeys with nothing to navigate skipped).
pub fn write_navigator_bundle(
    nav: &Navigator<'_>,
    options: &Nav2Options,
    dir: &Path,
) -> Result<BundleSummary, NavError> {
    write_navigator_bundle_with_progress(nav, options, dir, &crate::progress::none)
}

/// [`write_navigator_bundle`], telling `progress` about each storey written.
pub fn write_navigator_bundle_with_progress(
    nav: &Navigator<'_>,
    options: &Nav2Options,
    dir: &Path,
    progress: crate::progress::Progress<'_>,
) -> Result<BundleSummary, NavError> {
    let mkdir = |d: &Path| {
        std::fs::create_dir_all(d).map_err(|source| NavError::Write {
            path: d.to_path_buf(),
            source,
        })
    };
    mkdir(dir)?;
    let mut files = Vec::new();
    let mut storeys = Vec::new();
    let mut skipped = Vec::new();
    let mut graphs = Vec::new();
    let n = nav.building.floors.len();
    for (fi, floor) in nav.building.floors.iter().enumerate() {
        progress(crate::progress::Phase::Writing, fi, n);
        if let Some(reason) = nav.nothing_to_navigate[fi].clone() {
            skipped.push(SkippedStorey {
                floor: floor.name.clone(),
                reason,
            });
            continue;
        }
        let folder = format!("{fi:02}-{}", slug(&floor.name));
        let sub = dir.join(&folder);
        mkdir(&sub)?;
        let fnav = &nav.floors[fi];
        let g = &fnav.grid.occupancy;

        let map = pgm(g.width, g.height, |i| match g.cells[i] {
            CellState::Free => 254,
            CellState::Occupied => 0,
            CellState::Unknown => 205,
        });
        write(&mut files, sub.join("map.pgm"), &map)?;
        write(
            &mut files,
            sub.join("map.yaml"),
            map_yaml(g, "map.pgm", "trinary", 0.65, options.free_thresh).as_bytes(),
        )?;

        let keepout = keepout_mask(nav, fi);
        let keepout_cells = keepout.iter().filter(|k| **k).count();
        let img = pgm(g.width, g.height, |i| if keepout[i] { 0 } else { 254 });
        write(&mut files, sub.join("keepout_mask.pgm"), &img)?;
        write(
            &mut files,
            sub.join("keepout_mask.yaml"),
            map_yaml(g, "keepout_mask.pgm", "trinary", 0.65, options.free_thresh).as_bytes(),
        )?;

        let mut speed_cells = 0;
        let values: Vec<u8> = (0..g.len())
            .map(|i| {
                if g.cells[i] == CellState::Unknown {
                    return 0;
                }
                let f = fnav.speed(i);
                if f >= 1.0 {
                    0
                } else {
                    speed_cells += 1;
                    let percent = (f * 100.0).round().clamp(1.0, 100.0);
                    (100.0 - percent) as u8
                }
            })
            .collect();
        let img = pgm(g.width, g.height, |i| scale_pixel(values[i]));
        write(&mut files, sub.join("speed_mask.pgm"), &img)?;
        write(
            &mut files,
            sub.join("speed_mask.yaml"),
            map_yaml(g, "speed_mask.pgm", "scale", 1.0, 0.0).as_bytes(),
        )?;
        write(
            &mut files,
            sub.join("costmap_filter_info.yaml"),
            filter_info(&nav.options.speeds).as_bytes(),
        )?;

        let graph = crate::route_graph::storey_graph(nav, fi, options);
        let (n_nodes, n_edges) = (graph.nodes.len(), graph.edges.len());
        let json = crate::route_graph::storey_geojson(nav, &graph, options);
        let text = serde_json::to_string_pretty(&json).unwrap_or_default() + "\n";
        write(&mut files, sub.join("route_graph.geojson"), text.as_bytes())?;
        graphs.push((graph, folder.clone()));

        storeys.push(StoreyBundle {
            floor: floor.name.clone(),
            folder,
            width: g.width,
            height: g.height,
            origin: [round6(g.origin.x), round6(g.origin.y)],
            keepout_cells,
            speed_cells,
            graph_nodes: n_nodes,
            graph_edges: n_edges,
        });
    }
    progress(crate::progress::Phase::Writing, n, n);
    // The building's graph streamed to its file: held whole, it was the bundle's largest
    // allocation on big buildings.
    let path = dir.join("route_graph.geojson");
    let failed = |source: std::io::Error| NavError::Write {
        path: path.clone(),
        source,
    };
    let mut file = poinav_io::AtomicFile::create(&path).map_err(failed)?;
    let building_graph =
        crate::route_graph::write_building_geojson(nav, &graphs, options, &mut file)
            .map_err(|e| failed(e.into()))?;
    drop(graphs);
    std::io::Write::write_all(&mut file, b"\n").map_err(failed)?;
    file.commit().map_err(failed)?;
    files.push(path);
    let topo = nav.topology.to_json(nav.building, &nav.profile);
    let text = serde_json::to_string_pretty(&topo).unwrap_or_default() + "\n";
    write(&mut files, dir.join("topology.json"), text.as_bytes())?;
    write(
        &mut files,
        dir.join("README.md"),
        readme(nav, options, &storeys, &skipped, &building_graph).as_bytes(),
    )?;
    Ok(BundleSummary {
        profile: nav.profile.name.clone(),
        storeys,
        skipped,
        building_graph,
        files,
        gave_up: nav.gave_up.clone(),
    })
}

/// Cells a robot must never enter: BLOCKED doors' passages and stairs or ramps it cannot use.
fn keepout_mask(nav: &Navigator<'_>, fi: usize) -> Vec<bool> {
    let floor = &nav.building.floors[fi];
    let g = &nav.floors[fi].grid.occupancy;
    let mut mask = vec![false; g.len()];
    let blocked_doors: Vec<bool> = g
        .doors
        .iter()
        .map(|d| d.status == AccessibilityStatus::Blocked)
        .collect();
    for (m, &d) in mask.iter_mut().zip(&g.door) {
        if d.is_some_and(|d| blocked_doors[d.get()]) {
            *m = true;
        }
    }
    for o in floor
        .obstacles
        .iter()
        .filter(|o| o.kind == ObstacleKind::Transition)
    {
        let status = match nav.building.connections.iter().find(|c| c.id == o.id) {
            Some(c) => c.status(&nav.profile).0,
            None if o.class.to_ascii_lowercase().contains("stair") => {
                if nav.profile.climbs_stairs() {
                    AccessibilityStatus::FullAccess
                } else {
                    AccessibilityStatus::Blocked
                }
            }
            None => AccessibilityStatus::PendingValidation,
        };
        if status == AccessibilityStatus::Blocked {
            for ring in &o.rings {
                for_cells(g, ring, |i| mask[i] = true);
            }
        }
    }
    mask
}

fn for_cells(g: &OccupancyGrid, ring: &[DVec2], mut f: impl FnMut(usize)) {
    let Some((lo, hi)) = crate::polygon::bounds(ring) else {
        return;
    };
    let (Some(a), Some(b)) = (
        g.cell_of(lo.max(g.origin)),
        g.cell_of(
            hi.min(g.origin + DVec2::new(g.width as f64, g.height as f64) * g.resolution_m - 1e-9),
        ),
    ) else {
        return;
    };
    let (c0, r0, c1, r1) = (a % g.width, a / g.width, b % g.width, b / g.width);
    for r in r0..=r1 {
        for c in c0..=c1 {
            let i = r * g.width + c;
            if crate::polygon::contains(ring, g.center(i)) {
                f(i);
            }
        }
    }
}

fn filter_info(speeds: &crate::speed::RoleSpeeds) -> String {
    let pct = |f: f64| (f * 100.0).round();
    format!(
        "# Parameters for two nav2_map_server costmap_filter_info_server nodes.\n\
# Keepout: mask value 100 (black in keepout_mask.pgm) = never enter (BLOCKED doors, stairs or\n\
# ramps this robot cannot use); 0 = free. Filter value = base + multiplier * mask.\n\
# Speed: filter value = 100 - mask = speed limit in percent of the robot's maximum; mask 0 =\n\
# no limit. Role speeds: B-1 hazard {}%, B-2 narrow {}%, C-1 SPEED_REDUCTION {}%,\n\
# C-1 YIELD {}%, C-1 PRIORITY_PASS {}%, C-1 without protocol {}%.\n\
keepout_filter_info_server:\n  ros__parameters:\n    type: 0\n    filter_info_topic: \"keepout_filter_info\"\n    mask_topic: \"keepout_filter_mask\"\n    base: 0.0\n    multiplier: 1.0\n\
speed_filter_info_server:\n  ros__parameters:\n    type: 1\n    filter_info_topic: \"speed_filter_info\"\n    mask_topic: \"speed_filter_mask\"\n    base: 100.0\n    multiplier: -1.0\n",
        pct(speeds.hazard),
        pct(speeds.narrow),
        pct(speeds.speed_reduction),
        pct(speeds.yield_protocol),
        pct(speeds.priority_pass),
        pct(speeds.multi_robot),
    )
}

/// The nav2_route GeoJSON graph of storey `fi` ([`crate::route_graph`]).
pub fn route_graph(nav: &Navigator<'_>, fi: usize, options: &Nav2Options) -> serde_json::Value {
    let graph = crate::route_graph::storey_graph(nav, fi, options);
    crate::route_graph::storey_geojson(nav, &graph, options)
}

fn readme(
    nav: &Navigator<'_>,
    options: &Nav2Options,
    storeys: &[StoreyBundle],
    skipped: &[SkippedStorey],
    building_graph: &crate::route_graph::BuildingGraphCounts,
) -> String {
    let p = &nav.profile;
    let mut s = String::new();
    let _ = writeln!(s, "# Nav2 bundle for robot profile `{}`\n", p.name);
    let _ = writeln!(
        s,
        "Made by poinav from the building model: robot {:.2} m wide, needs {:.2} m clear width; door and stair statuses are this profile's.\n",
        p.width_m,
        p.min_clearance_width()
    );
    s.push_str("| storey | folder | map size (cells) | origin | keepout cells | speed-limited cells | route graph nodes / edges |\n|---|---|---|---|---|---|---|\n");
    for st in storeys {
        let _ = writeln!(
            s,
            "| {} | `{}/` | {} x {} | [{}, {}, 0.0] | {} | {} | {} / {} |",
            st.floor,
            st.folder,
            st.width,
            st.height,
            st.origin[0],
            st.origin[1],
            st.keepout_cells,
            st.speed_cells,
            st.graph_nodes,
            st.graph_edges
        );
    }
    if !skipped.is_empty() {
        s.push_str("\nStoreys with nothing to navigate have no folder:\n\n");
        for k in skipped {
            let _ = writeln!(s, "- {}: {}", k.floor, k.reason);
        }
    }
    let res = nav
        .floors
        .first()
        .map_or(0.05, |f| f.grid.occupancy.resolution_m);
    let lethal = nav.floors.first().map_or(0.0, |f| f.grid.lethal_radius_m);
    let apron = nav.options.grid.entrance_apron_m;
    let pct = |f: f64| (f * 100.0).round();
    let _ = write!(
        s,
        "
## Files per storey

- `map.yaml`, `map.pgm`: the occupancy map for `nav2_map_server` ({res} m per pixel, mode trinary:
  0 occupied, 254 free, 205 unknown; thresholds 0.65 / {free}; the top row is the largest y;
  origin is the lower-left pixel, yaw 0; a free threshold of 0.25, Nav2's default, would load
  the unknown grey 205 as free). Walls, furniture and closed (BLOCKED) doors are occupied, the
  inside of the building free, the outside unknown, except an entrance apron: a free strip
  {apron} m deep and as wide as the door in front of each open entrance (a door with a space
  on one side only; on both sides of an open door that joins no space, in models without
  spaces), so a robot can be sent to or from the entrance. It is not inflated:
  configure Nav2's inflation layer with `inflation_radius` = {infl:.3} m (the robot's circumscribed radius plus its
  clearance margin) and a footprint or `robot_radius` of your robot; poinav planned with a lethal
  radius of {lethal:.3} m (half the robot's width).
- `keepout_mask.yaml`, `keepout_mask.pgm`: keepout filter mask, black (100) = never enter:
  BLOCKED doors and the stairs or ramps this robot cannot use.
- `speed_mask.yaml`, `speed_mask.pgm`: speed filter mask (mode scale, free_thresh 0,
  occupied_thresh 1): mask value = 100 - speed limit in percent of the maximum speed, for B-1
  hazard zones, B-2 narrow doors and zones, and C-1 multi-robot zones; 0 = no limit.
- `costmap_filter_info.yaml`: parameters of the two `costmap_filter_info_server` nodes (keepout:
  type 0, base 0, multiplier 1; speed: type 1 = percent, base 100, multiplier -1, so the filter
  value base + multiplier x mask is the speed limit in percent).
- `route_graph.geojson`: this storey's graph for `nav2_route` (see \"Route graphs\" below),
  every node in frame `{frame}`.

`topology.json` (here) is the whole building's room/door graph with every door's and
connection's status and reason for this profile.

## Route graphs

`route_graph.geojson` here is the whole building's graph ({bn} nodes, {be} directed edges of
which {bl} join storeys); each storey folder has its own. GeoJSON as nav2_route's
`GeoJsonGraphFileLoader` reads it: `Point` features are nodes, `MultiLineString` features
directed edges (every edge in both directions); ids are unique across the nodes and edges of a
file. Closed doors and stairs, ramps or lifts (BLOCKED for this robot, or without room for it)
have no node and no edge.

Nodes (`properties`): `id`; `frame`: `{frame}` in a storey's file, the storey's own frame
`{frame}_<folder>` (`-` written `_`, e.g. `{frame}_00_ground_floor`) in the building's file, where
`metadata.frame` repeats it; `metadata`:
- `kind`: `zone` (a space: the spot farthest from obstacles in it), `door` (doors and
  doorless openings), `landing` (where a stair, ramp or lift is entered on a storey) or
  `waypoint` (a corner of a collision-free path between them);
- `storey` (name) and `storey_index` (the number in the folder name), on every node;
- zones, doors and landings: `element` (IFC GlobalId), `name`, `roles` (POI role labels:
  `A-2`, `B-1`, `B-2`, `C-1`, ...); doors: `status` (AccessibilityStatus for this robot),
  `clear_width_m`, `doorless`; landings: `connection` (`stair`, `ramp`, `lift`), `status`,
  `to_floors` (the storeys it leads to).

Edges on a storey (`properties`):
- `id`, `startid`, `endid`;
- `cost`: seconds of driving at the role speeds, `cost = sum of l_k / (v_max * f_k)` over the
  edge cut into pieces `l_k` at most a quarter cell long, `f_k` the speed fraction (the slower
  of the zone's and the door's, by the roles below) under each piece and `v_max` =
  {vmax} m/s; on an edge of one speed, `length_m / abs_speed_limit`;
- `overridable: true` (nav2_route's edge scorers may replace the cost);
- `metadata.speed_limit`: percent of the robot's maximum speed, the slowest along the edge
  (B-1 hazard {hz}%, B-2 narrow doors and zones {nr}%, C-1 SPEED_REDUCTION {sr}%, C-1 YIELD
  {yl}%, C-1 PRIORITY_PASS {pp}%, C-1 without protocol {mr}%; 100 elsewhere). nav2_route's
  `AdjustSpeedLimit` operation (in the server's default `operations`) publishes it on
  `speed_limit` each time an edge is entered; it is not listed in `operations` because the
  server runs it on every edge change by itself and rejects it as a graph operation;
- `metadata.abs_speed_limit` (the same in m/s), `length_m`, `speed_roles` (the role labels
  that set the speeds along the edge), `zones` and `doors` (GlobalIds crossed, in order),
  `zone_names`, `door_names`;
- `operations`, on an edge that crosses a door (not a doorless opening; not the edge leaving
  that door's own node): `\"{od} <GlobalId>\": {{\"type\": \"{od}\", \"trigger\": \"ON_ENTER\",
  \"metadata\": {{\"door_id\": <GlobalId>, \"door_name\": ..., \"service_name\":
  \"/poinav/doors/d<GlobalId>/open\"}}}}` (in the service name `_` is written `_u` and `$` `_d`:
  ROS names allow neither `$` nor `__`).

Edges joining storeys (building file only), from a landing to a landing of the same stair,
ramp or lift: `cost` = its travel time in seconds (the same `poinav route` counts: climbing
or lift speed and waiting), `overridable: false` (a distance scorer would make a lift free),
`metadata`: `connection` (`stair`, `ramp`, `lift`), `element`, `name`, `status`,
`from_storey`, `to_storey`, `to_frame`, `speed_limit` 100; lifts also carry the operation
`\"{cl} <GlobalId>\": {{\"type\": \"{cl}\", \"trigger\": \"ON_ENTER\", \"metadata\": {{\"lift_id\", \"from_storey\",
\"to_storey\", \"service_name\": \"/poinav/lifts/l<GlobalId>/call\"}}}}`.

The route server must know every operation `type` in the graph: add the two as
`TriggerEvent` plugins (each calls the `std_srvs/srv/Trigger` service named in the
operation's `metadata.service_name`), keeping the defaults:

```yaml
route_server:
  ros__parameters:
    graph_filepath: <bundle>/00-.../route_graph.geojson
    operations: [\"AdjustSpeedLimit\", \"ReroutingService\", \"{od}\", \"{cl}\"]
    AdjustSpeedLimit:
      plugin: \"nav2_route::AdjustSpeedLimit\"
    ReroutingService:
      plugin: \"nav2_route::ReroutingService\"
    {od}:
      plugin: \"nav2_route::TriggerEvent\"
    {cl}:
      plugin: \"nav2_route::TriggerEvent\"
```

## Loading it (ROS 2, Nav2)

```sh
# the map
ros2 run nav2_map_server map_server --ros-args -p yaml_filename:=00-.../map.yaml
# the masks, each by its own map_server, and their filter info servers
ros2 run nav2_map_server map_server --ros-args -r __node:=keepout_mask_server \\
    -p yaml_filename:=00-.../keepout_mask.yaml -p topic_name:=keepout_filter_mask
ros2 run nav2_map_server map_server --ros-args -r __node:=speed_mask_server \\
    -p yaml_filename:=00-.../speed_mask.yaml -p topic_name:=speed_filter_mask
ros2 run nav2_map_server costmap_filter_info_server --ros-args -r __node:=keepout_filter_info_server \\
    --params-file 00-.../costmap_filter_info.yaml
ros2 run nav2_map_server costmap_filter_info_server --ros-args -r __node:=speed_filter_info_server \\
    --params-file 00-.../costmap_filter_info.yaml
```

(Bring each lifecycle node up with `ros2 lifecycle set <node> configure` and `activate`, or add
them to a lifecycle manager.) In the global and local costmaps add the filters:

```yaml
global_costmap:
  global_costmap:
    ros__parameters:
      filters: [\"keepout_filter\", \"speed_filter\"]
      keepout_filter:
        plugin: \"nav2_costmap_2d::KeepoutFilter\"
        enabled: True
        filter_info_topic: \"keepout_filter_info\"
      speed_filter:
        plugin: \"nav2_costmap_2d::SpeedFilter\"
        enabled: True
        filter_info_topic: \"speed_filter_info\"
        speed_limit_topic: \"speed_limit\"
```

and point the route server at a graph (`graph_filepath`, see \"Route graphs\" above).

Several storeys: Nav2 has one map at a time. Load another storey's map with the map server's
`load_map` service (`ros2 service call /map_server/load_map nav2_msgs/srv/LoadMap
\"{{map_url: <folder>/map.yaml}}\"`), and the masks and graph likewise; landings of stairs,
ramps and lifts are route-graph nodes with `metadata.kind = landing` and `to_floors`. The
building's `route_graph.geojson` plans across storeys in one search: its edges joining storeys
say which storey (`to_storey`, `to_frame`) to load when the robot takes them.
",
        infl = nav.floors.first().map_or(0.0, |f| f.grid.inflation_radius_m),
        free = options.free_thresh,
        frame = options.frame,
        bn = building_graph.nodes,
        be = building_graph.edges,
        bl = building_graph.storey_links,
        vmax = p.max_speed_m_s,
        hz = pct(nav.options.speeds.hazard),
        nr = pct(nav.options.speeds.narrow),
        sr = pct(nav.options.speeds.speed_reduction),
        yl = pct(nav.options.speeds.yield_protocol),
        pp = pct(nav.options.speeds.priority_pass),
        mr = pct(nav.options.speeds.multi_robot),
        od = crate::route_graph::OPEN_DOOR,
        cl = crate::route_graph::CALL_LIFT,
    );
    if !storeys.is_empty() {
        s.push_str(
            "
## Frames of the building graph

nav2_route moves every node into its route frame through TF when it loads a graph, and
refuses a graph whose frames TF does not know. The storey graphs are all in the map frame;
for the building's graph, publish each storey's frame from the route frame. The storeys share
the building's x and y, so only z, the storey's elevation, differs:

```sh
",
        );
        for st in storeys {
            let floor = st
                .folder
                .split('-')
                .next()
                .and_then(|i| i.parse::<usize>().ok())
                .and_then(|i| nav.building.floors.get(i));
            let _ = writeln!(
                s,
                "ros2 run tf2_ros static_transform_publisher --z {} --frame-id {} --child-frame-id {}  # {}",
                round6(floor.map_or(0.0, |f| f.elevation_m)),
                options.frame,
                crate::route_graph::storey_frame(options, &st.folder),
                st.floor
            );
        }
        s.push_str("```\n");
    }
    s
}
