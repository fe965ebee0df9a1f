//! What a robot wants to do before Algorithm 1 shapes it: drive a route to a room (waypoints
//! through door centres), follow a wall with a PD law on the +90 or -90 degree ray, or replay
//! key presses (arrow keys or W A S D, and the brush button) at given times.

use glam::DVec2;
use poinav_nav::{DoorIdx, ZoneIdx};
use serde::Deserialize;

use crate::geometry::wrap_angle;
use crate::key_error::KeyError;
use crate::plan::Plan;
use crate::robot::Limits;

/// Which wall to follow.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Side {
    /// The +90 degree ray's side.
    Left,
    /// The -90 degree ray's side.
    Right,
}

impl Side {
    /// +1 for left, -1 for right.
    pub fn sign(self) -> f64 {
        match self {
            Side::Left => 1.0,
            Side::Right => -1.0,
        }
    }
}

/// Which keys drive the robot (paper: Robot1 arrow keys, Robot2 W A S D).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum KeyScheme {
    /// Up, Down, Left, Right.
    Arrows,
    /// W, S, A, D.
    Wasd,
}

/// A key of a scheme.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Key {
    /// Forward.
    Forward,
    /// Backward.
    Backward,
    /// Turn left.
    Left,
    /// Turn right.
    Right,
    /// The brush button (toggles on key down).
    Brush,
}

impl Key {
    /// Parses a key name of `scheme` (`Up`/`ArrowUp`, `W`, ..., `Brush`).
    pub fn parse(scheme: KeyScheme, name: &str) -> Result<Key, KeyError> {
        let n = name.trim().to_ascii_lowercase();
        let n = n.strip_prefix("arrow").unwrap_or(&n);
        let key = match (scheme, n) {
            (_, "brush") => Key::Brush,
            (KeyScheme::Arrows, "up") | (KeyScheme::Wasd, "w") => Key::Forward,
            (KeyScheme::Arrows, "down") | (KeyScheme::Wasd, "s") => Key::Backward,
            (KeyScheme::Arrows, "left") | (KeyScheme::Wasd, "a") => Key::Left,
            (KeyScheme::Arrows, "right") | (KeyScheme::Wasd, "d") => Key::Right,
            _ => {
                return Err(KeyError {
                    name: name.to_string(),
                    scheme,
                })
            }
        };
        Ok(key)
    }

    fn bit(self) -> u8 {
        1 << self as u8
    }
}

/// One scripted key event.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct KeyPress {
    /// Time, seconds from the start.
    pub t: f64,
    /// Key name.
    pub key: String,
    /// Pressed (true) or released (false).
    #[serde(default = "yes")]
    pub down: bool,
}

fn yes() -> bool {
    true
}

fn half_metre() -> f64 {
    0.5
}

/// A controller as a scenario file gives it.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(tag = "kind", rename_all = "kebab-case", deny_unknown_fields)]
pub enum ControllerSpec {
    /// Drive to a zone (Name or LongName) through doors.
    Route {
        /// Target zone.
        to: String,
        /// Cruise speed, m/s (default the profile's top speed).
        #[serde(default)]
        speed_m_s: Option<f64>,
    },
    /// Follow the wall on one side at a distance (ray distance from the robot's centre), then
    /// turn into the target zone's door when it is abeam.
    WallFollow {
        /// Which side.
        side: Side,
        /// Distance to keep, metres.
        #[serde(default = "half_metre")]
        distance_m: f64,
        /// Zone to enter at the end.
        #[serde(default)]
        to: Option<String>,
        /// Cruise speed, m/s (default the profile's top speed).
        #[serde(default)]
        speed_m_s: Option<f64>,
    },
    /// Replay key presses.
    Keys {
        /// Arrow keys or W A S D.
        scheme: KeyScheme,
        /// Key events.
        #[serde(default)]
        script: Vec<KeyPress>,
    },
    /// Stand still.
    Idle,
}

