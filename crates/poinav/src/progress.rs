//! Long work on standard error: one progress bar per stage (meshing, sectioning, rasterising,
//! ...) drawn by `indicatif` only when standard error is a terminal and `--quiet` is not given,
//! and each stage's wall time, printed by `--timings` when the command ends.
//!
//! Libraries know nothing of this: they take a plain `&dyn Fn(done, total)` callback and
//! [`tick`] is what the CLI hands them.

use std::io::IsTerminal as _;
use std::sync::Mutex;
use std::time::{Duration, Instant};

use indicatif::{ProgressBar, ProgressStyle};

/// The stage running now and the wall time of the stages done, in the order they started.
struct Stages {
    current: Option<(&'static str, Instant, ProgressBar)>,
    done: Vec<(&'static str, Duration)>,
    began: Option<Instant>,
}

static STAGES: Mutex<Stages> = Mutex::new(Stages {
    current: None,
    done: Vec::new(),
    began: None,
});

fn stages() -> std::sync::MutexGuard<'static, Stages> {
    STAGES
        .lock()
        .unwrap_or_else(std::sync::PoisonError::into_inner)
}

/// Whether bars are drawn: standard error is a terminal and `--quiet` was not given.
fn drawn() -> bool {
    !crate::flags().quiet && std::io::stderr().is_terminal()
}

impl Stages {
    fn end(&mut self) {
        if let Some((name, start, bar)) = self.current.take() {
            bar.finish_and_clear();
            let took = start.elapsed();
            match self.done.iter_mut().find(|(n, _)| *n == name) {
                Some((_, total)) => *total += took,
                None => self.done.push((name, took)),
            }
        }
    }
}

/// Ends the running stage (if any) and starts `name`: a spinner until [`tick`] gives a total.
pub fn stage(name: &'static str) {
    let mut s = stages();
    s.end();
    let now = Instant::now();
    s.began.get_or_insert(now);
    let bar = if drawn() {
        let bar = ProgressBar::new_spinner();
        bar.set_style(
            ProgressStyle::with_template("{spinner} {msg} {elapsed}").expect("valid template"),
        );
        bar.set_message(name);
        bar.enable_steady_tick(Duration::from_millis(120));
        bar
    } else {
        ProgressBar::hidden()
    };
    s.current = Some((name, now, bar));
}

/// Ends the running stage.
pub fn end() {
    stages().end();
}

/// Progress of the running stage: `done` of `total` items. Cheap; safe from any thread.
pub fn tick(done: usize, total: usize) {
    let s = stages();
    let Some((name, _, bar)) = &s.current else {
        return;
    };
    if bar.is_hidden() {
        return;
    }
    if bar.length() != Some(total as u64) {
        bar.set_style(
            ProgressStyle::with_template("{msg} [{bar:30}] {pos}/{len} {elapsed}")
                .expect("valid template")
                .progress_chars("=> "),
        );
        bar.set_length(total as u64);
        bar.set_message(*name);
    }
    bar.set_position(done as u64);
}

/// Runs `f` (which prints) with the running stage's bar out of the way.
pub fn suspend<T>(f: impl FnOnce() -> T) -> T {
    let bar = stages().current.as_ref().map(|(_, _, b)| b.clone());
    match bar {
        Some(b) => b.suspend(f),
        None => f(),
    }
}

/// The wall time of each stage, in the order they started, and of the whole command.
pub fn timings() -> (Vec<(&'static str, Duration)>, Duration) {
    let mut s = stages();
    s.end();
    let total = s.began.map(|b| b.elapsed()).unwrap_or_default();
    (s.done.clone(), total)
}

/// Ends the running stage; with `--timings`, prints every stage's wall time.
pub fn finish() {
    let (done, total) = timings();
    if !crate::flags().timings {
        return;
    }
    errln!("timings (wall clock):");
    for (name, took) in &done {
        errln!("  {name:<12} {:>9.3} s", took.as_secs_f64());
    }
    errln!("  {:<12} {:>9.3} s", "total", total.as_secs_f64());
}

/// Progress in a stage a library names (`rasterising`, `graph`, `writing`): starts that stage
/// when another one is running, then ticks.
pub fn phase(name: &'static str, done: usize, total: usize) {
    let running = stages().current.as_ref().map(|(n, _, _)| *n);
    if running != Some(name) {
        stage(name);
    }
    tick(done, total);
}
