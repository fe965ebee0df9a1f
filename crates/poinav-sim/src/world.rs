//! The spatial index of one storey: every obstacle outline edge and every door passage edge in a
//! uniform grid (compressed rows), the robots' boxes in the same grid (rebuilt at the start of a
//! step when some box changed cells), exact ray casts walking the grid cell by cell
//! (Amanatides-Woo), and box queries for contacts.
//!
//! Why not parry2d: measured on the same rays with equal distances (`benches/ray_casts.rs`),
//! this index casts 2.6-2.7x faster than parry2d-f64's BVH on the test building and on office-a
//! (README, Performance); FIELD-NOTES.md found the same for uniform grids. The tests check every
//! cast against brute force.

use glam::DVec2;
use poinav_nav::Floor;

use crate::geometry::{ray_segment, Obb};

const PASSAGE: u32 = 1 << 31;

/// What a ray hit.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Target {
    /// Nothing within range.
    None,
    /// Obstacle `i` of the floor.
    Obstacle(u32),
    /// Robot `i`.
    Robot(u32),
}

/// Door passages a ray crossed before its hit (at most [`Passages::CAP`]), ascending.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Passages {
    n: u8,
    doors: [u32; Passages::CAP],
}

/// The passages a walk has crossed so far, with the distance of each (only the walk needs
/// them: a reading keeps the doors).
#[derive(Debug, Clone, Copy, Default)]
struct Crossings {
    n: u8,
    doors: [u32; Passages::CAP],
    dist: [f64; Passages::CAP],
}

impl Crossings {
    fn add(&mut self, door: u32, t: f64) {
        for k in 0..self.n as usize {
            if self.doors[k] == door {
                self.dist[k] = self.dist[k].min(t);
                return;
            }
        }
        if (self.n as usize) < Passages::CAP {
            self.doors[self.n as usize] = door;
            self.dist[self.n as usize] = t;
            self.n += 1;
        }
    }

    /// The doors crossed no farther than `limit`, sorted by door index for determinism.
    #[inline]
    fn before(mut self, limit: f64) -> Passages {
        if self.n == 0 {
            return Passages::default();
        }
        let mut k = 0;
        while k < self.n as usize {
            if self.dist[k] > limit {
                let last = self.n as usize - 1;
                self.doors[k] = self.doors[last];
                self.dist[k] = self.dist[last];
                self.n -= 1;
            } else {
                k += 1;
            }
        }
        let n = self.n as usize;
        let mut doors = [0; Passages::CAP];
        for (k, &d) in self.doors[..n].iter().enumerate() {
            // Insertion into the sorted head (at most four doors).
            let mut j = k;
            while j > 0 && doors[j - 1] > d {
                doors[j] = doors[j - 1];
                j -= 1;
            }
            doors[j] = d;
        }
        Passages { n: self.n, doors }
    }
}

impl Passages {
    /// How many crossings are kept per ray.
    pub const CAP: usize = 4;

    /// The crossings of `doors` (ascending, at most [`Passages::CAP`]), as a compact trace
    /// stores them.
    pub(crate) fn of_doors(doors: &[u32]) -> Passages {
        let mut p = Passages::default();
        for (k, &d) in doors.iter().take(Self::CAP).enumerate() {
            p.doors[k] = d;
            p.n = k as u8 + 1;
        }
        p
    }

    /// Door indices crossed, ascending.
    pub fn doors(&self) -> &[u32] {
        &self.doors[..self.n as usize]
    }

    /// True when door `d` was crossed.
    pub fn contains(&self, d: u32) -> bool {
        self.doors().contains(&d)
    }

    /// True when none was crossed.
    pub fn is_empty(&self) -> bool {
        self.n == 0
    }
}

/// A ray origin inside the grid: its cell and the cell's borders (see [`World::origin`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Origin {
    o: DVec2,
    cx: usize,
    cy: usize,
    /// The cell's lower borders.
    low: DVec2,
    /// The cell's upper borders.
    high: DVec2,
}

