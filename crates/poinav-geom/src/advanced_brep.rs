//! `IfcAdvancedBrep` and `IfcAdvancedBrepWithVoids`: closed shells of `IfcAdvancedFace`s
//! bounded by loops of `IfcEdgeCurve`s ([`crate::edge_curve`]) on the surfaces of
//! [`crate::surface`], as one closed triangle mesh.
//!
//! Tessellation: every edge is sampled once (straight lines as their ends, arcs by
//! [`crate::curve::MAX_ARC_STEP`], B-splines by the chord rule [`crate::chord_rule`]) and its
//! points are shared by the faces on both sides (vertices are welded by exact position), so
//! a closed shell gives a closed mesh. Planar faces are triangulated from their bounds
//! (holes too). Curved faces are triangulated in their (u, v) parameters from their bounds
//! (angles unwrapped along each loop, so a seam edge used twice opens a cylinder into a
//! rectangle), then refined: every inner edge whose surface point halfway strays from the
//! chord more than the chord rule allows is split, with its neighbours (red-green
//! refinement, edges on the bounds are never split), until none does.

use rustc_hash::FxHashMap;

use glam::{DVec2, DVec3};
use poinav_ifc::Entity;

use crate::cartesian_point::point3;
use crate::chord_rule::too_coarse;
use crate::edge_curve::edge_points;
use crate::error::{degenerate, missing, required_ref, unsupported, GeomError};
use crate::mesh::Mesh;
use crate::polygon;
use crate::surface::{surface, Surface};
use crate::triangulation::{newell_normal, triangulate_2d, triangulate_3d};

/// Most refinement passes over one face.
const MAX_PASSES: usize = 16;

/// Most triangles one curved face may be refined into.
pub const MAX_FACE_TRIANGLES: usize = 200_000;

/// The mesh of an `IfcAdvancedBrep` (outer shell and, `...WithVoids`, void shells), metres
/// (`s` metres per file unit).
pub fn advanced_brep(item: Entity<'_>, s: f64) -> Result<Mesh, GeomError> {
    let mut m = Mesher {
        s,
        ..Mesher::default()
    };
    let outer = item
        .get_ref("Outer")
        .ok_or_else(|| missing(&item, "Outer"))?;
    m.shell(outer)?;
    for void in item.get_refs("Voids") {
        m.shell(void)?;
    }
    Ok(m.mesh)
}

#[derive(Default)]
struct Mesher {
    s: f64,
    mesh: Mesh,
    weld: FxHashMap<[u64; 3], u32>,
    edges: FxHashMap<poinav_ifc::EntityId, Vec<DVec3>>,
}

/// One loop of a face: its points in order (no repeated closing point), and whether it is
/// the outer bound.
struct Loop {
    outer: bool,
    points: Vec<DVec3>,
}

impl Mesher {
    fn vertex(&mut self, p: DVec3) -> u32 {
        let key = p.to_array().map(f64::to_bits);
        *self.weld.entry(key).or_insert_with(|| {
            self.mesh.positions.push(p);
            self.mesh.positions.len() as u32 - 1
        })
    }

    fn shell(&mut self, shell: Entity<'_>) -> Result<(), GeomError> {
        let faces = shell.get_refs("CfsFaces");
        if faces.is_empty() {
            return Err(missing(&shell, "CfsFaces"));
        }
        for face in faces {
            self.face(face)?;
        }
        Ok(())
    }

    fn edge(&mut self, edge: Entity<'_>) -> Result<Vec<DVec3>, GeomError> {
        if let Some(p) = self.edges.get(&edge.id()) {
            return Ok(p.clone());
        }
        let p = edge_points(edge, self.s)?;
        self.edges.insert(edge.id(), p.clone());
        Ok(p)
    }

