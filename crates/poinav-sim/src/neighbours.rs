//! A spatial hash of points (uniform grid, cells sorted by key) for neighbour-pair queries: the
//! separation checks over many robots (`no-contact`, the distance plot) visit only pairs in
//! adjacent cells instead of every pair, so their cost grows with the robots, not their square.

use glam::DVec2;

/// Points bucketed in square cells of a given size.
#[derive(Debug, Clone, Default)]
pub struct PointGrid {
    cell: f64,
    /// (cell x, cell y, point index), sorted.
    keys: Vec<(i64, i64, u32)>,
}

impl PointGrid {
    /// Rebuilds the grid over `points` with cells of `cell` metres (at least 1 mm).
    pub fn rebuild(&mut self, points: &[DVec2], cell: f64) {
        self.cell = if cell.is_finite() {
            cell.max(1e-3)
        } else {
            1e6
        };
        self.keys.clear();
        for (i, p) in points.iter().enumerate() {
            let (x, y) = self.key(*p);
            self.keys.push((x, y, i as u32));
        }
        self.keys.sort_unstable();
    }

    fn key(&self, p: DVec2) -> (i64, i64) {
        let q = p / self.cell;
        (q.x.floor() as i64, q.y.floor() as i64)
    }

    fn bucket(&self, x: i64, y: i64) -> &[(i64, i64, u32)] {
        let a = self.keys.partition_point(|k| (k.0, k.1) < (x, y));
        let b = a + self.keys[a..].partition_point(|k| (k.0, k.1) == (x, y));
        &self.keys[a..b]
    }

    /// Calls `f(a, b)` with `a < b` for every pair of points closer than the cell size (and some
    /// farther ones: callers test the exact distance), each pair once, in ascending `(a, b)`
    /// order of the first point.
    pub fn pairs(&self, points: &[DVec2], mut f: impl FnMut(usize, usize)) {
        for (a, p) in points.iter().enumerate() {
            let (cx, cy) = self.key(*p);
            for y in cy - 1..=cy + 1 {
                for x in cx - 1..=cx + 1 {
                    for &(_, _, b) in self.bucket(x, y) {
                        if (b as usize) > a {
                            f(a, b as usize);
                        }
                    }
                }
            }
        }
    }

    /// Indices of the points within `r` of `p` (cells within `r` are visited; callers test the
    /// exact distance), in no particular order.
    pub fn near(&self, p: DVec2, r: f64, mut f: impl FnMut(usize)) {
        let (x0, y0) = self.key(p - DVec2::splat(r));
        let (x1, y1) = self.key(p + DVec2::splat(r));
        // The keys sort by column first: a column's cells y0..=y1 follow each other, found by
        // one search per column (not two per cell).
        for x in x0..=x1 {
            let a = self.keys.partition_point(|k| (k.0, k.1) < (x, y0));
            for &(kx, ky, b) in &self.keys[a..] {
                if kx != x || ky > y1 {
                    break;
                }
                f(b as usize);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pairs_and_points_near_are_all_found_once() {
        let mut seed = 0x2545_F491_4F6C_DD1Du64;
        let mut rnd = || {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            (seed >> 11) as f64 / (1u64 << 53) as f64
        };
        let pts: Vec<DVec2> = (0..400)
            .map(|_| DVec2::new(rnd() * 40.0 - 20.0, rnd() * 30.0 - 15.0))
            .collect();
        let mut g = PointGrid::default();
        g.rebuild(&pts, 1.5);
        let mut found = Vec::new();
        g.pairs(&pts, |a, b| {
            if pts[a].distance(pts[b]) <= 1.5 {
                found.push((a, b));
            }
        });
        let mut brute = Vec::new();
        for a in 0..pts.len() {
            for b in a + 1..pts.len() {
                if pts[a].distance(pts[b]) <= 1.5 {
                    brute.push((a, b));
                }
            }
        }
        found.sort_unstable();
        assert_eq!(found, brute);
        assert!(brute.len() > 100, "{}", brute.len());
        // Queries at points of the set, between them, and beyond the set's edge.
        let mut queries: Vec<DVec2> = pts[..40].to_vec();
        queries.extend([DVec2::new(-21.0, 0.0), DVec2::new(22.5, 16.0), DVec2::ZERO]);
        let mut found = 0;
        for q in queries {
            for r in [0.7, 3.0] {
                let mut near = Vec::new();
                g.near(q, r, |b| {
                    if pts[b].distance(q) <= r {
                        near.push(b)
                    }
                });
                near.sort_unstable();
                let want: Vec<usize> = (0..pts.len())
                    .filter(|&b| pts[b].distance(q) <= r)
                    .collect();
                assert_eq!(near, want, "{q} {r}");
                found += near.len();
            }
        }
        assert!(found > 400, "{found}");
    }
}
