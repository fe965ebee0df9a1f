//! The fixed-step loop of one storey: every step (dt = 1/60 s by default) all robots sense on
//! the same snapshot, Algorithm 1 and the controllers decide, the state is recorded, then the
//! robots move one after the other in index order: turn, then translate with an exact time of
//! impact against walls and the other robots' boxes, sliding along what they hit. A move that
//! would still end overlapping is undone, so no robot ever tunnels or overlaps.

use glam::DVec2;
use poinav_nav::{DoorIdx, Floor, ZoneIdx};
use poinav_roles::runtime::Observation;
use poinav_roles::RobotProfile;

use rayon::prelude::*;

use crate::algorithm1::{self, Behaviour, Env, Mind, PendingClearance, Perception, Sink};
use crate::controller::{Command, ControlEvent, Controller, ControllerSpec, Ctx, Key, Mode};
use crate::error::SimError;
use crate::events::{Event, EventKind};
use crate::geometry::{overlap_segment, sweep_segment, wrap_angle, Obb, SKIN};
use crate::plan::Plan;
use crate::poi_db::{PoiDb, Start};
use crate::robot::{Brush, Limits, Robot, RobotState};
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
    /// The profile the POI database's Pset_RobotAccessibility values are for: the enrichment's
    /// (a scenario's `[building] profile`), not necessarily any robot's.
    pub poi_profile: RobotProfile,
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
            poi_profile: RobotProfile::paper(),
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

/// A robot's events of its perception in a step and the clearance measurement it made.
type Perceived = (Vec<Event>, Option<PendingClearance>);

/// Per-thread buffers of a move.
#[derive(Debug, Default)]
struct Scratch {
    edges: Vec<(DVec2, DVec2, Owner)>,
    segs: Vec<(DVec2, DVec2, u32)>,
    /// Edge indices of the last gather.
    ids: Vec<u32>,
    /// The robots the last gather looked at.
    robots: Vec<u32>,
}

/// The robots a move looked at: a few kept inline (the common case, no allocation per robot
/// and step), more on the heap.
#[derive(Debug, Clone)]
enum Near {
    Few(u8, [u32; 7]),
    Many(Vec<u32>),
}

impl Near {
    fn of(robots: &[u32]) -> Near {
        let mut few = [0u32; 7];
        match few.get_mut(..robots.len()) {
            Some(head) => {
                head.copy_from_slice(robots);
                Near::Few(robots.len() as u8, few)
            }
            None => Near::Many(robots.to_vec()),
        }
    }

    fn as_slice(&self) -> &[u32] {
        match self {
            Near::Few(n, few) => &few[..*n as usize],
            Near::Many(v) => v,
        }
    }
}

/// One robot's move in a step, before it is committed.
#[derive(Debug, Clone, Default)]
struct Move {
    pos: DVec2,
    heading: f64,
    omega: f64,
    actual_speed: f64,
    speed: f64,
    travelled: f64,
    footprint: Obb,
    /// The footprint's bounding box and the world's cells it covers.
    bounds: (DVec2, DVec2),
    cells: [u32; 4],
    touched: Vec<Owner>,
    /// Where the move tested its edges.
    looked: Region,
}

/// Candidate edges near box `b` widened by `reach`: static edges and other robots' sides.
fn gather(world: &World, me: usize, b: Obb, reach: f64, sc: &mut Scratch) {
    let (lo, hi) = b.aabb();
    let w = DVec2::splat(reach + 0.05);
    world.segments_near(lo - w, hi + w, &mut sc.ids, &mut sc.segs);
    world.robots_near(lo - w, hi + w, me, &mut sc.robots);
    sc.edges.clear();
    sc.edges
        .extend(sc.segs.iter().map(|&(a, b, o)| (a, b, Owner::Obstacle(o))));
    for &j in &sc.robots {
        let c = world.robot(j as usize).corners();
        for k in 0..4 {
            sc.edges.push((c[k], c[(k + 1) % 4], Owner::Robot(j)));
        }
    }
}