    fn bound(&mut self, bound: Entity<'_>) -> Result<Vec<DVec3>, GeomError> {
        let lp = bound
            .get_ref("Bound")
            .ok_or_else(|| missing(&bound, "Bound"))?;
        let mut pts: Vec<DVec3> = Vec::new();
        if lp.is_a("IfcEdgeLoop") {
            for oe in lp.get_refs("EdgeList") {
                let (edge, forward) = if oe.is_a("IfcOrientedEdge") {
                    let e = required_ref(&oe, "EdgeElement", "IfcEdge")?;
                    (
                        e,
                        oe.get("Orientation").and_then(|v| v.as_enum()) != Some("F"),
                    )
                } else {
                    (oe, true)
                };
                let mut e = self.edge(edge)?;
                if !forward {
                    e.reverse();
                }
                for p in e {
                    if pts.last() != Some(&p) {
                        pts.push(p);
                    }
                }
            }
        } else if lp.is_a("IfcPolyLoop") {
            for p in lp.get_refs("Polygon") {
                let p = point3(p)? * self.s;
                if pts.last() != Some(&p) {
                    pts.push(p);
                }
            }
        } else {
            return Err(unsupported(&lp, "face loop"));
        }
        while pts.len() > 1 && pts.first() == pts.last() {
            pts.pop();
        }
        if bound.get("Orientation").and_then(|v| v.as_enum()) == Some("F") {
            pts.reverse();
        }
        Ok(pts)
    }

    fn face(&mut self, face: Entity<'_>) -> Result<(), GeomError> {
        let mut loops = Vec::new();
        for bound in face.get_refs("Bounds") {
            let points = self.bound(bound)?;
            if points.len() >= 2 {
                loops.push(Loop {
                    outer: bound.is_a("IfcFaceOuterBound"),
                    points,
                });
            }
        }
        if loops.is_empty() {
            return Ok(());
        }
        let surf = match face.get_ref("FaceSurface") {
            Some(e) => surface(e, self.s)?,
            None if face.is_a("IfcFaceSurface") => return Err(missing(&face, "FaceSurface")),
            None => Surface::Plane,
        };
        if let Surface::Plane = surf {
            return self.planar(loops);
        }
        let same_sense = face.get("SameSense").and_then(|v| v.as_enum()) != Some("F");
        self.curved(&face, &surf, loops, same_sense)
    }

    fn planar(&mut self, mut loops: Vec<Loop>) -> Result<(), GeomError> {
        loops.retain(|l| l.points.len() >= 3);
        if loops.is_empty() {
            return Ok(());
        }
        let outer = outer_index(&loops, |l| newell_normal(&l.points).length());
        let outer = loops.swap_remove(outer);
        let holes: Vec<Vec<DVec3>> = loops.into_iter().map(|l| l.points).collect();
        let Some(tris) = triangulate_3d(&outer.points, &holes) else {
            return Ok(());
        };
        let all: Vec<DVec3> = outer
            .points
            .iter()
            .chain(holes.iter().flatten())
            .copied()
            .collect();
        let index: Vec<u32> = all.iter().map(|p| self.vertex(*p)).collect();
        self.push(tris.iter().map(|t| t.map(|i| index[i as usize])));
        Ok(())
    }

    fn push(&mut self, tris: impl Iterator<Item = [u32; 3]>) {
        self.mesh
            .triangles
            .extend(tris.filter(|t| t[0] != t[1] && t[1] != t[2] && t[0] != t[2]));
    }

    fn curved(
        &mut self,
        face: &Entity<'_>,
        surf: &Surface,
        loops: Vec<Loop>,
        same_sense: bool,
    ) -> Result<(), GeomError> {
        // Parameters along each loop, periodic ones unwrapped.
        let mut rings: Vec<(bool, Vec<DVec2>, Vec<DVec3>)> = Vec::new();
        for l in loops {
            let uv = loop_parameters(surf, &l.points)
                .ok_or_else(|| degenerate(face, "a bound does not lie on the face's surface"))?;
            rings.push((l.outer, uv, l.points));
        }
        let rings = close_wrapping_loops(surf, rings);
        let rings: Vec<_> = rings.into_iter().filter(|r| r.1.len() >= 3).collect();
        if rings.is_empty() {
            return Ok(());
        }
        let outer = outer_index(&rings, |r| polygon::signed_area(&r.1).abs());
        let mut order: Vec<usize> = vec![outer];
        order.extend((0..rings.len()).filter(|&i| i != outer));
        let holes: Vec<Vec<DVec2>> = order[1..].iter().map(|&i| rings[i].1.clone()).collect();
        let Some(tris) = triangulate_2d(&rings[outer].1, &holes) else {
            return Ok(());
        };
        let mut uv: Vec<DVec2> = Vec::new();
        let mut xyz: Vec<DVec3> = Vec::new();
        let mut boundary: rustc_hash::FxHashSet<(u32, u32)> = Default::default();
        for &i in &order {
            let start = uv.len() as u32;
            let n = rings[i].1.len() as u32;
            for k in 0..n {
                boundary.insert(edge_key(start + k, start + (k + 1) % n));
            }
            uv.extend_from_slice(&rings[i].1);
            xyz.extend_from_slice(&rings[i].2);
        }
        let tris = refine(surf, &mut uv, &mut xyz, tris, &boundary)
            .ok_or_else(|| degenerate(face, "face needs too many triangles"))?;
        let index: Vec<u32> = xyz.iter().map(|p| self.vertex(*p)).collect();
        self.push(tris.iter().map(|t| {
            let t = t.map(|i| index[i as usize]);
            if same_sense {
                t
            } else {
                [t[0], t[2], t[1]]
            }
        }));
        Ok(())
    }
}

