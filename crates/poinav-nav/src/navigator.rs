//! A building prepared for one robot profile: an inflated grid per storey, the topology, each
//! door's and connection's status, whether each door can be crossed in the grid, and the
//! speed fractions of every zone and door. Routes, the audit and the Nav2 bundle start here.
//! Each storey is rasterised only where there is something to navigate: cropped to its own
//! extent ([`crate::extent::for_grid`]), and a storey without spaces or doors not at all (an
//! empty grid; [`Navigator::skipped`] says why).

use poinav_roles::{AccessibilityStatus, RobotProfile};
use serde::Serialize;

use crate::building::{passable, Building};
use crate::graph::{NodeKind, Topology};
use crate::grid::{GridOptions, InflationOptions, NavGrid};
use crate::speed::RoleSpeeds;
use crate::NavError;

/// Everything that decides grids, routes and audits besides the profile.
#[derive(Debug, Clone, PartialEq, Default, Serialize)]
pub struct NavOptions {
    /// Rasterisation.
    pub grid: GridOptions,
    /// Inflation.
    pub inflation: InflationOptions,
    /// Speed fractions per role.
    pub speeds: RoleSpeeds,
}

/// Per storey: the grid and speed fractions.
#[derive(Debug, Clone)]
pub struct FloorNav {
    /// The inflated grid.
    pub grid: NavGrid,
    /// Speed fraction per zone (index as in `Floor::zones`).
    pub zone_speed: Vec<f64>,
    /// Speed fraction per door.
    pub door_speed: Vec<f64>,
}

impl FloorNav {
    /// Speed fraction on cell `i` (the slower of its zone and door).
    #[inline]
    pub fn speed(&self, i: usize) -> f64 {
        let g = &self.grid.occupancy;
        let mut f = 1.0;
        if let Some(z) = g.zone[i] {
            f = self.zone_speed[z.get()];
        }
        if let Some(d) = g.door[i] {
            f = f.min(self.door_speed[d.get()]);
        }
        f
    }
}

/// A building prepared for one profile.
#[derive(Debug, Clone)]
pub struct Navigator<'a> {
    /// The building.
    pub building: &'a Building,
    /// The profile.
    pub profile: RobotProfile,
    /// The options.
    pub options: NavOptions,
    /// The topology.
    pub topology: Topology,
    /// Per storey (a storey with nothing to navigate gets an empty grid of unknown cells).
    pub floors: Vec<FloorNav>,
    /// Per storey: why it has nothing to navigate ([`crate::extent::nothing_to_navigate`]),
    /// else `None`.
    pub nothing_to_navigate: Vec<Option<String>>,
    /// Per topology node: status and reason for the profile.
    pub status: Vec<(AccessibilityStatus, String)>,
    /// Per topology node: door nodes whether the robot's centre can cross the door in the
    /// inflated grid; `true` for other nodes.
    pub grid_passable: Vec<bool>,
    /// Per topology node: passable by status and (doors) in the grid.
    pub open: Vec<bool>,
    /// The elements rasterising and the graph gave up on ([`crate::bounds`]), storey by
    /// storey: their areas are unknown, such doors closed and no entrances.
    pub gave_up: Vec<crate::bounds::GaveUp>,
}

/// What a [`Navigator`] owns: all of it but the building it borrows
/// ([`Navigator::into_parts`], [`Navigator::from_parts`]).
#[derive(Debug)]
pub struct NavParts {
    profile: RobotProfile,
    options: NavOptions,
    topology: Topology,
    floors: Vec<FloorNav>,
    nothing_to_navigate: Vec<Option<String>>,
    status: Vec<(AccessibilityStatus, String)>,
    grid_passable: Vec<bool>,
    open: Vec<bool>,
    gave_up: Vec<crate::bounds::GaveUp>,
}

impl NavParts {
    /// The options the navigator was made with.
    pub fn options(&self) -> &NavOptions {
        &self.options
    }
}