impl Origin {
    /// The borders of the origin's cell a ray along `dir` leaves it by.
    #[inline]
    fn edge_ahead(&self, dir: DVec2) -> DVec2 {
        DVec2::new(
            if dir.x > 0.0 { self.high.x } else { self.low.x },
            if dir.y > 0.0 { self.high.y } else { self.low.y },
        )
    }
}

/// One ray's result.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RayHit {
    /// Distance to the hit, or the range when nothing was hit.
    pub dist: f64,
    /// What was hit.
    pub target: Target,
    /// Door passages crossed before the hit.
    pub passages: Passages,
}

impl RayHit {
    /// A ray of zero length that hit nothing (a placeholder).
    pub const NONE: RayHit = RayHit {
        dist: 0.0,
        target: Target::None,
        passages: Passages {
            n: 0,
            doors: [0; Passages::CAP],
        },
    };
}

#[derive(Debug, Clone, Copy)]
struct Seg {
    a: DVec2,
    b: DVec2,
    owner: u32,
}

/// A grid of cells in compressed rows: `start[c]..start[c + 1]` indexes `items`.
#[derive(Debug, Clone, Default)]
struct Rows {
    start: Vec<u32>,
    items: Vec<u32>,
}

impl Rows {
    /// The rows of `(cell, item)` pairs given in ascending item order (as the index generates
    /// them), placed by counting (no sort: the robots' grid is rebuilt every step); each cell
    /// lists its items in ascending order.
    fn build(cells: usize, pairs: &[(u32, u32)]) -> Rows {
        let mut rows = Rows::default();
        rows.rebuild(cells, pairs, &mut Vec::new());
        rows
    }

    /// [`Rows::build`] in the memory of these rows (`next` is scratch space): the robots' grid
    /// is rebuilt every step.
    fn rebuild(&mut self, cells: usize, pairs: &[(u32, u32)], next: &mut Vec<u32>) {
        let start = &mut self.start;
        start.clear();
        start.resize(cells + 1, 0);
        for &(c, _) in pairs {
            start[c as usize + 1] += 1;
        }
        // Running sums (an iterator: no bounds test per cell, the loop runs over every cell).
        let mut sum = 0;
        for v in start.iter_mut() {
            sum += *v;
            *v = sum;
        }
        next.clear();
        next.extend_from_slice(&start[..cells]);
        let items = &mut self.items;
        items.clear();
        items.resize(pairs.len(), 0);
        for &(c, item) in pairs {
            let k = &mut next[c as usize];
            items[*k as usize] = item;
            *k += 1;
        }
        debug_assert!((0..cells).all(|c| self.cell(c).is_sorted()));
    }

    #[inline]
    fn cell(&self, c: usize) -> &[u32] {
        &self.items[self.start[c] as usize..self.start[c + 1] as usize]
    }
}

/// The index of one storey and the robots on it.
#[derive(Debug, Clone)]
pub struct World {
    lo: DVec2,
    /// The grid's far corner: `lo` + (`nx`, `ny`) cells.
    hi: DVec2,
    cell: f64,
    nx: usize,
    ny: usize,
    segs: Vec<Seg>,
    passages: Vec<Seg>,
    statics: Rows,
    robots: Rows,
    robot_pairs: Vec<(u32, u32)>,
    /// Per robot: the cells its box covers, as `[x0, y0, x1, y1]` (kept up to date by
    /// [`World::place_robot`]).
    rects: Vec<[u32; 4]>,
    /// Per robot: its box's bounding box.
    aabbs: Vec<(DVec2, DVec2)>,
    /// Some robot's cells changed since the robots' grid was built.
    stale: bool,
    /// Scratch space of the robots' grid rebuild.
    robot_next: Vec<u32>,
    /// One bit per cell: the cell lists a static edge.
    static_bits: Vec<u64>,
    /// One bit per cell: the cell lists a static edge or a robot (rebuilt with the robots'
    /// grid); a ray walks through the cells without one at the cost of a bit test.
    busy: Vec<u64>,
    boxes: Vec<Obb>,
    /// Per robot box: the radius of a circle around it, a little larger than the box's own
    /// (see [`reach`]), for a cheap test before the exact ray test.
    reach: Vec<f64>,
    /// Per robot box: [`Obb::radius`] (a `hypot`, asked for often, the same while the box's
    /// size is).
    radius: Vec<f64>,
    slack: f64,
}

