//! The passage through a door in plan: where its clear width lies, along which direction, and
//! how deep the opening is, from the opening it fills (else its own body), its placement and
//! its clear width; and the passage through a wall opening no door fills (a doorway).
//!
//! The clear width is computed as `poinav-poi` computes it for the accessibility rules:
//! OverallWidth less twice the LiningThickness of its `IfcDoorLiningProperties` (occurrence
//! or type) when given, else OverallWidth, else the opening's width.

use glam::DVec2;
use poinav_ifc::{property, Entity, EntityId};
use serde::{Deserialize, Serialize};

use crate::door::door_geometry;
use crate::error::GeomError;
use crate::placement::PlacementCache;
use crate::polygon;
use crate::region::Region;

/// Where a door's clear width comes from.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub enum ClearWidthSource {
    /// OverallWidth less twice the lining thickness.
    Lining,
    /// OverallWidth.
    OverallWidth,
    /// The opening's width in plan (no OverallWidth).
    OpeningGeometry,
}

/// A door's passage in plan, world metres.
#[derive(Debug, Clone, PartialEq)]
pub struct DoorPassage {
    /// The door.
    pub door: EntityId,
    /// Its GlobalId.
    pub global_id: String,
    /// Its Name.
    pub name: Option<String>,
    /// The centre of the opening in plan.
    pub center: DVec2,
    /// Unit vector along the door's width (along its wall).
    pub along: DVec2,
    /// Unit vector across it (through the wall), `along` turned a quarter counter-clockwise.
    pub across: DVec2,
    /// The clear width, metres.
    pub clear_width_m: f64,
    /// Where the clear width comes from.
    pub clear_width_source: ClearWidthSource,
    /// The opening's extent along `along`.
    pub opening_width_m: f64,
    /// The opening's extent along `across` (the wall's thickness, or more).
    pub depth_m: f64,
    /// The opening (or, when it fills none that can be read, the door) measured.
    pub measured: EntityId,
    /// Lowest and highest z of the opening (world metres).
    pub z_range: (f64, f64),
}

impl DoorPassage {
    /// The rectangle centred on the opening reaching `half_width` along and `half_depth`
    /// across it, counter-clockwise.
    pub fn rectangle(&self, half_width: f64, half_depth: f64) -> Vec<DVec2> {
        let frame = polygon::PassageFrame {
            center: self.center,
            axis: self.along,
            normal: self.across,
            half_width,
            half_depth,
        };
        frame.rectangle(half_width, half_depth).into_vec()
    }

    /// The clear passage: the clear width across the opening's depth.
    pub fn passage(&self) -> Option<Region> {
        Region::from_ring(self.rectangle(self.clear_width_m / 2.0, self.depth_m / 2.0))
    }

    /// The clear width extended `half_depth` either side of the opening's centre line.
    pub fn strip(&self, half_depth: f64) -> Option<Region> {
        Region::from_ring(self.rectangle(self.clear_width_m / 2.0, half_depth))
    }
}

/// The passage of `door` (an `IfcDoor`): the opening it fills (else the door's own body)
/// measured along the door's placement x-axis, snapped to the sides of the outline's
/// minimum-area rectangle. Errors when neither has a footprint or the placement is unreadable.
pub fn door_passage<'m>(
    cache: &mut PlacementCache<'m>,
    door: Entity<'m>,
) -> Result<DoorPassage, GeomError> {
    let g = door_geometry(cache, door)?;
    let (Some(footprint), Some(measured)) = (g.footprint, g.footprint_of) else {
        return Err(g
            .problems
            .into_iter()
            .next()
            .unwrap_or(GeomError::NoGeometry {
                id: door.id(),
                class: door.type_name().to_string(),
            }));
    };
    let rect = polygon::min_area_rectangle(&footprint.polygon).ok_or(GeomError::Degenerate {
        id: measured,
        reason: "the opening spans no horizontal area",
    })?;
    let x = g.placement.matrix3.x_axis.truncate();
    let side = rect.direction;
    let other = side.perp();
    let along = if x.length() < 1e-9 || x.dot(side).abs() >= x.dot(other).abs() {
        if x.dot(side) < 0.0 {
            -side
        } else {
            side
        }
    } else if x.dot(other) < 0.0 {
        -other
    } else {
        other
    };
    let across = along.perp();
    let (u0, u1) = extent(&footprint.polygon, rect.center, along);
    let (v0, v1) = extent(&footprint.polygon, rect.center, across);
    let center = rect.center + along * (u0 + u1) / 2.0 + across * (v0 + v1) / 2.0;
    let opening_width_m = u1 - u0;
    let metres = cache.metres_per_unit();
    let (clear_width_m, clear_width_source) =
        clear_width(door, metres).unwrap_or((opening_width_m, ClearWidthSource::OpeningGeometry));
    Ok(DoorPassage {
        door: door.id(),
        global_id: door.global_id().unwrap_or_default(),
        name: door.name(),
        center,
        along,
        across,
        clear_width_m,
        clear_width_source,
        opening_width_m,
        depth_m: v1 - v0,
        measured,
        z_range: (footprint.z_min, footprint.z_max),
    })
}

