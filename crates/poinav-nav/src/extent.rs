//! Where there is something to navigate on a storey: its own extent (the bounds of its spaces,
//! doors and walls), a copy of the storey cropped to it (obstacles further out cut off at a
//! margin, so a site model, terrain or a neighbouring building does not widen every map), and
//! whether a storey has anything to navigate at all (a space or a door: a roof with its
//! parapet walls has not). [`crate::Navigator`] rasterises every storey through [`for_grid`],
//! so routes, the audit and the Nav2 bundle all see the same cropped storeys.

use std::borrow::Cow;

use glam::DVec2;
use serde::Serialize;

use crate::floor::{Floor, FloorObstacle};
use crate::grid::GridOptions;
use crate::Ring;

/// A storey with nothing to navigate ([`nothing_to_navigate`]): rasterised empty, no Nav2
/// folder, no audit drawing.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SkippedStorey {
    /// Storey name.
    pub floor: String,
    /// Why ([`nothing_to_navigate`]).
    pub reason: String,
}

impl SkippedStorey {
    /// The line the CLI prints: `skipped storey Roof: no spaces or doors (1 other element)`.
    pub fn line(&self) -> String {
        format!("skipped storey {}: {}", self.floor, self.reason)
    }
}

/// Whether an obstacle of this IFC class is a wall (walls bound what a robot can reach).
pub fn is_wall(class: &str) -> bool {
    class.starts_with("IfcWall") || class.starts_with("IfcCurtainWall")
}

/// The bounds of `floor`'s zones, doors and walls; `None` when it has none of them.
pub fn own_extent(floor: &Floor) -> Option<(DVec2, DVec2)> {
    let points = floor
        .zones
        .iter()
        .flat_map(|z| z.ring.iter())
        .chain(floor.doors.iter().flat_map(|d| d.ring.iter()))
        .chain(
            floor
                .obstacles
                .iter()
                .filter(|o| is_wall(&o.class))
                .flat_map(|o| o.rings.iter().flatten()),
        );
    crate::polygon::bounds_of(points)
}

/// Why `floor` has nothing to navigate (no spaces and no doors), or `None`.
pub fn nothing_to_navigate(floor: &Floor) -> Option<String> {
    if !(floor.zones.is_empty() && floor.doors.is_empty()) {
        return None;
    }
    let walls = floor.obstacles.iter().filter(|o| is_wall(&o.class)).count();
    let others = floor.obstacles.len() - walls;
    let count = |n: usize, what: &str| format!("{n} {what}{}", if n == 1 { "" } else { "s" });
    Some(match (walls, others) {
        (0, 0) => "nothing on it".to_string(),
        (0, o) => format!("no spaces or doors ({})", count(o, "other element")),
        (w, 0) => format!("no spaces or doors ({})", count(w, "wall")),
        (w, o) => format!(
            "no spaces or doors ({}, {})",
            count(w, "wall"),
            count(o, "other element")
        ),
    })
}

/// How far beyond its own extent a storey is kept for `options`: the entrance apron plus
/// [`GridOptions::crop_margin_m`].
pub fn margin(options: &GridOptions) -> f64 {
    options.entrance_apron_m.max(0.0) + options.crop_margin_m.max(0.0)
}

/// What is rasterised of `floor` with `options`: [`cropped`] at [`margin`], borrowed when
/// cropping leaves it as it is (every obstacle inside), so a building without a site around it
/// is not copied.
pub fn for_grid<'a>(floor: &'a Floor, options: &GridOptions) -> Cow<'a, Floor> {
    crop(floor, margin(options))
}

/// `floor` cropped to its own extent grown by `margin` metres on every side: obstacles wholly
/// outside dropped, those across the edge clipped to it (zones and doors are kept whole: they
/// are the extent). A floor with nothing to navigate ([`nothing_to_navigate`]) loses every
/// obstacle.
pub fn cropped(floor: &Floor, margin: f64) -> Floor {
    crop(floor, margin).into_owned()
}

fn crop(floor: &Floor, margin: f64) -> Cow<'_, Floor> {
    let without = |obstacles: Vec<FloorObstacle>| {
        Cow::Owned(Floor {
            name: floor.name.clone(),
            elevation_m: floor.elevation_m,
            obstacles,
            doors: floor.doors.clone(),
            zones: floor.zones.clone(),
        })
    };
    let extent = own_extent(floor).filter(|_| nothing_to_navigate(floor).is_none());
    let Some((lo, hi)) = extent else {
        return if floor.obstacles.is_empty() {
            Cow::Borrowed(floor)
        } else {
            without(Vec::new())
        };
    };
    let (lo, hi) = (lo - DVec2::splat(margin), hi + DVec2::splat(margin));
    let inside = |p: &DVec2| p.x >= lo.x && p.x <= hi.x && p.y >= lo.y && p.y <= hi.y;
    if floor
        .obstacles
        .iter()
        .all(|o| !o.rings.is_empty() && o.rings.iter().flatten().all(inside))
    {
        return Cow::Borrowed(floor);
    }
    let obstacles = floor
        .obstacles
        .iter()
        .filter_map(|o| {
            let rings: Vec<Ring> = o
                .rings
                .iter()
                .filter_map(|r| clip_ring(r, lo, hi).map(Ring::from))
                .collect();
            (!rings.is_empty()).then(|| FloorObstacle {
                rings,
                id: o.id.clone(),
                class: o.class.clone(),
                kind: o.kind,
                roles: o.roles.clone(),
            })
        })
        .collect();
    without(obstacles)
}

