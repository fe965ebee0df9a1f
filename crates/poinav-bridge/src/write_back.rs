//! The write-back of what a run's sensors found into a copy of the IFC: rule R5 through
//! `poinav_poi::runtime::apply` on the enrichment, written by `poinav_poi::write_enrichment`.

use poinav_ifc::{Editor, Model};
use poinav_poi::runtime::{self, Observation};
use poinav_poi::{Classification, WriteOptions};
use poinav_sim::Outcome;

use crate::error::BridgeError;

/// The enrichment `classification` of `model` with the run's findings applied (rule R5, in the
/// order observed): each door's last sensor clearance decides its B-2 and AccessibilityStatus
/// (ValidationMethod SENSOR_BASED); a zone where robots came closer than its
/// MinInterRobotSeparation keeps C-2 (a run that ends with the robots apart still records that
/// they interacted there).
pub fn apply_findings(classification: &Classification, outcome: &Outcome) -> Classification {
    let mut c = classification.clone();
    for (gid, observation, _) in &outcome.data.observations {
        let Some(el) = c.elements.iter_mut().find(|e| &e.global_id == gid) else {
            continue;
        };
        if let Observation::RobotDistance { distance_m } = observation {
            let close = el
                .coordination
                .as_ref()
                .is_some_and(|k| *distance_m < k.min_separation_m);
            if !close {
                continue;
            }
        }
        runtime::apply(el, *observation);
    }
    c
}

/// An editor holding `model` with the findings written (`opts.timestamp` is LastValidated);
/// write it with `Editor::write`.
pub fn write_back<'m>(
    model: &'m Model,
    classification: &Classification,
    outcome: &Outcome,
    opts: &WriteOptions,
) -> Result<Editor<'m>, BridgeError> {
    let c = apply_findings(classification, outcome);
    Ok(poinav_poi::write_enrichment(model, &c, opts)?)
}