/// What the controller is doing, as the trace shows it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Mode {
    /// Standing still.
    Idle,
    /// Following a route.
    Route,
    /// Following a wall.
    WallFollow,
    /// Driven by keys.
    Keys,
    /// At the target.
    Arrived,
}

impl Mode {
    /// Every mode, in declaration order (`mode as usize` indexes it).
    pub const ALL: [Mode; 5] = [
        Mode::Idle,
        Mode::Route,
        Mode::WallFollow,
        Mode::Keys,
        Mode::Arrived,
    ];

    /// The trace's name.
    pub fn label(self) -> &'static str {
        match self {
            Mode::Idle => "idle",
            Mode::Route => "route",
            Mode::WallFollow => "wall-follow",
            Mode::Keys => "keys",
            Mode::Arrived => "arrived",
        }
    }
}

/// A wanted speed and turn rate.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Command {
    /// Forward speed, m/s.
    pub v: f64,
    /// Turn rate, rad/s (counter-clockwise).
    pub omega: f64,
}

/// PD law keeping a side ray's distance to an A-3 element: `omega = side * (kp e + kd de/dt)`
/// with `e = distance - target`; gains scheduled on speed so the lateral motion has natural
/// frequency [`WallPd::OMEGA_N`] and damping 1 at any speed. When the reference is lost (the ray
/// looks through a door or jumps) the heading is held.
#[derive(Debug, Clone, PartialEq)]
pub struct WallPd {
    /// +1 left, -1 right.
    pub side: f64,
    /// Distance to keep.
    pub target: f64,
    prev: Option<(f64, f64)>,
    hold: Option<f64>,
    lost_since: Option<f64>,
}

impl WallPd {
    /// Natural frequency of the lateral loop, rad/s.
    pub const OMEGA_N: f64 = 4.0;
    /// Largest jump (metres) from the last distance still taken as the same wall.
    pub const JUMP_M: f64 = 0.25;

    /// A law for `side` at `target`.
    pub fn new(side: Side, target: f64) -> WallPd {
        WallPd {
            side: side.sign(),
            target,
            prev: None,
            hold: None,
            lost_since: None,
        }
    }

    /// The turn rate for a measured distance `d` (None: no A-3 reference on that ray).
    pub fn omega(&mut self, d: Option<f64>, t: f64, heading: f64, speed: f64) -> f64 {
        let same_wall = |d: f64, prev: Option<(f64, f64)>| {
            prev.is_none_or(|(_, pe)| (d - self.target - pe).abs() < Self::JUMP_M)
        };
        match d {
            Some(d) if same_wall(d, self.prev) => {
                let e = d - self.target;
                let de = match self.prev {
                    Some((pt, pe)) if t > pt => (e - pe) / (t - pt),
                    _ => 0.0,
                };
                self.prev = Some((t, e));
                self.hold = Some(heading);
                self.lost_since = None;
                let v = speed.abs().max(0.5);
                let kp = Self::OMEGA_N * Self::OMEGA_N / v;
                let kd = 2.0 * Self::OMEGA_N / v;
                self.side * (kp * e + kd * de)
            }
            _ => {
                let since = *self.lost_since.get_or_insert(t);
                if t - since > 1.5 {
                    // Long gone: take whatever wall comes next.
                    self.prev = None;
                }
                match self.hold {
                    Some(h) => 4.0 * wrap_angle(h - heading),
                    None => 0.0,
                }
            }
        }
    }
}

/// Drives through waypoints: aims at the next one, turns in place when it is more than
/// [`Follower::TURN_IN_PLACE_DEG`] off, slows for corners and stops at the last.
#[derive(Debug, Clone, PartialEq)]
pub struct Follower {
    wps: Vec<DVec2>,
    /// Per waypoint, the clear width of the door it passes through (empty: none known).
    widths: Vec<Option<f64>>,
    k: usize,
    prev: DVec2,
    cruise: f64,
    /// True at the last waypoint.
    pub arrived: bool,
}

