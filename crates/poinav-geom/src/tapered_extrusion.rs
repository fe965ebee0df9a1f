//! `IfcExtrudedAreaSolidTapered`: a profile swept along a direction while it changes
//! linearly into its `EndSweptArea` (same areas, rings and points, matched in order), as a
//! closed mesh: the start profile's cap, the end profile's cap, two triangles per edge.

use poinav_ifc::Entity;

use crate::error::{degenerate, required_ref, GeomError};
use crate::extrusion::extrusion_frame;
use crate::loft::{loft, Stations};
use crate::mesh::Mesh;
use crate::profile;
use crate::unit_assignment::Units;

/// The mesh of an `IfcExtrudedAreaSolidTapered` in the coordinates of the representation it
/// is an item of (metres), its `Position` applied.
pub fn tapered_extrusion(item: Entity<'_>, units: &Units) -> Result<Mesh, GeomError> {
    let start = profile::areas(required_ref(&item, "SweptArea", "IfcProfileDef")?, units)?;
    let end = profile::areas(required_ref(&item, "EndSweptArea", "IfcProfileDef")?, units)?;
    let (position, sweep) = extrusion_frame(item, units)?;
    if sweep.z.abs() <= 1e-9 * sweep.abs().max_element() {
        return Err(degenerate(&item, "swept along its own plane"));
    }
    let place = |p: glam::DVec2, k: usize| p.extend(0.0) + sweep * k as f64;
    let mut mesh = loft(
        &start,
        Some(&end),
        &Stations {
            count: 2,
            wrap: false,
            place: &place,
            pinned: &|_| false,
        },
    )
    .ok_or_else(|| {
        degenerate(
            &item,
            "the end profile does not match the start profile point for point",
        )
    })?;
    mesh.transform(&position);
    Ok(mesh)
}
