//! The section of a triangle mesh by a horizontal slab `z_min <= z <= z_max`: the region of
//! world XY over which the mesh occupies some height inside the slab (what a robot of that
//! height runs into), as polygons with holes.
//!
//! For a closed mesh (a solid) this is exact, not sampled: a vertical line meets the solid
//! inside the slab either because it is inside the solid at `z_min`, or because it crosses
//! the solid's surface inside the slab. So the section is the union of
//! - the slice at `z_min`: the parts of triangles above `z_min`, projected on XY and counted
//!   with their orientation (up-facing +1, down-facing -1); a point is inside the solid where
//!   the count is not zero (a vertical ray leaves a solid once more than it enters it);
//! - the projection of the parts of triangles inside the slab (a table top at 0.75 m, the
//!   underside of a shelf), each counted +1.
//!
//! Several closed parts that overlap (an element made of several solids) are filled once. An
//! open mesh (surfaces that enclose nothing) has no inside: only the second term is used.
//!
//! Neither term is built as a union of triangles: each is a sum of projected polygons, whose
//! count at a point is the winding number of the sum's boundary, in which the edges neighbouring
//! triangles share cancel ([`WindingChain`]). What is left is the slice's cut at `z_min` and
//! the outline of the band's surfaces (silhouettes and cuts), so only those edges go through
//! the polygon boolean, and the cost grows linearly with the number of triangles. Edges are cut
//! at points computed the same way from either triangle sharing them, so they cancel exactly.
//!
//! Booleans on coplanar faces (an opening flush with its wall's face) leave needle-thin
//! faces behind, whose projections would be slivers reaching into door gaps: every part of a
//! section thinner than 2 x [`SLIVER_M`] is removed ([`region::open`]).
//!
//! A surface crossing the slab (a fence or a balustrade modelled as an extruded open profile
//! or a surface model, a sheet of an open mesh) has (almost) no projected area there, and would
//! be lost: each part of a triangle inside the slab whose projection is thinner than
//! [`crate::section_lines::THIN_M`] gives the segment it lies along, and the segments the
//! areas above do not already hold (a solid's own side faces always lie in its section) are
//! drawn [`crate::section_lines::LINE_WIDTH_M`] wide and added. Solids, and open meshes whose
//! sides stand under faces they have in the slab, come out exactly as without lines. A mesh
//! that is a closed surface by its indices ([`Mesh::edges_pair_up`]: extrusions, sweeps,
//! boolean results, breps sharing their points; most walls, slabs, doors and windows) is not
//! searched at all: a point of a face in the slab has next to it, on one side of the face, a
//! point inside the surface at that height, which either is inside at the slab's bottom (the
//! slice) or lies over a face crossing the slab between the two (the band), so every such face
//! lies in the section and its line would be dropped.
//!
//! Sectioning is bounded ([`SectionBounds`]): a section whose outline has more edges than the
//! boolean should be given, or that takes too long, is given up ([`CutOff`]) with a
//! conservative outline instead, the convex hull of everything the mesh has in the slab (a
//! line when that hull has no area), which callers draw as unknown space.

use std::fmt;
use std::time::{Duration, Instant};

use glam::{DVec2, DVec3};
use i_overlay::core::overlay_rule::OverlayRule;
use serde::{Deserialize, Serialize};

use crate::mesh::Mesh;
use crate::region::{self, overlay_rings, Region};
use crate::section_lines::{hull_or_line, Cover, Lines};
use crate::winding_chain::WindingChain;

/// Half the thickness below which parts of a section are dropped as slivers, metres.
pub const SLIVER_M: f64 = 0.001;

/// Projected triangles smaller than this (square metres) are left out: vertical faces.
const MIN_TRIANGLE_AREA: f64 = 1e-10;

/// Triangles between two looks at the clock.
const CLOCK_EVERY: usize = 1024;

/// How much work sectioning one mesh may take before it is given up ([`CutOff`]). Only
/// pathological meshes reach these: the densest furniture of a real Revit model leaves a few
/// thousand edges.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct SectionBounds {
    /// Most edges of the outline handed to the polygon boolean (what is left of the mesh's
    /// projected edges after neighbours cancel, and four per line). Deterministic.
    pub max_edges: usize,
    /// Longest time for one mesh, seconds (only pathological meshes depend on the machine).
    pub time_limit_s: f64,
}

impl Default for SectionBounds {
    fn default() -> Self {
        SectionBounds {
            max_edges: 200_000,
            time_limit_s: 10.0,
        }
    }
}