impl Follower {
    /// Heading error above which the robot turns in place instead of driving.
    pub const TURN_IN_PLACE_DEG: f64 = 15.0;
    /// The same on the straight through a tight door.
    pub const PASSAGE_TURN_IN_PLACE_DEG: f64 = 3.0;
    /// A door is tight when it leaves the robot less than this much room in all (metres).
    pub const TIGHT_M: f64 = 0.25;

    /// Follows `wps` from `start`.
    pub fn new(start: DVec2, wps: Vec<DVec2>, cruise: f64) -> Follower {
        Follower {
            arrived: wps.is_empty(),
            wps,
            widths: Vec::new(),
            k: 0,
            prev: start,
            cruise,
        }
    }

    /// The same, knowing the clear width of the door each waypoint passes through
    /// ([`Plan::waypoints`]): through a door with little room to spare the robot keeps to
    /// the door's axis and drives only once aligned.
    pub fn with_widths(mut self, widths: Vec<Option<f64>>) -> Follower {
        self.widths = widths;
        self
    }

    /// The waypoints.
    pub fn waypoints(&self) -> &[DVec2] {
        &self.wps
    }

    /// The command at `pos`, `heading`.
    pub fn command(&mut self, pos: DVec2, heading: f64, lim: &Limits) -> Command {
        let n = self.wps.len();
        while !self.arrived {
            let wp = self.wps[self.k];
            let last = self.k + 1 == n;
            let reach = if last { 0.05 } else { 0.1 };
            let passed = !last && (wp - pos).dot(wp - self.prev) <= 0.0;
            if pos.distance(wp) < reach || passed {
                if last {
                    self.arrived = true;
                } else {
                    self.prev = wp;
                    self.k += 1;
                }
            } else {
                break;
            }
        }
        if self.arrived {
            return Command::default();
        }
        let wp = self.wps[self.k];
        let to = wp - pos;
        // Through a tight door (the lead point, the centre and the exit are on the door's axis,
        // less than TIGHT_M to spare): keep to the line, not just aim at the point, and drive
        // only once aligned within PASSAGE_TURN_IN_PLACE_DEG; a robot 7 cm narrower than the
        // door has 3.5 cm a side.
        let tight = self
            .widths
            .get(self.k)
            .copied()
            .flatten()
            .is_some_and(|w| w - 2.0 * lim.half_width < Self::TIGHT_M);
        let passage = tight && self.k + 1 < n && {
            let (a, b) = (wp - self.prev, self.wps[self.k + 1] - wp);
            a.length() > 1e-9 && b.length() > 1e-9 && a.angle_to(b).abs() < 1f64.to_radians()
        };
        let (err, in_place) = if passage {
            let u = (wp - self.prev).normalize();
            let cross = (pos - self.prev).dot(u.perp());
            let desired = u.y.atan2(u.x) - (2.0 * cross).atan();
            (
                wrap_angle(desired - heading),
                Self::PASSAGE_TURN_IN_PLACE_DEG,
            )
        } else {
            (
                wrap_angle(to.y.atan2(to.x) - heading),
                Self::TURN_IN_PLACE_DEG,
            )
        };
        let omega = (5.0 * err).clamp(-lim.max_turn, lim.max_turn);
        let mut v = if err.abs() > in_place.to_radians() {
            0.0
        } else {
            self.cruise * err.cos()
        };
        let corner = if self.k + 1 == n {
            0.0
        } else {
            let (a, b) = (wp - self.prev, self.wps[self.k + 1] - wp);
            let turn = a.angle_to(b).abs();
            if turn > 60f64.to_radians() {
                0.3
            } else {
                (self.cruise * turn.cos()).max(0.3)
            }
        };
        v = v.min((corner * corner + 1.6 * lim.decel * to.length()).sqrt());
        Command { v, omega }
    }
}