/// The smallest and largest offset of `points` from `origin` along `axis`.
fn extent(points: &[DVec2], origin: DVec2, axis: DVec2) -> (f64, f64) {
    points
        .iter()
        .map(|p| (*p - origin).dot(axis))
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), t| {
            (lo.min(t), hi.max(t))
        })
}

/// Openings narrower than this (metres) are no passage for anyone (cable and pipe chases).
pub const MIN_OPENING_PASSAGE_M: f64 = 0.3;

/// The passage through `opening`, an `IfcOpeningElement` that no door or window fills, in its
/// host `wall`: along the wall's length (the longer side of its footprint's minimum-area
/// rectangle), as wide as the opening, and as deep as the wall where both overlap (an
/// opening's cutting volume often reaches far beyond the wall's faces). The clear width is the
/// opening's width ([`ClearWidthSource::OpeningGeometry`]); `door` and `measured` are the
/// opening. Errors when the opening or the wall has no footprint.
pub fn opening_passage<'m>(
    cache: &mut PlacementCache<'m>,
    opening: Entity<'m>,
    wall: Entity<'m>,
) -> Result<DoorPassage, GeomError> {
    let hole = crate::footprint::footprint_of(cache, opening)?.footprint;
    let host = crate::footprint::footprint_of(cache, wall)?.footprint;
    let degenerate = |id| GeomError::Degenerate {
        id,
        reason: "the opening spans no horizontal area",
    };
    let wall_rect = polygon::min_area_rectangle(&host.polygon).ok_or(degenerate(wall.id()))?;
    let hole_rect = polygon::min_area_rectangle(&hole.polygon).ok_or(degenerate(opening.id()))?;
    let along = wall_rect.direction;
    let across = along.perp();
    let origin = hole_rect.center;
    let (u0, u1) = extent(&hole.polygon, origin, along);
    let (mut v0, mut v1) = extent(&hole.polygon, origin, across);
    // The wall's faces where the opening is: its outline's points within the opening's width.
    let near: Vec<DVec2> = host
        .polygon
        .iter()
        .copied()
        .filter(|p| {
            let u = (*p - origin).dot(along);
            u >= u0 - 1.0 && u <= u1 + 1.0
        })
        .collect();
    let (w0, w1) = extent(
        if near.len() >= 2 {
            &near
        } else {
            &host.polygon
        },
        origin,
        across,
    );
    if w0.max(v0) < w1.min(v1) {
        (v0, v1) = (w0.max(v0), w1.min(v1));
    }
    if !(u1 - u0 > 1e-6 && v1 - v0 > 1e-6) {
        return Err(degenerate(opening.id()));
    }
    let center = origin + along * (u0 + u1) / 2.0 + across * (v0 + v1) / 2.0;
    Ok(DoorPassage {
        door: opening.id(),
        global_id: opening.global_id().unwrap_or_default(),
        name: opening.name(),
        center,
        along,
        across,
        clear_width_m: u1 - u0,
        clear_width_source: ClearWidthSource::OpeningGeometry,
        opening_width_m: u1 - u0,
        depth_m: v1 - v0,
        measured: opening.id(),
        z_range: (hole.z_min, hole.z_max),
    })
}

/// The openings of `element` that no door or window fills.
pub fn unfilled_openings<'m>(element: Entity<'m>) -> Vec<Entity<'m>> {
    element
        .inverse("HasOpenings")
        .into_iter()
        .filter_map(|rel| rel.get_ref("RelatedOpeningElement"))
        .filter(|o| o.inverse("HasFillings").is_empty())
        .collect()
}

/// The clear width of a door or window in metres from its attributes: OverallWidth less twice
/// the LiningThickness where both are given (and the width is larger), else OverallWidth;
/// `None` without OverallWidth. `metres` is metres per file length unit.
pub fn clear_width(door: Entity<'_>, metres: f64) -> Option<(f64, ClearWidthSource)> {
    let w = door.get_f64("OverallWidth")? * metres;
    if !(w.is_finite() && w > 0.0) {
        return None;
    }
    let lining = property::own_definitions(door)
        .into_iter()
        .chain(property::type_definitions(door))
        .filter(|d| d.is_a("IfcDoorLiningProperties") || d.is_a("IfcWindowLiningProperties"))
        .find_map(|d| d.get_f64("LiningThickness"))
        .map(|t| t * metres);
    match lining {
        Some(t) if t > 0.0 && w > 2.0 * t => Some((w - 2.0 * t, ClearWidthSource::Lining)),
        _ => Some((w, ClearWidthSource::OverallWidth)),
    }
}
