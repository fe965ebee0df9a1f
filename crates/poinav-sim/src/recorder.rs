//! What a run keeps while it goes, step by step after each tick: the trace lines (or compact
//! records, [`crate::trace_bin`]) of the kept steps streamed to a writer (rendered in parallel
//! into reused buffers, written in robot order), each expectation's measures, each robot's summary figures and the plots' samples.
//! Nothing here grows with the run's length.

use std::collections::BTreeMap;
use std::io::Write;

use glam::DVec2;
use rayon::prelude::*;

use crate::error::SimError;
use crate::events::Event;
use crate::expect::Judge;
use crate::samples::PlotSamples;
use crate::step::Sim;
use crate::trace::{LineWriter, Names, StepRecord};
use crate::trace_bin;

/// How a trace is written.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum TraceFormat {
    /// JSON Lines ([`crate::trace`]): what every reader takes.
    #[default]
    Jsonl,
    /// Fixed-size binary records ([`crate::trace_bin`]), about a quarter of the bytes and a
    /// small part of the time; [`trace_bin::read_lines`] gives back the JSON Lines.
    Bin,
}

/// Where a run writes its trace.
#[allow(missing_debug_implementations)]
pub struct TraceOut<'w> {
    /// The writer (buffer it: lines are written one by one). `Send`: the run loop executes on
    /// a thread of rayon's pool ([`crate::on_pool`]).
    pub writer: &'w mut (dyn Write + Send),
    /// Keep every `every`-th step (1: all); the lines kept are those of the full trace.
    pub every: u64,
    /// Names the writer in errors (a path).
    pub name: String,
    /// The format.
    pub format: TraceFormat,
}

/// One robot's running figures for the summary.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct RobotFigures {
    /// Distance travelled, m.
    pub travelled: f64,
    /// Highest speed, m/s.
    pub max_speed: f64,
    /// Last position.
    pub end: Option<(DVec2, f64)>,
    /// Last zone.
    pub end_zone: Option<poinav_nav::ZoneIdx>,
    prev: Option<DVec2>,
}

impl RobotFigures {
    fn add(&mut self, r: &StepRecord) {
        if let Some(p) = self.prev {
            self.travelled += p.distance(r.pos);
        }
        self.prev = Some(r.pos);
        self.max_speed = self.max_speed.max(r.speed);
        self.end = Some((r.pos, r.heading));
        self.end_zone = r.zone;
    }
}

/// Records rendered by one task.
const CHUNK: usize = 32;

/// Writes the lines of one step's trace in robot order, rendered in parallel a batch of chunks
/// at a time into `bufs`, buffers kept from step to step: a few per thread, so the lines are
/// written into memory that is still in the cache (with fresh buffers for a whole step, 1 MB
/// for 1000 robots, a profile put half of the digits' time on their first stores).
fn write_step_lines(
    out: &mut TraceOut<'_>,
    bufs: &mut Vec<Vec<u8>>,
    step: &[StepRecord],
    dt: f64,
    writer: Option<&LineWriter>,
    events: &[Vec<&Event>],
) -> Result<(), SimError> {
    let per_batch = 2 * rayon::current_num_threads().max(1);
    for (b, batch) in step.chunks(CHUNK * per_batch).enumerate() {
        let first = b * CHUNK * per_batch;
        let n = batch.len().div_ceil(CHUNK);
        if bufs.len() < n {
            bufs.resize_with(n, || Vec::with_capacity(CHUNK * 1100));
        }
        bufs[..n]
            .par_iter_mut()
            .zip(batch.par_chunks(CHUNK))
            .enumerate()
            .for_each(|(c, (s, chunk))| {
                s.clear();
                for (k, r) in chunk.iter().enumerate() {
                    let ev = events
                        .get(first + c * CHUNK + k)
                        .map_or(&[][..], Vec::as_slice);
                    match writer {
                        Some(w) => {
                            w.line_into(s, r, dt, ev);
                            s.push(b'\n');
                        }
                        None => trace_bin::record_into(s, r, r.step as f64 * dt, ev),
                    }
                }
            });
        for s in &bufs[..n] {
            out.writer.write_all(s).map_err(|e| SimError::Io {
                path: out.name.clone(),
                message: e.to_string(),
            })?;
        }
    }
    Ok(())
}