#[derive(Debug, Clone)]
enum Kind {
    Idle,
    Route(Follower),
    WallFollow {
        pd: WallPd,
        cruise: f64,
        turn_at: Option<(DoorIdx, Vec<DoorIdx>, ZoneIdx)>,
        then: Option<Follower>,
    },
    Keys {
        script: Vec<(f64, Key, bool, String)>,
        next: usize,
        pressed: u8,
    },
}

/// Something a controller did that the trace records.
#[derive(Debug, Clone, PartialEq)]
pub enum ControlEvent {
    /// A key went down or up.
    Key(String, bool),
    /// The brush button was pressed.
    BrushToggle,
}

/// What a controller sees each step.
#[derive(Debug, Clone, Copy)]
pub struct Ctx<'a> {
    /// Time, s.
    pub t: f64,
    /// Position.
    pub pos: DVec2,
    /// Heading, rad.
    pub heading: f64,
    /// Current forward speed.
    pub speed: f64,
    /// Limits.
    pub limits: &'a Limits,
    /// A-3 reference distance on the +90 ray.
    pub left_ref: Option<f64>,
    /// A-3 reference distance on the -90 ray.
    pub right_ref: Option<f64>,
    /// The floor's graph.
    pub nav: &'a Plan,
}

/// One robot's controller.
#[derive(Debug, Clone)]
pub struct Controller {
    kind: Kind,
    /// The zone it drives to, if any.
    pub target: Option<ZoneIdx>,
}

impl Controller {
    /// A controller standing still.
    pub fn idle() -> Controller {
        Controller {
            kind: Kind::Idle,
            target: None,
        }
    }

    /// A route from `start` through `doors` to zone `to`.
    pub fn route(
        nav: &Plan,
        start: DVec2,
        doors: &[DoorIdx],
        to: ZoneIdx,
        cruise: f64,
        lead: f64,
    ) -> Controller {
        let (wps, widths) = nav.waypoints(start, doors, to, lead);
        Controller {
            kind: Kind::Route(Follower::new(start, wps, cruise).with_widths(widths)),
            target: Some(to),
        }
    }

    /// Wall following; with a target, the first door of `doors` is where it turns in.
    pub fn wall_follow(
        side: Side,
        distance: f64,
        cruise: f64,
        target: Option<(Vec<DoorIdx>, ZoneIdx)>,
    ) -> Controller {
        let to = target.as_ref().map(|t| t.1);
        Controller {
            kind: Kind::WallFollow {
                pd: WallPd::new(side, distance),
                cruise,
                turn_at: target
                    .and_then(|(doors, to)| doors.first().copied().map(|d| (d, doors, to))),
                then: None,
            },
            target: to,
        }
    }

    /// Key replay; `script` is sorted by time (stable).
    pub fn keys(mut script: Vec<(f64, Key, bool, String)>) -> Controller {
        script.sort_by(|a, b| a.0.total_cmp(&b.0));
        Controller {
            kind: Kind::Keys {
                script,
                next: 0,
                pressed: 0,
            },
            target: None,
        }
    }

    /// A key pressed or released live at time `t` (a person driving): a controller that is not
    /// key-driven hands over to the keys (the robot stops following its route or wall), and the
    /// press is played at the next step like a scripted one. Returns false, ignoring it, when
    /// it repeats the key's current state (auto-repeat), so events stay meaningful.
    pub fn press(&mut self, t: f64, key: Key, down: bool, name: &str) -> bool {
        if !matches!(self.kind, Kind::Keys { .. }) {
            self.kind = Kind::Keys {
                script: Vec::new(),
                next: 0,
                pressed: 0,
            };
            self.target = None;
        }
        let Kind::Keys {
            script,
            next,
            pressed,
        } = &mut self.kind
        else {
            return false;
        };
        // What the key's state will be once everything queued has been played.
        let mut state = *pressed;
        for &(_, k, d, _) in &script[*next..] {
            if k != Key::Brush {
                state = if d { state | k.bit() } else { state & !k.bit() };
            }
        }
        if key != Key::Brush && (state & key.bit() != 0) == down {
            return false;
        }
        if key == Key::Brush && !down {
            return false;
        }
        // Played entries are no longer needed: keep the live script short.
        script.drain(..*next);
        *next = 0;
        let t = script.last().map_or(t, |l| l.0.max(t));
        script.push((t, key, down, name.to_string()));
        true
    }