/// `ring` clipped to the box `lo`-`hi` (Sutherland-Hodgman: a concave ring may come back with
/// zero-width bridges along the box's edges, which cover no cell); `None` when nothing is left.
fn clip_ring(ring: &[DVec2], lo: DVec2, hi: DVec2) -> Option<Vec<DVec2>> {
    let inside_box = |p: &DVec2| p.x >= lo.x && p.x <= hi.x && p.y >= lo.y && p.y <= hi.y;
    if ring.iter().all(inside_box) {
        return Some(ring.to_vec());
    }
    // (axis, bound, keep below the bound)
    let edges = [
        (0, lo.x, false),
        (0, hi.x, true),
        (1, lo.y, false),
        (1, hi.y, true),
    ];
    let mut out = ring.to_vec();
    for (axis, bound, below) in edges {
        if out.is_empty() {
            break;
        }
        let inside = |p: DVec2| {
            let v = if axis == 0 { p.x } else { p.y };
            if below {
                v <= bound
            } else {
                v >= bound
            }
        };
        let cut = |a: DVec2, b: DVec2| {
            let (va, vb) = if axis == 0 { (a.x, b.x) } else { (a.y, b.y) };
            let t = (bound - va) / (vb - va);
            let p = a + (b - a) * t;
            if axis == 0 {
                DVec2::new(bound, p.y)
            } else {
                DVec2::new(p.x, bound)
            }
        };
        let input = std::mem::take(&mut out);
        for (i, &b) in input.iter().enumerate() {
            let a = input[(i + input.len() - 1) % input.len()];
            match (inside(a), inside(b)) {
                (true, true) => out.push(b),
                (true, false) => out.push(cut(a, b)),
                (false, true) => {
                    out.push(cut(a, b));
                    out.push(b);
                }
                (false, false) => {}
            }
        }
    }
    (out.len() >= 3 && crate::polygon::signed_area(&out).abs() > 0.0).then_some(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::floor::{FloorZone, ObstacleKind};
    use crate::polygon::rect;

    fn obstacle(class: &str, ring: Ring) -> FloorObstacle {
        FloorObstacle {
            id: class.into(),
            class: class.into(),
            kind: ObstacleKind::Structure,
            rings: vec![ring],
            roles: vec![],
        }
    }

    #[test]
    fn a_site_slab_is_cut_at_the_margin_around_the_rooms_and_walls() {
        let floor = Floor {
            name: "Ground".into(),
            obstacles: vec![
                obstacle("IfcWall", rect(0.0, 0.0, 10.0, 0.2)),
                obstacle("IfcSlab", rect(-100.0, -50.0, 200.0, 80.0)),
                obstacle("IfcFurnishingElement", rect(50.0, 50.0, 51.0, 51.0)),
            ],
            zones: vec![FloorZone {
                id: "room".into(),
                name: None,
                long_name: None,
                ring: rect(0.0, 0.2, 10.0, 6.0),
                roles: vec![],
                coordination: None,
            }],
            ..Floor::default()
        };
        assert_eq!(
            own_extent(&floor),
            Some((DVec2::new(0.0, 0.0), DVec2::new(10.0, 6.0)))
        );
        let c = cropped(&floor, 2.0);
        assert_eq!(c.obstacles.len(), 2, "the far chair is dropped");
        assert_eq!(c.obstacles[0], floor.obstacles[0]);
        let mut corners = c.obstacles[1].rings[0].to_vec();
        corners.sort_by(|a, b| a.x.total_cmp(&b.x).then(a.y.total_cmp(&b.y)));
        assert_eq!(
            corners,
            [(-2.0, -2.0), (-2.0, 8.0), (12.0, -2.0), (12.0, 8.0)].map(|(x, y)| DVec2::new(x, y))
        );
        assert_eq!(
            c.bounds(),
            Some((DVec2::new(-2.0, -2.0), DVec2::new(12.0, 8.0)))
        );
        assert_eq!(nothing_to_navigate(&floor), None);
    }

    #[test]
    fn a_storey_with_only_a_roof_and_its_parapet_has_nothing_to_navigate() {
        let floor = Floor {
            name: "Roof".into(),
            obstacles: vec![obstacle("IfcRoof", rect(0.0, 0.0, 10.0, 10.0))],
            ..Floor::default()
        };
        assert_eq!(own_extent(&floor), None);
        assert_eq!(
            nothing_to_navigate(&floor).as_deref(),
            Some("no spaces or doors (1 other element)")
        );
        assert!(cropped(&floor, 1.0).obstacles.is_empty());
        let mut parapet = floor.clone();
        parapet
            .obstacles
            .push(obstacle("IfcWallStandardCase", rect(0.0, 0.0, 10.0, 0.2)));
        assert_eq!(
            nothing_to_navigate(&parapet).as_deref(),
            Some("no spaces or doors (1 wall, 1 other element)")
        );
        assert_eq!(
            nothing_to_navigate(&Floor::default()).as_deref(),
            Some("nothing on it")
        );
    }

    #[test]
    fn a_concave_ring_across_the_edge_keeps_its_inside_area() {
        // An L: 0..4 x 0..1 plus 0..1 x 1..4, clipped at x <= 2.
        let l = vec![
            DVec2::new(0.0, 0.0),
            DVec2::new(4.0, 0.0),
            DVec2::new(4.0, 1.0),
            DVec2::new(1.0, 1.0),
            DVec2::new(1.0, 4.0),
            DVec2::new(0.0, 4.0),
        ];
        let c = clip_ring(&l, DVec2::new(-1.0, -1.0), DVec2::new(2.0, 5.0)).unwrap();
        assert!((crate::polygon::signed_area(&c).abs() - 5.0).abs() < 1e-12);
        assert_eq!(
            clip_ring(&l, DVec2::new(5.0, 5.0), DVec2::new(6.0, 6.0)),
            None
        );
    }
}