impl SectionBounds {
    /// No bound at all.
    pub fn unbounded() -> SectionBounds {
        SectionBounds {
            max_edges: usize::MAX,
            time_limit_s: f64::INFINITY,
        }
    }

    fn deadline(&self) -> Option<Instant> {
        let limit = Duration::try_from_secs_f64(self.time_limit_s).ok()?;
        Instant::now().checked_add(limit)
    }
}

/// Why a section was given up.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum SectionLimit {
    /// Its outline has more edges than [`SectionBounds::max_edges`].
    Edges {
        /// Edges of the outline.
        edges: usize,
        /// The bound.
        limit: usize,
    },
    /// It took longer than [`SectionBounds::time_limit_s`].
    Time {
        /// The bound, seconds.
        seconds: f64,
    },
}

impl fmt::Display for SectionLimit {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            SectionLimit::Edges { edges, limit } => {
                write!(f, "has an outline of {edges} edges, more than {limit}")
            }
            SectionLimit::Time { seconds } => write!(f, "took longer than {seconds} s"),
        }
    }
}

/// A section given up on: why, and a conservative outline in its place.
#[derive(Debug, Clone, PartialEq)]
pub struct CutOff {
    /// Which bound was reached.
    pub limit: SectionLimit,
    /// The convex hull of everything the mesh has inside the slab: it holds the section, so
    /// obstacles drawn from it only grow. Empty when nothing is in the slab.
    pub outline: Vec<Region>,
}

/// The section of `mesh` by the slab `z_min..=z_max` (world metres), see the module
/// documentation; empty when the mesh does not reach into the slab. Unbounded: see
/// [`mesh_section_within`].
pub fn mesh_section(mesh: &Mesh, z_min: f64, z_max: f64) -> Vec<Region> {
    mesh_section_within(mesh, z_min, z_max, &SectionBounds::unbounded())
        .unwrap_or_else(|c| c.outline)
}

/// [`mesh_section`] within `bounds`: a [`CutOff`] when a bound is reached.
pub fn mesh_section_within(
    mesh: &Mesh,
    z_min: f64,
    z_max: f64,
    bounds: &SectionBounds,
) -> Result<Vec<Region>, CutOff> {
    let Some((lo, hi)) = mesh.bounds() else {
        return Ok(Vec::new());
    };
    if hi.z < z_min || lo.z > z_max || z_min.is_nan() || z_max.is_nan() || z_min > z_max {
        return Ok(Vec::new());
    }
    section(mesh, Some((z_min, z_max)), bounds)
}

/// The projection on XY of every triangle of `mesh` (its whole shadow), whatever its height.
pub fn mesh_shadow(mesh: &Mesh) -> Vec<Region> {
    mesh_shadow_within(mesh, &SectionBounds::unbounded()).unwrap_or_else(|c| c.outline)
}

/// [`mesh_shadow`] within `bounds`: a [`CutOff`] when a bound is reached.
pub fn mesh_shadow_within(mesh: &Mesh, bounds: &SectionBounds) -> Result<Vec<Region>, CutOff> {
    section(mesh, None, bounds)
}

/// True once `deadline` (if any) is reached.
fn past(deadline: Option<Instant>) -> bool {
    deadline.is_some_and(|d| Instant::now() >= d)
}

/// The section by `slab`, or the whole shadow (`None`).
fn section(
    mesh: &Mesh,
    slab: Option<(f64, f64)>,
    bounds: &SectionBounds,
) -> Result<Vec<Region>, CutOff> {
    let closed = slab.is_some() && is_closed(mesh);
    // Every face a closed surface (its edges pair up) has in the slab lies in its section,
    // where its line would be dropped again: none is looked for.
    let thin_lines = slab.is_some() && !(closed && mesh.edges_pair_up());
    section_with(mesh, slab, closed, thin_lines, bounds)
}