/// What a run keeps as it goes: call [`Recorder::after_tick`] after every [`Sim::tick`].
#[allow(missing_debug_implementations)]
pub struct Recorder<'w> {
    trace: Option<TraceOut<'w>>,
    names: Names,
    lines: LineWriter,
    robot_of: BTreeMap<String, usize>,
    sizes: Vec<(f64, f64)>,
    seen: usize,
    judges: Vec<Judge>,
    figures: Vec<RobotFigures>,
    samples: PlotSamples,
    records: u64,
    /// Line buffers reused from step to step.
    bufs: Vec<Vec<u8>>,
    /// The compact trace's header, until it is written.
    header: Option<Vec<u8>>,
}

impl<'w> Recorder<'w> {
    /// For `sim` before its first tick, recorded `records` times (steps + 1), measuring
    /// `judges`, writing to `trace`.
    pub fn new(
        sim: &Sim<'_>,
        records: u64,
        judges: Vec<Judge>,
        trace: Option<TraceOut<'w>>,
    ) -> Recorder<'w> {
        let names = sim.names();
        let n = names.robots.len();
        Recorder {
            trace,
            robot_of: names
                .robots
                .iter()
                .enumerate()
                .map(|(i, name)| (name.clone(), i))
                .collect(),
            judges,
            lines: LineWriter::new(&names),
            names,
            sizes: sim.sizes(),
            seen: 0,
            figures: vec![RobotFigures::default(); n],
            samples: PlotSamples::new(n, records),
            records: 0,
            bufs: Vec::new(),
            header: None,
        }
        .with_header()
    }

    /// The names the trace writes.
    pub fn names(&self) -> &Names {
        &self.names
    }

    fn with_header(mut self) -> Self {
        if self
            .trace
            .as_ref()
            .is_some_and(|t| t.format == TraceFormat::Bin)
        {
            self.header = Some(trace_bin::header(&self.names));
        }
        self
    }

    /// Writes the compact trace's header if it is not written yet.
    fn write_header(&mut self) -> Result<(), SimError> {
        if let (Some(h), Some(t)) = (self.header.take(), self.trace.as_mut()) {
            t.writer.write_all(&h).map_err(|e| SimError::Io {
                path: t.name.clone(),
                message: e.to_string(),
            })?;
        }
        Ok(())
    }

    /// Flushes the trace; hands back the judges, figures, samples and the count of records.
    #[allow(clippy::type_complexity)]
    pub fn finish(mut self) -> Result<(Vec<Judge>, Vec<RobotFigures>, PlotSamples, u64), SimError> {
        self.write_header()?;
        if let Some(t) = self.trace.as_mut() {
            t.writer.flush().map_err(|e| SimError::Io {
                path: t.name.clone(),
                message: e.to_string(),
            })?;
        }
        Ok((self.judges, self.figures, self.samples, self.records))
    }

    /// Takes in the step `sim` just ticked (at step length `dt`).
    pub fn after_tick(&mut self, sim: &Sim<'_>, dt: f64) -> Result<(), SimError> {
        let step = sim.last_records();
        let events = &sim.events()[self.seen..];
        self.seen = sim.events().len();
        for j in &mut self.judges {
            j.observe(step, dt, &self.sizes, sim.db());
        }
        for (f, r) in self.figures.iter_mut().zip(step) {
            f.add(r);
        }
        self.samples.observe(step);
        self.records += 1;
        self.write_header()?;
        let Some(out) = self.trace.as_mut() else {
            return Ok(());
        };
        let Some(first) = step.first() else {
            return Ok(());
        };
        if first.step % out.every != 0 {
            return Ok(());
        }
        // Events on the line of their robot (unknown names on the first robot's), in order.
        let mut by_robot: Vec<Vec<&Event>> = Vec::new();
        for e in events {
            let r = self.robot_of.get(&e.robot).copied().unwrap_or(0);
            if by_robot.len() <= r {
                by_robot.resize_with(r + 1, Vec::new);
            }
            by_robot[r].push(e);
        }
        let lines = (out.format == TraceFormat::Jsonl).then_some(&self.lines);
        write_step_lines(out, &mut self.bufs, step, dt, lines, &by_robot)
    }
}