    /// The waypoints it follows (empty while wall following or driven by keys).
    pub fn waypoints(&self) -> &[DVec2] {
        match &self.kind {
            Kind::Route(f) => f.waypoints(),
            Kind::WallFollow { then: Some(f), .. } => f.waypoints(),
            _ => &[],
        }
    }

    /// The current mode.
    pub fn mode(&self) -> Mode {
        match &self.kind {
            Kind::Idle => Mode::Idle,
            Kind::Route(f) if f.arrived => Mode::Arrived,
            Kind::Route(_) => Mode::Route,
            Kind::WallFollow { then: Some(f), .. } if f.arrived => Mode::Arrived,
            Kind::WallFollow { then: Some(_), .. } => Mode::Route,
            Kind::WallFollow { .. } => Mode::WallFollow,
            Kind::Keys { .. } => Mode::Keys,
        }
    }

    /// The command for this step; key and brush events go to `events`.
    pub fn command(&mut self, c: &Ctx<'_>, events: &mut Vec<ControlEvent>) -> Command {
        let lim = c.limits;
        match &mut self.kind {
            Kind::Idle => Command::default(),
            Kind::Route(f) => f.command(c.pos, c.heading, lim),
            Kind::WallFollow {
                pd,
                cruise,
                turn_at,
                then,
            } => {
                if let Some(f) = then {
                    return f.command(c.pos, c.heading, lim);
                }
                let dir = DVec2::from_angle(c.heading);
                let mut v = *cruise;
                if let Some((door, doors, to)) = turn_at {
                    let centre = c.nav.doors[door.get()].center;
                    let s = (centre - c.pos).dot(dir);
                    if s <= 0.02 {
                        let (mut wps, mut widths) =
                            c.nav.waypoints(c.pos, doors, *to, lim.half_length + 0.5);
                        if c.nav.doors[door.get()].axis.is_some() {
                            wps.remove(0);
                            widths.remove(0);
                        }
                        let mut f = Follower::new(c.pos, wps, *cruise).with_widths(widths);
                        let cmd = f.command(c.pos, c.heading, lim);
                        *then = Some(f);
                        return cmd;
                    }
                    v = v.min((0.09 + 1.6 * lim.decel * s.max(0.0)).sqrt());
                }
                let d = if pd.side > 0.0 {
                    c.left_ref
                } else {
                    c.right_ref
                };
                let omega = pd.omega(d, c.t, c.heading, c.speed.max(0.5 * v));
                Command {
                    v,
                    omega: omega.clamp(-lim.max_turn, lim.max_turn),
                }
            }
            Kind::Keys {
                script,
                next,
                pressed,
            } => {
                while *next < script.len() && script[*next].0 <= c.t + 1e-9 {
                    let (_, key, down, ref name) = script[*next];
                    events.push(ControlEvent::Key(name.clone(), down));
                    *next += 1;
                    if key == Key::Brush {
                        if down {
                            events.push(ControlEvent::BrushToggle);
                        }
                    } else if down {
                        *pressed |= key.bit();
                    } else {
                        *pressed &= !key.bit();
                    }
                }
                let has = |k: Key| *pressed & k.bit() != 0;
                let v = if has(Key::Forward) {
                    lim.max_speed
                } else if has(Key::Backward) {
                    -lim.max_reverse
                } else {
                    0.0
                };
                let omega = if has(Key::Left) {
                    lim.max_turn
                } else if has(Key::Right) {
                    -lim.max_turn
                } else {
                    0.0
                };
                Command { v, omega }
            }
        }
    }
}

#[cfg(test)]
#[path = "controller_tests.rs"]
mod tests;
