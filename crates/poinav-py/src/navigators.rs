//! Navigators kept per navigation options on a `Building`, so that its routes (and grids)
//! after the first rasterise nothing: rasterising and inflating every storey is most of a
//! route's time.
//!
//! A `poinav_nav::Navigator` borrows the building it was made for; what it owns besides that
//! borrow is kept here and lent back to a navigator for each call (moving vectors, no copy).

use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::{Mutex, PoisonError};

use poinav_nav::navigator::FloorNav;
use poinav_nav::{GaveUp, NavError, NavOptions, Navigator, Topology};
use poinav_poi::{AccessibilityStatus, RobotProfile};

/// How many option sets a building keeps navigators for (the least recently used goes).
const KEPT: usize = 4;

/// What a navigator owns: all of it but the building.
#[derive(Debug)]
struct Owned {
    profile: RobotProfile,
    options: NavOptions,
    topology: Topology,
    floors: Vec<FloorNav>,
    nothing_to_navigate: Vec<Option<String>>,
    status: Vec<(AccessibilityStatus, String)>,
    grid_passable: Vec<bool>,
    open: Vec<bool>,
    gave_up: Vec<GaveUp>,
}

impl Owned {
    fn take(nav: Navigator<'_>) -> Owned {
        let Navigator {
            building: _,
            profile,
            options,
            topology,
            floors,
            nothing_to_navigate,
            status,
            grid_passable,
            open,
            gave_up,
        } = nav;
        Owned {
            profile,
            options,
            topology,
            floors,
            nothing_to_navigate,
            status,
            grid_passable,
            open,
            gave_up,
        }
    }

    fn lend(self, building: &poinav_nav::Building) -> Navigator<'_> {
        Navigator {
            building,
            profile: self.profile,
            options: self.options,
            topology: self.topology,
            floors: self.floors,
            nothing_to_navigate: self.nothing_to_navigate,
            status: self.status,
            grid_passable: self.grid_passable,
            open: self.open,
            gave_up: self.gave_up,
        }
    }
}

/// Navigators of one building and profile, by options, most recently used last.
#[derive(Debug, Default)]
pub struct Navigators {
    kept: Mutex<Vec<Owned>>,
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
        let owned = match kept.iter().position(|o| o.options == *options) {
            Some(i) => kept.remove(i),
            None => {
                let nav = Navigator::new(building, profile, options)?;
                self.built.fetch_add(1, Ordering::Relaxed);
                Owned::take(nav)
            }
        };
        let nav = owned.lend(building);
        let out = f(&nav);
        if kept.len() == KEPT {
            kept.remove(0);
        }
        kept.push(Owned::take(nav));
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
        let i = kept.iter().position(|o| o.options == *options)?;
        let nav = kept.remove(i).lend(building);
        let out = f(&nav);
        kept.push(Owned::take(nav));
        Some(out)
    }

    /// How many navigators were made (each rasterised every storey).
    pub fn built(&self) -> usize {
        self.built.load(Ordering::Relaxed)
    }
}