/// A radius safely above `b`'s circumradius: a ray missing this circle (or entering it beyond
/// the best hit so far) misses the box or hits it later, whatever the exact test's rounding.
fn reach(b: &Obb) -> f64 {
    (b.hl * b.hl + b.hw * b.hw).sqrt() * (1.0 + 1e-9) + 1e-9
}

impl World {
    /// Indexes `floor` with square cells of `cell` metres. `slack` is how far a robot may move
    /// within one step (queries for robots are widened by it, since the robot grid is rebuilt
    /// once per step).
    pub fn new(floor: &Floor, cell: f64, slack: f64) -> World {
        let mut segs = Vec::new();
        for (i, o) in floor.obstacles.iter().enumerate() {
            for ring in &o.rings {
                ring_edges(ring, i as u32, &mut segs);
            }
        }
        let mut passages = Vec::new();
        for (i, d) in floor.doors.iter().enumerate() {
            ring_edges(&d.ring, i as u32, &mut passages);
        }
        let (lo, hi) = floor
            .bounds()
            .unwrap_or((DVec2::splat(-1.0), DVec2::splat(1.0)));
        let lo = lo - DVec2::splat(1.0);
        let hi = hi + DVec2::splat(1.0);
        let nx = (((hi.x - lo.x) / cell).ceil() as usize).max(1);
        let ny = (((hi.y - lo.y) / cell).ceil() as usize).max(1);
        let mut w = World {
            lo,
            hi: lo + DVec2::new(nx as f64, ny as f64) * cell,
            cell,
            nx,
            ny,
            segs,
            passages,
            statics: Rows::default(),
            robots: Rows::default(),
            robot_pairs: Vec::new(),
            rects: Vec::new(),
            aabbs: Vec::new(),
            stale: false,
            robot_next: Vec::new(),
            static_bits: Vec::new(),
            busy: Vec::new(),
            boxes: Vec::new(),
            reach: Vec::new(),
            radius: Vec::new(),
            slack,
        };
        let mut pairs = Vec::new();
        for (i, s) in w.segs.iter().enumerate() {
            w.cover(s.a.min(s.b), s.a.max(s.b), |c| pairs.push((c, i as u32)));
        }
        for (i, s) in w.passages.iter().enumerate() {
            w.cover(s.a.min(s.b), s.a.max(s.b), |c| {
                pairs.push((c, i as u32 | PASSAGE))
            });
        }
        w.statics = Rows::build(nx * ny, &pairs);
        w.robots = Rows::build(nx * ny, &[]);
        w.static_bits = vec![0; (nx * ny).div_ceil(64)];
        for &(c, _) in &pairs {
            w.static_bits[c as usize >> 6] |= 1 << (c & 63);
        }
        w.busy = w.static_bits.clone();
        w
    }

    /// Number of static edges indexed.
    pub fn segment_count(&self) -> usize {
        self.segs.len()
    }

    fn cell_of(&self, p: DVec2) -> (usize, usize) {
        let q = (p - self.lo) / self.cell;
        // Clamped to the grid, then truncated (the floor here): negatives and NaN become cell
        // 0, beyond the grid the last cell. (Clamping first leaves a conversion without
        // saturation to do: the truncation and `min` of before gave the same cells.)
        let last = |n: usize| (n - 1) as u32 as f64;
        (
            q.x.max(0.0).min(last(self.nx)) as i64 as usize,
            q.y.max(0.0).min(last(self.ny)) as i64 as usize,
        )
    }

    fn cover(&self, lo: DVec2, hi: DVec2, mut f: impl FnMut(u32)) {
        let (x0, y0) = self.cell_of(lo);
        let (x1, y1) = self.cell_of(hi);
        for y in y0..=y1 {
            for x in x0..=x1 {
                f((y * self.nx + x) as u32);
            }
        }
    }

