//! The trace: one record per step and robot (time, pose, speed, command, the five rays with
//! distance, hit GlobalId and doors looked through, active roles, controller mode, zone, brush,
//! events), written as JSON Lines with fixed decimals so equal runs give equal bytes.

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
        self.out.push_str(&v.to_string());
        self
    }

    /// A number with at most `decimals` decimals.
    pub fn num(&mut self, v: f64, decimals: usize) -> &mut Json {
        self.sep();
        self.out.push_str(&fixed(v, decimals));
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
    out.push_str(&serde_json::to_string(s).expect("strings serialise"));
}

/// `v` with at most `decimals` decimals, deterministic: no `-0`, no trailing zeros.
pub fn fixed(v: f64, decimals: usize) -> String {
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
    let mut j = Json::default();
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
    j.finish()
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
}
