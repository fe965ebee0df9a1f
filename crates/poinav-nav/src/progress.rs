//! Progress of long work for whoever draws it (the CLI's progress bars and `--timings`): a
//! callback told the phase and `(done, total)` as each storey finishes. This crate draws nothing.

/// What is being done.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Phase {
    /// Occupancy grids and their inflation, per storey.
    Rasterising,
    /// The zone/door/landing graph and what the grids say about its doors.
    Graph,
    /// Writing files, per storey.
    Writing,
    /// Reachability and door checks of the audit, per profile.
    Auditing,
}

impl Phase {
    /// Lower-case name (`rasterising`, `graph`, `writing`, `auditing`).
    pub fn label(self) -> &'static str {
        match self {
            Phase::Rasterising => "rasterising",
            Phase::Graph => "graph",
            Phase::Writing => "writing",
            Phase::Auditing => "auditing",
        }
    }
}

/// A progress callback: `(phase, done, total)`.
pub type Progress<'a> = &'a dyn Fn(Phase, usize, usize);

/// The callback that ignores progress.
pub fn none(_phase: Phase, _done: usize, _total: usize) {}