/// The index of the outer loop: the one marked so, else the largest by `size`.
fn outer_index<T: HasOuter>(loops: &[T], size: impl Fn(&T) -> f64) -> usize {
    loops.iter().position(|l| l.is_outer()).unwrap_or_else(|| {
        (0..loops.len())
            .max_by(|&a, &b| size(&loops[a]).total_cmp(&size(&loops[b])))
            .unwrap_or(0)
    })
}

trait HasOuter {
    fn is_outer(&self) -> bool;
}

impl HasOuter for Loop {
    fn is_outer(&self) -> bool {
        self.outer
    }
}

impl HasOuter for (bool, Vec<DVec2>, Vec<DVec3>) {
    fn is_outer(&self) -> bool {
        self.0
    }
}

fn edge_key(a: u32, b: u32) -> (u32, u32) {
    (a.min(b), a.max(b))
}

/// The parameters of each point of a loop, periodic ones continuous along the loop;
/// undefined ones (a sphere's pole) take their predecessor's u.
fn loop_parameters(surf: &Surface, points: &[DVec3]) -> Option<Vec<DVec2>> {
    let mut out: Vec<DVec2> = Vec::with_capacity(points.len());
    let mut pending = 0;
    for p in points {
        match surf.parameters(*p, out.last().copied()) {
            Some(uv) => {
                // Poles met before any defined point take this one's u.
                for q in out.iter_mut().take(pending) {
                    q.x = uv.x;
                }
                pending = 0;
                out.push(uv);
            }
            None => {
                let v = surf.parameters(*p, Some(DVec2::ZERO))?.y;
                if out.is_empty() {
                    pending += 1;
                }
                out.push(DVec2::new(out.last().map_or(0.0, |q| q.x), v));
            }
        }
    }
    // Check: a point far from the surface means a wrong surface or bound.
    let size = points
        .iter()
        .fold(0.0f64, |m, p| m.max((*p - points[0]).length()))
        .max(1e-3);
    for (p, uv) in points.iter().zip(&out) {
        if surf.point(*uv).distance(*p) > 1e-3 * size.max(1.0) {
            return None;
        }
    }
    Some(out)
}

