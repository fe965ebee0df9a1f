//! Sweeping profile areas (holes included) along a 3D polyline path into closed triangle
//! meshes: the section at every path point is the profile in a frame whose normal is the
//! path's direction; frames either do not twist (rotation-minimising, by parallel transport:
//! each segment's frame is the previous one turned by the least rotation between their
//! directions) or keep their x axis towards a reference direction (fixed, or given per
//! segment). Joints at corners are mitred (each segment's section projected onto the plane
//! halving the corner; where the two differ, a strip in that plane joins them), so the
//! surface stays closed; a turn sharper than [`MAX_MITRE_TURN`] ends one piece and starts the
//! next. Open paths get caps triangulated as extrusion caps are, closed paths (rings) none.

use glam::{DQuat, DVec2, DVec3};

use crate::axis2_placement::build_axes;
use crate::mesh::Mesh;
use crate::profile::ProfileArea;
use crate::triangulation::triangulate_2d;

/// Largest turn (radians) between consecutive segments that is mitred (120 degrees: a mitre
/// then reaches at most twice the section's size beyond the corner); a sharper turn ends one
/// capped piece and starts another.
pub const MAX_MITRE_TURN: f64 = 2.0 * std::f64::consts::FRAC_PI_3;

/// How the x axis of each section is chosen (the y axis is the path direction cross x).
#[derive(Clone, Copy)]
pub enum SectionAxes<'a> {
    /// Without twist (parallel transport), starting from the IFC default axes for the first
    /// direction; rings spread the twist a non-planar loop gathers evenly over its length.
    RotationMinimising,
    /// Towards this direction projected onto each section's plane (where it is not along
    /// the path; there the previous section's axis is kept).
    Fixed(DVec3),
    /// Towards the direction the function gives for each segment (from its middle point and
    /// its direction), projected as for `Fixed`: a reference surface's normal there.
    Towards(&'a dyn Fn(DVec3, DVec3) -> DVec3),
}

impl std::fmt::Debug for SectionAxes<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            SectionAxes::RotationMinimising => f.write_str("RotationMinimising"),
            SectionAxes::Fixed(d) => write!(f, "Fixed({d})"),
            SectionAxes::Towards(_) => f.write_str("Towards(..)"),
        }
    }
}

/// The closed mesh of `areas` swept along `path` (metres), triangles facing out. `None` when
/// the path has no length or a cap cannot be triangulated.
pub fn sweep(areas: &[ProfileArea], path: &[DVec3], axes: SectionAxes<'_>) -> Option<Mesh> {
    let mut pts: Vec<DVec3> = Vec::with_capacity(path.len());
    for &p in path {
        if !p.is_finite() {
            return None;
        }
        if pts
            .last()
            .is_none_or(|q: &DVec3| q.distance(p) > 1e-9 * p.length().max(1.0))
        {
            pts.push(p);
        }
    }
    if pts.len() < 2 {
        return None;
    }
    let scale = pts.iter().map(|p| p.length()).fold(1.0, f64::max);
    let sharp = |a: DVec3, b: DVec3| a.angle_between(b) > MAX_MITRE_TURN;
    let n = pts.len();
    // A ring with a corner too sharp to mitre is swept as an open path split there.
    let closed = n > 3
        && pts[0].distance(pts[n - 1]) <= 1e-9 * scale
        && !sharp(pts[n - 1] - pts[n - 2], pts[1] - pts[0]);
    let mut mesh = Mesh::default();
    if closed {
        piece(areas, &pts, axes, true, &mut mesh)?;
    } else {
        let mut start = 0;
        for i in 1..n - 1 {
            if sharp(pts[i] - pts[i - 1], pts[i + 1] - pts[i]) {
                piece(areas, &pts[start..=i], axes, false, &mut mesh)?;
                start = i;
            }
        }
        piece(areas, &pts[start..], axes, false, &mut mesh)?;
    }
    if mesh.volume() < 0.0 {
        mesh.flip();
    }
    Some(mesh)
}

