//! Routes for the simulator's robots, planned with poinav-nav's router: the door path through
//! the floor's [`Topology`] (door sides decided once there) from the zone a robot starts in to
//! its target zone, and the waypoints that line the robot up with every door it passes.

use glam::DVec2;
use poinav_nav::building::passable;
use poinav_nav::door_status::door_verdict;
use poinav_nav::graph::zone_near;
use poinav_nav::zone_index::ZoneIndex;
use poinav_nav::{Building, DoorFrame, DoorIdx, Floor, Topology, ZoneIdx};
use poinav_roles::RobotProfile;

use crate::algorithm1::DOOR_CONFLICT_M;
use crate::neighbours::PointGrid;

/// A door as the robots steer through it.
#[derive(Debug, Clone, PartialEq)]
pub struct DoorWay {
    /// Centre.
    pub center: DVec2,
    /// Unit normal of the wall the door is in (the passage frame's normal, sign arbitrary);
    /// `None` for a door without a usable ring.
    pub axis: Option<DVec2>,
    /// Clear width, metres.
    pub width: f64,
}

/// A floor's doors and goals, and its topology for planning.
#[derive(Debug, Clone)]
pub struct Plan {
    /// Doors, in floor order.
    pub doors: Vec<DoorWay>,
    /// Per zone, the point a route to it ends at: its node in the topology (an interior point).
    pub goals: Vec<DVec2>,
    topology: Topology,
    zones: ZoneIndex,
    /// The doors' centres in cells as wide as the radius Algorithm 1 looks for doors in
    /// ([`DOOR_CONFLICT_M`]: a query visits two or three cells a side): the doors near a robot
    /// without a test of every door of the floor per robot and step ([`Plan::doors_near`]).
    centres: PointGrid,
}

impl Plan {
    /// The plan of `floor`.
    pub fn new(floor: &Floor) -> Plan {
        // The topology reads zones and doors only.
        let building = Building::single(Floor {
            name: floor.name.clone(),
            elevation_m: floor.elevation_m,
            obstacles: Vec::new(),
            doors: floor.doors.clone(),
            zones: floor.zones.clone(),
        });
        let topology = Topology::build(&building);
        let zones = ZoneIndex::new(floor);
        let goals = topology.zone_nodes[0]
            .iter()
            .map(|&n| topology.nodes[n].position())
            .collect();
        let doors = floor
            .doors
            .iter()
            .enumerate()
            .map(|(k, d)| DoorWay {
                center: d.center,
                axis: floor.door_frame_in(k, &zones).map(|f| f.normal),
                width: d.clear_width_m,
            })
            .collect();
        let mut centres = PointGrid::default();
        centres.rebuild(
            &floor.doors.iter().map(|d| d.center).collect::<Vec<_>>(),
            DOOR_CONFLICT_M,
        );
        Plan {
            doors,
            goals,
            topology,
            zones,
            centres,
        }
    }

    /// Calls `f` with every door whose centre lies within `r` of `p` (and some farther ones:
    /// callers test the distance), each once, in no particular order.
    pub fn doors_near(&self, p: DVec2, r: f64, f: impl FnMut(usize)) {
        self.centres.near(p, r, f);
    }

    /// The zone holding `p`, else the nearest within 0.5 m ([`zone_near`]).
    pub fn zone_at(&self, floor: &Floor, p: DVec2) -> Option<ZoneIdx> {
        zone_near(floor, &self.zones, p)
    }

    /// Doors on the shortest way from `from` to zone `to`, in order
    /// ([`Topology::door_path`]), through doors passable for `profile` by poinav-nav's status
    /// rule ([`door_verdict`]; PENDING_VALIDATION passable) and at least its width wide.
    pub fn door_path(
        &self,
        floor: &Floor,
        from: DVec2,
        to: ZoneIdx,
        profile: &RobotProfile,
    ) -> Option<Vec<DoorIdx>> {
        let start = self.zone_at(floor, from)?;
        self.topology.door_path(0, start, to, |k| {
            let d = &floor.doors[k.get()];
            passable(door_verdict(d, profile), true) && d.clear_width_m >= profile.width_m
        })
    }

    /// Waypoints from `from` through `doors` to zone `to`'s goal: before and after every door
    /// a point `lead` metres out on its axis, so the robot crosses it straight; with each, the
    /// clear width of the door it passes through (its centre and exit), `None` elsewhere.
    pub fn waypoints(
        &self,
        from: DVec2,
        doors: &[DoorIdx],
        to: ZoneIdx,
        lead: f64,
    ) -> (Vec<DVec2>, Vec<Option<f64>>) {
        let mut out = Vec::new();
        let mut widths = Vec::new();
        let mut prev = from;
        for &d in doors {
            let door = &self.doors[d.get()];
            // The next door's side is judged from where this one leads out: from its centre,
            // a door in the same wall lies on neither side.
            prev = match door.axis {
                Some(axis) => {
                    let n = if (door.center - prev).dot(axis) >= 0.0 {
                        axis
                    } else {
                        -axis
                    };
                    out.extend([door.center - n * lead, door.center, door.center + n * lead]);
                    widths.extend([None, Some(door.width), Some(door.width)]);
                    door.center + n * lead
                }
                None => {
                    out.push(door.center);
                    widths.push(Some(door.width));
                    door.center
                }
            };
        }
        out.push(self.goals[to.get()]);
        widths.push(None);
        (out, widths)
    }
}
