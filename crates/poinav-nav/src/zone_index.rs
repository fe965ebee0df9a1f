//! Which zone of a floor contains a point, through a uniform grid of buckets over the zones'
//! bounding boxes built once per floor: the same answers as [`crate::graph::zone_at`]'s fold
//! over every zone (the first zone in floor order containing the point, among zones within
//! [`crate::bounds::ELEMENT_VERTICES`]), at the cost of the few zones whose boxes cover the
//! point's bucket. Door side searches probe dozens of points per door, so a floor of many
//! doors and zones no longer pays doors x probes x zones.

use glam::DVec2;

use crate::floor::Floor;
use crate::polygon;
use crate::ZoneIdx;

/// Most bucket entries per zone before the buckets are made coarser (zones as large as the
/// floor would otherwise be listed in every bucket).
const ENTRIES_PER_ZONE: usize = 16;

/// A zone's bounding box.
type Box2 = (DVec2, DVec2);

/// Buckets over a floor's zones.
#[derive(Debug, Clone, PartialEq)]
pub struct ZoneIndex {
    /// Lower-left corner of bucket (0, 0).
    lo: DVec2,
    /// Bucket side, metres.
    cell: f64,
    /// Bucket columns.
    cols: usize,
    /// Bucket rows.
    rows: usize,
    /// Per bucket `b`, its zones are `items[starts[b]..starts[b + 1]]`, in floor order.
    starts: Vec<u32>,
    /// Zone indices, bucket by bucket.
    items: Vec<u32>,
    /// Per zone: its bounding box, `None` when it is never an answer (no ring, or past the
    /// vertex bound).
    boxes: Vec<Option<Box2>>,
    /// Zones whose boxes are not finite (coordinates NaN or infinite): in no bucket, always
    /// tried.
    loose: Vec<u32>,
}

fn finite(b: &Box2) -> bool {
    b.0.is_finite() && b.1.is_finite()
}

impl ZoneIndex {
    /// The index of `floor`'s zones.
    pub fn new(floor: &Floor) -> ZoneIndex {
        let boxes: Vec<Option<Box2>> = floor
            .zones
            .iter()
            .map(|z| {
                // A zone past the vertex bound is unknown in the grid, and doors near it are
                // undecided ([`crate::bounds::door_side_bounds`]): no search pays for it.
                if z.ring.len() > crate::bounds::ELEMENT_VERTICES {
                    return None;
                }
                polygon::bounds(&z.ring)
            })
            .collect();
        let loose: Vec<u32> = (0..boxes.len())
            .filter(|&z| boxes[z].as_ref().is_some_and(|b| !finite(b)))
            .map(|z| z as u32)
            .collect();
        let bucketed = || {
            boxes
                .iter()
                .enumerate()
                .filter_map(|(z, b)| b.filter(finite).map(|b| (z, b)))
        };
        let all = bucketed()
            .map(|(_, b)| b)
            .reduce(|(a, b), (c, d)| (a.min(c), b.max(d)));
        let Some((lo, hi)) = all else {
            return ZoneIndex {
                lo: DVec2::ZERO,
                cell: 1.0,
                cols: 1,
                rows: 1,
                starts: vec![0, 0],
                items: Vec::new(),
                boxes,
                loose,
            };
        };
        let n = bucketed().count();
        let size = (hi - lo).max(DVec2::splat(1e-9));
        // About one square bucket per zone (at most 4096 along a side), coarser while zones
        // would be listed too often.
        let mut cell = (size.x * size.y / n as f64)
            .sqrt()
            .max(size.max_element() / 4096.0);
        let (cols, rows) = loop {
            let (cols, rows) = dims(size, cell);
            let entries: usize = bucketed()
                .map(|(_, b)| {
                    let ((c0, r0), (c1, r1)) = span(lo, cell, cols, rows, b);
                    (c1 - c0 + 1) * (r1 - r0 + 1)
                })
                .sum();
            if entries <= ENTRIES_PER_ZONE * n || (cols == 1 && rows == 1) {
                break (cols, rows);
            }
            cell *= 2.0;
        };
        // A counting sort of (bucket, zone) pairs: zones stay in floor order in each bucket.
        let mut starts = vec![0u32; cols * rows + 1];
        for (_, b) in bucketed() {
            let ((c0, r0), (c1, r1)) = span(lo, cell, cols, rows, b);
            for r in r0..=r1 {
                for c in c0..=c1 {
                    starts[r * cols + c + 1] += 1;
                }
            }
        }
        for i in 1..starts.len() {
            starts[i] += starts[i - 1];
        }
        let mut next = starts.clone();
        let mut items = vec![0u32; starts[cols * rows] as usize];
        for (z, b) in bucketed() {
            let ((c0, r0), (c1, r1)) = span(lo, cell, cols, rows, b);
            for r in r0..=r1 {
                for c in c0..=c1 {
                    let k = &mut next[r * cols + c];
                    items[*k as usize] = z as u32;
                    *k += 1;
                }
            }
        }
        ZoneIndex {
            lo,
            cell,
            cols,
            rows,
            starts,
            items,
            boxes,
            loose,
        }
    }