/// The x axis of each segment's section (`pts`: the path, one more than `dirs`).
fn section_x(
    pts: &[DVec3],
    dirs: &[DVec3],
    axes: SectionAxes<'_>,
    closed: bool,
    lengths: &[f64],
) -> Vec<DVec3> {
    let first = build_axes(dirs[0], None).map_or(DVec3::X, |(x, _, _)| x);
    let mut xs: Vec<DVec3> = Vec::with_capacity(dirs.len());
    for (i, &d) in dirs.iter().enumerate() {
        let transported = match xs.last() {
            None => first,
            Some(&x) => {
                let x = DQuat::from_rotation_arc(dirs[i - 1], d) * x;
                (x - x.dot(d) * d).try_normalize().unwrap_or(first)
            }
        };
        let towards = match axes {
            SectionAxes::RotationMinimising => None,
            SectionAxes::Fixed(f) => Some(f),
            SectionAxes::Towards(f) => Some(f((pts[i] + pts[i + 1]) / 2.0, d)),
        };
        let x = towards
            .filter(|f| f.cross(d).length() > 1e-9 * f.length())
            .and_then(|f| (f - f.dot(d) * d).try_normalize())
            .unwrap_or(transported);
        xs.push(x);
    }
    if closed && matches!(axes, SectionAxes::RotationMinimising) {
        // The twist gathered around the ring, spread evenly along it.
        let (d0, last) = (dirs[0], dirs.len() - 1);
        let back = DQuat::from_rotation_arc(dirs[last], d0) * xs[last];
        let twist = xs[0].cross(back).dot(d0).atan2(xs[0].dot(back));
        let total: f64 = lengths.iter().sum();
        let mut along = 0.0;
        for (i, x) in xs.iter_mut().enumerate() {
            *x = DQuat::from_axis_angle(dirs[i], -twist * along / total) * *x;
            along += lengths[i];
        }
    }
    xs
}

