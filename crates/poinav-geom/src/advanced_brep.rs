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
//! rectangle; a loop round a sphere is closed through its pole), then seeded and refined by
//! [`crate::uv_mesh`].

use rustc_hash::FxHashMap;

use glam::{DVec2, DVec3};
use poinav_ifc::Entity;

use crate::cartesian_point::point3;
use crate::chord_rule;
use crate::curve::MAX_ARC_STEP;
use crate::edge_curve::edge_points;
use crate::error::{degenerate, missing, required_ref, unsupported, GeomError};
use crate::mesh::Mesh;
use crate::polygon;
use crate::surface::{surface, Surface};
use crate::triangulation::{newell_normal, triangulate_2d, triangulate_3d};
use crate::unit_assignment::Units;
use crate::uv_mesh::{self, edge_key};

/// The mesh of an `IfcAdvancedBrep` (outer shell and, `...WithVoids`, void shells), metres.
pub fn advanced_brep(item: Entity<'_>, units: &Units) -> Result<Mesh, GeomError> {
    let mut m = Mesher::new(units);
    let outer = item
        .get_ref("Outer")
        .ok_or_else(|| missing(&item, "Outer"))?;
    m.shell(outer)?;
    m.orient(0, true);
    for void in item.get_refs("Voids") {
        let from = m.mesh.triangles.len();
        m.shell(void)?;
        m.orient(from, false);
    }
    Ok(m.mesh)
}

/// True when a surface model (`IfcShellBasedSurfaceModel`, `IfcFaceBasedSurfaceModel`) has
/// faces on surfaces (`IfcFaceSurface`, `IfcAdvancedFace`) or faces bounded by edge loops
/// (`IfcEdgeLoop`, a circle's edges say), which [`surface_model`] meshes.
pub fn has_face_surfaces(item: Entity<'_>) -> bool {
    let shells = [item.get_refs("SbsmBoundary"), item.get_refs("FbsmFaces")].concat();
    // Exporters do not mix face kinds in one shell: its first face tells.
    shells.iter().any(|sh| {
        sh.get("CfsFaces")
            .and_then(|v| {
                v.as_list()
                    .and_then(|l| l.first().and_then(|f| f.as_ref_id()))
            })
            .and_then(|id| sh.model().entity(id))
            .is_some_and(|f| {
                f.is_a("IfcFaceSurface")
                    || f.get_refs("Bounds")
                        .iter()
                        .any(|b| b.get_ref("Bound").is_some_and(|lp| lp.is_a("IfcEdgeLoop")))
            })
    })
}

/// The open mesh of a surface model whose faces lie on surfaces, metres.
pub fn surface_model(item: Entity<'_>, units: &Units) -> Result<Mesh, GeomError> {
    let mut m = Mesher::new(units);
    for shell in [item.get_refs("SbsmBoundary"), item.get_refs("FbsmFaces")].concat() {
        m.shell(shell)?;
    }
    Ok(m.mesh)
}

struct Mesher {
    s: f64,
    units: Units,
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
    fn new(units: &Units) -> Mesher {
        Mesher {
            s: units.metres_per_unit,
            units: *units,
            mesh: Mesh::default(),
            weld: FxHashMap::default(),
            edges: FxHashMap::default(),
        }
    }

    /// Turns the triangles from `from` on inside out when they enclose a negative volume
    /// (`outward`: an outer shell) or a positive one (a void), whichever way the file wrote
    /// the shell.
    fn orient(&mut self, from: usize, outward: bool) {
        let o = self.mesh.positions.first().copied().unwrap_or_default();
        let v: f64 = self.mesh.triangles[from..]
            .iter()
            .map(|t| {
                let [a, b, c] = t.map(|i| self.mesh.positions[i as usize] - o);
                a.dot(b.cross(c))
            })
            .sum();
        if (v < 0.0) == outward {
            for t in &mut self.mesh.triangles[from..] {
                t.swap(1, 2);
            }
        }
    }

