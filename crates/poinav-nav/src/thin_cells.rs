//! Obstacle parts thinner than a grid cell, rasterised conservatively: a grid samples cells at
//! their centres ([`crate::grid`]), so a 5 mm glass panel, the 1 cm line drawn for a fence
//! modelled as a surface, or the thin fin of a larger outline can fall between two rows of
//! centres, or cross them only here and there, and leave free cells a route goes through.
//! `ThinCells::paint` paints a ring as the grid does (cells whose centre is inside), then
//! also every cell its boundary touches where the ring is thinner than a cell: no cell of its
//! own is in the 3 x 3 block around it, or two of its edges cross that block facing each other
//! across the inside closer than a cell. Along a part at least a cell thick neither holds, so
//! walls, door jambs and furniture come out exactly as before; the floor's obstacles themselves
//! are never widened (the simulator's rays hit them as they are). Around door passages
//! ([`DOOR_MARGIN_M`]) the thin parts of doors, walls and coverings are drawn by their centres
//! alone, as before: linings, casings and reveals thinner than a cell would otherwise narrow
//! the grid's passages ([`lines_doors`]). Every other element is drawn whole there too: a
//! glass sidelight, a railing or a panel beside a door must not leave free cells along it.
//!
//! The work is the grid's fill plus a walk along the boundary (each edge's cells, sorted once;
//! per cell the edges of its block): linear in the outline and its cells, in a window of the
//! ring's box.

use glam::DVec2;

use crate::grid::{spans, Frame};
use crate::polygon::{self, PassageFrame};

/// How far around a door's passage ring (its rectangle in its own frame, grown this much on
/// every side, metres) the thin parts of the elements that line doors ([`lines_doors`]) are
/// drawn by their centres alone, as before: door linings and casings are often thinner than
/// a cell, and touching cells there would narrow the passage in the grid (the clear width
/// checks and the corpus routes read it as it was).
pub const DOOR_MARGIN_M: f64 = 0.25;

/// True for the IFC classes whose thin parts around a door are its linings, casings or
/// reveals (doors, walls, coverings: [`DOOR_MARGIN_M`]); false for everything else (windows,
/// plates, members, curtain walls, railings, furniture), which is drawn whole beside a door.
pub fn lines_doors(class: &str) -> bool {
    ["IfcDoor", "IfcWall", "IfcCovering"]
        .iter()
        .any(|c| class.starts_with(c))
}

/// The cells where thin parts are added (all but those around doors, [`DOOR_MARGIN_M`]) and
/// reusable scratch for [`ThinCells::paint`]: per cell of the current ring's window, which
/// ring painted it (by a counter, so nothing is cleared between rings); the cells the ring's
/// edges touch with the edge, and the cells added.
#[derive(Debug, Default)]
pub(crate) struct ThinCells {
    /// Per grid cell, true around a door (empty: no door).
    at_door: Vec<bool>,
    painted: Vec<u32>,
    tag: u32,
    hits: Vec<(usize, u32)>,
    near: Vec<u32>,
    extra: Vec<usize>,
}