    /// The cells the bounding box `lo`-`hi` covers, as `[x0, y0, x1, y1]`.
    pub(crate) fn rect(&self, (lo, hi): (DVec2, DVec2)) -> [u32; 4] {
        let (x0, y0) = self.cell_of(lo);
        let (x1, y1) = self.cell_of(hi);
        [x0 as u32, y0 as u32, x1 as u32, y1 as u32]
    }

    /// Replaces the robots' boxes and rebuilds their grid.
    pub fn set_robots(&mut self, boxes: &[Obb]) {
        self.boxes.clear();
        self.boxes.extend_from_slice(boxes);
        self.reach.clear();
        self.reach.extend(boxes.iter().map(reach));
        self.radius.clear();
        self.radius.extend(boxes.iter().map(Obb::radius));
        self.aabbs = boxes.iter().map(Obb::aabb).collect();
        self.rects = self.aabbs.iter().map(|&a| self.rect(a)).collect();
        self.stale = true;
        self.refresh_robots();
    }

    /// Rebuilds the robots' grid from their current boxes (as the committed moves left them),
    /// unless no box has left or entered a cell since it was last built.
    pub fn refresh_robots(&mut self) {
        if !self.stale {
            return;
        }
        self.stale = false;
        let mut pairs = std::mem::take(&mut self.robot_pairs);
        pairs.clear();
        for (i, &[x0, y0, x1, y1]) in self.rects.iter().enumerate() {
            for y in y0..=y1 {
                for x in x0..=x1 {
                    pairs.push((y * self.nx as u32 + x, i as u32));
                }
            }
        }
        self.robots
            .rebuild(self.nx * self.ny, &pairs, &mut self.robot_next);
        self.busy.copy_from_slice(&self.static_bits);
        for &(c, _) in &pairs {
            self.busy[c as usize >> 6] |= 1 << (c & 63);
        }
        self.robot_pairs = pairs;
    }

    /// Moves robot `i`'s box within the step (its grid cells are refreshed next step; queries
    /// are widened by the slack), with the box's bounding box and its cells ([`World::rect`])
    /// already known: a move computes them in parallel, the moves are placed in order.
    pub(crate) fn place_robot(&mut self, i: usize, b: Obb, aabb: (DVec2, DVec2), rect: [u32; 4]) {
        let old = &self.boxes[i];
        if (old.hl, old.hw) != (b.hl, b.hw) {
            self.radius[i] = b.radius();
            self.reach[i] = reach(&b);
        }
        self.aabbs[i] = aabb;
        if rect != self.rects[i] {
            self.rects[i] = rect;
            self.stale = true;
        }
        self.boxes[i] = b;
    }

    /// Robot `i`'s box's bounding box.
    #[inline]
    pub(crate) fn robot_aabb(&self, i: usize) -> (DVec2, DVec2) {
        self.aabbs[i]
    }

    /// Robot `i`'s box's [`Obb::radius`].
    #[inline]
    pub fn robot_radius(&self, i: usize) -> f64 {
        self.radius[i]
    }

    /// Robot `i`'s box.
    pub fn robot(&self, i: usize) -> &Obb {
        &self.boxes[i]
    }

    /// The cell of a ray origin inside the grid and its borders, shared by the rays cast
    /// from it ([`World::cast_from`]); `None` outside the grid.
    pub fn origin(&self, o: DVec2) -> Option<Origin> {
        let (glo, ghi) = (self.lo, self.hi);
        if !(o.x >= glo.x && o.x <= ghi.x && o.y >= glo.y && o.y <= ghi.y) {
            return None;
        }
        let (cx, cy) = self.cell_of(o);
        // Cell borders as the walk computes them: low + (index + 0 or 1) x cell.
        let border = |lo: f64, c: usize, up: f64| lo + (c as u32 as f64 + up) * self.cell;
        Some(Origin {
            o,
            cx,
            cy,
            low: DVec2::new(border(glo.x, cx, 0.0), border(glo.y, cy, 0.0)),
            high: DVec2::new(border(glo.x, cx, 1.0), border(glo.y, cy, 1.0)),
        })
    }

