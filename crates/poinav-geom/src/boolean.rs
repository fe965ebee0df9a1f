//! Mesh booleans (difference, union, intersection, clipping by half-spaces) on closed
//! triangle meshes, computed by `manifold-rust` (a pure Rust port of the Manifold library:
//! exact predicates with symbolic perturbation, so coplanar faces and shared edges, common
//! where openings meet walls, give consistent closed results).
//!
//! Operands are imported strictly first; meshes that are closed but not manifold (vertices
//! repeated at one position, touching shells) are welded, then kept as triangle soup for the
//! library's robust engine. Open meshes (surface models) cannot take part in booleans: they
//! are clipped by planes triangle by triangle instead, and openings leave them alone.

use glam::{DAffine3, DVec2, DVec3};
use manifold_rust::linalg::Vec3;
use manifold_rust::manifold::Manifold;
use manifold_rust::types::{BooleanEngine, Error as ManifoldError, MeshGLP, OpType};

use crate::extrusion::extrude;
use crate::half_space::HalfSpace;
use crate::mesh::Mesh;
use crate::polygon;
use crate::profile::ProfileArea;

/// Results of booleans enclosing less than this (cubic metres: one cubic millimetre) count as
/// empty.
pub const MIN_VOLUME: f64 = 1e-9;

/// How far the polygon of a bounded half-space is grown on every side, metres (10 µm).
pub const PRISM_MARGIN: f64 = 1e-5;

/// A closed mesh imported for booleans: a manifold, or (`soup`) a closed but non-manifold
/// triangle soup that only the library's slower robust engine takes.
#[derive(Clone)]
pub struct Solid {
    manifold: Manifold,
    soup: bool,
}

impl std::fmt::Debug for Solid {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "Solid({} triangles)", self.manifold.num_tri())
    }
}

impl Solid {
    /// Imports a closed mesh; `None` when it is open, not orientable or not finite.
    pub fn new(mesh: &Mesh) -> Option<Solid> {
        if mesh.triangles.is_empty() || !mesh.is_finite() {
            return None;
        }
        let mut gl = MeshGLP::<f64, u32> {
            num_prop: 3,
            vert_properties: mesh
                .positions
                .iter()
                .flat_map(|p| [p.x, p.y, p.z])
                .collect(),
            tri_verts: mesh.triangles.iter().flatten().copied().collect(),
            ..Default::default()
        };
        let m = Manifold::from_mesh_glp(&gl);
        if m.status() == ManifoldError::NoError {
            return Some(Solid::exact(m));
        }
        // Vertices written twice at one position (separate points in the file) leave the
        // mesh open for the strict import: weld them, then try again, then as soup.
        if m.status() == ManifoldError::NotManifold && gl.merge() {
            let m = Manifold::from_mesh_glp(&gl);
            if m.status() == ManifoldError::NoError {
                return Some(Solid::exact(m));
            }
        }
        let m = Manifold::from_mesh_glp_robust(&gl);
        (m.status() == ManifoldError::NoError && !m.is_empty()).then_some(Solid {
            manifold: m,
            soup: true,
        })
    }

    fn exact(manifold: Manifold) -> Solid {
        Solid {
            manifold,
            soup: false,
        }
    }

    /// The triangles.
    pub fn mesh(&self) -> Mesh {
        let gl = self.manifold.get_mesh_glp::<f64, u32>(-1);
        let stride = (gl.num_prop as usize).max(3);
        Mesh {
            positions: gl
                .vert_properties
                .chunks_exact(stride)
                .map(|p| DVec3::new(p[0], p[1], p[2]))
                .collect(),
            triangles: gl
                .tri_verts
                .chunks_exact(3)
                .map(|t| [t[0], t[1], t[2]])
                .collect(),
        }
    }

    /// True when nothing is left, or no more than slivers of under [`MIN_VOLUME`] together
    /// (what a cut that almost removes a solid leaves along its edges).
    pub fn is_empty(&self) -> bool {
        self.manifold.is_empty() || self.manifold.volume().abs() < MIN_VOLUME
    }

    fn op(&self, other: &Solid, op: OpType) -> Option<Solid> {
        // The exact engine for manifolds (the library's `Auto` would first scan both operands
        // for self-intersections with exact arithmetic, which costs more than the boolean).
        let soup = self.soup || other.soup;
        let engine = if soup {
            BooleanEngine::Robust
        } else {
            BooleanEngine::Exact
        };
        let r = self
            .manifold
            .boolean_with_engine(&other.manifold, op, engine);
        (r.status() == ManifoldError::NoError).then_some(Solid { manifold: r, soup })
    }

    /// `self` less `other`; `None` when the library fails.
    pub fn difference(&self, other: &Solid) -> Option<Solid> {
        self.op(other, OpType::Subtract)
    }

    /// `self` and `other` together.
    pub fn union(&self, other: &Solid) -> Option<Solid> {
        self.op(other, OpType::Add)
    }

    /// What `self` and `other` share.
    pub fn intersection(&self, other: &Solid) -> Option<Solid> {
        self.op(other, OpType::Intersect)
    }