    /// The first zone (in floor order) containing `p`, as [`crate::graph::zone_at`] answers.
    /// `floor` must be the floor the index was built from.
    pub fn zone_at(&self, floor: &Floor, p: DVec2) -> Option<ZoneIdx> {
        let hit = |z: usize| {
            self.boxes[z]
                .is_some_and(|(lo, hi)| p.x >= lo.x && p.y >= lo.y && p.x <= hi.x && p.y <= hi.y)
                && polygon::contains(&floor.zones[z].ring, p)
        };
        if !p.is_finite() {
            return (0..self.boxes.len()).find(|&z| hit(z)).map(ZoneIdx::new);
        }
        let c = bucket(self.lo.x, self.cell, self.cols, p.x);
        let r = bucket(self.lo.y, self.cell, self.rows, p.y);
        let b = r * self.cols + c;
        let (from, to) = (self.starts[b] as usize, self.starts[b + 1] as usize);
        let boxed = self.items[from..to]
            .iter()
            .map(|&z| z as usize)
            .find(|&z| hit(z));
        let loose = self.loose.iter().map(|&z| z as usize).find(|&z| hit(z));
        match (boxed, loose) {
            (Some(a), Some(b)) => Some(a.min(b)),
            (a, b) => a.or(b),
        }
        .map(ZoneIdx::new)
    }
}

/// Bucket columns and rows of side `cell` over `size`.
fn dims(size: DVec2, cell: f64) -> (usize, usize) {
    let n = |len: f64| ((len / cell).floor() as usize).saturating_add(1);
    (n(size.x), n(size.y))
}

/// The bucket along one axis holding coordinate `v`, clamped to the `n` buckets: a point
/// outside every zone's box may land in any bucket, it is checked against the boxes after.
fn bucket(lo: f64, cell: f64, n: usize, v: f64) -> usize {
    let k = ((v - lo) / cell).floor();
    if k <= 0.0 {
        0
    } else {
        (k as usize).min(n - 1)
    }
}

