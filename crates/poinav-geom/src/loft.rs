//! A profile's areas carried through a sequence of stations (a revolution's angle steps, a
//! tapered extrusion's two ends) as one closed triangle mesh: every ring point joined to its
//! next station's by quads, caps at the first and last station unless the stations wrap
//! around (a full turn), points that do not move (on a revolution's axis) shared by all
//! stations so that the mesh stays closed where a profile touches its axis.

use glam::{DVec2, DVec3};

use crate::mesh::Mesh;
use crate::profile::ProfileArea;
use crate::triangulation::triangulate_2d;

/// Where the stations are and which points stay put.
pub struct Stations<'a> {
    /// Number of stations (at least 2; with `wrap`, the last joins the first).
    pub count: usize,
    /// True when the last station joins the first (no caps).
    pub wrap: bool,
    /// The position of profile point `p` (already interpolated between start and end
    /// profiles) at station `k`.
    pub place: &'a dyn Fn(DVec2, usize) -> DVec3,
    /// True for a point that is the same at every station.
    pub pinned: &'a dyn Fn(DVec2) -> bool,
}

impl std::fmt::Debug for Stations<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "Stations({}, wrap {})", self.count, self.wrap)
    }
}

/// The mesh of `start` carried through `stations`, changing linearly into `end` (same areas,
/// rings and point counts) when given, triangles facing out. `None` when the profiles do not
/// match, a cap cannot be triangulated or the result encloses no volume.
pub fn loft(start: &[ProfileArea], end: Option<&[ProfileArea]>, st: &Stations<'_>) -> Option<Mesh> {
    let end = end.unwrap_or(start);
    if st.count < 2 || start.len() != end.len() {
        return None;
    }
    let mut mesh = Mesh::default();
    for (a, b) in start.iter().zip(end) {
        loft_area(a, b, st, &mut mesh)?;
    }
    let v = mesh.volume();
    if !(v.is_finite() && v.abs() > 0.0) {
        return None;
    }
    if v < 0.0 {
        mesh.flip();
    }
    Some(mesh)
}

fn rings(a: &ProfileArea) -> Vec<&[DVec2]> {
    std::iter::once(&a.outer[..])
        .chain(a.holes.iter().map(|h| &h[..]))
        .collect()
}

fn loft_area(a: &ProfileArea, b: &ProfileArea, st: &Stations<'_>, mesh: &mut Mesh) -> Option<()> {
    let (ra, rb) = (rings(a), rings(b));
    if ra.len() != rb.len() || ra.iter().zip(&rb).any(|(x, y)| x.len() != y.len()) {
        return None;
    }
    let pa: Vec<DVec2> = ra.iter().flat_map(|r| r.iter().copied()).collect();
    let pb: Vec<DVec2> = rb.iter().flat_map(|r| r.iter().copied()).collect();
    let pinned: Vec<bool> = pa
        .iter()
        .zip(&pb)
        .map(|(p, q)| (st.pinned)(*p) && (st.pinned)(*q))
        .collect();
    let last = st.count - 1;
    // Index of point j at station k.
    let mut index: Vec<Vec<u32>> = Vec::with_capacity(st.count);
    for k in 0..st.count {
        let t = if st.wrap { 0.0 } else { k as f64 / last as f64 };
        let row = (0..pa.len())
            .map(|j| {
                if pinned[j] && k > 0 {
                    return index[0][j];
                }
                let p = pa[j].lerp(pb[j], t);
                mesh.positions.push((st.place)(p, k));
                mesh.positions.len() as u32 - 1
            })
            .collect();
        index.push(row);
    }
    let mut push = |t: [u32; 3]| {
        if t[0] != t[1] && t[1] != t[2] && t[0] != t[2] {
            mesh.triangles.push(t);
        }
    };
    if !st.wrap {
        let cap0 = triangulate_2d(&a.outer, &a.holes)?;
        let cap1 = triangulate_2d(&b.outer, &b.holes)?;
        for t in cap0 {
            push([
                index[0][t[0] as usize],
                index[0][t[2] as usize],
                index[0][t[1] as usize],
            ]);
        }
        for t in cap1 {
            push(t.map(|i| index[last][i as usize]));
        }
    }
    let steps = if st.wrap { st.count } else { last };
    for k in 0..steps {
        let (lo, hi) = (&index[k], &index[(k + 1) % st.count]);
        let mut start = 0;
        for ring in &ra {
            let len = ring.len();
            for i in 0..len {
                let (x, y) = (start + i, start + (i + 1) % len);
                push([lo[x], lo[y], hi[y]]);
                push([lo[x], hi[y], hi[x]]);
            }
            start += len;
        }
    }
    Some(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn square(h: f64) -> ProfileArea {
        ProfileArea {
            outer: vec![
                DVec2::new(-h, -h),
                DVec2::new(h, -h),
                DVec2::new(h, h),
                DVec2::new(-h, h),
            ],
            holes: Vec::new(),
        }
    }

    #[test]
    fn frustum_of_a_square_pyramid() {
        // Bottom 2 x 2, top 1 x 1, height 3: V = h/3 (A1 + A2 + sqrt(A1 A2)) = 7.
        let place = |p: DVec2, k: usize| p.extend(3.0 * k as f64);
        let m = loft(
            &[square(1.0)],
            Some(&[square(0.5)]),
            &Stations {
                count: 2,
                wrap: false,
                place: &place,
                pinned: &|_| false,
            },
        )
        .unwrap();
        assert!((m.volume() - 7.0).abs() < 1e-12, "{}", m.volume());
        assert!(loft(
            &[square(1.0)],
            Some(&[]),
            &Stations {
                count: 2,
                wrap: false,
                place: &place,
                pinned: &|_| false,
            }
        )
        .is_none());
    }
}