impl<'a> Navigator<'a> {
    /// Rasterises and inflates every storey and works out statuses for `profile`.
    pub fn new(
        building: &'a Building,
        profile: &RobotProfile,
        options: &NavOptions,
    ) -> Result<Navigator<'a>, NavError> {
        Navigator::with_progress(building, profile, options, &crate::progress::none)
    }

    /// [`Navigator::new`], telling `progress` about each storey rasterised and the graph.
    pub fn with_progress(
        building: &'a Building,
        profile: &RobotProfile,
        options: &NavOptions,
        progress: crate::progress::Progress<'_>,
    ) -> Result<Navigator<'a>, NavError> {
        use crate::progress::Phase;
        options.speeds.validate()?;
        progress(Phase::Graph, 0, 1);
        let mut topology = Topology::build_with(building, &options.grid.bounds);
        let status = topology.statuses(building, profile);
        let mut floors = Vec::with_capacity(building.floors.len());
        let n = building.floors.len();
        progress(Phase::Rasterising, 0, n);
        for (fi, floor) in building.floors.iter().enumerate() {
            let grid_options = GridOptions {
                at_ground: building.at_ground(fi),
                ..options.grid.clone()
            };
            // Only where there is something to navigate (the storey as a whole keeps its
            // obstacles for everything else).
            let cropped = crate::extent::for_grid(floor, &grid_options);
            let grid = NavGrid::build(&cropped, profile, &grid_options, &options.inflation)?;
            let zone_speed = floor
                .zones
                .iter()
                .map(|z| options.speeds.zone(z).0)
                .collect();
            let door_speed = floor
                .doors
                .iter()
                .zip(&grid.occupancy.doors)
                .map(|(d, g)| options.speeds.door(d, g.status).0)
                .collect();
            floors.push(FloorNav {
                grid,
                zone_speed,
                door_speed,
            });
            progress(Phase::Rasterising, floors.len(), n);
        }
        // The graph: what each door node's grid says, node by node.
        let total = topology.nodes.len();
        progress(Phase::Graph, 0, total);
        // A door whose side without a zone is walled in is no entrance (the grid found it).
        // A door the grid gave up on is no entrance and not passable either.
        for d in &mut topology.doors {
            let g = &floors[d.floor].grid.occupancy.doors[d.door.get()];
            d.walled_in = g.walled_in;
            d.gave_up |= g.gave_up;
        }
        for (fi, f) in floors.iter().enumerate() {
            topology.add_open_boundaries(fi, &f.grid, 2);
        }
        let grid_passable: Vec<bool> = topology
            .nodes
            .iter()
            .map(|n| {
                let passable = match n.door() {
                    Some(d) => {
                        let outside = topology.door(n.floor, d).and_then(|d| d.outside_side());
                        floors[n.floor].grid.door_passable(d.get(), outside)
                    }
                    None => true,
                };
                if n.kind() == NodeKind::Door {
                    progress(Phase::Graph, n.id + 1, total);
                }
                passable
            })
            .collect();
        progress(Phase::Graph, total, total);
        let pending = options.grid.pending_doors_open;
        let open = status
            .iter()
            .zip(&grid_passable)
            .map(|((s, _), g)| passable(*s, pending) && *g)
            .collect();
        let gave_up = floors
            .iter()
            .flat_map(|f| f.grid.occupancy.gave_up.iter().cloned())
            .collect();
        let nothing_to_navigate = building
            .floors
            .iter()
            .map(crate::extent::nothing_to_navigate)
            .collect();
        Ok(Navigator {
            building,
            profile: profile.clone(),
            options: options.clone(),
            topology,
            floors,
            nothing_to_navigate,
            status,
            grid_passable,
            open,
            gave_up,
        })
    }

    /// Everything but the building borrow, for a caller that keeps a navigator between calls
    /// on one building (the Python package's cache) and lends it back with
    /// [`Navigator::from_parts`]. Moves, no copies.
    pub fn into_parts(self) -> NavParts {
        let Navigator {
            building: _,
            profile,
            options,
            topology,
            floors,
            nothing_to_navigate,
            status,
            grid_passable,
            open,
            gave_up,
        } = self;
        NavParts {
            profile,
            options,
            topology,
            floors,
            nothing_to_navigate,
            status,
            grid_passable,
            open,
            gave_up,
        }
    }

    /// The navigator [`Navigator::into_parts`] took apart, on `building` again (the same
    /// building it was made for: the parts index its storeys, doors and zones).
    pub fn from_parts(building: &'a Building, parts: NavParts) -> Navigator<'a> {
        let NavParts {
            profile,
            options,
            topology,
            floors,
            nothing_to_navigate,
            status,
            grid_passable,
            open,
            gave_up,
        } = parts;
        Navigator {
            building,
            profile,
            options,
            topology,
            floors,
            nothing_to_navigate,
            status,
            grid_passable,
            open,
            gave_up,
        }
    }

    /// The storeys with nothing to navigate, with why, in order.
    pub fn skipped(&self) -> Vec<crate::extent::SkippedStorey> {
        self.building
            .floors
            .iter()
            .zip(&self.nothing_to_navigate)
            .filter_map(|(f, why)| {
                why.as_ref().map(|reason| crate::extent::SkippedStorey {
                    floor: f.name.clone(),
                    reason: reason.clone(),
                })
            })
            .collect()
    }

    /// The topology as JSON with this profile's statuses (open boundaries included).
    pub fn topology_json(&self) -> serde_json::Value {
        self.topology.to_json(self.building, &self.profile)
    }

    /// Why node `n` (a door or landing) cannot be passed: its status and reason, or that the
    /// inflated grid leaves no room for the robot's centre.
    pub fn closed_reason(&self, n: usize) -> String {
        let (s, why) = &self.status[n];
        let node = &self.topology.nodes[n];
        let gave_up = node
            .door()
            .is_some_and(|d| self.topology.door(node.floor, d).is_some_and(|d| d.gave_up));
        if gave_up {
            format!(
                "{} ({why}) but given up on: a size bound was passed, so it is taken as closed",
                s.label()
            )
        } else if !passable(*s, self.options.grid.pending_doors_open) {
            format!("{}: {why}", s.label())
        } else if !self.grid_passable[n] {
            let blockers = self.in_the_way(n);
            let more = if blockers.is_empty() {
                String::new()
            } else {
                format!("; in the way: {}", blockers.join(", "))
            };
            format!(
                "{} ({why}) but no free path through it in the grid inflated by {:.3} m{more}",
                s.label(),
                self.floors[self.topology.nodes[n].floor]
                    .grid
                    .lethal_radius_m
            )
        } else {
            format!("{}: {why}", s.label())
        }
    }

    /// What stands in the way of door node `n` in the grid (`IfcStairFlight 2Ab2...`, at most
    /// three, nearest first): the obstacles other than the door's own body that come within
    /// the robot's lethal radius of the way its centre would take through the passage, from
    /// three cells before one face to three cells beyond the other. Empty for other nodes.
    pub fn in_the_way(&self, n: usize) -> Vec<String> {
        let node = &self.topology.nodes[n];
        let Some(d) = node.door() else {
            return Vec::new();
        };
        let (floor, grid) = (
            &self.building.floors[node.floor],
            &self.floors[node.floor].grid,
        );
        let Some(door) = grid.occupancy.doors.get(d.get()) else {
            return Vec::new();
        };
        let (Some(frame), Some(half_width)) = (door.frame, door.passage_half_width_m) else {
            return Vec::new();
        };
        let res = grid.occupancy.resolution_m;
        let lethal = grid.lethal_radius_m;
        let way = frame.rectangle(
            (half_width - lethal).max(res / 2.0),
            frame.half_depth + 3.0 * res,
        );
        let own = &floor.doors[d.get()].id;
        let mut found: Vec<(f64, String)> = floor
            .obstacles
            .iter()
            .filter(|o| &o.id != own)
            .filter_map(|o| {
                // An element past the vertex bound stands as its bounding box, as in the grid.
                let vertices: usize = o.rings.iter().map(|r| r.len()).sum();
                let boxed: Vec<crate::Ring>;
                let rings = if vertices > crate::bounds::ELEMENT_VERTICES {
                    boxed = crate::polygon::bounds_of(o.rings.iter().flat_map(|r| r.iter()))
                        .map(|(lo, hi)| crate::polygon::rect(lo.x, lo.y, hi.x, hi.y))
                        .into_iter()
                        .collect();
                    &boxed
                } else {
                    &o.rings
                };
                let d = rings
                    .iter()
                    .map(|r| crate::polygon::ring_distance(r, &way))
                    .fold(f64::INFINITY, f64::min);
                (d < lethal - 1e-6).then(|| (d, format!("{} {}", o.class, o.id)))
            })
            .collect();
        // One entry per element (an element may stand as several obstacles), nearest first.
        found.sort_by(|a, b| a.1.cmp(&b.1).then_with(|| a.0.total_cmp(&b.0)));
        found.dedup_by(|a, b| a.1 == b.1);
        found.sort_by(|a, b| a.0.total_cmp(&b.0).then_with(|| a.1.cmp(&b.1)));
        found.into_iter().take(3).map(|(_, s)| s).collect()
    }
}
