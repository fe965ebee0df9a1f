//! The trace: one record per step and robot (time, pose, speed, command, the five rays with
//! distance, hit GlobalId and doors looked through, active roles, controller mode, zone, brush,
//! events), written as JSON Lines with fixed decimals so equal runs give equal bytes.

use glam::DVec2;
use poinav_io::number::{push_digits, push_fixed, push_int, Text};
use poinav_nav::ZoneIdx;

use crate::controller::{Command, Mode};
use crate::events::Event;
use crate::poi_db::RoleSet;
use crate::robot::Brush;
use crate::world::{RayHit, Target};
use poinav_roles::Role;

/// A minimal JSON writer with fixed-decimal numbers (`-0` is written as `0`, trailing zeros
/// are dropped, non-finite numbers are `null`).
#[derive(Debug, Default)]
pub struct Json {
    out: String,
    stack: Vec<bool>,
    after_key: bool,
}

impl Json {
    fn sep(&mut self) {
        if self.after_key {
            self.after_key = false;
            return;
        }
        if let Some(top) = self.stack.last_mut() {
            if *top {
                self.out.push(',');
            }
            *top = true;
        }
    }

    /// Writes an object key.
    pub fn key(&mut self, k: &str) -> &mut Json {
        self.sep();
        push_str(&mut self.out, k);
        self.out.push(':');
        self.after_key = true;
        self
    }

    /// A string.
    pub fn str(&mut self, s: &str) -> &mut Json {
        self.sep();
        push_str(&mut self.out, s);
        self
    }

    /// A string or null.
    pub fn opt_str(&mut self, s: Option<&str>) -> &mut Json {
        match s {
            Some(s) => self.str(s),
            None => self.null(),
        }
    }

    /// null.
    pub fn null(&mut self) -> &mut Json {
        self.sep();
        self.out.push_str("null");
        self
    }

    /// A boolean.
    pub fn bool(&mut self, b: bool) -> &mut Json {
        self.sep();
        self.out.push_str(if b { "true" } else { "false" });
        self
    }

    /// An integer.
    pub fn int(&mut self, v: i64) -> &mut Json {
        self.sep();
        push_int(&mut self.out, v);
        self
    }

    /// A number with at most `decimals` decimals.
    pub fn num(&mut self, v: f64, decimals: usize) -> &mut Json {
        self.sep();
        push_fixed(&mut self.out, v, decimals);
        self
    }

    /// `{`.
    pub fn begin_object(&mut self) -> &mut Json {
        self.sep();
        self.out.push('{');
        self.stack.push(false);
        self
    }

    /// `}`.
    pub fn end_object(&mut self) -> &mut Json {
        self.stack.pop();
        self.out.push('}');
        self
    }

    /// `[`.
    pub fn begin_array(&mut self) -> &mut Json {
        self.sep();
        self.out.push('[');
        self.stack.push(false);
        self
    }

    /// `]`.
    pub fn end_array(&mut self) -> &mut Json {
        self.stack.pop();
        self.out.push(']');
        self
    }

    /// Raw JSON text as one value.
    pub fn raw(&mut self, text: &str) -> &mut Json {
        self.sep();
        self.out.push_str(text);
        self
    }

    /// The text.
    pub fn finish(self) -> String {
        self.out
    }
}

/// A piece of text of at most [`Short::CAP`] bytes held in a fixed array, written with
/// [`Text::put_head`]; longer text is kept as it is.
#[derive(Debug, Clone)]
enum Short {
    Fixed([u8; Short::CAP], u8),
    Long(String),
}

impl Short {
    const CAP: usize = 64;

    fn new(s: String) -> Short {
        if s.len() <= Short::CAP {
            let mut b = [0u8; Short::CAP];
            b[..s.len()].copy_from_slice(s.as_bytes());
            Short::Fixed(b, s.len() as u8)
        } else {
            Short::Long(s)
        }
    }

    #[inline]
    fn put_into<T: Text>(&self, out: &mut T) {
        match self {
            Short::Fixed(b, n) => out.put_head(b, *n as usize),
            Short::Long(s) => out.put(s),
        }
    }
}

