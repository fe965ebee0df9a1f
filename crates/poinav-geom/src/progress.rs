//! Progress of long loops for whoever draws it (the CLI's progress bars): a `(done, total)`
//! callback, called from any thread as items finish. This crate draws nothing itself.

use std::sync::atomic::{AtomicUsize, Ordering};

/// A progress callback: `(done, total)` items.
pub type Progress<'a> = &'a (dyn Fn(usize, usize) + Sync);

/// The callback that ignores progress.
pub fn none(_done: usize, _total: usize) {}

/// Counts items finished on any thread and reports each to a [`Progress`].
pub struct Ticker<'a> {
    done: AtomicUsize,
    total: usize,
    progress: Progress<'a>,
}

impl std::fmt::Debug for Ticker<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Ticker")
            .field("done", &self.done)
            .field("total", &self.total)
            .finish_non_exhaustive()
    }
}

impl<'a> Ticker<'a> {
    /// A count of `total` items, reported to `progress` (at zero now).
    pub fn new(total: usize, progress: Progress<'a>) -> Ticker<'a> {
        progress(0, total);
        Ticker {
            done: AtomicUsize::new(0),
            total,
            progress,
        }
    }

    /// One more item done.
    pub fn tick(&self) {
        let done = self.done.fetch_add(1, Ordering::Relaxed) + 1;
        (self.progress)(done, self.total);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rayon::prelude::*;
    use std::sync::Mutex;

    #[test]
    fn every_item_is_counted_once_across_threads() {
        let seen = Mutex::new(Vec::new());
        let report = |d: usize, t: usize| seen.lock().unwrap().push((d, t));
        let ticker = Ticker::new(100, &report);
        (0..100).into_par_iter().for_each(|_| ticker.tick());
        let mut seen = seen.into_inner().unwrap();
        seen.sort_unstable();
        assert_eq!(seen.len(), 101);
        assert_eq!(seen[0], (0, 100));
        assert_eq!(seen[100], (100, 100));
        assert!(seen.iter().enumerate().all(|(i, &(d, _))| d == i));
    }
}