/// [`section`], taking the slice at the slab's bottom when `closed` and looking for lines
/// when `thin_lines`.
fn section_with(
    mesh: &Mesh,
    slab: Option<(f64, f64)>,
    closed: bool,
    thin_lines: bool,
    bounds: &SectionBounds,
) -> Result<Vec<Region>, CutOff> {
    let deadline = bounds.deadline();
    let give_up = |limit: SectionLimit| CutOff {
        limit,
        outline: hull_in(mesh, slab),
    };
    let time = || SectionLimit::Time {
        seconds: bounds.time_limit_s,
    };
    // A sum of oriented polygons per term: the slice at the slab's bottom, the band.
    let mut slice = WindingChain::new();
    let mut band = WindingChain::new();
    let mut lines = Lines::default();
    let (mut a, mut b) = (Vec::with_capacity(8), Vec::with_capacity(8));
    for (k, t) in mesh.triangles.iter().enumerate() {
        if k % CLOCK_EVERY == 0 && past(deadline) {
            return Err(give_up(time()));
        }
        let tri = t.map(|i| mesh.positions[i as usize]);
        let Some((z_min, z_max)) = slab else {
            add_normalised(&mut band, &tri);
            continue;
        };
        let (lo, hi) = z_range(&tri);
        if hi < z_min {
            continue;
        }
        // The part above the slab's bottom.
        let above: &[DVec3] = if lo >= z_min {
            &tri
        } else {
            clip(&tri, z_min, true, &mut a);
            &a
        };
        if closed && above.len() >= 3 {
            slice.add(above.iter().map(|p| p.truncate()));
        }
        if lo <= z_max {
            let inside: &[DVec3] = if hi <= z_max {
                above
            } else {
                clip(above, z_max, false, &mut b);
                &b
            };
            let area = add_normalised(&mut band, inside);
            if thin_lines {
                lines.add_if_thin(inside, area);
            }
        }
    }
    let edges = slice.len() + band.len();
    if edges > bounds.max_edges {
        return Err(give_up(SectionLimit::Edges {
            edges,
            limit: bounds.max_edges,
        }));
    }
    if past(deadline) {
        return Err(give_up(time()));
    }
    let rule = if slab.is_some() {
        OverlayRule::Union
    } else {
        OverlayRule::Subject
    };
    let (slice, band) = (slice.loops(), band.loops());
    let regions = if slab.is_some() {
        overlay_rings(&slice, &band, rule)
    } else {
        overlay_rings(&band, &[], rule)
    };
    // A closed solid's faces in the slab lie in its section, and so do an open mesh's sides
    // under a face it has in the slab: only what the areas do not hold (a sheet on its own, a
    // surface beside the solids of one element) is a line.
    if !lines.is_empty() {
        let cover = Cover::new(&regions);
        let mut k = 0usize;
        let mut late = false;
        lines.retain(|a, b| {
            k += 1;
            late = late || (k % CLOCK_EVERY == 0 && past(deadline));
            !late && !cover.holds_segment(a, b)
        });
        if late {
            return Err(give_up(time()));
        }
    }
    if lines.is_empty() {
        return Ok(region::open(&regions, SLIVER_M));
    }
    let edges = edges + 4 * lines.len();
    if edges > bounds.max_edges {
        return Err(give_up(SectionLimit::Edges {
            edges,
            limit: bounds.max_edges,
        }));
    }
    let mut all = regions;
    all.extend(lines.regions());
    Ok(region::open(&region::union(&all), SLIVER_M))
}

/// Adds the projection of `poly` counter-clockwise, unless it has (almost) no area; returns
/// that area (0 for fewer than three points).
fn add_normalised(chain: &mut WindingChain, poly: &[DVec3]) -> f64 {
    if poly.len() < 3 {
        return 0.0;
    }
    let a = projected_area(poly);
    if a.abs() < MIN_TRIANGLE_AREA || !a.is_finite() {
        return a;
    }
    if a > 0.0 {
        chain.add(poly.iter().map(|p| p.truncate()));
    } else {
        chain.add(poly.iter().rev().map(|p| p.truncate()));
    }
    a
}

/// The signed area of `poly` projected on XY (counter-clockwise positive).
fn projected_area(poly: &[DVec3]) -> f64 {
    let o = poly[0].truncate();
    let n = poly.len();
    (0..n)
        .map(|i| (poly[i].truncate() - o).perp_dot(poly[(i + 1) % n].truncate() - o))
        .sum::<f64>()
        / 2.0
}

fn z_range(poly: &[DVec3]) -> (f64, f64) {
    poly.iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), p| {
            (lo.min(p.z), hi.max(p.z))
        })
}

/// The convex hull of what `mesh` has inside `slab` (of all of it for `None`), as a region;
/// a line ([`hull_or_line`]) when that has no area (a sheet), empty when nothing is there.
fn hull_in(mesh: &Mesh, slab: Option<(f64, f64)>) -> Vec<Region> {
    let mut points: Vec<DVec2> = Vec::new();
    let (mut a, mut b) = (Vec::with_capacity(8), Vec::with_capacity(8));
    for t in &mesh.triangles {
        let tri = t.map(|i| mesh.positions[i as usize]);
        let Some((z_min, z_max)) = slab else {
            points.extend(tri.iter().map(|p| p.truncate()));
            continue;
        };
        let (lo, hi) = z_range(&tri);
        if hi < z_min || lo > z_max {
            continue;
        }
        clip(&tri, z_min, true, &mut a);
        clip(&a, z_max, false, &mut b);
        points.extend(b.iter().map(|p| p.truncate()));
    }
    hull_or_line(&points)
}

