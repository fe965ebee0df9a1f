//! Which way a door's passage faces on its floor ([`DoorFrame`]): of the two orientations of
//! its ring, the one with the door's own spaces, else the most zones, beyond its faces.

use std::borrow::Cow;

use poinav_floor::polygon::PassageFrame;
use poinav_floor::Floor;

use crate::zone_index::ZoneIndex;

/// A door's passage frame decided with the zones around it (navigation's side of
/// [`poinav_floor::FloorDoor::frame`], which looks at the ring alone).
pub trait DoorFrame {
    /// The frame of door `k`'s passage: of the two orientations of its ring, the one with
    /// more of the door's own spaces ([`poinav_floor::FloorDoor::spaces`]) beyond its faces,
    /// else with zones beyond more of its faces (a door joins two spaces); on a tie,
    /// [`poinav_floor::FloorDoor::frame`]. The other orientation is a candidate only when it
    /// is at least the clear width wide.
    fn door_frame(&self, k: usize) -> Option<PassageFrame>;

    /// [`DoorFrame::door_frame`] with this floor's [`ZoneIndex`] (for many doors, build it
    /// once).
    fn door_frame_in(&self, k: usize, zones: &ZoneIndex) -> Option<PassageFrame>;
}

impl DoorFrame for Floor {
    fn door_frame(&self, k: usize) -> Option<PassageFrame> {
        door_frame_with(self, k, &mut None)
    }

    fn door_frame_in(&self, k: usize, zones: &ZoneIndex) -> Option<PassageFrame> {
        door_frame_with(self, k, &mut Some(Cow::Borrowed(zones)))
    }
}

/// [`DoorFrame::door_frame`], the zone index built only when the zones are looked at.
fn door_frame_with(
    floor: &Floor,
    k: usize,
    zones: &mut Option<Cow<'_, ZoneIndex>>,
) -> Option<PassageFrame> {
    let d = floor.doors.get(k)?;
    let f = d.frame()?;
    let g = f.swapped();
    let w = d.clear_width_m;
    if w.is_finite() && w > 0.0 && 2.0 * g.half_width < w - 1e-6 {
        return Some(f);
    }
    let zones = zones.get_or_insert_with(|| Cow::Owned(ZoneIndex::new(floor)));
    let score = |f: &PassageFrame| {
        let sides = crate::graph::frame_zones(floor, zones, f);
        let own = sides
            .iter()
            .flatten()
            .filter(|&&z| {
                d.spaces
                    .as_ref()
                    .is_some_and(|s| s.contains(&floor.zones[z.get()].id))
            })
            .count();
        (own, sides.iter().flatten().count())
    };
    if score(&g) > score(&f) {
        Some(g)
    } else {
        Some(f)
    }
}
