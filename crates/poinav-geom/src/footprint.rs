//! The footprint of a product (an `IfcSpace`, a door, an opening, any `IfcProduct`): its
//! horizontal outline in world XY metres and its z-range, from its body representation.
//!
//! How the outline is made ([`FootprintMethod`]):
//! - one vertically extruded `IfcExtrudedAreaSolid` (directly, through mapped items, or as the
//!   first operand of a boolean result): the profile, placed in the world: exact, concave
//!   outlines kept ([`FootprintMethod::Outline`]);
//! - anything else (faceted breps, face sets, surface models, several items, non-vertical
//!   extrusions): the convex hull of all world vertices projected on XY
//!   ([`FootprintMethod::ConvexHull`]); exact for convex solids, larger than the real outline
//!   for L-shaped or otherwise concave ones.
//!
//! Voids of profiles are ignored (the footprint is the outer boundary), and so is the
//! clipping of boolean results (reported in [`ProductFootprint::approximations`]).

use glam::{DVec2, DVec3};
use poinav_ifc::{Entity, EntityId};
use serde::{Deserialize, Serialize};

use crate::error::GeomError;
use crate::placement::PlacementCache;
use crate::polygon::{self, Rectangle};
use crate::representation::{self, Approximation};

/// A horizontal outline and the heights it spans, in world metres.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Footprint {
    /// The outline in world XY, counter-clockwise, not repeating its first point.
    pub polygon: Vec<DVec2>,
    /// Lowest z of the solid.
    pub z_min: f64,
    /// Highest z of the solid.
    pub z_max: f64,
}

impl Footprint {
    /// The convex hull of `points` projected on XY, with their z-range; `None` when the points
    /// span no area.
    pub fn convex_hull_of(points: &[DVec3]) -> Option<Footprint> {
        let flat: Vec<DVec2> = points.iter().map(|p| p.truncate()).collect();
        let hull = polygon::clean(polygon::convex_hull(&flat))?;
        let (z_min, z_max) = z_range(points);
        Some(Footprint {
            polygon: hull,
            z_min,
            z_max,
        })
    }

    /// Enclosed area in square metres.
    pub fn area(&self) -> f64 {
        polygon::signed_area(&self.polygon).abs()
    }

    /// `z_max - z_min`.
    pub fn height(&self) -> f64 {
        self.z_max - self.z_min
    }

    /// The area centroid of the outline.
    pub fn centroid(&self) -> DVec2 {
        polygon::centroid(&self.polygon).unwrap_or_default()
    }

    /// The minimum-area rectangle around the outline (rotating calipers on its convex hull).
    pub fn min_area_rectangle(&self) -> Option<Rectangle> {
        polygon::min_area_rectangle(&self.polygon)
    }

    /// Long side over short side of [`Footprint::min_area_rectangle`]: 1 for a square, 5 for
    /// a 10 x 2 room whichever way it is turned; infinite for an outline with no width.
    pub fn elongation(&self) -> f64 {
        match self.min_area_rectangle() {
            Some(r) if r.width > 0.0 => r.length / r.width,
            Some(_) => f64::INFINITY,
            None => 1.0,
        }
    }

    /// True when `point` (world XY) is inside the outline or on its boundary.
    pub fn contains(&self, point: DVec2) -> bool {
        polygon::contains_closed(&self.polygon, point)
    }

    /// Distance from `point` (world XY) to the outline: 0 inside, else to the nearest edge.
    pub fn distance_to(&self, point: DVec2) -> f64 {
        if self.contains(point) {
            0.0
        } else {
            polygon::boundary_distance(&self.polygon, point)
        }
    }
}

fn z_range(points: &[DVec3]) -> (f64, f64) {
    points
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), p| {
            (lo.min(p.z), hi.max(p.z))
        })
}

/// How a footprint's outline was made.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub enum FootprintMethod {
    /// The placed profile of one vertical extrusion: exact.
    Outline,
    /// The convex hull of all vertices.
    ConvexHull,
}

/// A product's footprint and how it was obtained.
#[derive(Debug, Clone, PartialEq)]
pub struct ProductFootprint {
    /// The product.
    pub product: EntityId,
    /// The shape representation used.
    pub representation: EntityId,
    /// The footprint.
    pub footprint: Footprint,
    /// How its outline was made.
    pub method: FootprintMethod,
    /// Where it is less exact than the file (grid placements, clipping ignored, items left out,
    /// non-vertical extrusions).
    pub approximations: Vec<Approximation>,
}

/// The footprint of `product` from its `Body` (else first) shape representation, placed in
/// the world with its `ObjectPlacement`. Errors name the `#id` at fault: no representation,
/// an unreadable placement, or no item that could be read.
pub fn footprint_of<'m>(
    cache: &mut PlacementCache<'m>,
    product: Entity<'m>,
) -> Result<ProductFootprint, GeomError> {
    let (placement, grid) = cache.product_or_identity(product)?;
    let rep = representation::body_representation(product)?;
    let units = cache.units();
    let geometry = representation::evaluate(rep, placement, &units)?;
    let mut approximations: Vec<Approximation> =
        grid.into_iter().map(Approximation::GridPlacement).collect();
    approximations.extend(geometry.approximations);
    let all: Vec<DVec3> = geometry
        .items
        .iter()
        .flat_map(|i| i.points.iter().copied())
        .collect();
    let (z_min, z_max) = z_range(&all);
    if !(z_min.is_finite() && z_max.is_finite()) {
        return Err(GeomError::Degenerate {
            id: rep.id(),
            reason: "coordinates overflow",
        });
    }
    let degenerate = || GeomError::Degenerate {
        id: rep.id(),
        reason: "the representation spans no horizontal area",
    };
    let (footprint, method) = match &geometry.items[..] {
        [representation::ItemGeometry {
            outline: Some(outline),
            ..
        }] => (
            Footprint {
                polygon: outline.clone(),
                z_min,
                z_max,
            },
            FootprintMethod::Outline,
        ),
        _ => (
            Footprint::convex_hull_of(&all).ok_or_else(degenerate)?,
            FootprintMethod::ConvexHull,
        ),
    };
    Ok(ProductFootprint {
        product: product.id(),
        representation: rep.id(),
        footprint,
        method,
        approximations,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn elongation_contains_and_distance() {
        let r = DVec2::from_angle(30f64.to_radians());
        let f = Footprint {
            polygon: [(-5.0, -1.0), (5.0, -1.0), (5.0, 1.0), (-5.0, 1.0)]
                .iter()
                .map(|&(x, y)| r.rotate(DVec2::new(x, y)))
                .collect(),
            z_min: 0.0,
            z_max: 3.0,
        };
        assert!((f.elongation() - 5.0).abs() < 1e-9);
        assert!((f.area() - 20.0).abs() < 1e-9);
        assert!(f.contains(DVec2::ZERO));
        assert_eq!(f.distance_to(DVec2::ZERO), 0.0);
        let outside = r.rotate(DVec2::new(0.0, 3.0));
        assert!(!f.contains(outside));
        assert!((f.distance_to(outside) - 2.0).abs() < 1e-9);
        assert_eq!(f.height(), 3.0);
    }
}