    fn vertex(&mut self, p: DVec3) -> u32 {
        // + 0.0 makes -0.0 and 0.0 one key.
        let key = p.to_array().map(|x| (x + 0.0).to_bits());
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
        let p = edge_points(edge, &self.units)?;
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
        } else if lp.is_a("IfcVertexLoop") {
            // A loop of one vertex (a cone's apex) bounds nothing.
            return Ok(Vec::new());
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
            Some(e) => surface(e, &self.units)?,
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
        let rings = close_wrapping_loops(surf, rings, same_sense);
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
        let tris = uv_mesh::triangulate(surf, &mut uv, &mut xyz, tris, &boundary)
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
/// without a seam edge) joined in pairs into one ring through a seam, a single one on a
/// sphere closed through a pole; other loops as they are.
fn close_wrapping_loops(
    surf: &Surface,
    rings: Vec<(bool, Vec<DVec2>, Vec<DVec3>)>,
    same_sense: bool,
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
    let mut left = None;
    while let Some(a) = it.next() {
        let Some(b) = it.next() else {
            left = Some(a);
            break;
        };
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
        let (a0, b0) = (DVec2::new(end, uv[0].y), buv[0] + DVec2::X * shift);
        let seam = seam_points(surf, a0, b0);
        uv.push(a0);
        xyz.push(xyz[0]);
        for (q, p) in &seam {
            uv.push(*q);
            xyz.push(*p);
        }
        let mut prev = b0.x;
        for (q, p) in buv.iter().zip(&bxyz) {
            let x = q.x + ((prev - q.x) / period).round() * period;
            uv.push(DVec2::new(x, q.y));
            xyz.push(*p);
            prev = x;
        }
        let x = buv[0].x + ((prev - buv[0].x) / period).round() * period;
        uv.push(DVec2::new(x, buv[0].y));
        xyz.push(bxyz[0]);
        // The same seam back, one period over, through the same points.
        let back = DVec2::X * (x - b0.x);
        for (q, p) in seam.iter().rev() {
            uv.push(*q + back);
            xyz.push(*p);
        }
        rest.push((outer, uv, xyz));
    }
    // One loop left round a sphere: the face is a cap, closed through the pole on the
    // face's side (its interior lies left of its bounds in (u, v) when the face agrees with
    // the surface's normal).
    if let (Some((outer, mut uv, mut xyz)), Surface::Sphere { placement, radius }) = (left, surf) {
        let wa = winding(&uv);
        let v = if (wa > 0.0) == same_sense {
            std::f64::consts::FRAC_PI_2
        } else {
            -std::f64::consts::FRAC_PI_2
        };
        let pole = placement.transform_point3(DVec3::Z * radius * v.signum());
        let (u0, v0) = (uv[0].x, uv[0].y);
        let end = u0 + wa * period;
        // Up the meridian at the loop's end, along the pole (a line in (u, v), in arc-rule
        // steps so that the triangles reaching it stay narrow in u; in space one point),
        // down the same meridian one period back.
        let seam = seam_points(surf, DVec2::new(end, v0), DVec2::new(end, v));
        uv.push(DVec2::new(end, v0));
        xyz.push(xyz[0]);
        for (q, p) in &seam {
            uv.push(*q);
            xyz.push(*p);
        }
        let n = (period / MAX_ARC_STEP).round() as usize;
        for k in 0..=n {
            uv.push(DVec2::new(end + (u0 - end) * k as f64 / n as f64, v));
            xyz.push(pole);
        }
        for (q, p) in seam.iter().rev() {
            uv.push(DVec2::new(u0, q.y));
            xyz.push(*p);
        }
        rest.push((outer, uv, xyz));
    }
    rest
}

/// The points strictly between `a` and `b` (a straight line in (u, v)) that the chord rule
/// needs on `surf`, with their positions.
fn seam_points(surf: &Surface, a: DVec2, b: DVec2) -> Vec<(DVec2, DVec3)> {
    let f = |t: f64| surf.point(a.lerp(b, t));
    let pts = chord_rule::sample(&f, 0.0, 1.0, 4);
    let n = pts.len();
    pts.into_iter()
        .take(n.saturating_sub(1))
        .skip(1)
        .map(|(t, p)| (a.lerp(b, t), p))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use poinav_ifc::{EntityId, Model};

    fn mesh_of(data: &str, id: u64) -> Result<Mesh, GeomError> {
        let text = format!(
            "ISO-10303-21;HEADER;FILE_SCHEMA(('IFC4'));ENDSEC;DATA;\n{data}\nENDSEC;END-ISO-10303-21;"
        );
        let m = Model::from_bytes("t.ifc", text.into_bytes()).unwrap();
        advanced_brep(m.entity(EntityId(id)).unwrap(), &Units::SI)
    }

    /// Every edge used once each way.
    fn closed(m: &Mesh) -> bool {
        let mut directed = std::collections::HashMap::new();
        for t in &m.triangles {
            for k in 0..3 {
                *directed.entry((t[k], t[(k + 1) % 3])).or_insert(0) += 1;
            }
        }
        directed
            .iter()
            .all(|(&(a, b), &n)| n == 1 && directed.get(&(b, a)) == Some(&1))
    }

    const HEMISPHERE: &str = "#1=IFCCARTESIANPOINT((0.,0.,0.));#2=IFCDIRECTION((0.,0.,1.));\
        #3=IFCDIRECTION((1.,0.,0.));#4=IFCAXIS2PLACEMENT3D(#1,#2,#3);\
        #5=IFCCARTESIANPOINT((2.,0.,0.));#6=IFCVERTEXPOINT(#5);#7=IFCCIRCLE(#4,2.);\
        #8=IFCEDGECURVE(#6,#6,#7,.T.);#9=IFCORIENTEDEDGE(*,*,#8,.T.);#10=IFCEDGELOOP((#9));\
        #11=IFCFACEOUTERBOUND(#10,.T.);#12=IFCSPHERICALSURFACE(#4,2.);\
        #13=IFCADVANCEDFACE((#11),#12,.T.);#14=IFCORIENTEDEDGE(*,*,#8,.F.);\
        #15=IFCEDGELOOP((#14));#16=IFCFACEOUTERBOUND(#15,.T.);#17=IFCDIRECTION((0.,0.,-1.));\
        #18=IFCAXIS2PLACEMENT3D(#1,#17,#3);#19=IFCPLANE(#18);\
        #20=IFCADVANCEDFACE((#16),#19,.T.);#21=IFCCLOSEDSHELL((#13,#20));\
        #22=IFCADVANCEDBREP(#21);";

    #[test]
    fn torus_bounded_by_two_seams_is_closed() {
        // R = 2, r = 0.5: one face, its loop the outer equator and the tube circle at u = 0,
        // each run both ways; V = 2 pi^2 R r^2.
        let text = "#1=IFCCARTESIANPOINT((0.,0.,0.));#2=IFCDIRECTION((0.,0.,1.));\
            #3=IFCDIRECTION((1.,0.,0.));#4=IFCAXIS2PLACEMENT3D(#1,#2,#3);\
            #5=IFCCARTESIANPOINT((2.5,0.,0.));#6=IFCVERTEXPOINT(#5);#7=IFCCIRCLE(#4,2.5);\
            #8=IFCEDGECURVE(#6,#6,#7,.T.);#9=IFCCARTESIANPOINT((2.,0.,0.));\
            #10=IFCDIRECTION((0.,-1.,0.));#11=IFCAXIS2PLACEMENT3D(#9,#10,#3);\
            #12=IFCCIRCLE(#11,0.5);#13=IFCEDGECURVE(#6,#6,#12,.T.);\
            #14=IFCORIENTEDEDGE(*,*,#8,.T.);#15=IFCORIENTEDEDGE(*,*,#13,.T.);\
            #16=IFCORIENTEDEDGE(*,*,#8,.F.);#17=IFCORIENTEDEDGE(*,*,#13,.F.);\
            #18=IFCEDGELOOP((#14,#15,#16,#17));#19=IFCFACEOUTERBOUND(#18,.T.);\
            #20=IFCTOROIDALSURFACE(#4,2.,0.5);#21=IFCADVANCEDFACE((#19),#20,.T.);\
            #22=IFCCLOSEDSHELL((#21));#23=IFCADVANCEDBREP(#22);";
        let m = mesh_of(text, 23).unwrap();
        assert!(closed(&m));
        let exact = 2.0 * std::f64::consts::PI.powi(2) * 2.0 * 0.25;
        assert!(
            (m.volume() / exact - 1.0).abs() < 0.01,
            "{}",
            m.volume() / exact
        );
        // No folds: the area too is the torus's, 4 pi^2 R r.
        let area = 4.0 * std::f64::consts::PI.powi(2);
        assert!((m.area() / area - 1.0).abs() < 0.01, "{}", m.area() / area);
        let (lo, hi) = m.bounds().unwrap();
        assert!((hi - DVec3::new(2.5, 2.5, 0.5)).length() < 1e-3, "{hi}");
        assert!((lo + DVec3::new(2.5, 2.5, 0.5)).length() < 1e-3, "{lo}");
    }

    #[test]
    fn surface_model_of_an_advanced_face() {
        // The hemisphere's spherical face alone, as a shell-based surface model: open, its
        // area 2 pi r^2.
        let text =
            format!("{HEMISPHERE}#30=IFCOPENSHELL((#13));#31=IFCSHELLBASEDSURFACEMODEL((#30));");
        let text = format!(
            "ISO-10303-21;HEADER;FILE_SCHEMA(('IFC4'));ENDSEC;DATA;\n{text}\nENDSEC;END-ISO-10303-21;"
        );
        let model = Model::from_bytes("t.ifc", text.into_bytes()).unwrap();
        let item = model.entity(EntityId(31)).unwrap();
        assert!(has_face_surfaces(item));
        let (m, solid) = crate::brep::face_mesh(item, &Units::SI).unwrap();
        assert!(!solid && !closed(&m));
        let exact = 2.0 * std::f64::consts::PI * 4.0;
        assert!(
            (m.area() / exact - 1.0).abs() < 0.01,
            "{}",
            m.area() / exact
        );
    }

    #[test]
    fn damaged_faces_are_errors_naming_their_instance() {
        // The hemisphere's face on a sphere of the wrong radius, on an unsupported surface,
        // and on a B-spline surface whose knots do not fit its control points.
        let wrong_radius = HEMISPHERE.replace(
            "#12=IFCSPHERICALSURFACE(#4,2.)",
            "#12=IFCSPHERICALSURFACE(#4,3.)",
        );
        let e = mesh_of(&wrong_radius, 22).unwrap_err();
        assert!(
            matches!(
                e,
                GeomError::Degenerate {
                    id: EntityId(13),
                    ..
                }
            ),
            "{e}"
        );
        let unsupported = HEMISPHERE.replace(
            "#12=IFCSPHERICALSURFACE(#4,2.)",
            "#12=IFCCARTESIANPOINT((0.,0.,0.))",
        );
        let e = mesh_of(&unsupported, 22).unwrap_err();
        assert!(
            matches!(
                e,
                GeomError::Unsupported {
                    id: EntityId(12),
                    ..
                }
            ),
            "{e}"
        );
        let knots = HEMISPHERE.replace(
            "#12=IFCSPHERICALSURFACE(#4,2.)",
            "#12=IFCBSPLINESURFACEWITHKNOTS(1,1,((#5,#5),(#5,#5)),.UNSPECIFIED.,.F.,.F.,.F.,(2,2),(2,1),(0.,1.),(0.,1.),.UNSPECIFIED.)",
        );
        let e = mesh_of(&knots, 22).unwrap_err();
        assert!(
            matches!(
                e,
                GeomError::Degenerate {
                    id: EntityId(12),
                    ..
                }
            ),
            "{e}"
        );
    }

    #[test]
    fn hemisphere_is_closed_through_its_pole() {
        let m = mesh_of(HEMISPHERE, 22).unwrap();
        assert!(closed(&m));
        let exact = 2.0 / 3.0 * std::f64::consts::PI * 8.0;
        assert!(
            (m.volume() / exact - 1.0).abs() < 0.01,
            "{}",
            m.volume() / exact
        );
        // No folds along the seam meridian: the area is the dome's and the disc's, 3 pi r^2.
        let area = 3.0 * std::f64::consts::PI * 4.0;
        assert!((m.area() / area - 1.0).abs() < 0.01, "{}", m.area() / area);
        let (lo, hi) = m.bounds().unwrap();
        assert!((hi.z - 2.0).abs() < 1e-12 && lo.z == 0.0, "{lo} {hi}");
    }
}
