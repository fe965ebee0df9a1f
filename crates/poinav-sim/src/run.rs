//! Running a scenario on a floor: set the robots up, step for the duration with a
//! [`Recorder`] streaming the trace and measuring as it goes (memory flat in the run's length),
//! judge the expectations at the end; the summary of a finished run.

use poinav_nav::Floor;
use serde_json::{json, Value};

use crate::error::SimError;
use crate::events::Event;
use crate::expect::{Judge, Judged};
use crate::recorder::{Recorder, RobotFigures, TraceOut};
use crate::samples::PlotSamples;
use crate::scenario::{ExpectEntry, Scenario};
use crate::step::{RunData, Sim, SimOptions};

/// A finished run.
#[derive(Debug, Clone)]
pub struct Outcome {
    /// Scenario name.
    pub scenario: String,
    /// Variant name.
    pub variant: Option<String>,
    /// Floor name.
    pub floor: String,
    /// Events, observations, names, the POI database; `records` is empty (they were streamed).
    pub data: RunData,
    /// The judged expectations, scenario's first then the variant's.
    pub judged: Vec<Judged>,
    /// Records per robot (steps + 1).
    pub records: u64,
    /// Per robot figures for the summary.
    pub figures: Vec<RobotFigures>,
    /// What the plots draw.
    pub samples: PlotSamples,
    /// The whole trace, when [`run`] kept it in memory.
    pub trace: Option<Vec<u8>>,
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

    /// The summary: scenario, variant, steps, per robot figures, every expectation with its
    /// measured value and verdict, the events, and `pass`.
    pub fn summary(&self) -> Value {
        let robots: Vec<Value> = self
            .data
            .names
            .robots
            .iter()
            .enumerate()
            .map(|(i, name)| {
                let f = &self.figures[i];
                json!({
                    "name": name,
                    "global_id": self.data.names.robot_ids[i],
                    "travelled_m": round(f.travelled),
                    "max_speed_m_s": round(f.max_speed),
                    "end": f.end.map(|(p, h)| json!({"x": round(p.x), "y": round(p.y), "heading_deg": round(h.to_degrees())})),
                    "end_zone": f.end_zone.map(|z| self.data.names.zones[z.get()].clone()),
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
            "records": self.records,
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

/// Runs `work` on a thread of rayon's global pool and waits for it: a simulation loop calls the
/// pool several times per step (sensing, perception, decisions, moves, trace lines), and from
/// a thread outside the pool each call hands the work over and sleeps until it is done (two
/// context switches and a wake-up: with one thread 21,600 switches made 100 robots 2.6x slower
/// in wall time); on a pool thread the calls run in place and idle threads steal from it.
pub fn on_pool<R: Send>(work: impl FnOnce() -> R + Send) -> R {
    rayon::scope(|_| work())
}

/// Runs `scenario` (its variant `variant`, when it has variants) on `floor`, keeping the whole
/// trace in memory ([`Outcome::trace`]); [`run_with`] streams it instead.
pub fn run(scenario: &Scenario, variant: Option<&str>, floor: &Floor) -> Result<Outcome, SimError> {
    let mut buf: Vec<u8> = Vec::new();
    let out = TraceOut {
        writer: &mut buf,
        every: 1,
        name: "trace".into(),
        format: crate::TraceFormat::Jsonl,
    };
    let mut outcome = run_with(scenario, variant, floor, Some(out))?;
    outcome.trace = Some(buf);
    Ok(outcome)
}

/// Runs `scenario` (its variant `variant`) on `floor`, writing the trace lines to `trace` as the
/// steps are taken (none when `None`). The summary, expectations and plots do not depend on
/// the trace.
pub fn run_with(
    scenario: &Scenario,
    variant: Option<&str>,
    floor: &Floor,
    trace: Option<TraceOut<'_>>,
) -> Result<Outcome, SimError> {
    let v = scenario.variant(variant)?;
    let expects: Vec<&ExpectEntry> = scenario
        .expects
        .iter()
        .chain(v.iter().flat_map(|v| v.expects.iter()))
        .collect();
    for e in &expects {
        e.expect
            .check(floor)
            .map_err(|m| scenario.error(e.line, m.to_string()))?;
    }
    if let Some(t) = &trace {
        if t.every == 0 {
            return Err(SimError::Io {
                path: t.name.clone(),
                message: "a trace keeps every N-th step with N at least 1".into(),
            });
        }
    }
    let setups: Vec<_> = scenario.robots.iter().map(|r| r.setup.clone()).collect();
    let opts = SimOptions {
        dt: scenario.dt,
        start: scenario.start,
        poi_profile: crate::scenario::load_profile(&scenario.building.profile, &scenario.dir)?,
        behaviour: scenario.behaviour.clone(),
        record: false,
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
    let names = sim.names();
    let judges = expects
        .iter()
        .map(|e| Judge::new(&e.expect, e.line, &names))
        .collect();
    let mut rec = Recorder::new(&sim, steps + 1, judges, trace);
    let dt = scenario.dt;
    let (sim, finished) = on_pool(move || {
        for k in 0..=steps {
            sim.tick(k < steps);
            if let Err(e) = rec.after_tick(&sim, dt) {
                return (sim, Err(e));
            }
        }
        let finished = rec.finish();
        (sim, finished)
    });
    let (judges, figures, samples, records) = finished?;
    let data = sim.finish();
    let judged = judges
        .into_iter()
        .map(|j| j.finish(&data.events, floor))
        .collect();
    Ok(Outcome {
        scenario: scenario.name.clone(),
        variant: v.map(|v| v.name.clone()),
        floor: floor.name.clone(),
        data,
        judged,
        records,
        figures,
        samples,
        trace: None,
    })
}
