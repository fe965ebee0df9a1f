//! What the plots keep of a run while it goes: every robot's pose and speed at every `every`-th
//! step (the stride today's plots draw: at most 3000 points per line, widened so that all robots
//! together keep at most [`BUDGET`] samples), and each robot's last record. Memory stays flat
//! however long the run is.

use glam::DVec2;

use crate::trace::StepRecord;

/// Most samples kept over all robots (32 bytes each).
pub const BUDGET: u64 = 1_000_000;

/// Points per plotted line the plots aim at.
pub const POINTS_PER_LINE: u64 = 3000;

/// One robot at one step.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sample {
    /// Step number.
    pub step: u64,
    /// Centre.
    pub pos: DVec2,
    /// Heading, radians.
    pub heading: f64,
    /// Speed travelled in the step that led here, m/s.
    pub speed: f64,
}

impl From<&StepRecord> for Sample {
    fn from(r: &StepRecord) -> Sample {
        Sample {
            step: r.step,
            pos: r.pos,
            heading: r.heading,
            speed: r.speed,
        }
    }
}

/// The sampled steps of a run.
#[derive(Debug, Clone, Default)]
pub struct PlotSamples {
    every: u64,
    robots: usize,
    /// Step-major, `robots` per sampled step.
    kept: Vec<Sample>,
    last: Vec<Sample>,
}

impl PlotSamples {
    /// For `robots` robots recorded `records` times each (steps + 1).
    pub fn new(robots: usize, records: u64) -> PlotSamples {
        let mut every = (records / POINTS_PER_LINE).max(1);
        let n = robots.max(1) as u64;
        if n * records.div_ceil(every) > BUDGET {
            every = (n * records).div_ceil(BUDGET).max(every);
        }
        PlotSamples {
            every,
            robots,
            kept: Vec::new(),
            last: Vec::new(),
        }
    }

    /// The stride, in steps.
    pub fn every(&self) -> u64 {
        self.every
    }

    /// Adds one step's records (`step[i]` is robot `i`).
    pub fn observe(&mut self, step: &[StepRecord]) {
        let Some(first) = step.first() else {
            return;
        };
        if first.step % self.every == 0 {
            self.kept.extend(step.iter().map(Sample::from));
        }
        self.last.clear();
        self.last.extend(step.iter().map(Sample::from));
    }

    /// The sampled steps, each with one sample per robot.
    pub fn steps(&self) -> std::slice::ChunksExact<'_, Sample> {
        self.kept.chunks_exact(self.robots.max(1))
    }

    /// Robot `i`'s samples in step order.
    pub fn of(&self, i: usize) -> impl Iterator<Item = &Sample> + '_ {
        self.steps().map(move |s| &s[i])
    }

    /// Robot `i`'s last record.
    pub fn last(&self, i: usize) -> Option<&Sample> {
        self.last.get(i)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn strides_follow_the_plots_and_the_budget() {
        assert_eq!(PlotSamples::new(2, 2401).every(), 1);
        assert_eq!(PlotSamples::new(2, 36_001).every(), 12);
        // 1000 robots for 10 simulated minutes: at most BUDGET samples.
        let p = PlotSamples::new(1000, 36_001);
        assert_eq!(p.every(), 37);
        assert!(1000 * 36_001u64.div_ceil(p.every()) <= BUDGET);
    }
}