fn push_str<T: Text>(out: &mut T, s: &str) {
    // serde_json escapes only quotes, backslashes and control characters.
    if s.bytes().all(|b| b >= 0x20 && b != b'"' && b != b'\\') {
        out.put_ascii(b"\"");
        out.put(s);
        out.put_ascii(b"\"");
    } else {
        out.put(&serde_json::to_string(s).expect("strings serialise"));
    }
}

/// One robot in one step.
#[derive(Debug, Clone, PartialEq)]
pub struct StepRecord {
    /// Step number (time = step x dt).
    pub step: u64,
    /// Robot index.
    pub robot: u32,
    /// Centre.
    pub pos: DVec2,
    /// Heading, radians.
    pub heading: f64,
    /// Speed travelled in the step that led here, m/s.
    pub speed: f64,
    /// Turn rate of that step, rad/s.
    pub omega: f64,
    /// The navigation action chosen now.
    pub action: Command,
    /// The five rays sensed now.
    pub rays: [RayHit; 5],
    /// Active roles (elements sensed, zone, the robot's C-2).
    pub roles: RoleSet,
    /// Controller mode.
    pub mode: Mode,
    /// Zone index.
    pub zone: Option<ZoneIdx>,
    /// Brush.
    pub brush: Brush,
}

/// Names the trace writes for indices.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Names {
    /// Robot names.
    pub robots: Vec<String>,
    /// Robot GlobalIds.
    pub robot_ids: Vec<String>,
    /// Obstacle GlobalIds.
    pub obstacles: Vec<String>,
    /// Obstacle classes.
    pub obstacle_classes: Vec<String>,
    /// Door GlobalIds.
    pub doors: Vec<String>,
    /// Zone names (Name, else GlobalId).
    pub zones: Vec<String>,
}

impl Names {
    /// GlobalId and class of a ray target.
    pub fn target(&self, t: Target) -> Option<(&str, &str)> {
        match t {
            Target::None => None,
            Target::Obstacle(i) => Some((
                &self.obstacles[i as usize],
                &self.obstacle_classes[i as usize],
            )),
            Target::Robot(i) => Some((&self.robot_ids[i as usize], "Robot")),
        }
    }
}

/// Renders one record and its events as a JSON line (no newline).
pub fn line(r: &StepRecord, dt: f64, names: &Names, events: &[&Event]) -> String {
    let mut s = String::new();
    line_into(&mut s, r, dt, names, events);
    s
}

/// Appends [`line()`] to `out` (for many lines, prepare a [`LineWriter`] once instead).
pub fn line_into(out: &mut String, r: &StepRecord, dt: f64, names: &Names, events: &[&Event]) {
    let mut bytes = Vec::new();
    LineWriter::new(names).line_into(&mut bytes, r, dt, events);
    out.push_str(&String::from_utf8(bytes).expect("lines are written from UTF-8 text"));
}

/// Writes trace lines fast: the names rendered once as the JSON text a line holds (quoted and
/// escaped, a ray's hit with its class), the fixed keys as whole pieces of text and the
/// numbers without the general formatter. The bytes are those of a line built value by value
/// with [`Json`] (the tests compare both).
#[derive(Debug, Clone, Default)]
pub struct LineWriter {
    /// Robot names, quoted.
    robots: Vec<Short>,
    /// Per obstacle: `"hit":"GlobalId","class":"Class"`.
    obstacle_hits: Vec<Short>,
    /// Per robot: `"hit":"GlobalId","class":"Robot"`.
    robot_hits: Vec<Short>,
    /// Door GlobalIds, quoted.
    doors: Vec<Short>,
    /// Zone names, quoted.
    zones: Vec<Short>,
    /// Role labels, quoted, in [`Role::ALL`]'s order ([`RoleSet::indices`]).
    roles: Vec<Short>,
    /// Mode labels, quoted, in [`Mode::ALL`]'s order.
    modes: Vec<Short>,
}