impl ThinCells {
    /// Thin parts added everywhere in `g` but around the passage rings `doors`.
    pub(crate) fn around_doors<'a>(g: Frame, doors: impl Iterator<Item = &'a [DVec2]>) -> Self {
        let mut at_door = Vec::new();
        for ring in doors {
            let Some(f) = PassageFrame::of(ring) else {
                continue;
            };
            if at_door.is_empty() {
                at_door = vec![false; g.width * g.height];
            }
            let around = f.rectangle(f.half_width + DOOR_MARGIN_M, f.half_depth + DOOR_MARGIN_M);
            spans(g, &around, |row, a, b| {
                at_door[row * g.width + a..row * g.width + b].fill(true)
            });
        }
        ThinCells {
            at_door,
            ..ThinCells::default()
        }
    }

    /// Calls `f` with the index of every cell whose centre is inside `ring` (even-odd, as the
    /// grid paints); then, in increasing order, each once, with every other cell `ring`'s
    /// boundary touches where the ring is thinner than a cell: none of the painted cells is in
    /// the 3 x 3 block around it (a tip, a part too small for a centre), or two edges that do
    /// not meet pass through that block facing each other across the ring's inside closer than
    /// a cell ([`facing_closer`]: a panel, a fin); but none around a door ([`DOOR_MARGIN_M`])
    /// when the ring's element `lines_door` ([`lines_doors`] of its class).
    pub(crate) fn paint(
        &mut self,
        g: Frame,
        ring: &[DVec2],
        lines_door: bool,
        f: impl FnMut(usize),
    ) {
        self.paint_searching(g, ring, lines_door, f, false);
    }

    /// [`ThinCells::paint`], searching thick convex rings too when `always`.
    fn paint_searching(
        &mut self,
        g: Frame,
        ring: &[DVec2],
        lines_door: bool,
        mut f: impl FnMut(usize),
        always: bool,
    ) {
        let Some((lo, hi)) = polygon::bounds(ring) else {
            return;
        };
        if ring.len() < 3
            || g.width == 0
            || g.height == 0
            || !(lo.is_finite() && hi.is_finite())
            || (!always && thick_convex(ring, g.res))
        {
            spans(g, ring, |row, a, b| {
                (row * g.width + a..row * g.width + b).for_each(&mut f)
            });
            return;
        }
        // The window: the cells of the ring's box and one more around, within the grid.
        let cell = |v: f64, o: f64| ((v - o) / g.res).floor();
        let c0 = (cell(lo.x, g.origin.x) - 1.0).max(0.0);
        let c1 = (cell(hi.x, g.origin.x) + 1.0).min(g.width as f64 - 1.0);
        let r0 = (cell(lo.y, g.origin.y) - 1.0).max(0.0);
        let r1 = (cell(hi.y, g.origin.y) + 1.0).min(g.height as f64 - 1.0);
        if c1 < c0 || r1 < r0 {
            // Wholly outside the grid: no cell to paint.
            return;
        }
        let (c0, c1, r0, r1) = (c0 as usize, c1 as usize, r0 as usize, r1 as usize);
        let (bw, bh) = (c1 - c0 + 1, r1 - r0 + 1);
        if self.tag == u32::MAX {
            self.painted.iter_mut().for_each(|s| *s = 0);
            self.tag = 0;
        }
        self.tag += 1;
        if self.painted.len() < bw * bh {
            self.painted.resize(bw * bh, 0);
        }
        let tag = self.tag;
        let ThinCells {
            at_door,
            painted,
            hits,
            near,
            extra,
            ..
        } = self;
        spans(g, ring, |row, a, b| {
            (row * g.width + a..row * g.width + b).for_each(&mut f);
            let base = (row - r0) * bw;
            painted[base + a - c0..base + b - c0].fill(tag);
        });
        // Every (window cell, edge) the boundary touches, by cell.
        hits.clear();
        let n = ring.len();
        for k in 0..n {
            touched(g, ring[k], ring[(k + 1) % n], |col, row| {
                hits.push(((row - r0) * bw + col - c0, k as u32));
            });
        }
        hits.sort_unstable();
        hits.dedup();
        let inward = if polygon::signed_area(ring) >= 0.0 {
            1.0
        } else {
            -1.0
        };
        extra.clear();
        let mut k = 0;
        while k < hits.len() {
            let i = hits[k].0;
            while k < hits.len() && hits[k].0 == i {
                k += 1;
            }
            if painted[i] == tag {
                continue;
            }
            let (col, row) = (i % bw, i / bw);
            // The block's cells in the window (a cell's margin around the ring's box, but where
            // the grid ends).
            let mut cells = (0..3usize)
                .flat_map(|dr| (0..3usize).map(move |dc| (col + dc, row + dr)))
                .filter(|&(c, r)| c >= 1 && r >= 1 && c - 1 < bw && r - 1 < bh)
                .map(|(c, r)| (r - 1) * bw + c - 1);
            let thin = if !cells.any(|j| painted[j] == tag) {
                true
            } else {
                // The edges through the block, a row of three cells at a time.
                near.clear();
                for r in row.max(1) - 1..(row + 2).min(bh) {
                    let (a, b) = (r * bw + col.max(1) - 1, r * bw + (col + 1).min(bw - 1));
                    let from = hits.partition_point(|h| h.0 < a);
                    near.extend(hits[from..].iter().take_while(|h| h.0 <= b).map(|h| h.1));
                }
                near.sort_unstable();
                near.dedup();
                let centre =
                    g.origin + (DVec2::new((col + c0) as f64, (row + r0) as f64) + 0.5) * g.res;
                let edge = |e: u32| (ring[e as usize], ring[(e as usize + 1) % n]);
                near.iter().enumerate().any(|(x, &e)| {
                    near[x + 1..].iter().any(|&h| {
                        let meet = (e as usize + 1) % n == h as usize
                            || (h as usize + 1) % n == e as usize;
                        !meet && facing_closer(edge(e), edge(h), centre, inward, g.res)
                    })
                })
            };
            let cell = (row + r0) * g.width + col + c0;
            if thin && !(lines_door && at_door.get(cell).copied().unwrap_or(false)) {
                extra.push(cell);
            }
        }
        extra.sort_unstable();
        extra.iter().copied().for_each(f);
    }
}

