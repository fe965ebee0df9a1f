//! The live simulation: one thread owns the storeys' floors and a [`poinav_sim::Sim`] on one of
//! them, steps it at the
//! fixed step paced to real time, applies the pages' commands between steps and publishes
//! every step's state as one JSON text that all pages receive. A page can switch the storey: the
//! simulation then starts again there with that storey's robots.
//!
//! A slow page never slows the simulation: states go through a bounded broadcast channel and
//! a page that falls behind skips to the newest ones.

use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::mpsc::{self, Receiver, Sender};
use std::sync::{Arc, Mutex};
use std::thread::JoinHandle;
use std::time::{Duration, Instant};

use poinav_nav::Floor;
use poinav_sim::controller::Key;
use poinav_sim::sensor::RAY_DEG;
use poinav_sim::world::Target;
use poinav_sim::{RobotSetup, Sim, SimOptions};
use serde_json::{json, Value};
use tokio::sync::broadcast;

use crate::error::ViewerError;

/// How many recent POI events a page gets when it connects.
const EVENT_HISTORY: usize = 200;
/// States buffered per page before a slow page starts skipping.
const STATE_BUFFER: usize = 32;

/// A command for the simulation thread.
#[derive(Debug, Clone, PartialEq)]
pub(crate) enum Command {
    /// A key of a robot.
    Key {
        robot: usize,
        key: Key,
        down: bool,
        name: String,
    },
    /// Toggle a robot's brush.
    Brush { robot: usize },
    /// Pause or resume.
    Pause(bool),
    /// Start again.
    Reset,
    /// Simulate on storey `index` (one with robots) from its robots' start poses.
    Storey(usize),
}

/// What a page gets when it connects: the newest state and the recent events.
#[derive(Debug, Default)]
struct Snapshot {
    state: Option<Arc<str>>,
    events: std::collections::VecDeque<Value>,
}

/// The running simulation thread; stopped when dropped.
#[derive(Debug)]
pub struct Live {
    commands: Mutex<Sender<Command>>,
    states: broadcast::Sender<Arc<str>>,
    snapshot: Arc<Mutex<Snapshot>>,
    stop: Arc<AtomicBool>,
    thread: Option<JoinHandle<()>>,
    /// Robots on the storey simulated now.
    robots: Arc<AtomicUsize>,
    /// Robots per storey (0: the storey cannot be chosen).
    per_storey: Vec<usize>,
}

impl Live {
    /// Starts the simulation on `storeys[current]` (each storey a floor and its robots);
    /// fails (before any step) when that storey's robots cannot be placed.
    pub fn start(
        storeys: Vec<(Floor, Vec<RobotSetup>)>,
        current: usize,
        options: SimOptions,
    ) -> Result<Live, ViewerError> {
        let options = SimOptions {
            record: false,
            ..options
        };
        let (floor, robots) = storeys.get(current).ok_or_else(|| {
            ViewerError::Serve(format!(
                "storey {current} does not exist ({} storeys)",
                storeys.len()
            ))
        })?;
        // Checked here so the caller gets the error, not a dead thread.
        Sim::new(floor, robots, options.clone())?;
        let count = Arc::new(AtomicUsize::new(robots.len()));
        let per_storey = storeys.iter().map(|(_, r)| r.len()).collect();
        let (tx, rx) = mpsc::channel();
        let (states, _) = broadcast::channel(STATE_BUFFER);
        let snapshot = Arc::new(Mutex::new(Snapshot::default()));
        let stop = Arc::new(AtomicBool::new(false));
        let thread = {
            let channels = Channels {
                rx,
                states: states.clone(),
                snapshot: snapshot.clone(),
                stop: stop.clone(),
                robots: count.clone(),
            };
            std::thread::Builder::new()
                .name("poinav-sim".into())
                .spawn(move || run(storeys, current, options, channels))
                .map_err(|e| {
                    ViewerError::Serve(format!("cannot start the simulation thread: {e}"))
                })?
        };
        Ok(Live {
            commands: Mutex::new(tx),
            states,
            snapshot,
            stop,
            thread: Some(thread),
            robots: count,
            per_storey,
        })
    }

    /// Number of robots on the storey simulated now.
    pub fn robots(&self) -> usize {
        self.robots.load(Ordering::SeqCst)
    }

    /// Number of robots on each storey (0 where none could be placed).
    pub fn robots_per_storey(&self) -> &[usize] {
        &self.per_storey
    }

    pub(crate) fn send(&self, c: Command) {
        if let Ok(tx) = self.commands.lock() {
            // The thread only ends when `Live` is dropped, so a failed send cannot be acted on.
            let _ = tx.send(c);
        }
    }

    /// A receiver of every following state (JSON text).
    pub fn subscribe(&self) -> broadcast::Receiver<Arc<str>> {
        self.states.subscribe()
    }

    /// The newest state and the recent events (`{"type":"events",...}`), for a new page.
    pub fn snapshot(&self) -> (Option<Arc<str>>, String) {
        let s = self.snapshot.lock().unwrap_or_else(|e| e.into_inner());
        let events: Vec<&Value> = s.events.iter().collect();
        (
            s.state.clone(),
            json!({"type": "events", "events": events}).to_string(),
        )
    }
}