/// A ray's object up to its distance, per ray in [`crate::sensor::RAY_DEG`] order.
const RAY_START: [&str; 5] = [
    "{\"deg\":0,\"d\":",
    ",{\"deg\":30,\"d\":",
    ",{\"deg\":-30,\"d\":",
    ",{\"deg\":90,\"d\":",
    ",{\"deg\":-90,\"d\":",
];

impl LineWriter {
    /// Renders `names`.
    pub fn new(names: &Names) -> LineWriter {
        let quoted = |s: &str| {
            let mut q = String::new();
            push_str(&mut q, s);
            Short::new(q)
        };
        let hit = |id: &str, class: &str| {
            let mut q = String::from("\"hit\":");
            push_str(&mut q, id);
            q.push_str(",\"class\":");
            push_str(&mut q, class);
            Short::new(q)
        };
        LineWriter {
            robots: names.robots.iter().map(|n| quoted(n)).collect(),
            obstacle_hits: names
                .obstacles
                .iter()
                .zip(&names.obstacle_classes)
                .map(|(id, class)| hit(id, class))
                .collect(),
            robot_hits: names.robot_ids.iter().map(|id| hit(id, "Robot")).collect(),
            doors: names.doors.iter().map(|d| quoted(d)).collect(),
            zones: names.zones.iter().map(|z| quoted(z)).collect(),
            roles: Role::ALL.iter().map(|r| quoted(r.label())).collect(),
            modes: Mode::ALL.iter().map(|m| quoted(m.label())).collect(),
        }
    }

    /// Appends the line of `r` and its `events` (no newline) to `out`.
    pub fn line_into(&self, out: &mut Vec<u8>, r: &StepRecord, dt: f64, events: &[&Event]) {
        self.line_with(out, r, r.step as f64 * dt, |out| {
            if !events.is_empty() {
                out.put(&events_json(events));
            }
        });
    }

    /// Appends the line of `r` at time `t` (no newline) to `out`, the text inside its events
    /// array written by `events` (what [`events_json`] gives).
    pub(crate) fn line_with(
        &self,
        out: &mut Vec<u8>,
        r: &StepRecord,
        t: f64,
        events: impl FnOnce(&mut Vec<u8>),
    ) {
        out.put("{\"step\":");
        push_digits(out, r.step, 1);
        out.put(",\"t\":");
        push_fixed(out, t, 6);
        out.put(",\"robot\":");
        self.robots[r.robot as usize].put_into(out);
        out.put(",\"x\":");
        push_fixed(out, r.pos.x, 6);
        out.put(",\"y\":");
        push_fixed(out, r.pos.y, 6);
        out.put(",\"heading_deg\":");
        push_fixed(out, r.heading.to_degrees(), 4);
        out.put(",\"speed\":");
        push_fixed(out, r.speed, 6);
        out.put(",\"omega_deg_s\":");
        push_fixed(out, r.omega.to_degrees(), 4);
        out.put(",\"cmd\":{\"v\":");
        push_fixed(out, r.action.v, 6);
        out.put(",\"omega_deg_s\":");
        push_fixed(out, r.action.omega.to_degrees(), 4);
        out.put("},\"mode\":");
        self.modes[r.mode as usize].put_into(out);
        out.put(",\"zone\":");
        match r.zone {
            Some(z) => self.zones[z.get()].put_into(out),
            None => out.put("null"),
        }
        out.put(",\"roles\":[");
        for (n, k) in r.roles.indices().enumerate() {
            if n > 0 {
                out.put_ascii(b",");
            }
            self.roles[k].put_into(out);
        }
        out.put("],\"brush\":{\"on\":");
        out.put(if r.brush.on { "true" } else { "false" });
        out.put(",\"angle_deg\":");
        push_fixed(out, r.brush.angle_deg, 3);
        out.put("},\"rays\":[");
        for (k, ray) in r.rays.iter().enumerate() {
            out.put(RAY_START[k]);
            push_fixed(out, ray.dist, 6);
            out.put_ascii(b",");
            match ray.target {
                Target::None => out.put("\"hit\":null"),
                Target::Obstacle(i) => self.obstacle_hits[i as usize].put_into(out),
                Target::Robot(i) => self.robot_hits[i as usize].put_into(out),
            }
            if !ray.passages.is_empty() {
                out.put(",\"through\":[");
                for (n, &d) in ray.passages.doors().iter().enumerate() {
                    if n > 0 {
                        out.put_ascii(b",");
                    }
                    self.doors[d as usize].put_into(out);
                }
                out.put_ascii(b"]");
            }
            out.put_ascii(b"}");
        }
        out.put("],\"events\":[");
        events(out);
        out.put("]}");
    }
}

