//! The trace: one record per step and robot (time, pose, speed, command, the five rays with
//! distance, hit GlobalId and doors looked through, active roles, controller mode, zone, brush,
//! events), written as JSON Lines with fixed decimals so equal runs give equal bytes.

use std::fmt::Write;

use glam::DVec2;

use crate::controller::{Command, Mode};
use crate::events::Event;
use crate::poi_db::RoleSet;
use crate::robot::Brush;
use crate::sensor::RAY_DEG;
use crate::world::{RayHit, Target};

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
        let _ = write!(self.out, "{v}");
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

fn push_str(out: &mut String, s: &str) {
    // serde_json escapes only quotes, backslashes and control characters.
    if s.bytes().all(|b| b >= 0x20 && b != b'"' && b != b'\\') {
        out.push('"');
        out.push_str(s);
        out.push('"');
    } else {
        out.push_str(&serde_json::to_string(s).expect("strings serialise"));
    }
}

/// `v` with at most `decimals` decimals, deterministic: no `-0`, no trailing zeros.
pub fn fixed(v: f64, decimals: usize) -> String {
    let mut s = String::new();
    push_fixed(&mut s, v, decimals);
    s
}

const POW10: [f64; 7] = [1.0, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6];

/// Appends [`fixed`]`(v, decimals)` to `out`. The same digits as `format!("{v:.decimals$}")`
/// (the exact binary value correctly rounded), trimmed; the common case without the general
/// formatter: `v` scaled by `10^decimals` in `f64` is off the exact product by at most half an
/// ulp, so when it is farther than that from a rounding boundary (half an integer) it rounds
/// like the exact product, and the integer is printed.
fn push_fixed(out: &mut String, v: f64, decimals: usize) {
    if !v.is_finite() {
        out.push_str("null");
        return;
    }
    if decimals < POW10.len() {
        let x = v * POW10[decimals];
        let frac = x - x.floor();
        let margin = x.abs() * 2.3e-16 + 1e-300;
        if x.abs() < 1e15 && (frac - 0.5).abs() > margin {
            let m = x.round() as i64;
            if m == 0 {
                out.push('0');
                return;
            }
            if m < 0 {
                out.push('-');
            }
            let m = m.unsigned_abs();
            let p = 10u64.pow(decimals as u32);
            let _ = write!(out, "{}", m / p);
            let mut f = m % p;
            if f != 0 {
                let mut digits = decimals;
                while f % 10 == 0 {
                    f /= 10;
                    digits -= 1;
                }
                let _ = write!(out, ".{f:0digits$}");
            }
            return;
        }
    }
    let start = out.len();
    let _ = write!(out, "{v:.decimals$}");
    if out[start..].contains('.') {
        while out.ends_with('0') {
            out.pop();
        }
        if out.ends_with('.') {
            out.pop();
        }
    }
    if &out[start..] == "-0" {
        out.truncate(start);
        out.push('0');
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
    pub zone: Option<u32>,
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

/// Appends [`line`] to `out`.
pub fn line_into(out: &mut String, r: &StepRecord, dt: f64, names: &Names, events: &[&Event]) {
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
        .opt_str(r.zone.map(|z| names.zones[z as usize].as_str()));
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_are_fixed_and_signless_at_zero() {
        assert_eq!(fixed(-0.0000001, 6), "0");
        assert_eq!(fixed(1.5, 6), "1.5");
        assert_eq!(fixed(2.0, 6), "2");
        assert_eq!(fixed(-3.1234567, 6), "-3.123457");
        assert_eq!(fixed(f64::NAN, 6), "null");
        let mut j = Json::default();
        j.begin_object();
        j.key("a").num(1.0, 3);
        j.key("b").begin_array();
        j.str("x\"y").null();
        j.end_array();
        j.end_object();
        assert_eq!(j.finish(), r#"{"a":1,"b":["x\"y",null]}"#);
    }

    /// The general formatter's digits, trimmed (what `fixed` wrote before its fast path).
    fn reference(v: f64, decimals: usize) -> String {
        if !v.is_finite() {
            return "null".into();
        }
        let mut s = format!("{v:.decimals$}");
        if s.contains('.') {
            while s.ends_with('0') {
                s.pop();
            }
            if s.ends_with('.') {
                s.pop();
            }
        }
        if s == "-0" {
            s = "0".into();
        }
        s
    }

    #[test]
    fn fast_fixed_numbers_equal_the_general_formatter() {
        let mut seed = 0x9E37_79B9_7F4A_7C15u64;
        let mut next = || {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            seed
        };
        for k in 0..400_000 {
            let r = next();
            let v = match k % 4 {
                // Any magnitude.
                0 => f64::from_bits(r),
                // Poses and speeds.
                1 => (r >> 11) as f64 / (1u64 << 53) as f64 * 200.0 - 100.0,
                // Halves and exact decimals: the rounding boundaries.
                2 => ((r % 2_000_001) as f64 - 1_000_000.0) / 2f64.powi((r >> 40) as i32 % 12),
                _ => ((r % 20_000_001) as f64 - 10_000_000.0) * 1e-7,
            };
            for d in [0usize, 3, 4, 6] {
                assert_eq!(fixed(v, d), reference(v, d), "{v:e} with {d} decimals");
            }
        }
        for v in [
            0.5, 1.5, 2.5, -0.5, 0.0000005, 0.0000015, 1e15, -1e-300, 5e-7, -5e-7,
        ] {
            for d in [0usize, 3, 4, 6] {
                assert_eq!(fixed(v, d), reference(v, d), "{v:e} with {d} decimals");
            }
        }
    }
}