impl Drop for Live {
    fn drop(&mut self) {
        self.stop.store(true, Ordering::Relaxed);
        if let Some(t) = self.thread.take() {
            let _ = t.join();
        }
    }
}

fn state_json(sim: &Sim<'_>, storey: usize, paused: bool, events: &[Value]) -> String {
    let floor = sim.floor();
    let readings = sim.readings();
    let robots: Vec<Value> = sim
        .robots()
        .iter()
        .enumerate()
        .map(|(i, r)| {
            let rays: Vec<Value> = readings
                .get(i)
                .map(|rd| {
                    rd.rays
                        .iter()
                        .enumerate()
                        .map(|(k, ray)| {
                            let (hit, class) = match ray.target {
                                Target::None => (Value::Null, Value::Null),
                                Target::Obstacle(o) => {
                                    let ob = &floor.obstacles[o as usize];
                                    (json!(ob.id), json!(ob.class))
                                }
                                Target::Robot(j) => {
                                    (json!(sim.robots()[j as usize].name), json!("Robot"))
                                }
                            };
                            json!({"deg": RAY_DEG[k], "d": round(ray.dist, 4), "hit": hit, "class": class})
                        })
                        .collect()
                })
                .unwrap_or_default();
            let roles: Vec<&str> = sim
                .roles(i)
                .map(|r| r.roles().map(|r| r.label()).collect())
                .unwrap_or_default();
            json!({
                "name": r.name,
                "x": round(r.state.pos.x, 4),
                "y": round(r.state.pos.y, 4),
                "heading_deg": round(r.state.heading.to_degrees(), 3),
                "speed": round(r.state.actual_speed, 4),
                "mode": sim.mode(i).map(|m| m.label()),
                "brush": {"on": r.state.brush.on, "angle_deg": round(r.state.brush.angle_deg, 2)},
                "roles": roles,
                "rays": rays,
            })
        })
        .collect();
    json!({
        "type": "state",
        "storey": storey,
        "step": sim.steps(),
        "t": round(sim.time(), 4),
        "paused": paused,
        "robots": robots,
        "events": events,
    })
    .to_string()
}

fn round(v: f64, decimals: i32) -> f64 {
    let f = 10f64.powi(decimals);
    (v * f).round() / f
}

/// The simulation thread's ends of the channels.
struct Channels {
    rx: Receiver<Command>,
    states: broadcast::Sender<Arc<str>>,
    snapshot: Arc<Mutex<Snapshot>>,
    stop: Arc<AtomicBool>,
    robots: Arc<AtomicUsize>,
}

fn run(
    storeys: Vec<(Floor, Vec<RobotSetup>)>,
    mut current: usize,
    options: SimOptions,
    channels: Channels,
) {
    let Channels {
        rx,
        states,
        snapshot,
        stop,
        robots,
    } = channels;
    let dt = options.dt;
    let start = |i: usize| {
        let (floor, setups) = storeys.get(i)?;
        if setups.is_empty() {
            return None;
        }
        Sim::new(floor, setups, options.clone()).ok()
    };
    let Some(mut sim) = start(current) else {
        return;
    };
    let mut paused = false;
    let mut clock = Instant::now();
    let mut done: u64 = 0;
    while !stop.load(Ordering::Relaxed) {
        while let Ok(c) = rx.try_recv() {
            match c {
                Command::Key {
                    robot,
                    key,
                    down,
                    name,
                } => {
                    // A key sent for the storey before a switch may name a robot this storey
                    // does not have.
                    if robot < sim.robots().len() {
                        sim.press(robot, key, down, &name);
                    }
                }
                Command::Brush { robot } => {
                    if robot < sim.robots().len() {
                        sim.press(robot, Key::Brush, true, "Brush");
                    }
                }
                Command::Pause(p) => paused = p,
                Command::Reset => {
                    if let Some(s) = start(current) {
                        sim = s;
                    }
                }
                Command::Storey(i) => {
                    if let Some(s) = start(i) {
                        sim = s;
                        current = i;
                        robots.store(sim.robots().len(), Ordering::SeqCst);
                    }
                }
            }
        }
        if !paused {
            sim.tick(true);
        }
        let events: Vec<Value> = sim
            .take_events()
            .iter()
            .filter_map(|e| serde_json::from_str(&e.to_json()).ok())
            .collect();
        let text: Arc<str> = state_json(&sim, current, paused, &events).into();
        {
            let mut s = snapshot.lock().unwrap_or_else(|e| e.into_inner());
            s.state = Some(text.clone());
            for e in events {
                if s.events.len() == EVENT_HISTORY {
                    s.events.pop_front();
                }
                s.events.push_back(e);
            }
        }
        // No page connected is not an error.
        let _ = states.send(text);
        done += 1;
        let due = clock + Duration::from_secs_f64(done as f64 * dt);
        let now = Instant::now();
        if due > now {
            std::thread::sleep(due - now);
        } else if now - due > Duration::from_millis(250) {
            // Far behind (a stalled machine): catch up by starting the clock again rather than
            // running many steps at once.
            clock = now;
            done = 0;
        }
    }
}