/// Loops that wind once around a periodic direction (a cylinder bounded by two circles
/// without a seam edge) joined in pairs into one ring through a seam; other loops as
/// they are.
fn close_wrapping_loops(
    surf: &Surface,
    rings: Vec<(bool, Vec<DVec2>, Vec<DVec3>)>,
) -> Vec<(bool, Vec<DVec2>, Vec<DVec3>)> {
    let [Some(period), _] = surf.periods() else {
        return rings;
    };
    let winding = |uv: &[DVec2]| -> f64 {
        // Closing step included: u from the last point back to the first, unwrapped.
        let (first, last) = (uv[0].x, uv[uv.len() - 1].x);
        let close = (first - last) - ((first - last) / period).round() * period;
        ((last + close - first) / period).round()
    };
    let (wrapping, mut rest): (Vec<_>, Vec<_>) = rings
        .into_iter()
        .partition(|r| r.1.len() >= 2 && winding(&r.1) != 0.0);
    let mut it = wrapping.into_iter();
    while let (Some(a), Some(b)) = (it.next(), it.next()) {
        let (outer, mut uv, mut xyz) = (a.0 || b.0, a.1, a.2);
        let wa = winding(&uv);
        let (mut buv, mut bxyz) = (b.1, b.2);
        if winding(&buv) == wa {
            buv.reverse();
            bxyz.reverse();
        }
        // a runs from u0 to u0 + wa * period; b starts at the point nearest that end.
        let end = uv[0].x + wa * period;
        let start = (0..buv.len())
            .min_by(|&i, &j| {
                let d = |k: usize| {
                    let x = buv[k].x - end;
                    (x - (x / period).round() * period).abs()
                };
                d(i).total_cmp(&d(j))
            })
            .unwrap_or(0);
        buv.rotate_left(start);
        bxyz.rotate_left(start);
        let shift = ((end - buv[0].x) / period).round() * period;
        uv.push(DVec2::new(end, uv[0].y));
        xyz.push(xyz[0]);
        let mut prev = buv[0].x + shift;
        for (q, p) in buv.iter().zip(&bxyz) {
            let x = q.x + ((prev - q.x) / period).round() * period;
            uv.push(DVec2::new(x, q.y));
            xyz.push(*p);
            prev = x;
        }
        let x = buv[0].x + ((prev - buv[0].x) / period).round() * period;
        uv.push(DVec2::new(x, buv[0].y));
        xyz.push(bxyz[0]);
        rest.push((outer, uv, xyz));
    }
    rest
}

/// Red-green refinement of `tris` (indices into `uv` / `xyz`, counter-clockwise in uv):
/// inner edges that are [`too_coarse`] on `surf` are split at their middle in uv; `None`
/// past [`MAX_FACE_TRIANGLES`].
fn refine(
    surf: &Surface,
    uv: &mut Vec<DVec2>,
    xyz: &mut Vec<DVec3>,
    mut tris: Vec<[u32; 3]>,
    boundary: &rustc_hash::FxHashSet<(u32, u32)>,
) -> Option<Vec<[u32; 3]>> {
    for _ in 0..MAX_PASSES {
        let mut split: FxHashMap<(u32, u32), u32> = FxHashMap::default();
        for t in &tris {
            for k in 0..3 {
                let key = edge_key(t[k], t[(k + 1) % 3]);
                if boundary.contains(&key) || split.contains_key(&key) {
                    continue;
                }
                let (a, b) = (key.0 as usize, key.1 as usize);
                let m = (uv[a] + uv[b]) / 2.0;
                let pm = surf.point(m);
                if too_coarse(xyz[a], xyz[b], pm) {
                    uv.push(m);
                    xyz.push(pm);
                    split.insert(key, uv.len() as u32 - 1);
                }
            }
        }
        if split.is_empty() {
            return Some(tris);
        }
        let mut next = Vec::with_capacity(tris.len() * 2);
        for t in &tris {
            let mid = |k: usize| split.get(&edge_key(t[k], t[(k + 1) % 3])).copied();
            let m = [mid(0), mid(1), mid(2)];
            match m.iter().filter(|x| x.is_some()).count() {
                0 => next.push(*t),
                3 => {
                    let [ab, bc, ca] = m.map(|x| x.expect("three splits"));
                    next.extend([[t[0], ab, ca], [ab, t[1], bc], [ca, bc, t[2]], [ab, bc, ca]]);
                }
                1 => {
                    let k = (0..3).find(|&k| m[k].is_some()).expect("one split");
                    let (a, b, c) = (t[k], t[(k + 1) % 3], t[(k + 2) % 3]);
                    let x = m[k].expect("split");
                    next.extend([[a, x, c], [x, b, c]]);
                }
                _ => {
                    // The unsplit edge is c-a: split a-b at x and b-c at y.
                    let k = (0..3).find(|&k| m[k].is_none()).expect("one unsplit");
                    let (a, b, c) = (t[(k + 1) % 3], t[(k + 2) % 3], t[k]);
                    let x = m[(k + 1) % 3].expect("split");
                    let y = m[(k + 2) % 3].expect("split");
                    next.extend([[x, b, y], [a, x, y], [a, y, c]]);
                }
            }
        }
        tris = next;
        if tris.len() > MAX_FACE_TRIANGLES {
            return None;
        }
    }
    Some(tris)
}