/// True when the mesh encloses volumes, as far as sections need: its triangles' projections on
/// XY cancel out (up-facing area equals down-facing area, as for any closed surface, whether
/// or not its edges are shared: T-junctions and unwelded vertices are fine). A lone face, or
/// a box without its bottom, is open.
pub fn is_closed(mesh: &Mesh) -> bool {
    let (mut signed, mut total) = (0.0, 0.0);
    let Some(&o) = mesh.positions.first() else {
        return false;
    };
    for t in &mesh.triangles {
        let [a, b, c] = t.map(|i| (mesh.positions[i as usize] - o).truncate());
        let area = (b - a).perp_dot(c - a) / 2.0;
        signed += area;
        total += area.abs();
    }
    total > 0.0 && signed.abs() <= 1e-6 * total
}

/// The part of the convex polygon `poly` above the plane at height `z` (`keep_above`) or below
/// it, into `out` (points on the plane are kept). Sutherland-Hodgman, but an edge crossing the
/// plane is cut at a point computed from its ends in a fixed order, so the two triangles
/// sharing an edge cut it at the same point, to the last bit.
pub(crate) fn clip(poly: &[DVec3], z: f64, keep_above: bool, out: &mut Vec<DVec3>) {
    out.clear();
    let kept = |p: DVec3| if keep_above { p.z >= z } else { p.z <= z };
    let n = poly.len();
    for i in 0..n {
        let (a, b) = (poly[i], poly[(i + 1) % n]);
        let (ka, kb) = (kept(a), kept(b));
        if ka {
            out.push(a);
        }
        if ka != kb {
            out.push(crossing(a, b, z));
        }
    }
}