    /// Casts a ray from `o` along unit `dir` up to `range`, ignoring robot `skip`.
    ///
    /// The cells are walked as before this was tuned (the same crossing times, computed by the
    /// same expressions), with the cell index stepped in place and the steps left to the
    /// grid's edge counted down instead of bounds tests; a ray from inside the grid (every
    /// robot's) is not clipped to it: it stops at the grid's edge or its range, and the grid's
    /// outer cells (a margin of 1 m around the floor) hold nothing a ray could hit.
    pub fn cast(&self, o: DVec2, dir: DVec2, range: f64, skip: Option<u32>) -> RayHit {
        if let Some(origin) = self.origin(o) {
            return self.cast_from(&origin, dir, range, skip);
        }
        let miss = RayHit {
            dist: range,
            target: Target::None,
            passages: Passages::default(),
        };
        let (glo, ghi) = (self.lo, self.hi);
        // Clip the ray to the grid.
        let (mut t_in, mut t_out) = (0.0f64, range);
        for (o, dir, glo, ghi) in [(o.x, dir.x, glo.x, ghi.x), (o.y, dir.y, glo.y, ghi.y)] {
            if dir.abs() < 1e-300 {
                if o < glo || o > ghi {
                    return miss;
                }
            } else {
                let a = (glo - o) / dir;
                let b = (ghi - o) / dir;
                t_in = t_in.max(a.min(b));
                t_out = t_out.min(a.max(b));
            }
        }
        if t_in > t_out {
            return miss;
        }
        let (cx, cy) = self.cell_of(o + dir * t_in);
        let border = |lo: f64, c: usize, up: bool| {
            lo + (c as u32 as f64 + if up { 1.0 } else { 0.0 }) * self.cell
        };
        let edge = DVec2::new(
            border(glo.x, cx, dir.x > 0.0),
            border(glo.y, cy, dir.y > 0.0),
        );
        self.walk(o, dir, range, skip, (cx, cy), edge, t_out)
    }

    /// [`World::cast`] from an [`World::origin`]: the same hit.
    #[inline]
    pub fn cast_from(&self, origin: &Origin, dir: DVec2, range: f64, skip: Option<u32>) -> RayHit {
        let [hit] = self.cast_each(origin, &[dir], range, skip);
        hit
    }

    /// [`World::cast_from`] along each of `dirs`: the same hits, the grid's slices loaded once
    /// for all the rays (a robot's five rays share their origin).
    pub fn cast_each<const N: usize>(
        &self,
        origin: &Origin,
        dirs: &[DVec2; N],
        range: f64,
        skip: Option<u32>,
    ) -> [RayHit; N] {
        let mut hits = [RayHit::NONE; N];
        for (hit, &dir) in hits.iter_mut().zip(dirs) {
            *hit = self.walk(
                origin.o,
                dir,
                range,
                skip,
                (origin.cx, origin.cy),
                origin.edge_ahead(dir),
                range,
            );
        }
        hits
    }