/// The first and last buckets box `b` covers: the same rounding as [`bucket`], so every
/// point in the box is in one of them.
fn span(
    lo: DVec2,
    cell: f64,
    cols: usize,
    rows: usize,
    b: Box2,
) -> ((usize, usize), (usize, usize)) {
    (
        (
            bucket(lo.x, cell, cols, b.0.x),
            bucket(lo.y, cell, rows, b.0.y),
        ),
        (
            bucket(lo.x, cell, cols, b.1.x),
            bucket(lo.y, cell, rows, b.1.y),
        ),
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::floor::FloorZone;
    use proptest::prelude::*;

    fn zone(ring: Vec<DVec2>) -> FloorZone {
        FloorZone {
            id: format!("z{}", ring.len()).into(),
            name: None,
            long_name: None,
            ring: ring.into(),
            roles: vec![],
            coordination: None,
        }
    }

    /// A floor of zones from (x, y, w, h, kind): rectangles, triangles, L shapes; overlapping,
    /// touching, thin and large ones, far from the origin.
    fn floor(shapes: &[(f64, f64, f64, f64, u8)]) -> Floor {
        let zones = shapes
            .iter()
            .map(|&(x, y, w, h, kind)| {
                let p = |a: f64, b: f64| DVec2::new(x + a * w, y + b * h);
                zone(match kind % 3 {
                    0 => vec![p(0.0, 0.0), p(1.0, 0.0), p(1.0, 1.0), p(0.0, 1.0)],
                    1 => vec![p(0.0, 0.0), p(1.0, 0.0), p(0.0, 1.0)],
                    _ => vec![
                        p(0.0, 0.0),
                        p(1.0, 0.0),
                        p(1.0, 0.4),
                        p(0.4, 0.4),
                        p(0.4, 1.0),
                        p(0.0, 1.0),
                    ],
                })
            })
            .collect();
        Floor {
            name: "F".into(),
            zones,
            ..Floor::default()
        }
    }

    fn same_answers(f: &Floor, points: &[DVec2]) {
        let index = ZoneIndex::new(f);
        for p in points {
            assert_eq!(
                index.zone_at(f, *p),
                crate::graph::zone_at(f, *p),
                "at {p:?}"
            );
        }
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(64))]

        #[test]
        fn the_index_answers_as_the_fold_over_every_zone(
            shapes in prop::collection::vec(
                (-50.0..50.0f64, -50.0..50.0f64, 0.01..40.0f64, 0.01..40.0f64, 0u8..3),
                0..40,
            ),
            offset in prop::sample::select(vec![0.0, 1e5, -3.7e6]),
            probes in prop::collection::vec((-60.0..100.0f64, -60.0..100.0f64), 200),
        ) {
            let moved: Vec<_> = shapes
                .iter()
                .map(|&(x, y, w, h, k)| (x + offset, y - offset, w, h, k))
                .collect();
            let f = floor(&moved);
            let mut points: Vec<DVec2> = probes
                .iter()
                .map(|&(x, y)| DVec2::new(x + offset, y - offset))
                .collect();
            // Corners and edges of every zone: on its box's boundary.
            for z in &f.zones {
                points.extend(z.ring.iter().copied());
                points.push((z.ring[0] + z.ring[1]) / 2.0);
            }
            same_answers(&f, &points);
        }
    }

    #[test]
    fn odd_zones_and_points_answer_as_the_fold() {
        let mut f = floor(&[
            (0.0, 0.0, 10.0, 10.0, 0),
            (2.0, 2.0, 1.0, 1.0, 0),
            (5.0, 5.0, 0.0, 3.0, 0),
            (-1e4, -1e4, 2e4, 2e4, 0),
        ]);
        // Past the vertex bound: never an answer; without a ring; with a NaN corner.
        let many: Vec<DVec2> = (0..=crate::bounds::ELEMENT_VERTICES)
            .map(|k| {
                let a = k as f64 / crate::bounds::ELEMENT_VERTICES as f64 * std::f64::consts::TAU;
                DVec2::new(a.cos(), a.sin()) * 3.0
            })
            .collect();
        f.zones.insert(0, zone(many));
        f.zones.push(zone(Vec::new()));
        f.zones.push(zone(vec![
            DVec2::new(0.0, 0.0),
            DVec2::new(f64::NAN, 0.0),
            DVec2::new(1.0, 1.0),
        ]));
        let points = [
            DVec2::new(2.5, 2.5),
            DVec2::new(0.5, 0.5),
            DVec2::new(5.0, 6.0),
            DVec2::new(9e3, -9e3),
            DVec2::new(3e4, 0.0),
            DVec2::new(f64::NAN, 1.0),
            DVec2::new(f64::INFINITY, 1.0),
            DVec2::new(-f64::INFINITY, f64::NEG_INFINITY),
        ];
        same_answers(&f, &points);
        let index = ZoneIndex::new(&f);
        assert_eq!(
            index.zone_at(&f, DVec2::new(2.5, 2.5)),
            Some(ZoneIdx::new(1))
        );
        assert_eq!(
            index.zone_at(&f, DVec2::new(20.0, 20.0)),
            Some(ZoneIdx::new(4))
        );
        assert_eq!(index.zone_at(&f, DVec2::new(3e4, 0.0)), None);
        // A floor without zones.
        same_answers(&Floor::default(), &points);
    }

    #[test]
    fn many_zones_are_spread_over_buckets() {
        // A 40 x 40 grid of 2 m rooms and one hall over all of them.
        let mut shapes: Vec<(f64, f64, f64, f64, u8)> = (0..1600)
            .map(|k| ((k % 40) as f64 * 2.0, (k / 40) as f64 * 2.0, 2.0, 2.0, 0))
            .collect();
        shapes.push((0.0, 0.0, 80.0, 80.0, 0));
        let f = floor(&shapes);
        let index = ZoneIndex::new(&f);
        // Each bucket lists a handful of rooms besides the hall, not all 1,601 zones.
        let longest = index.starts.windows(2).map(|w| w[1] - w[0]).max().unwrap();
        assert!(longest <= 10, "{longest}");
        assert!(
            index.cols * index.rows >= 400,
            "{} x {}",
            index.cols,
            index.rows
        );
        let points: Vec<DVec2> = (0..4000)
            .map(|k| DVec2::new((k % 97) as f64 * 0.83, (k / 97) as f64 * 1.97))
            .collect();
        same_answers(&f, &points);
        assert_eq!(
            index.zone_at(&f, DVec2::new(3.0, 1.0)),
            Some(ZoneIdx::new(1))
        );
        assert_eq!(
            index.zone_at(&f, DVec2::new(79.9, 79.9)),
            Some(ZoneIdx::new(1599))
        );
        assert_eq!(
            index.zone_at(&f, DVec2::new(80.0, 80.0)),
            crate::graph::zone_at(&f, DVec2::new(80.0, 80.0))
        );
    }
}