/// Sweeps `areas` along one piece of path (no repeated points, at least two).
fn piece(
    areas: &[ProfileArea],
    pts: &[DVec3],
    axes: SectionAxes<'_>,
    closed: bool,
    mesh: &mut Mesh,
) -> Option<()> {
    let n = pts.len();
    let segs = n - 1;
    let lengths: Vec<f64> = pts.windows(2).map(|w| w[0].distance(w[1])).collect();
    let dirs: Vec<DVec3> = pts
        .windows(2)
        .map(|w| (w[1] - w[0]).try_normalize())
        .collect::<Option<_>>()?;
    let xs = section_x(pts, &dirs, axes, closed, &lengths);
    // The corners (a ring's last point is its first).
    let corners = if closed { n - 1 } else { n };
    let incoming = |v: usize| match v {
        0 if closed => Some(segs - 1),
        0 => None,
        _ => Some(v - 1),
    };
    let outgoing = |v: usize| (v < segs).then_some(v);
    // The section of segment `seg` at corner `v`, projected along the segment onto the
    // plane halving the corner (the section's own plane at an open end).
    let section = |v: usize, seg: usize, q: DVec2| -> DVec3 {
        let (d, x) = (dirs[seg], xs[seg]);
        let p = pts[v];
        let s = p + x * q.x + d.cross(x) * q.y;
        let plane = match (incoming(v), outgoing(v)) {
            (Some(a), Some(b)) => (dirs[a] + dirs[b]).try_normalize().unwrap_or(d),
            _ => d,
        };
        let along = d.dot(plane);
        if along.abs() < 1e-9 {
            return s;
        }
        s + d * ((p - s).dot(plane) / along)
    };
    let scale = pts.iter().map(|p| p.length()).fold(1.0, f64::max);
    for area in areas {
        let loops: Vec<&[DVec2]> = std::iter::once(&area.outer[..])
            .chain(area.holes.iter().map(|h| &h[..]))
            .collect();
        let flat: Vec<DVec2> = loops.iter().flat_map(|l| l.iter().copied()).collect();
        let m = flat.len();
        // Rings in order along the path: at each corner the incoming segment's section and,
        // where its frame differs (a fixed reference round a non-planar corner), the
        // outgoing one's, joined by a strip in the corner's plane.
        let base = mesh.positions.len();
        let mut rings = 0;
        for v in 0..corners {
            let mut last: Option<Vec<DVec3>> = None;
            for seg in [incoming(v), outgoing(v)].into_iter().flatten() {
                let ring: Vec<DVec3> = flat.iter().map(|&q| section(v, seg, q)).collect();
                let same = last.as_ref().is_some_and(|l| {
                    l.iter()
                        .zip(&ring)
                        .all(|(a, b)| a.distance(*b) <= 1e-9 * scale)
                });
                if !same {
                    mesh.positions.extend_from_slice(&ring);
                    rings += 1;
                    last = Some(ring);
                }
            }
        }
        let at = |r: usize, j: usize| (base + (r % rings) * m + j) as u32;
        let strips = if closed { rings } else { rings - 1 };
        for r in 0..strips {
            let mut start = 0;
            for l in &loops {
                let len = l.len();
                for k in 0..len {
                    let k1 = (k + 1) % len;
                    let (a, a1) = (at(r, start + k), at(r, start + k1));
                    let (b, b1) = (at(r + 1, start + k), at(r + 1, start + k1));
                    mesh.triangles.push([a, a1, b1]);
                    mesh.triangles.push([a, b1, b]);
                }
                start += len;
            }
        }
        if !closed {
            let cap = triangulate_2d(&area.outer, &area.holes)?;
            let end = rings - 1;
            for t in &cap {
                mesh.triangles.push([
                    at(0, t[0] as usize),
                    at(0, t[2] as usize),
                    at(0, t[1] as usize),
                ]);
                mesh.triangles.push(t.map(|i| at(end, i as usize)));
            }
        }
    }
    Some(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::{PI, TAU};

    fn disk(r: f64, n: usize) -> ProfileArea {
        ProfileArea {
            outer: (0..n)
                .map(|i| r * DVec2::from_angle(TAU * i as f64 / n as f64))
                .collect(),
            holes: Vec::new(),
        }
    }

    #[test]
    fn frames_do_not_twist_on_a_helix() {
        // A helix (cos t, sin t, c t) rising 0.5 per turn, two turns in 5 degree chords. A
        // frame without twist turns against the Frenet frame (normal towards the axis) at
        // the torsion's rate: by -c / sqrt(1 + c^2) per radian of t, about -57 degrees here;
        // a Frenet frame, or one kept towards the axis or the vertical, would not turn at all.
        let c = 0.5 / TAU;
        let step = TAU / 72.0;
        let pts: Vec<DVec3> = (0..=144)
            .map(|i| {
                let t = step * i as f64;
                DVec3::new(t.cos(), t.sin(), c * t)
            })
            .collect();
        let dirs: Vec<DVec3> = pts.windows(2).map(|w| (w[1] - w[0]).normalize()).collect();
        let lengths: Vec<f64> = pts.windows(2).map(|w| w[0].distance(w[1])).collect();
        let xs = section_x(
            &pts,
            &dirs,
            SectionAxes::RotationMinimising,
            false,
            &lengths,
        );
        let angle = |i: usize| {
            let t = step * (i as f64 + 0.5);
            let normal = DVec3::new(-t.cos(), -t.sin(), 0.0);
            let binormal = dirs[i].cross(normal);
            xs[i].dot(binormal).atan2(xs[i].dot(normal))
        };
        let mut turned = 0.0;
        for i in 1..xs.len() {
            assert!(xs[i].dot(dirs[i]).abs() < 1e-12);
            let d = angle(i) - angle(i - 1);
            turned += (d + PI).rem_euclid(TAU) - PI;
        }
        let expected = -c / (1.0 + c * c).sqrt() * step * 143.0;
        assert!(
            (turned / expected - 1.0).abs() < 0.01,
            "{turned} vs {expected}"
        );
        let mesh = sweep(&[disk(0.05, 24)], &pts, SectionAxes::RotationMinimising).unwrap();
        // Volume: section area times path length (mitred joints neither add nor lose any).
        let area = 0.5 * 24.0 * 0.05f64.powi(2) * (TAU / 24.0).sin();
        let length: f64 = lengths.iter().sum();
        let v = mesh.volume();
        assert!(
            (v / (area * length) - 1.0).abs() < 1e-3,
            "{v} vs {}",
            area * length
        );
    }

    #[test]
    fn tube_volume_is_annulus_times_length() {
        // An L-shaped path, 3 m then 2 m up, tube R = 0.1, r = 0.06.
        let pts = [
            DVec3::ZERO,
            DVec3::new(3.0, 0.0, 0.0),
            DVec3::new(3.0, 0.0, 2.0),
        ];
        let mut hole = disk(0.06, 24).outer;
        hole.reverse();
        let area = ProfileArea {
            outer: disk(0.1, 24).outer,
            holes: vec![hole],
        };
        let mesh = sweep(
            std::slice::from_ref(&area),
            &pts,
            SectionAxes::RotationMinimising,
        )
        .unwrap();
        let exact = PI * (0.1f64.powi(2) - 0.06f64.powi(2)) * 5.0;
        assert!(
            (mesh.volume() / exact - 1.0).abs() < 0.015,
            "{}",
            mesh.volume()
        );
        assert!((mesh.volume() / (area.area() * 5.0) - 1.0).abs() < 1e-9);
        let (lo, hi) = mesh.bounds().unwrap();
        assert!(
            (hi.x - 3.1).abs() < 1e-9 && (lo.x - 0.0).abs() < 1e-9,
            "{lo} {hi}"
        );
        assert!((hi.z - 2.0).abs() < 1e-9, "{hi}");
    }

    #[test]
    fn hairpin_is_split_not_mitred_to_a_spike() {
        // Out 2 m and back 0.5 m beside itself (a 170 degree turn): two capped pieces, no
        // point further than the radius from the path.
        let pts = [
            DVec3::ZERO,
            DVec3::new(2.0, 0.0, 0.0),
            DVec3::new(1.5, 0.1, 0.0),
        ];
        let mesh = sweep(&[disk(0.05, 24)], &pts, SectionAxes::RotationMinimising).unwrap();
        let (lo, hi) = mesh.bounds().unwrap();
        assert!(hi.x <= 2.05 + 1e-9 && lo.x >= -1e-9, "{lo} {hi}");
        assert!(
            hi.y <= 0.1 + 0.05 + 1e-9 && lo.y >= -0.05 - 1e-9,
            "{lo} {hi}"
        );
        let area = 0.5 * 24.0 * 0.05f64.powi(2) * (TAU / 24.0).sin();
        let length = 2.0 + (0.25f64 + 0.01).sqrt();
        assert!((mesh.volume() / (area * length) - 1.0).abs() < 1e-9);
    }

    #[test]
    fn ring_is_closed_without_caps() {
        let pts: Vec<DVec3> = (0..=72)
            .map(|i| DQuat::from_rotation_z(TAU * i as f64 / 72.0) * DVec3::X)
            .collect();
        let mesh = sweep(&[disk(0.1, 24)], &pts, SectionAxes::RotationMinimising).unwrap();
        assert_eq!(mesh.triangles.len(), 72 * 24 * 2);
        assert_eq!(mesh.positions.len(), 72 * 24);
        let area = 0.5 * 24.0 * 0.01 * (TAU / 24.0).sin();
        let length = 72.0 * 2.0 * (PI / 72.0).sin();
        assert!((mesh.volume() / (area * length) - 1.0).abs() < 1e-9);
    }
}