/// Rings of at most this many points are tested for [`thick_convex`].
const CONVEX_POINTS: usize = 64;

/// True when `ring` (of at most [`CONVEX_POINTS`] points) is convex, with no corner sharper
/// than a right angle, and at least a cell of `res` wide (but for [`SAME_M`]) across every
/// edge: a wall or a table top, which has no part thinner than a cell, so its centres alone
/// draw it ([`ThinCells::paint`] adds nothing to such a ring, and skips the search).
fn thick_convex(ring: &[DVec2], res: f64) -> bool {
    let n = ring.len();
    if n > CONVEX_POINTS {
        return false;
    }
    let (mut left, mut right) = (false, false);
    for i in 0..n {
        let (a, b, c) = (ring[i], ring[(i + 1) % n], ring[(i + 2) % n]);
        let (d, e) = (b - a, c - b);
        let turn = d.perp_dot(e);
        left |= turn > 0.0;
        right |= turn < 0.0;
        if d.dot(e) < -1e-9 * d.length() * e.length() || (left && right) {
            return false;
        }
    }
    (0..n).all(|i| {
        let (a, b) = (ring[i], ring[(i + 1) % n]);
        let Some(u) = (b - a).try_normalize() else {
            return true;
        };
        ring.iter()
            .map(|p| u.perp_dot(*p - a).abs())
            .fold(0.0, f64::max)
            >= res - SAME_M
    })
}

/// The point of the segment `a`-`b` nearest `p`.
fn nearest(a: DVec2, b: DVec2, p: DVec2) -> DVec2 {
    let ab = b - a;
    let len2 = ab.length_squared();
    if len2 > 0.0 {
        a + ab * ((p - a).dot(ab) / len2).clamp(0.0, 1.0)
    } else {
        a
    }
}

/// How much thinner than a cell two edges must be to be a thin part, metres: a door lining
/// modelled 5 cm wide comes out 4.9999999 cm in world coordinates, and is a cell thick.
const SAME_M: f64 = 1e-4;

/// True when the edges `e` and `f` of a ring (inside on their left for `inward` 1, right for
/// -1) face each other across its inside near `centre` closer than a cell of `res`: from the
/// point of `e` nearest `centre` to that of `f` is within 45 degrees of both inward normals,
/// and shorter (by [`SAME_M`]) than `res` times the larger of `e`'s direction's components (a strip at least
/// that thick has a cell centre in every column, or row, it crosses: a 4 cm panel at 45
/// degrees is drawn by its centres alone, one at 10 degrees is thin).
fn facing_closer(
    e: (DVec2, DVec2),
    f: (DVec2, DVec2),
    centre: DVec2,
    inward: f64,
    res: f64,
) -> bool {
    let (Some(ue), Some(uf)) = ((e.1 - e.0).try_normalize(), (f.1 - f.0).try_normalize()) else {
        return false;
    };
    let (p, q) = (nearest(e.0, e.1, centre), nearest(f.0, f.1, centre));
    let v = q - p;
    let d = v.length();
    let limit = res * ue.x.abs().max(ue.y.abs()).max(uf.x.abs().max(uf.y.abs())) - SAME_M;
    if !(d > 0.0 && d < limit) {
        return false;
    }
    let (ne, nf) = (ue.perp() * inward, uf.perp() * inward);
    let cos45 = std::f64::consts::FRAC_1_SQRT_2;
    v.dot(ne) >= cos45 * d && -v.dot(nf) >= cos45 * d
}