/// How far a move's tests may reach beyond the boxes they test, metres: a margin over the
/// rounding of the exact tests (about 1e-13 m at building coordinates), so an edge whose
/// bounding box lies farther than this from every box a move tested cannot have touched it.
const REACH_MARGIN: f64 = 1e-6;

/// The axis-aligned box holding every box a move tested edges against (turned footprints,
/// push-outs, the swept boxes of its translations): an edge apart from it played no part in
/// the move, so another robot's box moving from one place to another, both apart from it,
/// leaves the move as it was.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Region {
    lo: DVec2,
    hi: DVec2,
}

impl Default for Region {
    fn default() -> Region {
        Region::EMPTY
    }
}

impl Region {
    const EMPTY: Region = Region {
        lo: DVec2::splat(f64::INFINITY),
        hi: DVec2::splat(f64::NEG_INFINITY),
    };

    fn add(&mut self, lo: DVec2, hi: DVec2) {
        self.lo = self.lo.min(lo);
        self.hi = self.hi.max(hi);
    }

    /// True when the box `lo`-`hi` comes within twice [`REACH_MARGIN`] of the region: twice,
    /// so that a box that does not is farther than the margin from the region even after the
    /// rounding of its sides' end points (every edge of it is [`apart`] from every swept box).
    fn meets(&self, lo: DVec2, hi: DVec2) -> bool {
        let m = 2.0 * REACH_MARGIN;
        lo.x <= self.hi.x + m
            && hi.x >= self.lo.x - m
            && lo.y <= self.hi.y + m
            && hi.y >= self.lo.y - m
    }
}

/// True when the bounding box of edge `a`-`e` lies more than [`REACH_MARGIN`] from `lo`-`hi`.
#[inline]
fn apart(a: DVec2, e: DVec2, lo: DVec2, hi: DVec2) -> bool {
    let m = REACH_MARGIN;
    a.x.max(e.x) < lo.x - m
        || a.x.min(e.x) > hi.x + m
        || a.y.max(e.y) < lo.y - m
        || a.y.min(e.y) > hi.y + m
}