/// The text inside a trace line's events array: `events` as objects, written value by value.
pub(crate) fn events_json(events: &[&Event]) -> String {
    let mut j = Json {
        stack: vec![false],
        ..Json::default()
    };
    for e in events {
        j.begin_object();
        j.key("kind").str(e.kind.tag());
        e.kind.write_fields(&mut j);
        j.end_object();
    }
    j.out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sensor::RAY_DEG;

    /// The line built value by value with [`Json`] (how [`LineWriter`] wrote it before).
    fn reference_line(out: &mut String, r: &StepRecord, dt: f64, names: &Names, events: &[&Event]) {
        let mut j = Json {
            out: std::mem::take(out),
            ..Json::default()
        };
        j.begin_object();
        j.key("step").int(r.step as i64);
        j.key("t").num(r.step as f64 * dt, 6);
        j.key("robot").str(&names.robots[r.robot as usize]);
        j.key("x").num(r.pos.x, 6);
        j.key("y").num(r.pos.y, 6);
        j.key("heading_deg").num(r.heading.to_degrees(), 4);
        j.key("speed").num(r.speed, 6);
        j.key("omega_deg_s").num(r.omega.to_degrees(), 4);
        j.key("cmd").begin_object();
        j.key("v").num(r.action.v, 6);
        j.key("omega_deg_s").num(r.action.omega.to_degrees(), 4);
        j.end_object();
        j.key("mode").str(r.mode.label());
        j.key("zone")
            .opt_str(r.zone.map(|z| names.zones[z.get()].as_str()));
        j.key("roles").begin_array();
        for role in r.roles.roles() {
            j.str(role.label());
        }
        j.end_array();
        j.key("brush").begin_object();
        j.key("on").bool(r.brush.on);
        j.key("angle_deg").num(r.brush.angle_deg, 3);
        j.end_object();
        j.key("rays").begin_array();
        for (k, ray) in r.rays.iter().enumerate() {
            j.begin_object();
            j.key("deg").num(RAY_DEG[k], 0);
            j.key("d").num(ray.dist, 6);
            match names.target(ray.target) {
                Some((id, class)) => {
                    j.key("hit").str(id);
                    j.key("class").str(class);
                }
                None => {
                    j.key("hit").null();
                }
            }
            if !ray.passages.is_empty() {
                j.key("through").begin_array();
                for &d in ray.passages.doors() {
                    j.str(&names.doors[d as usize]);
                }
                j.end_array();
            }
            j.end_object();
        }
        j.end_array();
        j.key("events").begin_array();
        for e in events {
            j.begin_object();
            j.key("kind").str(e.kind.tag());
            e.kind.write_fields(&mut j);
            j.end_object();
        }
        j.end_array();
        j.end_object();
        *out = j.finish();
    }

    /// Every record of two shipped scenarios (a door measured, robots meeting: hits on walls
    /// and robots, looks through doors, events), then the same records with awkward numbers:
    /// the fast writer writes the bytes of the line built value by value.
    #[test]
    fn line_writer_writes_the_reference_bytes() {
        let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("scenarios");
        let awkward = [
            0.0,
            -0.0,
            1e-7,
            -1e-7,
            5e-7,
            -4.9999999e-7,
            0.5,
            -2.5,
            12345678.9,
            -9.87654321e14,
            3.0e15,
            1e300,
            f64::NAN,
            f64::INFINITY,
            f64::MIN_POSITIVE,
            123.4564999,
        ];
        let (mut lines, mut with_events, mut through, mut robot_hits) = (0, 0, 0, 0);
        for (file, variant) in [("doorway.toml", Some("door-0.80")), ("yield.toml", None)] {
            let scenario = crate::Scenario::load(&dir.join(file)).unwrap();
            let floor = crate::test_floor::prepared(&scenario, variant);
            let setups: Vec<_> = scenario.robots.iter().map(|r| r.setup.clone()).collect();
            let mut sim = crate::Sim::new(&floor, &setups, crate::SimOptions::default()).unwrap();
            let names = sim.names();
            let writer = LineWriter::new(&names);
            // The same names made longer than a fixed piece holds (and not ASCII).
            let mut long = names.clone();
            for s in long
                .robots
                .iter_mut()
                .chain(&mut long.robot_ids)
                .chain(&mut long.obstacles)
                .chain(&mut long.doors)
                .chain(&mut long.zones)
            {
                s.push_str(&" \u{fc}ber-lang \"x\"".repeat(6));
            }
            let long_writer = LineWriter::new(&long);
            assert!(matches!(writer.robots[0], Short::Fixed(..)));
            assert!(matches!(long_writer.robots[0], Short::Long(_)));
            let mut seen = 0;
            for k in 0..=240 {
                sim.tick(k < 240);
                let events = &sim.events()[seen..];
                seen = sim.events().len();
                for r in sim.last_records() {
                    let mine: Vec<&Event> = events
                        .iter()
                        .filter(|e| e.robot == names.robots[r.robot as usize])
                        .collect();
                    let mut variants = vec![r.clone()];
                    let a = awkward[(r.step as usize + r.robot as usize) % awkward.len()];
                    let b = awkward[(r.step as usize * 7 + 3) % awkward.len()];
                    let mut odd = r.clone();
                    odd.pos = DVec2::new(a, b);
                    odd.heading = b;
                    odd.speed = -a;
                    odd.omega = a;
                    odd.action = Command { v: b, omega: -b };
                    odd.brush.angle_deg = a;
                    odd.rays[r.step as usize % 5].dist = b;
                    odd.step = r.step * 1_000_003;
                    variants.push(odd);
                    for v in &variants {
                        let mut fast = b"prefix ".to_vec();
                        writer.line_into(&mut fast, v, 1.0 / 60.0, &mine);
                        let mut want = String::from("prefix ");
                        reference_line(&mut want, v, 1.0 / 60.0, &names, &mine);
                        assert_eq!(String::from_utf8(fast).unwrap(), want);
                        let mut via_names = String::from("prefix ");
                        line_into(&mut via_names, v, 1.0 / 60.0, &names, &mine);
                        assert_eq!(via_names, want);
                        let mut fast = Vec::new();
                        long_writer.line_into(&mut fast, v, 1.0 / 60.0, &mine);
                        let mut want = String::new();
                        reference_line(&mut want, v, 1.0 / 60.0, &long, &mine);
                        assert_eq!(String::from_utf8(fast).unwrap(), want);
                        lines += 1;
                    }
                    with_events += usize::from(!mine.is_empty());
                    through += r.rays.iter().filter(|h| !h.passages.is_empty()).count();
                    robot_hits += r
                        .rays
                        .iter()
                        .filter(|h| matches!(h.target, Target::Robot(_)))
                        .count();
                }
            }
        }
        assert_eq!(
            lines, 1446,
            "lines: 241 steps of 1 + 2 robots, each as is and with odd numbers"
        );
        assert!(with_events > 10, "{with_events} lines with events");
        assert!(through > 100, "{through} rays through doors");
        assert!(robot_hits > 20, "{robot_hits} rays on robots");
    }

    #[test]
    fn numbers_are_fixed_and_signless_at_zero() {
        let mut j = Json::default();
        j.begin_object();
        j.key("a").num(1.0, 3);
        j.key("b").begin_array();
        j.str("x\"y").null();
        j.end_array();
        j.end_object();
        assert_eq!(j.finish(), r#"{"a":1,"b":["x\"y",null]}"#);
    }
}
