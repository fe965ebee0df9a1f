//! Running a scenario on a floor: set the robots up, step for the duration with a
//! [`Recorder`] streaming the trace and measuring as it goes (memory flat in the run's length),
//! judge the expectations at the end; the summary of a finished run.

use std::sync::atomic::{AtomicBool, Ordering};

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

/// Runs `work`, the simulation loop of a crowd of `robots`, on a thread of rayon's global pool
/// and waits for it: the loop calls the pool several times per step (sensing and perception,
/// decisions and moves, trace lines), and from a thread outside the pool each call hands the
/// work over and sleeps until it is done (two context switches and a wake-up: with one thread
/// 21,600 switches made 100 robots 2.6x slower in wall time); on a pool thread the calls run in
/// place and idle threads steal from it.
///
/// For a crowd the step splits over threads ([`KEEP_BUSY_ROBOTS`] robots or more), the pool's
/// other threads are kept awake looking for work while `work` runs (polling rayon) instead of
/// falling asleep between the step's calls: waking a sleeping thread costs a system call and a
/// context switch each time, about a fifth of the samples of 100 robots on two threads
/// (`perf`: the scheduler and rayon's idle loop). Smaller crowds run on one thread anyway.
pub fn on_pool<R: Send>(robots: usize, work: impl FnOnce() -> R + Send) -> R {
    let done = AtomicBool::new(false);
    rayon::scope(|s| {
        if robots >= KEEP_BUSY_ROBOTS {
            let me = rayon::current_thread_index();
            for _ in 1..rayon::current_num_threads() {
                let done = &done;
                s.spawn(move |_| keep_busy(me, done));
            }
        }
        // Set however `work` ends (a panic too): the threads kept busy stop.
        let _stop = SetOnDrop(&done);
        work()
    })
}

/// The smallest crowd [`on_pool`] keeps the pool's threads awake for: two of the step's
/// tasks (`MIN_ROBOTS_PER_TASK` robots each); smaller crowds run on one thread.
pub const KEEP_BUSY_ROBOTS: usize = 2 * crate::step::MIN_ROBOTS_PER_TASK;

/// Sets its flag when dropped.
struct SetOnDrop<'a>(&'a AtomicBool);

impl Drop for SetOnDrop<'_> {
    fn drop(&mut self) {
        self.0.store(true, Ordering::Release);
    }
}

/// Runs the pool's pending work (stolen from the thread `on` runs on) until `done`, polling
/// between jobs (after a few idle polls, giving the core to other processes at each poll). A
/// no-op on the thread `work` runs on (were it picked up there, it would wait for itself).
fn keep_busy(on: Option<usize>, done: &AtomicBool) {
    if rayon::current_thread_index() == on {
        return;
    }
    let mut idle = 0u32;
    while !done.load(Ordering::Acquire) {
        match rayon::yield_now() {
            Some(rayon::Yield::Executed) => idle = 0,
            Some(rayon::Yield::Idle) => {
                idle = idle.saturating_add(1);
                if idle < 64 {
                    std::hint::spin_loop();
                } else {
                    std::thread::yield_now();
                }
            }
            None => return,
        }
    }
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
    let (sim, finished) = on_pool(setups.len(), move || {
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

#[cfg(test)]
mod tests {
    use rayon::prelude::*;

    use super::*;

    #[test]
    fn work_on_the_pool_with_its_threads_kept_busy_returns_and_ends() {
        // Four threads whatever the machine: three kept busy.
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(4)
            .build()
            .unwrap();
        pool.install(|| {
            // Parallel calls inside, one nested on_pool, small and large crowds.
            let sum = on_pool(1000, || {
                let a: u64 = (0..100_000u64).into_par_iter().sum();
                let b = on_pool(1000, || {
                    (0..1000u64).into_par_iter().map(|x| x * 2).sum::<u64>()
                });
                a + b
            });
            assert_eq!(sum, 4_999_950_000 + 999_000);
            assert_eq!(on_pool(2, || 7), 7);
            // A panic in the work stops the busy threads too, and reaches the caller.
            let caught = std::panic::catch_unwind(|| on_pool(1000, || panic!("in the work")));
            assert!(caught.is_err());
            // The pool is still there to use.
            assert_eq!(
                on_pool(1000, || (1..=10u64).into_par_iter().sum::<u64>()),
                55
            );
        });
    }
}