    /// Walks the cells from `(cx, cy)` (whose borders ahead are `edge`) until a hit, `t_out`
    /// or the grid's edge. Always inlined: a robot's five rays are walked in one call
    /// ([`World::cast_each`]).
    #[allow(clippy::too_many_arguments)]
    #[inline(always)]
    fn walk(
        &self,
        o: DVec2,
        dir: DVec2,
        range: f64,
        skip: Option<u32>,
        (cx, cy): (usize, usize),
        edge: DVec2,
        t_out: f64,
    ) -> RayHit {
        let mut best = range;
        let mut target = Target::None;
        let mut passages = Crossings::default();
        let (flat_x, flat_y) = (dir.x.abs() < 1e-300, dir.y.abs() < 1e-300);
        let cell = self.cell;
        let (up_x, up_y) = (dir.x > 0.0, dir.y > 0.0);
        let mut t_max_x = if flat_x {
            f64::INFINITY
        } else {
            (edge.x - o.x) / dir.x
        };
        let mut t_max_y = if flat_y {
            f64::INFINITY
        } else {
            (edge.y - o.y) / dir.y
        };
        let dt_x = if flat_x {
            f64::INFINITY
        } else {
            cell / dir.x.abs()
        };
        let dt_y = if flat_y {
            f64::INFINITY
        } else {
            cell / dir.y.abs()
        };
        // Steps left to the grid's edge, and the cell index's change per step.
        let (mut left_x, step_x) = if up_x {
            (self.nx - 1 - cx, 1usize)
        } else {
            (cx, 1usize.wrapping_neg())
        };
        let (mut left_y, step_y) = if up_y {
            (self.ny - 1 - cy, self.nx)
        } else {
            (cy, self.nx.wrapping_neg())
        };
        let mut c = cy * self.nx + cx;
        let skip = skip.unwrap_or(u32::MAX);
        loop {
            // Cells listing nothing are passed by a bit test, cells listing only robots skip
            // the static lists by a second one.
            let (word, bit) = (c >> 6, 1u64 << (c & 63));
            if self.busy[word] & bit != 0 {
                if self.static_bits[word] & bit != 0 {
                    for &item in self.statics.cell(c) {
                        if item & PASSAGE != 0 {
                            let s = &self.passages[(item & !PASSAGE) as usize];
                            if let Some(t) = ray_segment(o, dir, s.a, s.b) {
                                if t <= range {
                                    passages.add(s.owner, t);
                                }
                            }
                        } else {
                            let s = &self.segs[item as usize];
                            if let Some(t) = ray_segment(o, dir, s.a, s.b) {
                                if t < best {
                                    best = t;
                                    target = Target::Obstacle(s.owner);
                                }
                            }
                        }
                    }
                }
                for &r in self.robots.cell(c) {
                    if r == skip {
                        continue;
                    }
                    // The circle around the box first (`dir` is a unit vector): missed, or entered
                    // no nearer than the best hit, the box cannot give a nearer hit.
                    let b = &self.boxes[r as usize];
                    let rel = b.c - o;
                    let rad = self.reach[r as usize];
                    if rel.perp_dot(dir).abs() > rad || rel.dot(dir) - rad >= best {
                        continue;
                    }
                    if let Some(t) = b.ray(o, dir) {
                        if t < best {
                            best = t;
                            target = Target::Robot(r);
                        }
                    }
                }
            }
            let t_exit = t_max_x.min(t_max_y);
            if best <= t_exit || t_exit >= t_out {
                break;
            }
            if t_max_x < t_max_y {
                if left_x == 0 {
                    break;
                }
                left_x -= 1;
                c = c.wrapping_add(step_x);
                t_max_x += dt_x;
            } else {
                if left_y == 0 {
                    break;
                }
                left_y -= 1;
                c = c.wrapping_add(step_y);
                t_max_y += dt_y;
            }
        }
        RayHit {
            dist: best,
            target,
            passages: passages.before(best),
        }
    }

    /// The same cast by testing everything (the reference for tests).
    pub fn cast_brute_force(&self, o: DVec2, dir: DVec2, range: f64, skip: Option<u32>) -> RayHit {
        let mut best = range;
        let mut target = Target::None;
        let mut passages = Crossings::default();
        for s in &self.segs {
            if let Some(t) = ray_segment(o, dir, s.a, s.b) {
                if t < best {
                    best = t;
                    target = Target::Obstacle(s.owner);
                }
            }
        }
        for (r, b) in self.boxes.iter().enumerate() {
            if Some(r as u32) == skip {
                continue;
            }
            if let Some(t) = b.ray(o, dir) {
                if t < best {
                    best = t;
                    target = Target::Robot(r as u32);
                }
            }
        }
        for s in &self.passages {
            if let Some(t) = ray_segment(o, dir, s.a, s.b) {
                if t <= range {
                    passages.add(s.owner, t);
                }
            }
        }
        RayHit {
            dist: best,
            target,
            passages: passages.before(best),
        }
    }