/// How far into a cell a segment must reach to touch it, in cells (5 µm at 5 cm): a corner or
/// an edge that lies on a cell's side but for rounding (a model's 18.300000006 m) does not
/// touch the cell beyond.
const GRAZE: f64 = 1e-4;

/// Calls `f(col, row)` for every cell of `g` the segment `a`-`b` touches (its extent in each
/// row it crosses, but for [`GRAZE`] at either end; cells are `[col, col + 1) x [row, row + 1)`),
/// row by row.
fn touched(g: Frame, a: DVec2, b: DVec2, mut f: impl FnMut(usize, usize)) {
    let (p, q) = ((a - g.origin) / g.res, (b - g.origin) / g.res);
    if !(p.is_finite() && q.is_finite()) {
        return;
    }
    let (ylo, yhi) = (p.y.min(q.y), p.y.max(q.y));
    let Some(rows) = cells_between(ylo, yhi, g.height) else {
        return;
    };
    for row in rows {
        // The part of the segment in the row's band.
        let (y0, y1) = ((row as f64).max(ylo), (row as f64 + 1.0).min(yhi));
        let (x0, x1) = if q.y == p.y {
            (p.x.min(q.x), p.x.max(q.x))
        } else {
            let x = |y: f64| p.x + (y - p.y) / (q.y - p.y) * (q.x - p.x);
            let (u, v) = (x(y0), x(y1));
            (u.min(v), u.max(v))
        };
        for col in cells_between(x0, x1, g.width).into_iter().flatten() {
            f(col, row);
        }
    }
}

/// The cells `[i, i + 1)`, of `n` along one axis, the span `lo`..`hi` (in cells) reaches more
/// than [`GRAZE`] into; a span shorter than 2 x GRAZE is in the cell its start is in. `None`
/// when that is outside the grid.
fn cells_between(lo: f64, hi: f64, n: usize) -> Option<std::ops::RangeInclusive<usize>> {
    let i0 = (lo + GRAZE).floor();
    let i1 = (hi - GRAZE).floor().max(i0);
    let (i0, i1) = (i0.max(0.0), i1.min(n as f64 - 1.0));
    (i0 <= i1).then_some(i0 as usize..=i1 as usize)
}

#[cfg(test)]
mod tests {
    use super::*;

    const G: Frame = Frame {
        width: 200,
        height: 200,
        origin: DVec2::ZERO,
        res: 0.05,
    };

    /// The cells `ring` paints with the centre rule alone and with thin parts.
    fn both(ring: &[DVec2]) -> (Vec<usize>, Vec<usize>) {
        let mut centre = Vec::new();
        spans(G, ring, |row, a, b| {
            centre.extend(row * G.width + a..row * G.width + b)
        });
        let mut all = Vec::new();
        ThinCells::default().paint_searching(G, ring, false, |i| all.push(i), true);
        centre.sort_unstable();
        all.sort_unstable();
        (centre, all)
    }