    /// The part on the side of the plane through `origin` that `keep` points to.
    pub fn trim(&self, origin: DVec3, keep: DVec3) -> Option<Solid> {
        let r = self
            .manifold
            .trim_by_plane(Vec3::new(keep.x, keep.y, keep.z), origin.dot(keep));
        (r.status() == ManifoldError::NoError).then_some(Solid {
            manifold: r,
            soup: self.soup,
        })
    }
}

/// Overlap test of two boxes (min, max), with a margin.
pub(crate) fn boxes_overlap(a: (DVec3, DVec3), b: (DVec3, DVec3), margin: f64) -> bool {
    a.0.cmple(b.1 + margin).all() && b.0.cmple(a.1 + margin).all()
}

/// The solid a half-space removes from `host` as a closed mesh around `host`: the half-space
/// (within the host's box, enlarged) bounded by its prism.
fn cutter(host: (DVec3, DVec3), hs: &HalfSpace) -> Option<Solid> {
    let prism = hs.prism.as_ref()?;
    // The host's extent along the prism's axis, in the prism's frame, enlarged.
    let inv = prism.placement.inverse();
    let (lo, hi) = host;
    let size = (hi - lo).length().max(1.0);
    let (mut zmin, mut zmax) = (f64::INFINITY, f64::NEG_INFINITY);
    for i in 0..8 {
        let c = DVec3::new(
            if i & 1 == 0 { lo.x } else { hi.x },
            if i & 2 == 0 { lo.y } else { hi.y },
            if i & 4 == 0 { lo.z } else { hi.z },
        );
        let z = inv.transform_point3(c).z;
        zmin = zmin.min(z);
        zmax = zmax.max(z);
    }
    // The polygon grows by PRISM_MARGIN on every side, so that prism faces lying in faces of
    // the host (a wall clipped over its whole length) cut through cleanly.
    let (plo, phi) = polygon::bounds(&prism.polygon).unwrap_or_default();
    let centre = (plo + phi) / 2.0;
    let half = ((phi - plo) / 2.0).max(DVec2::splat(PRISM_MARGIN));
    let scale = (half + PRISM_MARGIN) / half;
    let area = ProfileArea {
        outer: prism
            .polygon
            .iter()
            .map(|p| centre + (*p - centre) * scale)
            .collect(),
        holes: Vec::new(),
    };
    let mut mesh = extrude(&[area], DVec3::new(0.0, 0.0, zmax - zmin + 2.0 * size))?;
    mesh.transform(&(prism.placement * DAffine3::from_translation(DVec3::Z * (zmin - size))));
    Solid::new(&mesh)?.trim(hs.origin, -hs.outward)
}

/// `host` less the material of the half-space `hs`. Closed meshes are cut and capped;
/// open ones are clipped triangle by triangle (a polygonal bound then leaves them alone).
/// `None` when the boolean library fails.
pub fn clip(host: &Mesh, hs: &HalfSpace) -> Option<Mesh> {
    let Some(bounds) = host.bounds() else {
        return Some(Mesh::default());
    };
    let size = (bounds.1 - bounds.0).length();
    let eps = 1e-9 * size.max(1.0);
    let d: Vec<f64> = host.positions.iter().map(|p| hs.distance(*p)).collect();
    if d.iter().all(|&x| x >= -eps) {
        return Some(host.clone());
    }
    if hs.prism.is_none() && d.iter().all(|&x| x <= eps) {
        return Some(Mesh::default());
    }
    match Solid::new(host) {
        Some(solid) => {
            let result = match &hs.prism {
                None => solid.trim(hs.origin, hs.outward)?,
                Some(_) => solid.difference(&cutter(bounds, hs)?)?,
            };
            Some(if result.is_empty() {
                Mesh::default()
            } else {
                result.mesh()
            })
        }
        None if hs.prism.is_none() => Some(clip_triangles(host, &d)),
        None => Some(host.clone()),
    }
}

/// The parts of the triangles where `d` (per vertex) is not negative, uncapped.
fn clip_triangles(host: &Mesh, d: &[f64]) -> Mesh {
    let mut out = Mesh {
        positions: host.positions.clone(),
        triangles: Vec::new(),
    };
    for t in &host.triangles {
        let dv = t.map(|i| d[i as usize]);
        if dv.iter().all(|&x| x >= 0.0) {
            out.triangles.push(*t);
            continue;
        }
        // Sutherland-Hodgman on one triangle, then a fan.
        let mut poly: Vec<u32> = Vec::with_capacity(4);
        for k in 0..3 {
            let (a, b) = (t[k], t[(k + 1) % 3]);
            let (da, db) = (dv[k], dv[(k + 1) % 3]);
            if da >= 0.0 {
                poly.push(a);
            }
            if (da >= 0.0) != (db >= 0.0) {
                let f = da / (da - db);
                let (pa, pb) = (host.positions[a as usize], host.positions[b as usize]);
                out.positions.push(pa + (pb - pa) * f);
                poly.push(out.positions.len() as u32 - 1);
            }
        }
        for k in 1..poly.len().saturating_sub(1) {
            out.triangles.push([poly[0], poly[k], poly[k + 1]]);
        }
    }
    out
}