    /// Static edges (as `(a, b, obstacle)`) whose cells overlap the box `lo`-`hi`, each once;
    /// `ids` is scratch space (kept between calls, it saves an allocation per query).
    pub fn segments_near(
        &self,
        lo: DVec2,
        hi: DVec2,
        ids: &mut Vec<u32>,
        out: &mut Vec<(DVec2, DVec2, u32)>,
    ) {
        out.clear();
        ids.clear();
        self.cover(lo, hi, |c| {
            // Cells without a static edge (most, in open space) by a bit test.
            if self.static_bits[c as usize >> 6] & (1 << (c & 63)) != 0 {
                ids.extend(
                    self.statics
                        .cell(c as usize)
                        .iter()
                        .filter(|&&i| i & PASSAGE == 0),
                )
            }
        });
        if ids.is_empty() {
            return;
        }
        ids.sort_unstable();
        ids.dedup();
        out.extend(ids.iter().map(|&i| {
            let s = &self.segs[i as usize];
            (s.a, s.b, s.owner)
        }));
    }

    /// True when `f` is true for some robot whose (slack-widened) cells overlap `lo`-`hi`;
    /// robots are offered cell by cell, one spanning several cells more than once, and the
    /// search stops at the first true.
    pub fn any_robot_near(&self, lo: DVec2, hi: DVec2, f: &mut dyn FnMut(u32) -> bool) -> bool {
        let [x0, y0, x1, y1] = self.slack_cells(lo, hi);
        for y in y0..=y1 {
            for x in x0..=x1 {
                if self.robots.cell(y * self.nx + x).iter().any(|&r| f(r)) {
                    return true;
                }
            }
        }
        false
    }

    /// True when robot `i` is one [`World::any_robot_near`] offers for `lo`-`hi`: its box's
    /// cells (as the robot grid was last built) meet the slack-widened cells of the box.
    pub fn robot_listed_near(&self, i: usize, lo: DVec2, hi: DVec2) -> bool {
        debug_assert!(!self.stale, "the robot grid lists the boxes' cells");
        let [x0, y0, x1, y1] = self.slack_cells(lo, hi);
        let [a0, b0, a1, b1] = self.rects[i].map(|v| v as usize);
        a0 <= x1 && a1 >= x0 && b0 <= y1 && b1 >= y0
    }

    /// The cells `[x0, y0, x1, y1]` of the box `lo`-`hi` widened by the slack: where
    /// [`World::any_robot_near`] looks, and so where [`World::robot_listed_near`] tests.
    fn slack_cells(&self, lo: DVec2, hi: DVec2) -> [usize; 4] {
        let s = DVec2::splat(self.slack);
        let (x0, y0) = self.cell_of(lo - s);
        let (x1, y1) = self.cell_of(hi + s);
        [x0, y0, x1, y1]
    }

    /// Robots other than `skip` whose box's bounding box comes within the slack of `lo`-`hi`,
    /// ascending. Found through their (slack-widened) cells: the grid is rebuilt once per step
    /// while boxes move within it, and a robot whose box is now farther than the slack could
    /// not reach the box by its next move in this step either.
    pub fn robots_near(&self, lo: DVec2, hi: DVec2, skip: usize, out: &mut Vec<u32>) {
        out.clear();
        let s = DVec2::splat(self.slack);
        let (qlo, qhi) = (lo - s, hi + s);
        self.cover(qlo, qhi, |c| {
            for &r in self.robots.cell(c as usize) {
                let (blo, bhi) = self.aabbs[r as usize];
                let near = blo.x <= qhi.x && bhi.x >= qlo.x && blo.y <= qhi.y && bhi.y >= qlo.y;
                if near && r as usize != skip && !out.contains(&r) {
                    out.push(r);
                }
            }
        });
        out.sort_unstable();
    }
}