/// Where the segment `a`-`b` (one end strictly on each side) meets the plane at height `z`.
fn crossing(a: DVec3, b: DVec3, z: f64) -> DVec3 {
    let (lo, hi) = if (a.z, a.x, a.y) < (b.z, b.x, b.y) {
        (a, b)
    } else {
        (b, a)
    };
    let t = (z - lo.z) / (hi.z - lo.z);
    DVec3::new(lo.x + (hi.x - lo.x) * t, lo.y + (hi.y - lo.y) * t, z)
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;
    use crate::polygon;
    use crate::region::total_area;

    /// A closed box, faces outwards.
    pub(crate) fn cuboid(lo: DVec3, hi: DVec3) -> Mesh {
        let p = |i: u32| {
            DVec3::new(
                if i & 1 == 0 { lo.x } else { hi.x },
                if i & 2 == 0 { lo.y } else { hi.y },
                if i & 4 == 0 { lo.z } else { hi.z },
            )
        };
        let quads = [
            [0, 2, 3, 1],
            [4, 5, 7, 6],
            [0, 1, 5, 4],
            [2, 6, 7, 3],
            [0, 4, 6, 2],
            [1, 3, 7, 5],
        ];
        Mesh {
            positions: (0..8).map(p).collect(),
            triangles: quads
                .iter()
                .flat_map(|q| [[q[0], q[1], q[2]], [q[0], q[2], q[3]]])
                .collect(),
        }
    }

    #[test]
    fn a_wall_a_table_top_and_a_lamp() {
        let wall = cuboid(DVec3::new(0.0, 0.0, 0.0), DVec3::new(5.0, 0.2, 3.0));
        assert!(is_closed(&wall));
        assert!(wall.volume() > 0.0);
        let s = mesh_section(&wall, 0.05, 1.0);
        assert_eq!(s.len(), 1);
        assert!((total_area(&s) - 1.0).abs() < 1e-6, "{}", total_area(&s));
        // Only its top face is inside the slab: the slice at z_min is empty.
        let mut table = cuboid(DVec3::new(0.0, 0.0, 0.72), DVec3::new(1.6, 0.8, 0.75));
        table.append(&cuboid(
            DVec3::new(0.0, 0.0, 0.0),
            DVec3::new(0.05, 0.05, 0.72),
        ));
        let s = mesh_section(&table, 0.05, 1.0);
        assert!((total_area(&s) - 1.28).abs() < 1e-6);
        let lamp = cuboid(DVec3::new(0.0, 0.0, 2.0), DVec3::new(0.3, 0.3, 2.2));
        assert!(mesh_section(&lamp, 0.05, 1.0).is_empty());
        // A slab below the band, and one that reaches into it.
        let floor = cuboid(DVec3::new(0.0, 0.0, -0.3), DVec3::new(4.0, 4.0, 0.0));
        assert!(mesh_section(&floor, 0.05, 1.0).is_empty());
        let step = cuboid(DVec3::new(0.0, 0.0, -0.3), DVec3::new(4.0, 4.0, 0.1));
        assert!((total_area(&mesh_section(&step, 0.05, 1.0)) - 16.0).abs() < 1e-6);
        assert!((total_area(&mesh_shadow(&table)) - 1.28).abs() < 1e-6);
    }

    #[test]
    fn overlapping_solids_fill_once_and_an_open_surface_counts_by_its_faces() {
        let mut two = cuboid(DVec3::ZERO, DVec3::new(2.0, 1.0, 3.0));
        two.append(&cuboid(
            DVec3::new(1.0, 0.0, 0.0),
            DVec3::new(3.0, 1.0, 3.0),
        ));
        let s = mesh_section(&two, 0.05, 1.0);
        assert_eq!(s.len(), 1);
        assert!((total_area(&s) - 3.0).abs() < 1e-6);
        // The top face alone of a tall box: open, and above the slab.
        let mut top = cuboid(DVec3::ZERO, DVec3::new(1.0, 1.0, 3.0));
        top.triangles.truncate(4);
        top.triangles.drain(0..2);
        assert!(!is_closed(&top));
        assert!(mesh_section(&top, 0.05, 1.0).is_empty());
    }

    /// A closed surface of revolution about the z axis through `profile` (points (radius, z)
    /// from bottom to top, radius 0 at the poles), `slices` around; faces outwards.
    fn revolved(profile: &[(f64, f64)], slices: usize, closed_loop: bool) -> Mesh {
        let n = profile.len();
        let mut m = Mesh::default();
        for &(r, z) in profile {
            for k in 0..slices {
                let a = std::f64::consts::TAU * k as f64 / slices as f64;
                m.positions.push(DVec3::new(r * a.cos(), r * a.sin(), z));
            }
        }
        let at = |i: usize, k: usize| ((i % n) * slices + k % slices) as u32;
        let rows = if closed_loop { n } else { n - 1 };
        for i in 0..rows {
            for k in 0..slices {
                let (a, b, c, d) = (at(i, k), at(i, k + 1), at(i + 1, k + 1), at(i + 1, k));
                m.triangles.push([a, b, c]);
                m.triangles.push([a, c, d]);
            }
        }
        // Degenerate triangles at the poles have no area and no effect.
        m
    }

    /// A UV sphere of radius `r` about the origin with about `2 * stacks * slices` triangles.
    fn sphere(r: f64, stacks: usize, slices: usize) -> Mesh {
        let profile: Vec<(f64, f64)> = (0..=stacks)
            .map(|i| {
                let t = std::f64::consts::PI * (i as f64 / stacks as f64 - 0.5);
                (r * t.cos(), r * t.sin())
            })
            .collect();
        revolved(&profile, slices, false)
    }

    /// A torus about the z axis: tube radius `r` at distance `big` from the axis.
    fn torus(big: f64, r: f64, around: usize, slices: usize) -> Mesh {
        // The tube's profile counter-clockwise seen from -y (outwards faces).
        let profile: Vec<(f64, f64)> = (0..around)
            .map(|i| {
                let t = std::f64::consts::TAU * i as f64 / around as f64;
                (big + r * t.cos(), r * t.sin())
            })
            .collect();
        revolved(&profile, slices, true)
    }

    fn close(got: f64, want: f64, rel: f64) {
        assert!(
            (got - want).abs() <= rel * want,
            "area {got}, analytic {want} (relative error {:.4})",
            (got - want).abs() / want
        );
    }

    #[test]
    fn dense_solids_section_to_their_analytic_outlines() {
        use std::f64::consts::PI;
        // 2 x 125 x 200 = 50,000 triangles.
        let s = sphere(1.0, 125, 200);
        assert_eq!(s.triangles.len(), 50_000);
        assert!(is_closed(&s));
        assert!((s.volume() - 4.0 / 3.0 * PI).abs() < 0.01);
        // A band around the equator: the equator's disk (the surfaces inside the band).
        let r = mesh_section(&s, -0.2, 0.5);
        assert_eq!(r.len(), 1);
        assert!(r[0].holes.is_empty());
        close(total_area(&r), PI, 0.01);
        // A band above the equator: the slice at its bottom, radius sqrt(1 - 0.3^2).
        let r = mesh_section(&s, 0.3, 0.6);
        assert_eq!(r.len(), 1);
        close(total_area(&r), PI * 0.91, 0.01);
        assert!(mesh_section(&s, 1.01, 2.0).is_empty());
        // Only the upper half (an open dome): the surface inside the band only, an annulus
        // between the radii at 0.6 and 0.3.
        let mut dome = s.clone();
        dome.triangles
            .retain(|t| t.iter().all(|&i| s.positions[i as usize].z >= 0.0));
        assert!(!is_closed(&dome));
        let r = mesh_section(&dome, 0.3, 0.6);
        assert_eq!(r.len(), 1);
        assert_eq!(r[0].holes.len(), 1);
        close(total_area(&r), PI * (0.91 - 0.64), 0.01);
        // A torus: an annulus through its middle, a narrower one in its upper part.
        let t = torus(2.0, 0.5, 100, 250);
        assert_eq!(t.triangles.len(), 50_000);
        assert!(is_closed(&t));
        let r = mesh_section(&t, -0.1, 0.2);
        assert_eq!(r.len(), 1);
        assert_eq!(r[0].holes.len(), 1);
        close(total_area(&r), PI * (2.5f64.powi(2) - 1.5f64.powi(2)), 0.01);
        let r = mesh_section(&t, 0.3, 0.4);
        assert_eq!(r[0].holes.len(), 1);
        close(total_area(&r), PI * (2.4f64.powi(2) - 1.6f64.powi(2)), 0.01);
        // Its whole shadow: the widest annulus.
        close(
            total_area(&mesh_shadow(&t)),
            PI * (2.5f64.powi(2) - 1.5f64.powi(2)),
            0.01,
        );
    }

    #[test]
    fn a_section_past_its_bound_gives_a_hull_that_holds_it() {
        let s = sphere(1.0, 40, 60);
        let exact = mesh_section(&s, 0.3, 0.6);
        let bounds = SectionBounds {
            max_edges: 10,
            ..SectionBounds::default()
        };
        let cut = mesh_section_within(&s, 0.3, 0.6, &bounds).unwrap_err();
        assert!(matches!(
            cut.limit,
            SectionLimit::Edges { edges, limit: 10 } if edges >= 60
        ));
        assert_eq!(cut.outline.len(), 1);
        let hull = &cut.outline[0];
        // (Up to the 0.1 µm the section's points are merged on.)
        assert!(hull.area() >= total_area(&exact) - 1e-6);
        assert!(exact[0]
            .outer
            .iter()
            .all(|p| hull.contains(*p) || polygon::boundary_distance(&hull.outer, *p) < 1e-6));
        // Within the default bounds nothing is cut off.
        assert_eq!(
            mesh_section_within(&s, 0.3, 0.6, &SectionBounds::default()).unwrap(),
            exact
        );
        // A time limit of zero: given up at once.
        let now = SectionBounds {
            time_limit_s: 0.0,
            ..SectionBounds::default()
        };
        let cut = mesh_shadow_within(&s, &now).unwrap_err();
        assert_eq!(cut.limit, SectionLimit::Time { seconds: 0.0 });
        assert!((cut.outline[0].area() - total_area(&mesh_shadow(&s))).abs() < 1e-5);
    }

    /// A vertical quad (two triangles) from `a` to `b` between heights `z0` and `z1`.
    pub(crate) fn sheet(a: DVec2, b: DVec2, z0: f64, z1: f64) -> Mesh {
        Mesh {
            positions: vec![a.extend(z0), b.extend(z0), b.extend(z1), a.extend(z1)],
            triangles: vec![[0, 1, 2], [0, 2, 3]],
        }
    }

    #[test]
    fn a_sheet_in_the_band_is_a_line_and_solids_stay_exact() {
        use crate::section_lines::LINE_WIDTH_M as W;
        let (a, b) = (DVec2::ZERO, DVec2::new(3.0, 0.0));
        // A fence 3 m long and 1.2 m high: a strip as wide as a line, square ends.
        let fence = sheet(a, b, 0.0, 1.2);
        assert!(!is_closed(&fence));
        let s = mesh_section(&fence, 0.05, 1.0);
        assert_eq!(s.len(), 1);
        assert!(
            (total_area(&s) - (3.0 + W) * W).abs() < 1e-6,
            "{}",
            total_area(&s)
        );
        let (lo, hi) = s[0].bounds();
        assert!(
            (lo - DVec2::new(-W / 2.0, -W / 2.0)).length() < 1e-6,
            "{lo}"
        );
        assert!(
            (hi - DVec2::new(3.0 + W / 2.0, W / 2.0)).length() < 1e-6,
            "{hi}"
        );
        // Below the band and above it: nothing; reaching into its top only: the same line.
        assert!(mesh_section(&sheet(a, b, 0.0, 0.04), 0.05, 1.0).is_empty());
        assert!(mesh_section(&sheet(a, b, 1.1, 2.0), 0.05, 1.0).is_empty());
        assert_eq!(mesh_section(&sheet(a, b, 0.9, 2.0), 0.05, 1.0), s);
        // Posts with a sheet between them (closed as a whole: the sheet has no shadow): the
        // posts and the line, 0.02 + 3 x W m² once the overlaps are taken off.
        let mut rail = cuboid(DVec3::new(-0.1, -0.05, 0.0), DVec3::new(0.0, 0.05, 1.2));
        rail.append(&cuboid(
            DVec3::new(3.0, -0.05, 0.0),
            DVec3::new(3.1, 0.05, 1.2),
        ));
        rail.append(&fence);
        assert!(is_closed(&rail));
        let s = mesh_section(&rail, 0.05, 1.0);
        assert_eq!(s.len(), 1);
        assert!(
            (total_area(&s) - (0.02 + 3.0 * W)).abs() < 1e-6,
            "{}",
            total_area(&s)
        );
        // The same with the sheet starting and ending at the posts' corners.
        let mut cornered = cuboid(DVec3::new(-0.1, 0.0, 0.0), DVec3::new(0.0, 0.1, 1.2));
        cornered.append(&cuboid(
            DVec3::new(3.0, 0.0, 0.0),
            DVec3::new(3.1, 0.1, 1.2),
        ));
        cornered.append(&fence);
        let s = mesh_section(&cornered, 0.05, 1.0);
        let want = 0.02 + (3.0 + W) * W - 2.0 * (W / 2.0) * (W / 2.0);
        assert!((total_area(&s) - want).abs() < 1e-6, "{}", total_area(&s));
        // A sheet on a wall's face, and an open desk (no bottom) whose sides stand under its
        // top: the areas hold them, the sections are the solids' alone, value for value.
        let wall = cuboid(DVec3::ZERO, DVec3::new(5.0, 0.2, 3.0));
        let mut faced = wall.clone();
        faced.append(&sheet(DVec2::new(1.0, 0.0), DVec2::new(2.0, 0.0), 0.0, 3.0));
        assert_eq!(
            mesh_section(&faced, 0.05, 1.0),
            mesh_section(&wall, 0.05, 1.0)
        );
        let mut desk = cuboid(DVec3::ZERO, DVec3::new(1.0, 0.6, 0.75));
        desk.triangles.drain(0..2);
        assert!(!is_closed(&desk));
        let s = mesh_section(&desk, 0.05, 1.0);
        assert_eq!(s.len(), 1);
        assert!((total_area(&s) - 0.6).abs() < 1e-6);
        // A 5 mm glass panel is a solid: its exact 5 mm strip (the navigation grid occupies
        // every cell it touches).
        let glass = cuboid(DVec3::ZERO, DVec3::new(3.0, 0.005, 2.0));
        let s = mesh_section(&glass, 0.05, 1.0);
        assert!((total_area(&s) - 0.015).abs() < 1e-6, "{}", total_area(&s));
        // A sheet past the edge bound: the line stands in for its hull, which has no area.
        let few = SectionBounds {
            max_edges: 1,
            ..SectionBounds::default()
        };
        let cut = mesh_section_within(&fence, 0.05, 1.0, &few).unwrap_err();
        assert!((total_area(&cut.outline) - (3.0 + W) * W).abs() < 1e-6);
    }

    #[test]
    fn a_wall_with_a_door_hole_cut_through() {
        // Two solids either side of a 0.9 m gap, joined above 2.1 m by a lintel.
        let mut wall = cuboid(DVec3::ZERO, DVec3::new(2.0, 0.2, 3.0));
        wall.append(&cuboid(
            DVec3::new(2.9, 0.0, 0.0),
            DVec3::new(5.0, 0.2, 3.0),
        ));
        wall.append(&cuboid(
            DVec3::new(2.0, 0.0, 2.1),
            DVec3::new(2.9, 0.2, 3.0),
        ));
        let s = mesh_section(&wall, 0.05, 1.0);
        assert_eq!(s.len(), 2);
        assert!((total_area(&s) - 0.82).abs() < 1e-6, "{}", total_area(&s));
        assert!(s.iter().all(|r| !r.contains(DVec2::new(2.45, 0.1))));
    }

    #[test]
    fn closed_surfaces_skip_the_line_search_and_section_the_same() {
        use crate::boolean::Solid;
        use crate::extrusion::extrude;
        use crate::profile::ProfileArea;
        let ring =
            |c: &[(f64, f64)]| -> Vec<DVec2> { c.iter().map(|&(x, y)| DVec2::new(x, y)).collect() };
        // An L-shaped column with a square hole, its sides leaning 0.3 mm over 3 m: every
        // side's part in the band is thinner than a line.
        let l_shape = ProfileArea {
            outer: ring(&[
                (0.0, 0.0),
                (2.0, 0.0),
                (2.0, 0.5),
                (0.5, 0.5),
                (0.5, 2.0),
                (0.0, 2.0),
            ]),
            holes: vec![ring(&[(0.1, 0.1), (0.1, 0.3), (0.3, 0.3), (0.3, 0.1)])],
        };
        let leaning = extrude(&[l_shape], DVec3::new(0.0003, 0.0, 3.0)).unwrap();
        // A round column of 64 sides.
        let circle = (0..64)
            .map(|k| {
                let t = std::f64::consts::TAU * k as f64 / 64.0;
                DVec2::new(0.2 * t.cos(), 0.2 * t.sin())
            })
            .collect();
        let column = extrude(
            &[ProfileArea {
                outer: circle,
                holes: Vec::new(),
            }],
            DVec3::new(0.0, 0.0, 2.5),
        )
        .unwrap();
        // A wall less a door and a window (a boolean's result), two walls in one mesh.
        let wall = Solid::new(&cuboid(DVec3::ZERO, DVec3::new(5.0, 0.2, 3.0))).unwrap();
        let door = Solid::new(&cuboid(
            DVec3::new(1.0, -0.1, -0.1),
            DVec3::new(1.9, 0.3, 2.1),
        ))
        .unwrap();
        let window = Solid::new(&cuboid(
            DVec3::new(3.0, -0.1, 0.9),
            DVec3::new(4.2, 0.3, 2.1),
        ))
        .unwrap();
        let cut = wall
            .difference(&door)
            .unwrap()
            .difference(&window)
            .unwrap()
            .mesh();
        let mut two = cut.clone();
        two.append(&cuboid(
            DVec3::new(5.0, 0.0, 0.0),
            DVec3::new(5.2, 4.0, 3.0),
        ));
        let bands = [(0.05, 1.0), (0.3, 0.6), (0.95, 2.0), (2.0, 2.6)];
        for (name, mesh) in [
            ("leaning", &leaning),
            ("column", &column),
            ("cut wall", &cut),
            ("two walls", &two),
            ("torus", &torus(2.0, 0.5, 24, 60)),
        ] {
            assert!(is_closed(mesh) && mesh.edges_pair_up(), "{name}");
            for (z0, z1) in bands {
                // The search finds the side faces (vertical or leaning) and drops every one.
                let sides = mesh
                    .triangles
                    .iter()
                    .map(|t| t.map(|i| mesh.positions[i as usize]))
                    .filter(|t| {
                        let (lo, hi) = z_range(t);
                        lo < z1 && hi > z0 && projected_area(t).abs() < 1e-3
                    })
                    .count();
                let searched = section_with(
                    mesh,
                    Some((z0, z1)),
                    true,
                    true,
                    &SectionBounds::unbounded(),
                );
                let fast = mesh_section(mesh, z0, z1);
                assert_eq!(searched.unwrap(), fast, "{name} {z0}..{z1}");
                if (z0, z1) == (0.05, 1.0) && name != "torus" {
                    assert!(sides >= 8 && !fast.is_empty(), "{name}: {sides}");
                }
            }
        }
        let area = |m: &Mesh| total_area(&mesh_section(m, 0.05, 1.0));
        assert!(
            (area(&cut) - (5.0 - 0.9) * 0.2).abs() < 1e-6,
            "{}",
            area(&cut)
        );
        let l_area = 2.0 * 0.5 + 0.5 * 1.5 - 0.04;
        // Leaning 0.3 mm over 3 m: at most 0.1 mm more along the x-facing sides.
        assert!((area(&leaning) - l_area).abs() < 5e-4, "{}", area(&leaning));
        // The rail (posts and a sheet between them) is closed, but its edges do not pair up:
        // the sheet's line is looked for and drawn.
        let mut rail = cuboid(DVec3::new(-0.1, -0.05, 0.0), DVec3::new(0.0, 0.05, 1.2));
        rail.append(&sheet(DVec2::ZERO, DVec2::new(3.0, 0.0), 0.0, 1.2));
        assert!(is_closed(&rail) && !rail.edges_pair_up());
        let w = crate::section_lines::LINE_WIDTH_M;
        let want = 0.01 + (3.0 + w) * w - (w / 2.0) * w;
        assert!((area(&rail) - want).abs() < 1e-6, "{}", area(&rail));
    }
}
