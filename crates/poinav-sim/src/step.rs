//! The fixed-step loop of one storey: every step (dt = 1/60 s by default) all robots sense on
//! the same snapshot, Algorithm 1 and the controllers decide, the state is recorded, then the
//! robots move one after the other in index order: turn, then translate with an exact time of
//! impact against walls and the other robots' boxes, sliding along what they hit. A move that
//! would still end overlapping is undone, so no robot ever tunnels or overlaps.

use glam::DVec2;
use poinav_nav::Floor;
use poinav_poi::runtime::Observation;
use poinav_poi::RobotProfile;

use crate::algorithm1::{self, Behaviour, Env, Mind, Perception, Sink};
use crate::controller::{Command, ControlEvent, Controller, ControllerSpec, Ctx, Key, Mode};
use crate::error::SimError;
use crate::events::{Event, EventKind};
use crate::geometry::{overlap_segment, sweep_segment, wrap_angle, Obb, SKIN};
use crate::poi_db::{PoiDb, Start};
use crate::robot::{Brush, Limits, Robot, RobotState};
use crate::route::NavGraph;
use crate::sensor::{self, Reading, RANGE_M};
use crate::trace::{Names, StepRecord};
use crate::world::World;

/// The paper's control rate: 60 Hz.
pub const DT: f64 = 1.0 / 60.0;

/// One robot as a run starts it.
#[derive(Debug, Clone)]
pub struct RobotSetup {
    /// Name.
    pub name: String,
    /// GlobalId reported to other robots' sensors (default derived from the name).
    pub global_id: Option<String>,
    /// Profile.
    pub profile: RobotProfile,
    /// Start position.
    pub start: DVec2,
    /// Start heading, degrees.
    pub heading_deg: f64,
    /// Controller.
    pub controller: ControllerSpec,
    /// Priority for YIELD and PRIORITY_PASS (higher first).
    pub priority: i64,
    /// Brush running at the start.
    pub brush_on: bool,
    /// Drive force, N (acceleration = force / mass).
    pub drive_force_n: f64,
    /// Brake force, N.
    pub brake_force_n: f64,
}

/// How to run.
#[derive(Debug, Clone)]
pub struct SimOptions {
    /// Step, seconds.
    pub dt: f64,
    /// Grid cell size of the world index, metres.
    pub cell_m: f64,
    /// How the POI database starts.
    pub start: Start,
    /// Behaviour constants.
    pub behaviour: Behaviour,
    /// Keep a record per step and robot.
    pub record: bool,
}

impl Default for SimOptions {
    fn default() -> Self {
        SimOptions {
            dt: DT,
            cell_m: 1.0,
            start: Start::Keep,
            behaviour: Behaviour::default(),
            record: true,
        }
    }
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Owner {
    Obstacle(u32),
    Robot(u32),
}

/// What a finished run leaves.
#[derive(Debug, Clone)]
pub struct RunData {
    /// Records, step-major, robots in index order.
    pub records: Vec<StepRecord>,
    /// Events in the order they happened.
    pub events: Vec<Event>,
    /// Observations that changed a POI record: (GlobalId, observation, time).
    pub observations: Vec<(String, Observation, f64)>,
    /// Names for the trace.
    pub names: Names,
    /// The POI database at the end.
    pub db: PoiDb,
    /// Steps taken.
    pub steps: u64,
    /// The step length.
    pub dt: f64,
    /// Each robot's waypoints (empty unless it follows a route).
    pub routes: Vec<Vec<DVec2>>,
    /// Each robot's half length and half width.
    pub sizes: Vec<(f64, f64)>,
}

/// A running simulation of one storey.
#[derive(Debug)]
pub struct Sim<'f> {
    floor: &'f Floor,
    nav: NavGraph,
    world: World,
    db: PoiDb,
    robots: Vec<Robot>,
    minds: Vec<Mind>,
    ctrls: Vec<Controller>,
    opts: SimOptions,
    step: u64,
    events: Vec<Event>,
    observations: Vec<(String, Observation, f64)>,
    records: Vec<StepRecord>,
    touching: Vec<Vec<Owner>>,
    arrived: Vec<bool>,
    readings: Vec<Reading>,
    perceptions: Vec<Perception>,
    edges: Vec<(DVec2, DVec2, Owner)>,
    seg_scratch: Vec<(DVec2, DVec2, u32)>,
    robot_scratch: Vec<u32>,
}