fn ring_edges(ring: &[DVec2], owner: u32, out: &mut Vec<Seg>) {
    let n = ring.len();
    if n < 2 {
        return;
    }
    for i in 0..n {
        let (a, b) = (ring[i], ring[(i + 1) % n]);
        if a.distance_squared(b) > 1e-18 {
            out.push(Seg { a, b, owner });
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use poinav_nav::{FloorObstacle, ObstacleKind};

    /// A deterministic pseudo-random sequence (xorshift) for test inputs.
    fn rng(seed: &mut u64) -> f64 {
        *seed ^= *seed << 13;
        *seed ^= *seed >> 7;
        *seed ^= *seed << 17;
        (*seed >> 11) as f64 / (1u64 << 53) as f64
    }

    #[test]
    fn grid_casts_equal_brute_force_casts() {
        let mut seed = 0x9E37_79B9_7F4A_7C15u64;
        let mut floor = Floor::default();
        for i in 0..60 {
            let c = DVec2::new(rng(&mut seed) * 20.0, rng(&mut seed) * 12.0);
            let h = DVec2::new(0.05 + rng(&mut seed), 0.05 + rng(&mut seed) * 0.3);
            floor.obstacles.push(FloorObstacle {
                id: format!("w{i}").into(),
                class: "IfcWall".into(),
                kind: ObstacleKind::Structure,
                rings: vec![vec![
                    c - h,
                    DVec2::new(c.x + h.x, c.y - h.y),
                    c + h,
                    DVec2::new(c.x - h.x, c.y + h.y),
                ]
                .into()],
                roles: vec![],
            });
        }
        let mut world = World::new(&floor, 0.7, 0.2);
        let boxes: Vec<Obb> = (0..30)
            .map(|_| {
                Obb::new(
                    DVec2::new(rng(&mut seed) * 20.0, rng(&mut seed) * 12.0),
                    rng(&mut seed) * 6.3,
                    0.4,
                    0.35,
                )
            })
            .collect();
        world.set_robots(&boxes);
        for _ in 0..20_000 {
            let o = DVec2::new(rng(&mut seed) * 22.0 - 1.0, rng(&mut seed) * 14.0 - 1.0);
            let dir = DVec2::from_angle(rng(&mut seed) * std::f64::consts::TAU);
            let skip = Some((rng(&mut seed) * 30.0) as u32);
            let a = world.cast(o, dir, 5.0, skip);
            let b = world.cast_brute_force(o, dir, 5.0, skip);
            assert!((a.dist - b.dist).abs() < 1e-12, "{a:?} {b:?}");
            if (a.dist - b.dist).abs() == 0.0 {
                assert_eq!(a.target, b.target);
            }
        }
        // From outside the grid (clipped to it), and from its inside through a shared origin.
        let (mut outside, mut shared) = (0, 0);
        for _ in 0..5_000 {
            let o = DVec2::new(rng(&mut seed) * 40.0 - 10.0, rng(&mut seed) * 30.0 - 9.0);
            let dir = DVec2::from_angle(rng(&mut seed) * std::f64::consts::TAU);
            let a = world.cast(o, dir, 12.0, None);
            let b = world.cast_brute_force(o, dir, 12.0, None);
            assert!((a.dist - b.dist).abs() < 1e-12, "{o} {dir} {a:?} {b:?}");
            match world.origin(o) {
                None => outside += 1,
                Some(origin) => {
                    assert_eq!(world.cast_from(&origin, dir, 12.0, None), a);
                    shared += 1;
                }
            }
        }
        assert!(
            outside > 1000 && shared > 1000,
            "{outside} outside, {shared} inside"
        );
        // Axis-parallel rays along cell borders.
        for k in 0..200 {
            let o = DVec2::new(k as f64 * 0.1, 0.7 * (k % 17) as f64);
            for dir in [DVec2::X, DVec2::Y, -DVec2::X, -DVec2::Y] {
                let a = world.cast(o, dir, 5.0, None);
                let b = world.cast_brute_force(o, dir, 5.0, None);
                assert!((a.dist - b.dist).abs() < 1e-12, "{o} {dir} {a:?} {b:?}");
            }
        }
    }
}
