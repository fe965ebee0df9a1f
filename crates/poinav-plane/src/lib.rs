//! Plane geometry on rings, knowing no IFC and no floor: the owned [`Ring`] and the functions
//! on rings and points (`&[DVec2]`, metres, implicitly closed) that the geometry crate
//! (`poinav-geom`), the floor model (`poinav-floor`) and everything above them share, each
//! with one argument order: the ring (or segment) first, the point last.
//!
//! - [`ring`]: [`Ring`], an owned ring that serialises as its point list; [`rect`].
//! - [`measure`]: signed area, centroid, bounds (of a ring or any points), containment (even-odd, or with the boundary),
//!   crossings of a horizontal line, a point inside.
//! - [`distance`]: distances from a point to a segment, a ring's boundary, a ring as an area,
//!   and between two rings; where a line crosses a segment's line.
//! - [`clean`]: rings without repeated points, counter-clockwise.
//! - [`hull`]: convex hulls and minimum-area enclosing rectangles ([`Rectangle`]).
//! - [`frame`]: the frame of a passage ring ([`PassageFrame`]).

pub mod clean;
pub mod distance;
pub mod frame;
pub mod hull;
pub mod measure;
pub mod ring;

pub use clean::{clean, without_repeats};
pub use distance::{
    area_distance, boundary_distance, line_crossing, ring_distance, segment_distance,
};
pub use frame::PassageFrame;
pub use hull::{convex_hull, min_area_rectangle, Rectangle};
pub use measure::{
    bounds, bounds_of, centroid, centroid_about, contains, contains_closed, crossings,
    crossings_into, interior_point, signed_area,
};
pub use ring::{rect, Ring};