fn zone_index(floor: &Floor, name: &str) -> Option<u32> {
    floor
        .zones
        .iter()
        .position(|z| {
            z.name.as_deref() == Some(name) || z.long_name.as_deref() == Some(name) || z.id == name
        })
        .map(|i| i as u32)
}

impl<'f> Sim<'f> {
    /// Places the robots on `floor`; fails when a target zone is unknown or unreachable, or a
    /// robot starts overlapping a wall or another robot.
    pub fn new(
        floor: &'f Floor,
        setups: &[RobotSetup],
        opts: SimOptions,
    ) -> Result<Sim<'f>, SimError> {
        let nav = NavGraph::new(floor);
        let max_speed = setups
            .iter()
            .map(|s| s.profile.max_speed_m_s)
            .fold(0.0, f64::max);
        let slack = 2.0 * max_speed * opts.dt + 0.1;
        let mut world = World::new(floor, opts.cell_m, slack);
        let db = PoiDb::new(floor, opts.start);
        let mut robots = Vec::new();
        let mut ctrls = Vec::new();
        for s in setups {
            let limits = Limits::new(&s.profile, s.drive_force_n, s.brake_force_n);
            let global_id = s.global_id.clone().unwrap_or_else(|| {
                poinav_ifc::GlobalId::from_name("poinav-sim/robot", &s.name).to_string()
            });
            let robot = Robot {
                name: s.name.clone(),
                global_id,
                profile: s.profile.clone(),
                limits,
                priority: s.priority,
                state: RobotState {
                    pos: s.start,
                    heading: wrap_angle(s.heading_deg.to_radians()),
                    speed: 0.0,
                    actual_speed: 0.0,
                    omega: 0.0,
                    odometer: 0.0,
                    brush: Brush {
                        on: s.brush_on,
                        ..Brush::paper()
                    },
                },
            };
            let err = |message: String| SimError::Setup {
                robot: s.name.clone(),
                message,
            };
            let cruise = |v: Option<f64>| {
                v.unwrap_or(robot.limits.max_speed)
                    .min(robot.limits.max_speed)
            };
            let plan = |to: &str| -> Result<(Vec<u32>, u32), SimError> {
                let z = zone_index(floor, to)
                    .ok_or_else(|| err(format!("zone `{to}` is not on floor `{}`", floor.name)))?;
                let doors = nav
                    .door_path(s.start, z, s.profile.width_m)
                    .ok_or_else(|| {
                        err(format!(
                            "no route from the start to `{to}` through doors at least {} m wide",
                            s.profile.width_m
                        ))
                    })?;
                Ok((doors, z))
            };
            let ctrl = match &s.controller {
                ControllerSpec::Idle => Controller::idle(),
                ControllerSpec::Route { to, speed_m_s } => {
                    let (doors, z) = plan(to)?;
                    Controller::route(
                        &nav,
                        s.start,
                        &doors,
                        z,
                        cruise(*speed_m_s),
                        robot.limits.half_length + 0.5,
                    )
                }
                ControllerSpec::WallFollow {
                    side,
                    distance_m,
                    to,
                    speed_m_s,
                } => {
                    let target = to.as_deref().map(plan).transpose()?;
                    Controller::wall_follow(*side, *distance_m, cruise(*speed_m_s), target)
                }
                ControllerSpec::Keys { scheme, script } => {
                    let mut keys = Vec::new();
                    for k in script {
                        let key = Key::parse(*scheme, &k.key).map_err(err)?;
                        keys.push((k.t, key, k.down, k.key.clone()));
                    }
                    Controller::keys(keys)
                }
            };
            robots.push(robot);
            ctrls.push(ctrl);
        }
        let boxes: Vec<Obb> = robots.iter().map(|r| r.footprint()).collect();
        world.set_robots(&boxes);
        let n = robots.len();
        let mut sim = Sim {
            floor,
            nav,
            world,
            db,
            robots,
            minds: vec![Mind::new(); n],
            ctrls,
            opts,
            step: 0,
            events: Vec::new(),
            observations: Vec::new(),
            records: Vec::new(),
            touching: vec![Vec::new(); n],
            arrived: vec![false; n],
            readings: Vec::with_capacity(n),
            perceptions: Vec::with_capacity(n),
            edges: Vec::new(),
            seg_scratch: Vec::new(),
            robot_scratch: Vec::new(),
        };
        for i in 0..n {
            let b = sim.robots[i].footprint();
            sim.gather(i, b, 0.0);
            if let Some(owner) = sim.overlapping(&b) {
                return Err(SimError::Setup {
                    robot: sim.robots[i].name.clone(),
                    message: format!(
                        "starts overlapping {} at ({:.3}, {:.3})",
                        sim.owner_name(owner),
                        b.c.x,
                        b.c.y
                    ),
                });
            }
        }
        Ok(sim)
    }

    /// The robots.
    pub fn robots(&self) -> &[Robot] {
        &self.robots
    }

    /// Steps taken.
    pub fn steps(&self) -> u64 {
        self.step
    }

    /// The floor it runs on.
    pub fn floor(&self) -> &'f Floor {
        self.floor
    }

    /// The time of the next step, seconds.
    pub fn time(&self) -> f64 {
        self.step as f64 * self.opts.dt
    }

    /// The readings of the last [`Sim::tick`], one per robot (empty before the first).
    pub fn readings(&self) -> &[Reading] {
        &self.readings
    }

    /// The roles robot `i` perceived in the last [`Sim::tick`] (elements sensed, its zone, its
    /// own C-2).
    pub fn roles(&self, i: usize) -> Option<crate::poi_db::RoleSet> {
        self.perceptions.get(i).map(|p| p.roles)
    }

    /// Robot `i`'s controller mode.
    pub fn mode(&self, i: usize) -> Option<Mode> {
        self.ctrls.get(i).map(|c| c.mode())
    }

    /// Events so far, in the order they happened.
    pub fn events(&self) -> &[Event] {
        &self.events
    }

    /// Takes the events so far out of the simulation (a live run that never finishes keeps
    /// its memory bounded this way; [`Sim::finish`] then returns only later ones).
    pub fn take_events(&mut self) -> Vec<Event> {
        std::mem::take(&mut self.events)
    }

    /// A key of robot `i` pressed or released live (see [`Controller::press`]): it takes effect
    /// at the next step. False when `i` is not a robot or the press changes nothing.
    pub fn press(&mut self, i: usize, key: Key, down: bool, name: &str) -> bool {
        let t = self.time();
        match self.ctrls.get_mut(i) {
            Some(c) => c.press(t, key, down, name),
            None => false,
        }
    }

    /// The POI database.
    pub fn db(&self) -> &PoiDb {
        &self.db
    }

    fn owner_name(&self, o: Owner) -> String {
        match o {
            Owner::Obstacle(i) => {
                let ob = &self.floor.obstacles[i as usize];
                format!("{} {}", ob.class, ob.id)
            }
            Owner::Robot(j) => format!("robot {}", self.robots[j as usize].name),
        }
    }

    /// Senses, decides and records at the current time, then (when `advance`) moves every
    /// robot one step.
    pub fn tick(&mut self, advance: bool) {
        let t = self.step as f64 * self.opts.dt;
        let n = self.robots.len();
        let boxes: Vec<Obb> = self.robots.iter().map(|r| r.footprint()).collect();
        self.world.set_robots(&boxes);
        self.readings.clear();
        for (i, r) in self.robots.iter().enumerate() {
            self.readings.push(sensor::sense(
                &self.world,
                i,
                r.state.pos,
                r.state.heading,
                RANGE_M,
            ));
        }
        let env = Env {
            floor: self.floor,
            nav: &self.nav,
            robots: &self.robots,
            behaviour: &self.opts.behaviour,
            step: self.step,
            t,
        };
        let mut sink = Sink {
            events: &mut self.events,
            observations: &mut self.observations,
        };
        self.perceptions.clear();
        for i in 0..n {
            let p = algorithm1::perceive(
                i,
                &self.readings[i],
                &env,
                &mut self.db,
                &mut self.minds[i],
                &mut sink,
            );
            self.perceptions.push(p);
        }
        let nearest: Vec<Option<(u32, f64)>> = self.perceptions.iter().map(|p| p.nearest).collect();
        algorithm1::zone_coordination(&env, &self.minds, &nearest, &mut self.db, &mut sink);
        let mut actions = Vec::with_capacity(n);
        let mut control = Vec::new();
        for i in 0..n {
            let r = &self.robots[i];
            let p = &self.perceptions[i];
            let ctx = Ctx {
                t,
                pos: r.state.pos,
                heading: r.state.heading,
                speed: r.state.speed,
                limits: &r.limits,
                left_ref: p.left_ref,
                right_ref: p.right_ref,
                nav: &self.nav,
            };
            control.clear();
            let cmd = self.ctrls[i].command(&ctx, &mut control);
            let mode = self.ctrls[i].mode();
            let action = algorithm1::decide(
                p,
                cmd,
                r,
                &mut self.minds[i],
                t,
                mode == Mode::Keys,
                &self.opts.behaviour,
            );
            actions.push(action);
            for c in &control {
                let kind = match c {
                    ControlEvent::Key(key, down) => EventKind::Key {
                        key: key.clone(),
                        down: *down,
                    },
                    ControlEvent::BrushToggle => {
                        let b = &mut self.robots[i].state.brush;
                        b.on = !b.on;
                        EventKind::Brush { on: b.on }
                    }
                };
                self.events.push(Event {
                    step: self.step,
                    t,
                    robot: self.robots[i].name.clone(),
                    kind,
                });
            }
            if mode == Mode::Arrived && !self.arrived[i] {
                self.arrived[i] = true;
                if let Some(z) = self.ctrls[i].target {
                    let zr = &self.floor.zones[z as usize];
                    self.events.push(Event {
                        step: self.step,
                        t,
                        robot: self.robots[i].name.clone(),
                        kind: EventKind::Arrived {
                            zone: zr.id.clone(),
                            name: zr.name.clone(),
                        },
                    });
                }
            }
            if self.opts.record {
                let r = &self.robots[i];
                self.records.push(StepRecord {
                    step: self.step,
                    robot: i as u32,
                    pos: r.state.pos,
                    heading: r.state.heading,
                    speed: r.state.actual_speed,
                    omega: r.state.omega,
                    action,
                    rays: self.readings[i].rays,
                    roles: p.roles,
                    mode,
                    zone: self.minds[i].zone,
                    brush: r.state.brush,
                });
            }
        }
        if !advance {
            return;
        }
        for (i, action) in actions.into_iter().enumerate() {
            self.move_robot(i, action, t);
            self.robots[i].state.brush.advance(self.opts.dt);
        }
        self.step += 1;
    }

    /// Candidate edges near box `b` widened by `reach`: static edges and other robots' sides.
    fn gather(&mut self, me: usize, b: Obb, reach: f64) {
        let (lo, hi) = b.aabb();
        let w = DVec2::splat(reach + 0.05);
        self.world
            .segments_near(lo - w, hi + w, &mut self.seg_scratch);
        self.world
            .robots_near(lo - w, hi + w, me, &mut self.robot_scratch);
        self.edges.clear();
        self.edges.extend(
            self.seg_scratch
                .iter()
                .map(|&(a, b, o)| (a, b, Owner::Obstacle(o))),
        );
        for &j in &self.robot_scratch {
            let c = self.world.robot(j as usize).corners();
            for k in 0..4 {
                self.edges.push((c[k], c[(k + 1) % 4], Owner::Robot(j)));
            }
        }
    }

    fn deepest(&self, b: &Obb) -> Option<(f64, DVec2, Owner)> {
        let corners = b.corners();
        let (lo, hi) = b.aabb();
        let mut best: Option<(f64, DVec2, Owner)> = None;
        for &(a, e, o) in &self.edges {
            // Bounding boxes apart: no overlap (the exact test is the costly part).
            if a.x.max(e.x) <= lo.x
                || a.x.min(e.x) >= hi.x
                || a.y.max(e.y) <= lo.y
                || a.y.min(e.y) >= hi.y
            {
                continue;
            }
            if let Some((d, n)) = overlap_segment(&corners, a, e) {
                if best.is_none_or(|(bd, _, _)| d > bd) {
                    best = Some((d, n, o));
                }
            }
        }
        best
    }

    fn overlapping(&self, b: &Obb) -> Option<Owner> {
        self.deepest(b).map(|x| x.2)
    }

    /// Pushes `b` out of what it overlaps (a few iterations); `None` when it cannot.
    fn resolve(&self, mut b: Obb) -> Option<DVec2> {
        for _ in 0..4 {
            match self.deepest(&b) {
                None => return Some(b.c),
                Some((d, n, _)) => b.c += n * (d + SKIN),
            }
        }
        self.deepest(&b).is_none().then_some(b.c)
    }

    fn move_robot(&mut self, i: usize, action: Command, t: f64) {
        let dt = self.opts.dt;
        let (lim, st) = (&self.robots[i].limits, self.robots[i].state);
        let v = lim.next_speed(st.speed, action.v, dt);
        let omega = lim.turn(action.omega);
        let start = self.robots[i].footprint();
        self.gather(i, start, v.abs() * dt + start.radius() * omega.abs() * dt);
        let mut heading = wrap_angle(st.heading + omega * dt);
        let mut pos = st.pos;
        if heading != st.heading {
            let turned = self.robots[i].footprint_at(pos, heading);
            match self.resolve(turned) {
                Some(p) => pos = p,
                None => heading = st.heading,
            }
        }
        let dir = DVec2::from_angle(heading);
        let mut rem = dir * (v * dt);
        let mut touched: Vec<Owner> = Vec::new();
        for _ in 0..4 {
            if rem.length_squared() < 1e-24 {
                break;
            }
            let corners = self.robots[i].footprint_at(pos, heading).corners();
            let mut hit: Option<(f64, DVec2, Owner)> = None;
            for &(a, b, o) in &self.edges {
                if let Some((s, n)) = sweep_segment(&corners, rem, a, b) {
                    if hit.is_none_or(|(hs, _, _)| s < hs) {
                        hit = Some((s, n, o));
                    }
                }
            }
            match hit {
                None => {
                    pos += rem;
                    break;
                }
                Some((s, n, o)) => {
                    pos += rem * s + n * SKIN;
                    if !touched.contains(&o) {
                        touched.push(o);
                    }
                    rem *= 1.0 - s;
                    let into = rem.dot(n);
                    if into < 0.0 {
                        rem -= n * into;
                    }
                }
            }
        }
        if self
            .overlapping(&self.robots[i].footprint_at(pos, heading))
            .is_some()
        {
            pos = st.pos;
            heading = st.heading;
        }
        let moved = pos - st.pos;
        let r = &mut self.robots[i];
        r.state.pos = pos;
        r.state.heading = heading;
        r.state.omega = wrap_angle(heading - st.heading) / dt;
        r.state.actual_speed = moved.length() / dt;
        r.state.speed = if touched.is_empty() {
            v
        } else {
            moved.dot(DVec2::from_angle(heading)) / dt
        };
        r.state.odometer += moved.length();
        let b = r.footprint();
        self.world.update_robot(i, b);
        for o in &touched {
            if !self.touching[i].contains(o) {
                let (with, class) = match *o {
                    Owner::Obstacle(k) => {
                        let ob = &self.floor.obstacles[k as usize];
                        (ob.id.clone(), ob.class.clone())
                    }
                    Owner::Robot(j) => (
                        self.robots[j as usize].global_id.clone(),
                        "Robot".to_string(),
                    ),
                };
                self.events.push(Event {
                    step: self.step,
                    t,
                    robot: self.robots[i].name.clone(),
                    kind: EventKind::Contact { with, class },
                });
            }
        }
        self.touching[i] = touched;
    }

    /// Ends the run.
    pub fn finish(self) -> RunData {
        let f = self.floor;
        let names = Names {
            robots: self.robots.iter().map(|r| r.name.clone()).collect(),
            robot_ids: self.robots.iter().map(|r| r.global_id.clone()).collect(),
            obstacles: f.obstacles.iter().map(|o| o.id.clone()).collect(),
            obstacle_classes: f.obstacles.iter().map(|o| o.class.clone()).collect(),
            doors: f.doors.iter().map(|d| d.id.clone()).collect(),
            zones: f
                .zones
                .iter()
                .map(|z| z.name.clone().unwrap_or_else(|| z.id.clone()))
                .collect(),
        };
        RunData {
            records: self.records,
            events: self.events,
            observations: self.observations,
            names,
            db: self.db,
            steps: self.step,
            dt: self.opts.dt,
            routes: self.ctrls.iter().map(|c| c.waypoints().to_vec()).collect(),
            sizes: self
                .robots
                .iter()
                .map(|r| (r.limits.half_length, r.limits.half_width))
                .collect(),
        }
    }
}
