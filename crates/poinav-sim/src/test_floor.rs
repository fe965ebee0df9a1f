//! Tiny hand-built floors, robots and one robot's view of them for the simulator core's unit
//! tests (Algorithm 1, the step, the controllers, the expectations).

use glam::DVec2;
use poinav_nav::{Floor, FloorDoor, FloorObstacle, FloorZone, ObstacleKind, Ring};
use poinav_roles::{CoordinationProtocol, RobotProfile, Role};

use crate::algorithm1::{self, Behaviour, Env, Mind, PendingClearance, Perception, Sink};
use crate::events::Event;
use crate::geometry::Obb;
use crate::plan::Plan;
use crate::poi_db::{PoiDb, Start};
use crate::robot::{Brush, Limits, Robot, RobotState};
use crate::sensor::{self, RANGE_M};
use crate::world::World;
pub(crate) use poinav_nav::polygon::rect;

/// The test building's floors as `poinav_bridge::prepare` makes them for the scenarios the unit
/// tests run (the simulator cannot make them: it knows no IFC), by scenario name and variant.
/// The bridge's unit test `sim_fixtures_are_what_prepare_makes` keeps them current
/// (`POINAV_BLESS=1` rewrites them).
const PREPARED: &[(&str, Option<&str>, &str)] = &[
    ("doors", None, include_str!("../testdata/doors.floor.json")),
    (
        "doorway",
        Some("door-0.80"),
        include_str!("../testdata/doorway-door-0.80.floor.json"),
    ),
    ("yield", None, include_str!("../testdata/yield.floor.json")),
];

/// The floor `poinav_bridge::prepare` makes for `scenario`'s `variant` (one of [`PREPARED`]).
pub(crate) fn prepared(scenario: &crate::Scenario, variant: Option<&str>) -> Floor {
    let (_, _, json) = PREPARED
        .iter()
        .find(|(n, v, _)| *n == scenario.name && *v == variant)
        .unwrap_or_else(|| panic!("no prepared floor for `{}` {variant:?}", scenario.name));
    serde_json::from_str(json).expect("a floor")
}

/// The test building with three rooms a side (the "doors" floor of [`PREPARED`]).
pub(crate) fn doors_floor() -> Floor {
    let scenario = crate::Scenario::from_toml(
        "name = \"doors\"\nduration_s = 1.0\n[building]\ndemo = { rooms_per_side = 3 }\n[[robot]]\nname = \"R\"\nstart = { x = 1.0, y = 1.0 }\ncontroller = { kind = \"idle\" }\n",
        "doors.toml",
        std::path::Path::new("."),
    )
    .unwrap();
    prepared(&scenario, None)
}

/// A wall with one ring.
pub(crate) fn wall(id: &str, ring: Ring) -> FloorObstacle {
    FloorObstacle {
        id: id.into(),
        class: "IfcWall".into(),
        kind: ObstacleKind::Structure,
        rings: vec![ring],
        roles: vec![Role::Avoidance, Role::PathGuidance],
    }
}

/// A zone with `roles` and an optional C-1 coordination.
pub(crate) fn zone(
    id: &str,
    ring: Ring,
    roles: Vec<Role>,
    coordination: Option<(f64, CoordinationProtocol)>,
) -> FloorZone {
    FloorZone {
        id: id.into(),
        name: Some(id.into()),
        long_name: None,
        ring,
        roles,
        coordination,
    }
}

/// A wall along y = 0..t from x = -5 to 5 with a door of clear width `w` centred on x = 0
/// (PENDING, requiring 0.90 m), the room `room` below (y in -4..0) and the hall `hall` above.
pub(crate) fn door_floor(w: f64, t: f64) -> Floor {
    Floor {
        name: "test".into(),
        elevation_m: 0.0,
        obstacles: vec![
            wall("wall-left", rect(-5.0, 0.0, -w / 2.0, t)),
            wall("wall-right", rect(w / 2.0, 0.0, 5.0, t)),
            wall("back", rect(-5.0, -4.2, 5.0, -4.0)),
        ],
        doors: vec![FloorDoor {
            id: "door".into(),
            name: Some("Door".into()),
            ring: rect(-w / 2.0, 0.0, w / 2.0, t),
            center: DVec2::new(0.0, t / 2.0),
            clear_width_m: w,
            classified_width_m: None,
            blocked: None,
            roles: vec![Role::Transition],
            spaces: None,
            doorless: false,
            terrain: false,
        }],
        zones: vec![
            zone(
                "room",
                rect(-5.0, -4.0, 5.0, 0.0),
                vec![Role::Destination],
                None,
            ),
            zone(
                "hall",
                rect(-5.0, t, 5.0, t + 4.0),
                vec![Role::PathGuidance],
                None,
            ),
        ],
    }
}

