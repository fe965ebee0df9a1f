//! `IfcDoor` / `IfcWindow` geometry: the world frame of the door and the footprint of the
//! opening it fills (`FillsVoids` -> `IfcOpeningElement`), else of the door itself.

use glam::{DAffine3, DVec3};
use poinav_ifc::{Entity, EntityId};

use crate::error::GeomError;
use crate::footprint::{footprint_of, Footprint};
use crate::placement::PlacementCache;

/// Where a door (or window) is.
#[derive(Debug, Clone, PartialEq)]
pub struct DoorGeometry {
    /// The door's world frame (metres); its translation is the placement origin.
    pub placement: DAffine3,
    /// The centre of [`DoorGeometry::footprint`]: its area centroid in XY, halfway between
    /// `z_min` and `z_max` in z. The placement origin when there is no footprint.
    pub center: DVec3,
    /// The footprint of the opening the door fills when it can be read, else the door's own.
    pub footprint: Option<Footprint>,
    /// The opening (or the door) the footprint is of.
    pub footprint_of: Option<EntityId>,
    /// Why a footprint was not used: each opening or door representation that failed.
    pub problems: Vec<GeomError>,
}

/// The geometry of a door or window (any product that fills openings). An error only when its
/// own placement cannot be read; missing footprints are listed in `problems`.
pub fn door_geometry<'m>(
    cache: &mut PlacementCache<'m>,
    door: Entity<'m>,
) -> Result<DoorGeometry, GeomError> {
    let placement = cache.product(door)?;
    let mut problems = Vec::new();
    let openings = door
        .inverse("FillsVoids")
        .into_iter()
        .filter_map(|rel| rel.get_ref("RelatingOpeningElement"));
    let mut found = None;
    for candidate in openings.chain(std::iter::once(door)) {
        match footprint_of(cache, candidate) {
            Ok(f) => {
                found = Some((f.footprint, candidate.id()));
                break;
            }
            Err(e) => problems.push(e),
        }
    }
    let center = match &found {
        Some((f, _)) => f.centroid().extend((f.z_min + f.z_max) / 2.0),
        None => placement.translation,
    };
    let (footprint, footprint_of) = found.unzip();
    Ok(DoorGeometry {
        placement,
        center,
        footprint,
        footprint_of,
        problems,
    })
}
