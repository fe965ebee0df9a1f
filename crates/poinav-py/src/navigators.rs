//! Navigators kept per navigation options on a `Building`, so that its routes (and grids)
//! after the first rasterise nothing: rasterising and inflating every storey is most of a
//! route's time.
//!
//! A `poinav_nav::Navigator` borrows the building it was made for; what it owns besides that
//! borrow (`NavParts`) is kept here and lent back to a navigator for each call (moves, no copy).

use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::{Mutex, PoisonError};

use poinav_nav::navigator::NavParts;
use poinav_nav::{NavError, NavOptions, Navigator};
use poinav_poi::RobotProfile;

/// How many option sets a building keeps navigators for (the least recently used goes).
const KEPT: usize = 4;

/// Navigators of one building and profile, by options, most recently used last.
#[derive(Debug, Default)]
pub struct Navigators {
    kept: Mutex<Vec<NavParts>>,
    built: AtomicUsize,
}

impl Navigators {
    /// Runs `f` with the navigator of `building` for `profile` and `options`, made on first
    /// use and kept. Calls on one building take turns (the navigator is lent to one at a time).
    pub fn with<R>(
        &self,
        building: &poinav_nav::Building,
        profile: &RobotProfile,
        options: &NavOptions,
        f: impl FnOnce(&Navigator<'_>) -> R,
    ) -> Result<R, NavError> {
        // A panic inside `f` loses only the navigator lent out: the list stays sound.
        let mut kept = self.kept.lock().unwrap_or_else(PoisonError::into_inner);
        let parts = match kept.iter().position(|o| o.options() == options) {
            Some(i) => kept.remove(i),
            None => {
                let nav = Navigator::new(building, profile, options)?;
                self.built.fetch_add(1, Ordering::Relaxed);
                nav.into_parts()
            }
        };
        let nav = Navigator::from_parts(building, parts);
        let out = f(&nav);
        if kept.len() == KEPT {
            kept.remove(0);
        }
        kept.push(nav.into_parts());
        Ok(out)
    }

    /// Runs `f` with the kept navigator for `options`, if there is one (nothing is made).
    pub fn with_kept<R>(
        &self,
        building: &poinav_nav::Building,
        options: &NavOptions,
        f: impl FnOnce(&Navigator<'_>) -> R,
    ) -> Option<R> {
        let mut kept = self.kept.lock().unwrap_or_else(PoisonError::into_inner);
        let i = kept.iter().position(|o| o.options() == options)?;
        let nav = Navigator::from_parts(building, kept.remove(i));
        let out = f(&nav);
        kept.push(nav.into_parts());
        Some(out)
    }

    /// How many navigators were made (each rasterised every storey).
    pub fn built(&self) -> usize {
        self.built.load(Ordering::Relaxed)
    }
}