/// An open hall 20 x 10 m (x in -10..10, y in -5..5) without walls; a C-1 zone with
/// `coordination` when given.
pub(crate) fn open_floor(coordination: Option<(f64, CoordinationProtocol)>) -> Floor {
    let roles = if coordination.is_some() {
        vec![Role::MultiRobotZone]
    } else {
        vec![Role::PathGuidance]
    };
    Floor {
        name: "open".into(),
        elevation_m: 0.0,
        obstacles: Vec::new(),
        doors: Vec::new(),
        zones: vec![zone(
            "hall",
            rect(-10.0, -5.0, 10.0, 5.0),
            roles,
            coordination,
        )],
    }
}

/// The paper robot (0.70 x 0.80 m, margin 0.10 m, 5 m/s, 5 kg braking with 100 N: 20 m/s²) at
/// `pos`, heading `heading` (radians), at rest.
pub(crate) fn robot(name: &str, pos: DVec2, heading: f64, priority: i64) -> Robot {
    let profile = RobotProfile::paper();
    Robot {
        name: name.into(),
        global_id: format!("id-{name}"),
        limits: Limits::new(&profile, 50.0, 100.0),
        profile,
        priority,
        giving_way: None,
        waits_for: None,
        arrived: false,
        state: RobotState {
            pos,
            heading,
            speed: 0.0,
            actual_speed: 0.0,
            omega: 0.0,
            odometer: 0.0,
            brush: Brush::paper(),
        },
    }
}

/// The run-wide things Algorithm 1 reads, built for `robots` on `floor` as a step builds them.
pub(crate) struct View<'f> {
    pub floor: &'f Floor,
    pub nav: Plan,
    pub world: World,
    pub db: PoiDb,
    pub robots: Vec<Robot>,
    pub behaviour: Behaviour,
    pub events: Vec<Event>,
}

impl<'f> View<'f> {
    /// The view with the database as the floor says (`Start::Keep`).
    pub fn new(floor: &'f Floor, robots: Vec<Robot>) -> View<'f> {
        let mut world = World::new(floor, 1.0, 0.2);
        let boxes: Vec<Obb> = robots.iter().map(Robot::footprint).collect();
        world.set_robots(&boxes);
        View {
            floor,
            nav: Plan::new(floor),
            world,
            db: PoiDb::new(floor, Start::Keep, &RobotProfile::paper()),
            robots,
            behaviour: Behaviour::default(),
            events: Vec::new(),
        }
    }

    /// Moves robot `i` (and its box in the world).
    pub fn place(&mut self, i: usize, pos: DVec2, heading: f64) {
        self.robots[i].state.pos = pos;
        self.robots[i].state.heading = heading;
        let boxes: Vec<Obb> = self.robots.iter().map(Robot::footprint).collect();
        self.world.set_robots(&boxes);
    }

    /// Robot `me` senses and runs Algorithm 1's per-element part; events go to `self.events`.
    pub fn perceive(
        &mut self,
        me: usize,
        mind: &mut Mind,
    ) -> (Perception, Option<PendingClearance>) {
        let r = &self.robots[me].state;
        let reading = sensor::sense(&self.world, me, r.pos, r.heading, RANGE_M);
        let env = Env {
            floor: self.floor,
            nav: &self.nav,
            robots: &self.robots,
            world: &self.world,
            behaviour: &self.behaviour,
            step: 0,
            t: 0.0,
            waiters: None,
        };
        let mut observations = Vec::new();
        let mut sink = Sink {
            events: &mut self.events,
            observations: &mut observations,
        };
        algorithm1::perceive(me, &reading, &env, &self.db, mind, &mut sink)
    }
}

impl View<'_> {
    /// Applies robot `me`'s clearance measurement to the database (rule R5).
    pub fn apply(&mut self, me: usize, pending: &PendingClearance) -> bool {
        let env = Env {
            floor: self.floor,
            nav: &self.nav,
            robots: &self.robots,
            world: &self.world,
            behaviour: &self.behaviour,
            step: 0,
            t: 0.0,
            waiters: None,
        };
        let mut observations = Vec::new();
        let mut sink = Sink {
            events: &mut self.events,
            observations: &mut observations,
        };
        algorithm1::apply_clearance(me, pending, &env, &mut self.db, &mut sink)
    }
}

/// The paper robot as a run starts it (default forces: 50 N drive, 100 N brake), brush off.
pub(crate) fn setup(
    name: &str,
    start: DVec2,
    heading_deg: f64,
    controller: crate::controller::ControllerSpec,
) -> crate::step::RobotSetup {
    crate::step::RobotSetup {
        name: name.into(),
        global_id: None,
        profile: RobotProfile::paper(),
        start,
        heading_deg,
        controller,
        priority: 0,
        brush_on: false,
        drive_force_n: 50.0,
        brake_force_n: 100.0,
    }
}