    /// A rectangle `length` x `width` centred on `c`, turned by `deg`.
    fn turned(c: DVec2, length: f64, width: f64, deg: f64) -> Vec<DVec2> {
        let (s, co) = deg.to_radians().sin_cos();
        let u = DVec2::new(co, s);
        let v = u.perp();
        [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)]
            .iter()
            .map(|&(a, b)| c + u * (a * length / 2.0) + v * (b * width / 2.0))
            .collect()
    }

    /// True when `cells`, 8-connected (as a grid's own slanting walls are), join a cell next to
    /// (or at) the one holding `from` to one next to that holding `to` (both well inside the
    /// grid).
    fn joined(cells: &[usize], from: DVec2, to: DVec2) -> bool {
        let w = G.width;
        let at = |p: DVec2| {
            let q = (p - G.origin) / G.res;
            q.y.floor() as usize * w + q.x.floor() as usize
        };
        let block = |i: usize| {
            [
                i,
                i + 1,
                i - 1,
                i + w,
                i - w,
                i + w + 1,
                i + w - 1,
                i - w + 1,
                i - w - 1,
            ]
        };
        let set: std::collections::HashSet<usize> = cells.iter().copied().collect();
        let goal = block(at(to));
        let mut stack: Vec<usize> = block(at(from))
            .into_iter()
            .filter(|i| set.contains(i))
            .collect();
        let mut seen: std::collections::HashSet<usize> = stack.iter().copied().collect();
        while let Some(i) = stack.pop() {
            if goal.contains(&i) {
                return true;
            }
            for j in block(i) {
                if set.contains(&j) && seen.insert(j) {
                    stack.push(j);
                }
            }
        }
        false
    }

    #[test]
    fn parts_a_cell_thick_are_painted_by_their_centres_alone() {
        // Walls of 5 cm (one cell) and more, at every angle and offset: nothing added.
        for k in 0..720 {
            let deg = k as f64 * 0.5;
            let width = 0.05 + 0.01 * (k % 7) as f64;
            let c = DVec2::new(
                5.0 + 0.0037 * (k % 13) as f64,
                5.0 + 0.0051 * (k % 11) as f64,
            );
            let ring = turned(c, 2.0, width, deg);
            // (Searched all the same: the search adds nothing, so skipping it is right.)
            assert!(thick_convex(&ring, G.res));
            let (centre, all) = both(&ring);
            assert!(!centre.is_empty());
            assert_eq!(centre, all, "{width} m wide at {deg} degrees");
        }
        // An L of 10 cm arms and a square with a door gap cut in it: the same.
        let ell: Vec<DVec2> = [
            (1.01, 1.02),
            (3.0, 1.02),
            (3.0, 1.12),
            (1.11, 1.12),
            (1.11, 3.0),
            (1.01, 3.0),
        ]
        .iter()
        .map(|&(x, y)| DVec2::new(x, y))
        .collect();
        let (centre, all) = both(&ell);
        assert_eq!(centre, all);
    }

    #[test]
    fn a_panel_thinner_than_a_cell_is_a_line_of_cells() {
        // 5 mm glass between two rows of centres: no centre inside, one row of cells along it.
        let glass = polygon::rect(2.01, 2.51, 5.99, 2.515);
        assert!(!thick_convex(&glass, G.res));
        assert!(!thick_convex(
            &turned(DVec2::ONE, 1.0, 0.5, 0.0)[..3],
            G.res
        ));
        let (centre, all) = both(&glass);
        assert!(centre.is_empty());
        // Columns 40..=119 (x = 2.01 to 5.99) of row 50 (y 2.50 to 2.55).
        assert_eq!(
            all,
            (40..=119).map(|c| 50 * G.width + c).collect::<Vec<_>>()
        );
        // Slanting, 5 mm to 4.5 cm, in any direction: a chain of cells from end to end (where
        // the centres alone leave gaps).
        for k in 0..60 {
            let (deg, width) = (3.0 * k as f64, [0.005, 0.03, 0.045][k % 3]);
            let c = DVec2::new(5.0 + 0.0013 * k as f64, 5.0);
            let ring = turned(c, 3.0, width, deg);
            let (_, all) = both(&ring);
            let (s, co) = f64::to_radians(deg).sin_cos();
            let u = DVec2::new(co, s) * 1.45;
            assert!(joined(&all, c - u, c + u), "{width} m at {deg} degrees");
        }
        // A square with a 1.5 cm fin: the square as its centres paint it, the fin's cells
        // added from a cell beyond the square to the fin's end.
        let finned: Vec<DVec2> = [
            (1.01, 1.01),
            (2.01, 1.01),
            (2.01, 1.505),
            (4.01, 1.505),
            (4.01, 1.52),
            (2.01, 1.52),
            (2.01, 2.01),
            (1.01, 2.01),
        ]
        .iter()
        .map(|&(x, y)| DVec2::new(x, y))
        .collect();
        let (centre, all) = both(&finned);
        let added: Vec<usize> = all
            .iter()
            .copied()
            .filter(|i| !centre.contains(i))
            .collect();
        // Row 30 (y 1.50 to 1.55, its centres above the fin), columns 41 (a cell past the
        // square's last column of centres, 39) to 80 (x = 4.01, the fin's end), and the cells
        // of the square's side next to its root (rows 29 and 31 of column 40), whose blocks
        // hold the fin's two faces.
        let mut want: Vec<usize> = (40..=80).map(|c| 30 * G.width + c).collect();
        want.extend([29 * G.width + 40, 31 * G.width + 40]);
        want.sort_unstable();
        assert_eq!(added, want);
        assert!(joined(&all, DVec2::new(1.5, 1.5), DVec2::new(4.0, 1.51)));
        // Outside the grid: nothing.
        let mut none = Vec::new();
        ThinCells::default().paint(G, &polygon::rect(-3.0, -3.0, -2.0, -2.995), false, |i| {
            none.push(i)
        });
        assert!(none.is_empty());
    }

    #[test]
    fn around_a_door_thin_linings_are_drawn_by_their_centres_other_parts_whole() {
        // A 1 m door passage over x 3.0 .. 4.0, y 2.4 .. 2.6, and a casing beside it
        // reaching into the cells of the passage (2 cm deep); and a 5 mm panel from x 2.01 to 5.99.
        let door = polygon::rect(3.0, 2.4, 4.0, 2.6);
        let g = G;
        let casing = polygon::rect(3.924, 2.6, 4.08, 2.62);
        let glass = polygon::rect(2.01, 3.51, 5.99, 3.515);
        let mut thin = ThinCells::around_doors(g, std::iter::once(&door[..]));
        let mut plain = ThinCells::default();
        let paint = |t: &mut ThinCells, ring: &[DVec2], lines_door: bool| {
            let mut v = Vec::new();
            t.paint(g, ring, lines_door, |i| v.push(i));
            v
        };
        // The casing (the door's own, or a wall's reveal): column 78 (x 3.90 to 3.95, in the
        // passage) and row 52 touched, no centre inside; with the door, as its centres draw it
        // (nothing), without, its cells. A part of any other element there is drawn whole.
        let casing_cells: Vec<usize> = (78..=81).map(|c| 52 * G.width + c).collect();
        assert!(paint(&mut thin, &casing, true).is_empty());
        assert_eq!(paint(&mut plain, &casing, true), casing_cells);
        assert_eq!(paint(&mut thin, &casing, false), casing_cells);
        // The panel, 0.9 m from the door (beyond DOOR_MARGIN_M): a line of cells either way.
        let want: Vec<usize> = (40..=119).map(|c| 70 * G.width + c).collect();
        for lines_door in [true, false] {
            assert_eq!(paint(&mut thin, &glass, lines_door), want);
            assert_eq!(paint(&mut plain, &glass, lines_door), want);
        }
        // Moved to 0.2 m from the door, within the margin: as a lining, its cells over the
        // door's width and the margin either side (x 2.75 .. 4.25) left out; as a glass
        // sidelight (any other element), the whole line.
        let near = polygon::rect(2.01, 2.81, 5.99, 2.815);
        let cols = |cells: Vec<usize>| cells.iter().map(|i| i % G.width).collect::<Vec<_>>();
        assert_eq!(
            cols(paint(&mut thin, &near, true)),
            (40..=54).chain(85..=119).collect::<Vec<_>>()
        );
        assert_eq!(
            paint(&mut thin, &near, false),
            (40..=119).map(|c| 56 * G.width + c).collect::<Vec<_>>()
        );
    }

    #[test]
    fn doors_walls_and_coverings_line_doors_nothing_else() {
        for class in [
            "IfcDoor",
            "IfcDoorStandardCase",
            "IfcWall",
            "IfcWallStandardCase",
        ] {
            assert!(lines_doors(class), "{class}");
        }
        assert!(lines_doors("IfcCovering"));
        for class in [
            "IfcWindow",
            "IfcPlate",
            "IfcMember",
            "IfcCurtainWall",
            "IfcRailing",
        ] {
            assert!(!lines_doors(class), "{class}");
        }
        assert!(!lines_doors("IfcFurniture"));
    }
}
