//! Rule R5, runtime constraints, on classified elements: `poinav_roles::runtime`'s updates
//! (what a robot's sensors find changes an element's conditional roles and status) applied to a
//! [`Classified`], as the write-back of a run's findings does.

pub use poinav_roles::runtime::{Observation, RolesMut, RuntimeChange};

use crate::classify::Classified;

/// Applies R5 to `c` ([`poinav_roles::runtime::apply`]).
pub fn apply(c: &mut Classified, observation: Observation) -> RuntimeChange {
    poinav_roles::runtime::apply(c.roles_mut(), observation)
}