/// The deepest overlap of box `b` with `edges`; `b`'s bounds are added to `looked`.
fn deepest(
    edges: &[(DVec2, DVec2, Owner)],
    b: &Obb,
    looked: &mut Region,
) -> Option<(f64, DVec2, Owner)> {
    let corners = b.corners();
    let (lo, hi) = b.aabb();
    looked.add(lo, hi);
    let mut best: Option<(f64, DVec2, Owner)> = None;
    for &(a, e, o) in edges {
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

/// Pushes `b` out of what it overlaps (a few iterations); `None` when it cannot.
fn resolve(edges: &[(DVec2, DVec2, Owner)], mut b: Obb, looked: &mut Region) -> Option<DVec2> {
    for _ in 0..4 {
        match deepest(edges, &b, looked) {
            None => return Some(b.c),
            Some((d, n, _)) => b.c += n * (d + SKIN),
        }
    }
    deepest(edges, &b, looked).is_none().then_some(b.c)
}

/// Where robot `i` (`robot`) ends a step of `dt` with `action`, against the boxes `world`
/// holds.
fn plan_move(
    world: &World,
    robot: &Robot,
    i: usize,
    action: Command,
    dt: f64,
    sc: &mut Scratch,
) -> Move {
    let lim = &robot.limits;
    let v = lim.next_speed(robot.state.speed, action.v, dt);
    let omega = lim.turn(action.omega);
    if v == 0.0 && omega == 0.0 {
        if let Some(m) = standing(world, robot.state, (v, omega), *world.robot(i), dt, sc) {
            return m;
        }
    }
    turn_and_slide(world, robot, i, (v, omega), dt, sc)
}

/// [`plan_move`] at speed `v` and turn rate `omega` (the limits applied): the box turned, then
/// slid along what it meets.
fn turn_and_slide(
    world: &World,
    robot: &Robot,
    i: usize,
    (v, omega): (f64, f64),
    dt: f64,
    sc: &mut Scratch,
) -> Move {
    let st = robot.state;
    // The world holds robot i's footprint at its current pose.
    let start = *world.robot(i);
    gather(
        world,
        i,
        start,
        v.abs() * dt + world.robot_radius(i) * omega.abs() * dt,
        sc,
    );
    let edges = &sc.edges;
    let mut looked = Region::EMPTY;
    let mut heading = wrap_angle(st.heading + omega * dt);
    let mut pos = st.pos;
    // The box's axis at `heading` (its sine and cosine computed once: every box below is
    // the robot's footprint at `heading`, bit for bit as `footprint_at` builds it).
    let (hl, hw) = (start.hl, start.hw);
    let mut dir = start.ax;
    if heading != st.heading {
        let turned_dir = DVec2::from_angle(heading);
        let turned = Obb {
            c: pos,
            ax: turned_dir,
            hl,
            hw,
        };
        match resolve(edges, turned, &mut looked) {
            Some(p) => {
                pos = p;
                dir = turned_dir;
            }
            None => heading = st.heading,
        }
    } else if heading.to_bits() != st.heading.to_bits() {
        // -0 and 0: no turn, but the sine's sign differs.
        dir = DVec2::from_angle(heading);
    }
    let at = |pos: DVec2, ax: DVec2| Obb { c: pos, ax, hl, hw };
    let mut rem = dir * (v * dt);
    let mut touched: Vec<Owner> = Vec::new();
    for _ in 0..4 {
        if rem.length_squared() < 1e-24 {
            break;
        }
        let moving = at(pos, dir);
        let corners = moving.corners();
        // Only edges near the swept box can be hit (the sweep's contacts lie in it).
        let (lo, hi) = moving.aabb();
        let (lo, hi) = (lo.min(lo + rem), hi.max(hi + rem));
        looked.add(lo, hi);
        let mut hit: Option<(f64, DVec2, Owner)> = None;
        for &(a, b, o) in edges {
            if apart(a, b, lo, hi) {
                continue;
            }
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
    if deepest(edges, &at(pos, dir), &mut looked).is_some() {
        pos = st.pos;
        heading = st.heading;
        dir = start.ax;
    }
    let moved = pos - st.pos;
    let footprint = at(pos, dir);
    let bounds = footprint.aabb();
    Move {
        pos,
        heading,
        omega: wrap_angle(heading - st.heading) / dt,
        actual_speed: moved.length() / dt,
        speed: if touched.is_empty() {
            v
        } else {
            moved.dot(dir) / dt
        },
        travelled: moved.length(),
        footprint,
        bounds,
        cells: world.rect(bounds),
        touched,
        looked,
    }
}

/// The move of a robot that neither drives nor turns in this step (`v` and the turn zero), as
/// [`plan_move`] computes it, without looking at anything: such a robot stays where it is
/// whatever is around it (where it stands is free, or its move would be undone to it), so its
/// move looks at no edge and no robot, and no other robot's move in this step can change it.
/// Robots waiting at doors and in crowds do this most of the time. `None` when the heading
/// would change bits (wrapped, or -0 turned to 0): [`plan_move`] then turns the box.
fn standing(
    world: &World,
    st: crate::robot::RobotState,
    (v, omega): (f64, f64),
    start: Obb,
    dt: f64,
    sc: &mut Scratch,
) -> Option<Move> {
    let heading = wrap_angle(st.heading + omega * dt);
    if heading.to_bits() != st.heading.to_bits() {
        return None;
    }
    sc.robots.clear();
    let footprint = Obb { c: st.pos, ..start };
    let bounds = footprint.aabb();
    Some(Move {
        pos: st.pos,
        heading,
        omega: wrap_angle(heading - st.heading) / dt,
        actual_speed: 0.0,
        speed: v,
        travelled: 0.0,
        footprint,
        bounds,
        cells: world.rect(bounds),
        touched: Vec::new(),
        looked: Region::EMPTY,
    })
}

/// The fewest robots one task of the step's parallel passes takes (fewer are not worth a
/// hand-over to another thread).
pub(crate) const MIN_ROBOTS_PER_TASK: usize = 8;

/// A record's placeholder before a step writes it.
fn blank_record() -> StepRecord {
    StepRecord {
        step: 0,
        robot: 0,
        pos: DVec2::ZERO,
        heading: 0.0,
        speed: 0.0,
        omega: 0.0,
        action: Command::default(),
        rays: [crate::world::RayHit::NONE; 5],
        roles: crate::poi_db::RoleSet::default(),
        mode: Mode::Idle,
        zone: None,
        brush: Brush::paper(),
    }
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
    nav: Plan,
    world: World,
    db: PoiDb,
    robots: Vec<Robot>,
    minds: Vec<Mind>,
    /// Last step's minds, the memory the next step's copies reuse.
    next_minds: Vec<Mind>,
    ctrls: Vec<Controller>,
    opts: SimOptions,
    step: u64,
    events: Vec<Event>,
    observations: Vec<(String, Observation, f64)>,
    records: Vec<StepRecord>,
    current: Vec<StepRecord>,
    /// Scratch space of a step: the robots' navigation actions and events (kept from step
    /// to step for their memory).
    actions: Vec<Command>,
    step_events: Vec<Vec<Event>>,
    touching: Vec<Vec<Owner>>,
    arrived: Vec<bool>,
    /// Who waits for whom this step (remade before the robots perceive).
    waiters: crate::give_way::Waiters,
    readings: Vec<Reading>,
    perceptions: Vec<Perception>,
    /// Each robot's events and clearance measurement of its perception in this step (kept for
    /// their memory).
    perceived: Vec<Perceived>,
    /// Each robot's move of the step planned with its decision (against the boxes at the
    /// start of the step), before the moves are committed.
    guesses: Vec<Move>,
    /// The robots each of those moves looked at.
    nears: Vec<Near>,
    /// Every move planned again at its commit (the plain sequential loop; tests compare it).
    sequential_moves: bool,
    /// Per robot: the heading (its bits) its ray directions were last computed for, and
    /// those directions (five sines and cosines saved per robot and step while it keeps its
    /// heading).
    ray_dirs: Vec<(Option<u64>, [DVec2; 5])>,
}

fn zone_index(floor: &Floor, name: &str) -> Option<ZoneIdx> {
    floor
        .zones
        .iter()
        .position(|z| {
            z.name.as_deref() == Some(name) || z.long_name.as_deref() == Some(name) || z.id == name
        })
        .map(ZoneIdx::new)
}

impl<'f> Sim<'f> {
    /// Places the robots on `floor`; fails when a target zone is unknown or unreachable, or a
    /// robot starts overlapping a wall or another robot.
    pub fn new(
        floor: &'f Floor,
        setups: &[RobotSetup],
        opts: SimOptions,
    ) -> Result<Sim<'f>, SimError> {
        let nav = Plan::new(floor);
        let max_speed = setups
            .iter()
            .map(|s| s.profile.max_speed_m_s)
            .fold(0.0, f64::max);
        let slack = 2.0 * max_speed * opts.dt + 0.1;
        let mut world = World::new(floor, opts.cell_m, slack);
        let db = PoiDb::new(floor, opts.start, &opts.poi_profile);
        let mut robots = Vec::new();
        let mut ctrls = Vec::new();
        for s in setups {
            let limits = Limits::new(&s.profile, s.drive_force_n, s.brake_force_n);
            let global_id = s.global_id.clone().unwrap_or_else(|| {
                poinav_io::GlobalId::from_name("poinav-sim/robot", &s.name).to_string()
            });
            let robot = Robot {
                name: s.name.clone(),
                global_id,
                profile: s.profile.clone(),
                limits,
                priority: s.priority,
                giving_way: None,
                waits_for: None,
                arrived: false,
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
            let plan = |to: &str| -> Result<(Vec<DoorIdx>, ZoneIdx), SimError> {
                let z = zone_index(floor, to)
                    .ok_or_else(|| err(format!("zone `{to}` is not on floor `{}`", floor.name)))?;
                let doors = nav
                    .door_path(floor, s.start, z, &s.profile)
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
                        let key = Key::parse(*scheme, &k.key).map_err(|e| err(e.to_string()))?;
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
        let sim = Sim {
            floor,
            nav,
            world,
            db,
            robots,
            minds: vec![Mind::new(); n],
            next_minds: Vec::new(),
            ctrls,
            opts,
            step: 0,
            events: Vec::new(),
            observations: Vec::new(),
            records: Vec::new(),
            current: Vec::with_capacity(n),
            actions: Vec::with_capacity(n),
            step_events: Vec::new(),
            touching: vec![Vec::new(); n],
            arrived: vec![false; n],
            waiters: Default::default(),
            readings: Vec::with_capacity(n),
            perceptions: Vec::with_capacity(n),
            perceived: Vec::new(),
            guesses: Vec::with_capacity(n),
            nears: Vec::with_capacity(n),
            sequential_moves: false,
            ray_dirs: vec![(None, [DVec2::ZERO; 5]); n],
        };
        let mut sc = Scratch::default();
        for i in 0..n {
            let b = sim.robots[i].footprint();
            gather(&sim.world, i, b, 0.0, &mut sc);
            let mut looked = Region::EMPTY;
            if let Some((_, _, owner)) = deepest(&sc.edges, &b, &mut looked) {
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
    ///
    /// Parallel over robots (rayon) and bit-identical for any thread count: every robot senses
    /// and perceives from the same snapshot at once, then the database updates are applied in
    /// robot order (a robot that perceived after an earlier one changed a record's roles in
    /// this step perceives again, as the sequential loop would); the controllers decide at
    /// once; the moves are computed at once against the boxes at the start of the step and
    /// committed in robot order, a move redone when a robot near it moved before it.
    pub fn tick(&mut self, advance: bool) {
        let t = self.step as f64 * self.opts.dt;
        // The world holds every robot's footprint at its current pose (set when placed, then
        // by each committed move): only their grid is rebuilt.
        self.world.refresh_robots();
        self.sense_and_perceive(t);
        let mut actions = std::mem::take(&mut self.actions);
        let mut events = std::mem::take(&mut self.step_events);
        self.decide_all(t, &mut actions, &mut events, advance);
        for e in &mut events {
            self.events.append(e);
        }
        self.step_events = events;
        if self.opts.record {
            self.records.extend_from_slice(&self.current);
        }
        if advance {
            let (mut guesses, nears) = (
                std::mem::take(&mut self.guesses),
                std::mem::take(&mut self.nears),
            );
            self.commit_moves(&mut guesses, &nears, &actions, t);
            (self.guesses, self.nears) = (guesses, nears);
        }
        self.actions = actions;
        if !advance {
            return;
        }
        for r in &mut self.robots {
            r.state.brush.advance(self.opts.dt);
        }
        self.step += 1;
    }

    /// Every robot's five rays and Algorithm 1's perception of them (one parallel pass: a
    /// robot perceives its reading while it is in the cache, and the pool is called once less
    /// per step), then C-1 at the zone level.
    fn sense_and_perceive(&mut self, t: f64) {
        self.waiters.rebuild(&self.robots);
        let env = Env {
            floor: self.floor,
            nav: &self.nav,
            robots: &self.robots,
            world: &self.world,
            behaviour: &self.opts.behaviour,
            step: self.step,
            t,
            waiters: Some(&self.waiters),
        };
        // Robot `i` perceives into its perception, its events and its clearance measurement.
        let run = |i: usize,
                   db: &PoiDb,
                   mind: &mut Mind,
                   reading: &Reading,
                   p: &mut Perception,
                   (events, pending): &mut Perceived| {
            events.clear();
            let mut observations = Vec::new();
            let mut sink = Sink {
                events,
                observations: &mut observations,
            };
            (*p, *pending) = algorithm1::perceive(i, reading, &env, db, mind, &mut sink);
        };
        // Each robot perceives on a copy of its mind (the copies reuse last step's memory).
        let n = self.robots.len();
        let mut next = std::mem::take(&mut self.next_minds);
        next.resize_with(n, Mind::new);
        self.readings.resize(n, Reading::NONE);
        self.perceptions.resize_with(n, Perception::default);
        let mut perceived = std::mem::take(&mut self.perceived);
        perceived.resize_with(n, Default::default);
        let (db, minds, robots, world) = (&self.db, &self.minds, &self.robots, &self.world);
        next.par_iter_mut()
            .zip(self.readings.par_iter_mut())
            .zip(self.ray_dirs.par_iter_mut())
            .zip(self.perceptions.par_iter_mut())
            .zip(perceived.par_iter_mut())
            .enumerate()
            .with_min_len(MIN_ROBOTS_PER_TASK)
            .for_each(|(i, ((((mind, reading), (key, dirs)), p), out))| {
                let r = &robots[i];
                let h = r.state.heading;
                if *key != Some(h.to_bits()) {
                    *key = Some(h.to_bits());
                    *dirs = sensor::directions(h);
                }
                *reading = sensor::sense_along(world, i, r.state.pos, *dirs, RANGE_M);
                mind.clone_from(&minds[i]);
                run(i, db, mind, reading, p, out);
            });
        // The database's updates in robot order; after a change, the later robots perceive
        // again (as the sequential loop would have them).
        let mut changed = false;
        for (i, out) in perceived.iter_mut().enumerate() {
            if changed {
                next[i].clone_from(&self.minds[i]);
                run(
                    i,
                    &self.db,
                    &mut next[i],
                    &self.readings[i],
                    &mut self.perceptions[i],
                    out,
                );
            }
            let (events, pending) = out;
            let split = pending.map_or(events.len(), |c| c.events_before);
            self.events.extend(events.drain(..split));
            if let Some(c) = pending {
                let mut sink = Sink {
                    events: &mut self.events,
                    observations: &mut self.observations,
                };
                changed |= algorithm1::apply_clearance(i, c, &env, &mut self.db, &mut sink);
            }
            self.events.append(events);
        }
        self.perceived = perceived;
        std::mem::swap(&mut self.minds, &mut next);
        self.next_minds = next;
        let nearest: Vec<Option<(u32, f64)>> = self.perceptions.iter().map(|p| p.nearest).collect();
        let mut sink = Sink {
            events: &mut self.events,
            observations: &mut self.observations,
        };
        algorithm1::zone_coordination(&env, &self.minds, &nearest, &mut self.db, &mut sink);
    }

    /// Every robot's controller command shaped by Algorithm 1 into `actions`, its events of
    /// this step into `events` (one list per robot) and its record into the step's records;
    /// with `plan`, also its move against the boxes at the start of the step into `guesses`
    /// (in the same pass: one call into the pool less per step).
    fn decide_all(
        &mut self,
        t: f64,
        actions: &mut Vec<Command>,
        events: &mut Vec<Vec<Event>>,
        plan: bool,
    ) {
        let step = self.step;
        let n = self.robots.len();
        actions.resize(n, Command::default());
        events.resize_with(n, Vec::new);
        let (nav, floor, behaviour) = (&self.nav, self.floor, &self.opts.behaviour);
        let (readings, perceptions) = (&self.readings, &self.perceptions);
        let (world, dt) = (&self.world, self.opts.dt);
        // Written in place: a record is about 350 bytes, a move about 200.
        self.current.resize_with(n, blank_record);
        self.guesses.resize_with(n, Move::default);
        self.nears.resize(n, Near::of(&[]));
        self.ctrls
            .par_iter_mut()
            .zip(self.minds.par_iter_mut())
            .zip(self.robots.par_iter_mut())
            .zip(self.arrived.par_iter_mut())
            .zip(actions.par_iter_mut())
            .zip(events.par_iter_mut())
            .zip(self.current.par_iter_mut())
            .zip(self.guesses.par_iter_mut())
            .zip(self.nears.par_iter_mut())
            .enumerate()
            .with_min_len(MIN_ROBOTS_PER_TASK)
            .for_each_init(
                Scratch::default,
                |sc,
                 (
                    i,
                    (
                        (((((((ctrl, mind), robot), arrived), action_out), events), record), guess),
                        near,
                    ),
                )| {
                    let p = &perceptions[i];
                    let ctx = Ctx {
                        t,
                        pos: robot.state.pos,
                        heading: robot.state.heading,
                        speed: robot.state.speed,
                        limits: &robot.limits,
                        left_ref: p.left_ref,
                        right_ref: p.right_ref,
                        nav,
                    };
                    let mut control = Vec::new();
                    let cmd = ctrl.command(&ctx, &mut control);
                    let mode = ctrl.mode();
                    let action =
                        algorithm1::decide(p, cmd, robot, mind, t, mode == Mode::Keys, behaviour);
                    *action_out = action;
                    // Shared with the others for the next step, as the pose is.
                    robot.giving_way = mind.give_way.map(|g| g.other);
                    robot.waits_for = mind.waits_for;
                    robot.arrived = *arrived;
                    for c in &control {
                        let kind = match c {
                            ControlEvent::Key(key, down) => EventKind::Key {
                                key: key.clone(),
                                down: *down,
                            },
                            ControlEvent::BrushToggle => {
                                let b = &mut robot.state.brush;
                                b.on = !b.on;
                                EventKind::Brush { on: b.on }
                            }
                        };
                        events.push(Event {
                            step,
                            t,
                            robot: robot.name.clone(),
                            kind,
                        });
                    }
                    if mode == Mode::Arrived && !*arrived {
                        *arrived = true;
                        if let Some(z) = ctrl.target {
                            let zr = &floor.zones[z.get()];
                            events.push(Event {
                                step,
                                t,
                                robot: robot.name.clone(),
                                kind: EventKind::Arrived {
                                    zone: zr.id.to_string(),
                                    name: zr.name.clone(),
                                },
                            });
                        }
                    }
                    if plan {
                        *guess = plan_move(world, robot, i, action, dt, sc);
                        *near = Near::of(&sc.robots);
                    }
                    *record = StepRecord {
                        step,
                        robot: i as u32,
                        pos: robot.state.pos,
                        heading: robot.state.heading,
                        speed: robot.state.actual_speed,
                        omega: robot.state.omega,
                        action,
                        rays: readings[i].rays,
                        roles: p.roles,
                        mode,
                        zone: mind.zone,
                        brush: robot.state.brush,
                    };
                },
            );
    }

    /// Moves every robot with `actions` (what [`Sim::tick`] does with the moves planned with the
    /// decisions; the tests move robots with chosen commands): computed in parallel against the
    /// boxes at the start of the step, committed in index order; a robot whose neighbours (the
    /// robots its move looked at) already moved in this step, from or to where its move tested
    /// edges ([`Region`]), is moved again against their new boxes, so the result is the
    /// sequential one.
    #[cfg(test)]
    fn move_all(&mut self, actions: &[Command], t: f64) {
        let this = &*self;
        let (mut guesses, nears): (Vec<Move>, Vec<Near>) = (0..actions.len())
            .into_par_iter()
            .with_min_len(MIN_ROBOTS_PER_TASK)
            .map_init(Scratch::default, |sc, i| {
                let m = this.plan_move(i, actions[i], sc);
                (m, Near::of(&sc.robots))
            })
            .unzip();
        self.commit_moves(&mut guesses, &nears, actions, t);
    }

    /// Commits the moves `guesses` (each robot's, in index order, planned against the boxes at
    /// the start of the step, with the robots it looked at), redoing those whose neighbours
    /// moved where they looked.
    fn commit_moves(&mut self, guesses: &mut [Move], nears: &[Near], actions: &[Command], t: f64) {
        // Per robot already moved in this step: its box's bounding box before the move.
        let mut moved: Vec<Option<(DVec2, DVec2)>> = vec![None; actions.len()];
        let mut sc = Scratch::default();
        for (i, (guess, near)) in guesses.iter_mut().zip(nears).enumerate() {
            let mut redone;
            // Redone only when a neighbour that moved was, or now is, where the move looked.
            let redo = self.sequential_moves
                || near.as_slice().iter().any(|&j| {
                    moved[j as usize].is_some_and(|(lo, hi)| {
                        let (nlo, nhi) = self.world.robot_aabb(j as usize);
                        guess.looked.meets(lo, hi) || guess.looked.meets(nlo, nhi)
                    })
                });
            let m = if redo {
                redone = self.plan_move(i, actions[i], &mut sc);
                &mut redone
            } else {
                guess
            };
            if m.footprint != *self.world.robot(i) {
                moved[i] = Some(self.world.robot_aabb(i));
            }
            self.commit_move(i, m, t);
        }
    }

    /// Where robot `i` ends this step with `action`, against the robots' current boxes.
    fn plan_move(&self, i: usize, action: Command, sc: &mut Scratch) -> Move {
        plan_move(&self.world, &self.robots[i], i, action, self.opts.dt, sc)
    }

    /// Places robot `i` where its move `m` ends (its contacts taken out of it).
    fn commit_move(&mut self, i: usize, m: &mut Move, t: f64) {
        let r = &mut self.robots[i];
        r.state.pos = m.pos;
        r.state.heading = m.heading;
        r.state.omega = m.omega;
        r.state.actual_speed = m.actual_speed;
        r.state.speed = m.speed;
        r.state.odometer += m.travelled;
        // `m.footprint` is the footprint at the new pose.
        self.world.place_robot(i, m.footprint, m.bounds, m.cells);
        for o in &m.touched {
            if !self.touching[i].contains(o) {
                let (with, class) = match *o {
                    Owner::Obstacle(k) => {
                        let ob = &self.floor.obstacles[k as usize];
                        (ob.id.to_string(), ob.class.clone())
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
        // The touched list changes hands: the move's memory becomes the robot's contacts.
        std::mem::swap(&mut self.touching[i], &mut m.touched);
    }

    /// The records of the last [`Sim::tick`], one per robot in index order (empty before the
    /// first), whether or not [`SimOptions::record`] keeps them all.
    pub fn last_records(&self) -> &[StepRecord] {
        &self.current
    }

    /// The names the trace writes for indices.
    pub fn names(&self) -> Names {
        let f = self.floor;
        Names {
            robots: self.robots.iter().map(|r| r.name.clone()).collect(),
            robot_ids: self.robots.iter().map(|r| r.global_id.clone()).collect(),
            obstacles: f.obstacles.iter().map(|o| o.id.to_string()).collect(),
            obstacle_classes: f.obstacles.iter().map(|o| o.class.clone()).collect(),
            doors: f.doors.iter().map(|d| d.id.to_string()).collect(),
            zones: f
                .zones
                .iter()
                .map(|z| z.name.clone().unwrap_or_else(|| z.id.to_string()))
                .collect(),
        }
    }

    /// Each robot's half length and half width.
    pub fn sizes(&self) -> Vec<(f64, f64)> {
        self.robots
            .iter()
            .map(|r| (r.limits.half_length, r.limits.half_width))
            .collect()
    }

    /// Ends the run.
    pub fn finish(self) -> RunData {
        let names = self.names();
        let sizes = self.sizes();
        RunData {
            records: self.records,
            events: self.events,
            observations: self.observations,
            names,
            db: self.db,
            steps: self.step,
            dt: self.opts.dt,
            routes: self.ctrls.iter().map(|c| c.waypoints().to_vec()).collect(),
            sizes,
        }
    }
}

#[cfg(test)]
#[path = "step_tests.rs"]
mod tests;
