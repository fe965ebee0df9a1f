//! Running a scenario on a floor: set the robots up, step for the duration, judge the
//! expectations, and hand back the trace, events, observations and summary.

use std::collections::BTreeMap;

use poinav_nav::Floor;
use serde_json::{json, Value};

use crate::error::SimError;
use crate::events::Event;
use crate::expect::{judge, Judged};
use crate::scenario::{ExpectEntry, Scenario};
use crate::step::{RunData, Sim, SimOptions};
use crate::trace;

/// A finished run.
#[derive(Debug, Clone)]
pub struct Outcome {
    /// Scenario name.
    pub scenario: String,
    /// Variant name.
    pub variant: Option<String>,
    /// Floor name.
    pub floor: String,
    /// Everything recorded.
    pub data: RunData,
    /// The judged expectations, scenario's first then the variant's.
    pub judged: Vec<Judged>,
}

impl Outcome {
    /// True when every expectation holds.
    pub fn passed(&self) -> bool {
        self.judged.iter().all(|j| j.pass)
    }

    /// The events.
    pub fn events(&self) -> &[Event] {
        &self.data.events
    }

    /// The trace as JSON Lines: one line per step and robot, steps in order, robots in
    /// scenario order, events on the line of the robot and step they belong to.
    pub fn trace_jsonl(&self) -> String {
        let robot_of: BTreeMap<&str, usize> = self
            .data
            .names
            .robots
            .iter()
            .enumerate()
            .map(|(i, n)| (n.as_str(), i))
            .collect();
        let mut by_line: BTreeMap<(u64, usize), Vec<&Event>> = BTreeMap::new();
        for e in &self.data.events {
            let r = robot_of.get(e.robot.as_str()).copied().unwrap_or(0);
            by_line.entry((e.step, r)).or_default().push(e);
        }
        let mut out = String::with_capacity(self.data.records.len() * 900);
        for r in &self.data.records {
            let events = by_line
                .get(&(r.step, r.robot as usize))
                .map(Vec::as_slice)
                .unwrap_or(&[]);
            out.push_str(&trace::line(r, self.data.dt, &self.data.names, events));
            out.push('\n');
        }
        out
    }

    /// The summary: scenario, variant, steps, per robot figures, every expectation with its
    /// measured value and verdict, the events, and `pass`.
    pub fn summary(&self) -> Value {
        let n = self.data.names.robots.len().max(1);
        let robots: Vec<Value> = self
            .data
            .names
            .robots
            .iter()
            .enumerate()
            .map(|(i, name)| {
                let mine: Vec<_> = self.data.records.iter().filter(|r| r.robot as usize == i).collect();
                let travelled: f64 = mine.windows(2).map(|w| w[0].pos.distance(w[1].pos)).sum();
                let max_speed = mine.iter().map(|r| r.speed).fold(0.0, f64::max);
                let last = mine.last();
                json!({
                    "name": name,
                    "global_id": self.data.names.robot_ids[i],
                    "travelled_m": round(travelled),
                    "max_speed_m_s": round(max_speed),
                    "end": last.map(|r| json!({"x": round(r.pos.x), "y": round(r.pos.y), "heading_deg": round(r.heading.to_degrees())})),
                    "end_zone": last.and_then(|r| r.zone).map(|z| self.data.names.zones[z as usize].clone()),
                })
            })
            .collect();
        let expectations: Vec<Value> = self
            .judged
            .iter()
            .map(|j| {
                json!({
                    "kind": j.kind,
                    "line": j.line,
                    "expected": j.expected,
                    "measured": j.measured,
                    "pass": j.pass,
                })
            })
            .collect();
        let events: Vec<Value> = self
            .data
            .events
            .iter()
            .map(|e| serde_json::from_str(&e.to_json()).expect("events are JSON"))
            .collect();
        json!({
            "scenario": self.scenario,
            "variant": self.variant,
            "floor": self.floor,
            "dt_s": self.data.dt,
            "steps": self.data.steps,
            "duration_s": round(self.data.steps as f64 * self.data.dt),
            "records": self.data.records.len() / n,
            "robots": robots,
            "expectations": expectations,
            "events": events,
            "pass": self.passed(),
        })
    }
}

fn round(v: f64) -> Value {
    if v.is_finite() {
        json!((v * 1e6).round() / 1e6 + 0.0)
    } else {
        Value::Null
    }
}

/// Runs `scenario` (its variant `variant`, when it has variants) on `floor`.
pub fn run(scenario: &Scenario, variant: Option<&str>, floor: &Floor) -> Result<Outcome, SimError> {
    let v = scenario.variant(variant)?;
    let expects: Vec<&ExpectEntry> = scenario
        .expects
        .iter()
        .chain(v.iter().flat_map(|v| v.expects.iter()))
        .collect();
    for e in &expects {
        e.expect
            .check(floor)
            .map_err(|m| scenario.error(e.line, m))?;
    }
    let setups: Vec<_> = scenario.robots.iter().map(|r| r.setup.clone()).collect();
    let opts = SimOptions {
        dt: scenario.dt,
        start: scenario.start,
        behaviour: scenario.behaviour.clone(),
        ..SimOptions::default()
    };
    let mut sim = Sim::new(floor, &setups, opts).map_err(|e| match e {
        SimError::Setup { robot, message } => {
            let line = scenario
                .robots
                .iter()
                .find(|r| r.setup.name == robot)
                .map_or(1, |r| r.line);
            scenario.error(line, format!("robot `{robot}`: {message}"))
        }
        other => other,
    })?;
    let steps = (scenario.duration_s / scenario.dt).round() as u64;
    for k in 0..=steps {
        sim.tick(k < steps);
    }
    let data = sim.finish();
    let judged = expects
        .iter()
        .map(|e| judge(&e.expect, e.line, &data, floor))
        .collect();
    Ok(Outcome {
        scenario: scenario.name.clone(),
        variant: v.map(|v| v.name.clone()),
        floor: floor.name.clone(),
        data,
        judged,
    })
}
