//! `IfcParameterizedProfileDef`: rectangles (plain, rounded, hollow), circles (plain, hollow),
//! ellipses, trapezia, the steel shapes I, L, T, U, C and Z and IFC2X3's crane rail A shape,
//! as polygons with holes in the profile's own coordinates (metres, before its `Position`).
//!
//! Shapes follow the IFC definitions (origin at the centre of the bounding box, as
//! IfcOpenShell does). Rounded corners of rectangles are drawn as arcs, and so are the root
//! fillets and edge radii of the I, L, T, U and Z shapes (a rolled IPE 200's fillets are
//! 4 % of its area), and the C shape's bends (inside and outside); flange slopes are left
//! out.

use std::f64::consts::{FRAC_PI_2, PI, TAU};

use glam::DVec2;
use poinav_ifc::Entity;

use crate::curve::MAX_ARC_STEP;
use crate::error::{degenerate, missing, unsupported, GeomError};

/// A polygon with holes: counter-clockwise outer boundary and holes (any orientation), no
/// repeated closing points.
pub(crate) type Shape = (Vec<DVec2>, Vec<Vec<DVec2>>);

/// The shape of a parameterized profile, lengths in metres (`s` metres per file unit).
pub(crate) fn shape(profile: Entity<'_>, s: f64) -> Result<Shape, GeomError> {
    let dim = |name: &'static str| -> Result<f64, GeomError> {
        let v = profile
            .get_f64(name)
            .ok_or_else(|| missing(&profile, name))?;
        if v.is_finite() && v > 0.0 {
            Ok(v * s)
        } else {
            Err(degenerate(&profile, "dimension is not a positive number"))
        }
    };
    // Optional dimensions: absent or zero is "none".
    let opt = |name: &'static str| -> f64 {
        profile
            .get_f64(name)
            .filter(|v| v.is_finite() && *v > 0.0)
            .map_or(0.0, |v| v * s)
    };
    let thin = |outer: f64, t: f64| -> Result<(), GeomError> {
        if t < outer {
            Ok(())
        } else {
            Err(degenerate(&profile, "wall thicker than the profile"))
        }
    };
    let p = |x: f64, y: f64| DVec2::new(x, y);
    if profile.is_a("IfcRectangleHollowProfileDef") {
        let (hx, hy) = (dim("XDim")? / 2.0, dim("YDim")? / 2.0);
        let t = dim("WallThickness")?;
        thin(hx.min(hy), t)?;
        let outer = rounded_rectangle(hx, hy, opt("OuterFilletRadius"));
        let inner = rounded_rectangle(hx - t, hy - t, opt("InnerFilletRadius"));
        Ok((outer, vec![inner]))
    } else if profile.is_a("IfcRoundedRectangleProfileDef") {
        let (hx, hy) = (dim("XDim")? / 2.0, dim("YDim")? / 2.0);
        Ok((rounded_rectangle(hx, hy, opt("RoundingRadius")), vec![]))
    } else if profile.is_a("IfcRectangleProfileDef") {
        let (hx, hy) = (dim("XDim")? / 2.0, dim("YDim")? / 2.0);
        Ok((rounded_rectangle(hx, hy, 0.0), vec![]))
    } else if profile.is_a("IfcCircleHollowProfileDef") {
        let r = dim("Radius")?;
        let t = dim("WallThickness")?;
        thin(r, t)?;
        Ok((ellipse(r, r), vec![ellipse(r - t, r - t)]))
    } else if profile.is_a("IfcCircleProfileDef") {
        let r = dim("Radius")?;
        Ok((ellipse(r, r), vec![]))
    } else if profile.is_a("IfcEllipseProfileDef") {
        Ok((ellipse(dim("SemiAxis1")?, dim("SemiAxis2")?), vec![]))
    } else if profile.is_a("IfcTrapeziumProfileDef") {
        let (bottom, top, h) = (dim("BottomXDim")?, dim("TopXDim")?, dim("YDim")?);
        let off = profile.get_f64("TopXOffset").unwrap_or(0.0) * s;
        let hh = h / 2.0;
        // The schema centres the trapezium's bounding box on the position, so a top line
        // reaching past the bottom one (a negative offset, or offset + top > bottom) moves
        // both lines, as IfcOpenShell 0.9 does.
        let (lo, hi) = ((0.0f64).min(off), bottom.max(off + top));
        let x0 = -(lo + hi) / 2.0;
        Ok((
            vec![
                p(x0, -hh),
                p(x0 + bottom, -hh),
                p(x0 + off + top, hh),
                p(x0 + off, hh),
            ],
            vec![],
        ))
    } else if profile.is_a("IfcCraneRailAShapeProfileDef") {
        // IFC2X3: the 14-point outline IfcOpenShell 0.9 draws (head, web, sloped base; no
        // radii). (IfcOpenShell does not mesh the F shape.)
        let (oh, hw, wt) = (
            dim("OverallHeight")? / 2.0,
            dim("HeadWidth")? / 2.0,
            dim("WebThickness")? / 2.0,
        );
        let (bw2, bw4) = (dim("BaseWidth2")? / 2.0, dim("BaseWidth4")? / 2.0);
        let (hd2, hd3) = (dim("HeadDepth2")?, dim("HeadDepth3")?);
        let (bd1, bd2, bd3) = (dim("BaseDepth1")?, dim("BaseDepth2")?, dim("BaseDepth3")?);
        let left = [
            p(-hw, oh),
            p(-hw, oh - hd3),
            p(-wt, oh - hd2),
            p(-wt, -oh + bd2),
            p(-bw4, -oh + bd3),
            p(-bw2, -oh + bd1),
            p(-bw2, -oh),
        ];
        let right = left.iter().rev().map(|q| p(-q.x, q.y));
        Ok((left.iter().copied().chain(right).collect(), vec![]))
    } else if profile.is_a("IfcAsymmetricIShapeProfileDef") {
        // IFC4 names first, IFC2X3 names (OverallWidth = bottom flange) as the fallback.
        let d = dim("OverallDepth")?;
        let bw = dim("BottomFlangeWidth").or_else(|_| dim("OverallWidth"))?;
        let bt = dim("BottomFlangeThickness").or_else(|_| dim("FlangeThickness"))?;
        let tw = dim("TopFlangeWidth")?;
        let tt = profile
            .get_f64("TopFlangeThickness")
            .filter(|v| *v > 0.0)
            .map_or(bt, |v| v * s);
        let wt = dim("WebThickness")?;
        thin(d, bt + tt)?;
        // IFC2X3 names the bottom fillet FilletRadius (inherited from the I shape).
        let rb = match opt("BottomFlangeFilletRadius") {
            r if r > 0.0 => r,
            _ => opt("FilletRadius"),
        };
        let radii = [
            rb,
            opt("TopFlangeFilletRadius"),
            opt("BottomFlangeEdgeRadius"),
            opt("TopFlangeEdgeRadius"),
        ];
        Ok((i_shape(d, bw, bt, tw, tt, wt, radii), vec![]))
    } else if profile.is_a("IfcIShapeProfileDef") {
        let (w, d) = (dim("OverallWidth")?, dim("OverallDepth")?);
        let (wt, ft) = (dim("WebThickness")?, dim("FlangeThickness")?);
        thin(d, 2.0 * ft)?;
        thin(w, wt)?;
        let (f, e) = (opt("FilletRadius"), opt("FlangeEdgeRadius"));
        Ok((i_shape(d, w, ft, w, ft, wt, [f, f, e, e]), vec![]))
    } else if profile.is_a("IfcLShapeProfileDef") {
        let d = dim("Depth")?;
        let w = profile
            .get_f64("Width")
            .filter(|v| *v > 0.0)
            .map_or(d, |v| v * s);
        let t = dim("Thickness")?;
        thin(w.min(d), t)?;
        let (x, y) = (w / 2.0, d / 2.0);
        let (f, e) = (opt("FilletRadius"), opt("EdgeRadius"));
        let outline = [
            p(-x, -y),
            p(x, -y),
            p(x, -y + t),
            p(-x + t, -y + t),
            p(-x + t, y),
            p(-x, y),
        ];
        Ok((round_corners(&outline, &[(2, e), (3, f), (4, e)]), vec![]))
    } else if profile.is_a("IfcTShapeProfileDef") {
        let (d, fw) = (dim("Depth")?, dim("FlangeWidth")?);
        let (wt, ft) = (dim("WebThickness")?, dim("FlangeThickness")?);
        thin(d, ft)?;
        thin(fw, wt)?;
        let (x, y, w) = (fw / 2.0, d / 2.0, wt / 2.0);
        let f = opt("FilletRadius");
        let (fe, we) = (opt("FlangeEdgeRadius"), opt("WebEdgeRadius"));
        let outline = [
            p(-w, -y),
            p(w, -y),
            p(w, y - ft),
            p(x, y - ft),
            p(x, y),
            p(-x, y),
            p(-x, y - ft),
            p(-w, y - ft),
        ];
        let corners = [(0, we), (1, we), (2, f), (3, fe), (6, fe), (7, f)];
        Ok((round_corners(&outline, &corners), vec![]))
    } else if profile.is_a("IfcUShapeProfileDef") {
        let (d, fw) = (dim("Depth")?, dim("FlangeWidth")?);
        let (wt, ft) = (dim("WebThickness")?, dim("FlangeThickness")?);
        thin(d, 2.0 * ft)?;
        thin(fw, wt)?;
        let (x, y) = (fw / 2.0, d / 2.0);
        let (f, e) = (opt("FilletRadius"), opt("EdgeRadius"));
        let corners = [(2, e), (3, f), (4, f), (5, e)];
        Ok((round_corners(&channel(x, y, wt, ft), &corners), vec![]))
    } else if profile.is_a("IfcCShapeProfileDef") {
        let (d, w) = (dim("Depth")?, dim("Width")?);
        let t = dim("WallThickness")?;
        let g = opt("Girth");
        thin(w.min(d), 2.0 * t)?;
        let (x, y) = (w / 2.0, d / 2.0);
        // A cold-formed section: each bend rounded inside by the internal fillet radius and
        // outside by that plus the wall thickness, as IfcOpenShell draws it.
        let ri = opt("InternalFilletRadius");
        let ro = if ri > 0.0 { ri + t } else { 0.0 };
        let (pts, corners) = if g > t {
            (
                vec![
                    p(-x, -y),
                    p(x, -y),
                    p(x, -y + g),
                    p(x - t, -y + g),
                    p(x - t, -y + t),
                    p(-x + t, -y + t),
                    p(-x + t, y - t),
                    p(x - t, y - t),
                    p(x - t, y - g),
                    p(x, y - g),
                    p(x, y),
                    p(-x, y),
                ],
                vec![
                    (0, ro),
                    (1, ro),
                    (4, ri),
                    (5, ri),
                    (6, ri),
                    (7, ri),
                    (10, ro),
                    (11, ro),
                ],
            )
        } else {
            (
                channel(x, y, t, t).to_vec(),
                vec![(0, ro), (3, ri), (4, ri), (7, ro)],
            )
        };
        Ok((round_corners(&pts, &corners), vec![]))
    } else if profile.is_a("IfcZShapeProfileDef") {
        let (d, fw) = (dim("Depth")?, dim("FlangeWidth")?);
        let (wt, ft) = (dim("WebThickness")?, dim("FlangeThickness")?);
        thin(d, 2.0 * ft)?;
        let (y, w) = (d / 2.0, wt / 2.0);
        let (f, e) = (opt("FilletRadius"), opt("EdgeRadius"));
        let outline = [
            p(-fw + w, -y),
            p(w, -y),
            p(w, y - ft),
            p(fw - w, y - ft),
            p(fw - w, y),
            p(-w, y),
            p(-w, -y + ft),
            p(-fw + w, -y + ft),
        ];
        let corners = [(2, f), (3, e), (6, f), (7, e)];
        Ok((round_corners(&outline, &corners), vec![]))
    } else {
        Err(unsupported(&profile, "profile"))
    }
}

/// An I shape of depth `d`: bottom flange `bw` x `bt`, top flange `tw` x `tt`, web `wt`;
/// `radii`: the root fillets at the bottom and top flanges, then the edge radii of the
/// bottom and top flanges' inner edges (0: sharp).
fn i_shape(d: f64, bw: f64, bt: f64, tw: f64, tt: f64, wt: f64, radii: [f64; 4]) -> Vec<DVec2> {
    let (y, w, b, t) = (d / 2.0, wt / 2.0, bw / 2.0, tw / 2.0);
    let [rb, rt, eb, et] = radii;
    let outline: Vec<DVec2> = [
        (-b, -y),
        (b, -y),
        (b, -y + bt),
        (w, -y + bt),
        (w, y - tt),
        (t, y - tt),
        (t, y),
        (-t, y),
        (-t, y - tt),
        (-w, y - tt),
        (-w, -y + bt),
        (-b, -y + bt),
    ]
    .iter()
    .map(|&(x, y)| DVec2::new(x, y))
    .collect();
    let corners = [
        (2, eb),
        (3, rb),
        (4, rt),
        (5, et),
        (8, et),
        (9, rt),
        (10, rb),
        (11, eb),
    ];
    round_corners(&outline, &corners)
}

/// A channel's outline (a U, a C without lips) of half width `x` and half depth `y`, its web
/// `web` thick on the left, its flanges `flange` thick, counter-clockwise from the bottom left.
fn channel(x: f64, y: f64, web: f64, flange: f64) -> [DVec2; 8] {
    let p = DVec2::new;
    [
        p(-x, -y),
        p(x, -y),
        p(x, -y + flange),
        p(-x + web, -y + flange),
        p(-x + web, y - flange),
        p(x, y - flange),
        p(x, y),
        p(-x, y),
    ]
}

/// `outline` with the corners `corners` (vertex index, radius; 0: sharp) rounded: each
/// replaced by an arc of that radius tangent to both of its edges, as chords of at most
/// [`MAX_ARC_STEP`]. A concave corner gains material (a root fillet), a convex one loses it
/// (an edge radius). Radii too large for their edges are cut to fit: the two arcs on one
/// edge share it in proportion (radii wider than half a web end in a half-round end).
fn round_corners(outline: &[DVec2], corners: &[(usize, f64)]) -> Vec<DVec2> {
    let n = outline.len();
    let edge = |i: usize| outline[(i + 1) % n] - outline[i];
    // Per corner: the half angle between its edges and the tangent length its radius needs.
    let mut cut: Vec<(f64, f64)> = (0..n)
        .map(|i| {
            let r = corners
                .iter()
                .find(|c| c.0 == i)
                .map_or(0.0, |c| c.1.max(0.0));
            let (a, b) = (-edge((i + n - 1) % n), edge(i));
            // The angle between the corner's two edges, in (0, pi) for a real corner.
            let angle = a.perp_dot(b).atan2(a.dot(b)).abs();
            let real = a.length() > 0.0 && b.length() > 0.0;
            if r <= 0.0 || !real || !(1e-6..=PI - 1e-6).contains(&angle) {
                (0.0, 0.0)
            } else {
                (angle / 2.0, r / (angle / 2.0).tan())
            }
        })
        .collect();
    for i in 0..n {
        let j = (i + 1) % n;
        let (len, want) = (edge(i).length(), cut[i].1 + cut[j].1);
        if want > len {
            cut[i].1 *= len / want;
            cut[j].1 *= len / want;
        }
    }
    let mut out = Vec::with_capacity(n + 8 * corners.len());
    for (i, &v) in outline.iter().enumerate() {
        let (half, t) = cut[i];
        if t <= 0.0 {
            out.push(v);
            continue;
        }
        let (u, w) = (-edge((i + n - 1) % n).normalize(), edge(i).normalize());
        let r = t * half.tan();
        let centre = v + (u + w).normalize() * (r / half.sin());
        let (from, to) = (v + u * t - centre, v + w * t - centre);
        let sweep = from.perp_dot(to).atan2(from.dot(to));
        let steps = ((sweep.abs() / MAX_ARC_STEP).ceil() as usize).max(1);
        let start = from.y.atan2(from.x);
        for k in 0..=steps {
            let angle = start + sweep * k as f64 / steps as f64;
            // Two arcs meeting mid-edge share their end point: written once.
            let q = centre + r * DVec2::from_angle(angle);
            if out.last().is_none_or(|p: &DVec2| p.distance(q) > 1e-12) {
                out.push(q);
            }
        }
    }
    out
}

/// A centred rectangle of half-sizes `hx`, `hy`, counter-clockwise, corners rounded with
/// radius `r` (0: sharp) drawn as arcs.
pub(crate) fn rounded_rectangle(hx: f64, hy: f64, r: f64) -> Vec<DVec2> {
    let r = r.min(hx).min(hy);
    if r <= 0.0 {
        return vec![
            DVec2::new(-hx, -hy),
            DVec2::new(hx, -hy),
            DVec2::new(hx, hy),
            DVec2::new(-hx, hy),
        ];
    }
    let n = ((FRAC_PI_2 / MAX_ARC_STEP).ceil() as usize).max(1);
    let corners = [
        (DVec2::new(hx - r, -hy + r), -FRAC_PI_2),
        (DVec2::new(hx - r, hy - r), 0.0),
        (DVec2::new(-hx + r, hy - r), FRAC_PI_2),
        (DVec2::new(-hx + r, -hy + r), PI),
    ];
    let mut out = Vec::with_capacity(4 * (n + 1));
    for (c, start) in corners {
        for i in 0..=n {
            let a = start + FRAC_PI_2 * i as f64 / n as f64;
            out.push(c + r * DVec2::from_angle(a));
        }
    }
    out
}

/// An ellipse with semi-axes `a` (x) and `b` (y), as 72 chords, counter-clockwise.
pub(crate) fn ellipse(a: f64, b: f64) -> Vec<DVec2> {
    let n = (TAU / MAX_ARC_STEP).round() as usize;
    (0..n)
        .map(|i| {
            let t = TAU * i as f64 / n as f64;
            DVec2::new(a * t.cos(), b * t.sin())
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::polygon::{bounds, clean, signed_area};
    use poinav_ifc::{EntityId, Model};

    /// Area (outer less holes) and bounding box of profile `#id` in a metre model.
    fn measure(data: &str, id: u64) -> (f64, DVec2, DVec2) {
        let text = format!(
            "ISO-10303-21;HEADER;FILE_SCHEMA(('IFC4'));ENDSEC;DATA;\n{data}\nENDSEC;END-ISO-10303-21;"
        );
        let m = Model::from_bytes("t.ifc", text.into_bytes()).unwrap();
        let (outer, holes) = shape(m.entity(EntityId(id)).unwrap(), 1.0).unwrap();
        let outer = clean(outer).expect("a simple outer boundary");
        let holes: f64 = holes.iter().map(|h| signed_area(h).abs()).sum();
        let (lo, hi) = bounds(&outer).unwrap();
        (signed_area(&outer) - holes, lo, hi)
    }

    #[test]
    fn steel_shapes_and_hollow_profiles_have_their_areas() {
        let cases = [
            // I: two 0.2 x 0.02 flanges and a 0.26 x 0.01 web.
            (
                "IFCISHAPEPROFILEDEF(.AREA.,$,$,0.2,0.3,0.01,0.02,$,$,$)",
                2.0 * 0.004 + 0.0026,
                0.2,
                0.3,
            ),
            // L: 0.1 x 0.15, 0.01 thick.
            (
                "IFCLSHAPEPROFILEDEF(.AREA.,$,$,0.15,0.1,0.01,$,$,$)",
                0.001 + 0.0014,
                0.1,
                0.15,
            ),
            // T: 0.2 flange x 0.02, web 0.01 over the remaining 0.28.
            (
                "IFCTSHAPEPROFILEDEF(.AREA.,$,$,0.3,0.2,0.01,0.02,$,$,$,$,$)",
                0.004 + 0.0028,
                0.2,
                0.3,
            ),
            // U: 0.1 flanges x 0.02 (twice), web 0.01 over the remaining 0.26.
            (
                "IFCUSHAPEPROFILEDEF(.AREA.,$,$,0.3,0.1,0.01,0.02,$,$,$)",
                0.004 + 0.0026,
                0.1,
                0.3,
            ),
            // C: 0.1 x 0.2, 0.005 wall, 0.02 lips: perimeter strips 2 (0.1 + 0.2) - 4 t, lips.
            (
                "IFCCSHAPEPROFILEDEF(.AREA.,$,$,0.2,0.1,0.005,0.02,$)",
                0.005 * (0.2 + 2.0 * 0.1 + 2.0 * 0.02) - 4.0 * 0.005 * 0.005,
                0.1,
                0.2,
            ),
            // Z: web 0.01 x 0.3 and two flanges 0.1 (from the web's far face) x 0.02.
            (
                "IFCZSHAPEPROFILEDEF(.AREA.,$,$,0.3,0.1,0.01,0.02,$,$)",
                0.01 * 0.26 + 2.0 * 0.1 * 0.02,
                0.19,
                0.3,
            ),
            (
                "IFCRECTANGLEHOLLOWPROFILEDEF(.AREA.,$,$,0.2,0.1,0.01,$,$)",
                0.02 - 0.18 * 0.08,
                0.2,
                0.1,
            ),
            (
                "IFCTRAPEZIUMPROFILEDEF(.AREA.,$,$,2.,1.,1.,0.5)",
                1.5,
                2.0,
                1.0,
            ),
        ];
        for (profile, area, w, h) in cases {
            let (a, lo, hi) = measure(&format!("#1={profile};"), 1);
            assert!((a - area).abs() < 1e-12, "{profile}: {a} vs {area}");
            assert!(
                ((hi - lo) - DVec2::new(w, h)).length() < 1e-12,
                "{profile}: {lo} {hi}"
            );
        }
        // Curved ones, as chords: a hollow circle and a rounded rectangle.
        let (a, _, _) = measure("#1=IFCCIRCLEHOLLOWPROFILEDEF(.AREA.,$,$,0.5,0.1);", 1);
        assert!(
            (a - std::f64::consts::PI * (0.25 - 0.16)).abs() < 0.002,
            "{a}"
        );
        let (a, lo, hi) = measure(
            "#1=IFCROUNDEDRECTANGLEPROFILEDEF(.AREA.,$,$,2.,1.,0.25);",
            1,
        );
        let exact = 2.0 - (4.0 - std::f64::consts::PI) * 0.0625;
        assert!((a - exact).abs() < 0.001, "{a} vs {exact}");
        assert!(((hi - lo) - DVec2::new(2.0, 1.0)).length() < 1e-12);
    }

    #[test]
    fn root_fillets_add_and_edge_radii_take_area() {
        // A fillet of radius r in a right-angled corner adds (1 - pi/4) r2; an edge radius
        // rounding off a right-angled corner takes as much. Chords: within 0.1 % of that.
        let corner = |r: f64| (1.0 - std::f64::consts::PI / 4.0) * r * r;
        let cases = [
            // IPE 200: 2 x 0.1 x 0.0085 flanges, 0.0056 web, four 0.012 fillets.
            (
                "IFCISHAPEPROFILEDEF(.AREA.,$,$,0.1,0.2,0.0056,0.0085,0.012,$,$)",
                2.0 * 0.1 * 0.0085 + 0.183 * 0.0056 + 4.0 * corner(0.012),
                0.1,
                0.2,
            ),
            // The same with 0.004 edge radii on the four inner flange edges.
            (
                "IFCISHAPEPROFILEDEF(.AREA.,$,$,0.1,0.2,0.0056,0.0085,0.012,0.004,$)",
                2.0 * 0.1 * 0.0085 + 0.183 * 0.0056 + 4.0 * corner(0.012) - 4.0 * corner(0.004),
                0.1,
                0.2,
            ),
            // L 0.1 x 0.15 x 0.01: one 0.01 root fillet, two 0.005 toe radii.
            (
                "IFCLSHAPEPROFILEDEF(.AREA.,$,$,0.15,0.1,0.01,0.01,0.005,$)",
                0.001 + 0.0014 + corner(0.01) - 2.0 * corner(0.005),
                0.1,
                0.15,
            ),
            // C 0.2 x 0.1, 0.005 wall, 0.02 lips, internal radius 0.002: four bends, each
            // rounded outside by 0.007 and inside by 0.002.
            (
                "IFCCSHAPEPROFILEDEF(.AREA.,$,$,0.2,0.1,0.005,0.02,0.002)",
                0.005 * (0.2 + 2.0 * 0.1 + 2.0 * 0.02)
                    - 4.0 * 0.005 * 0.005
                    - 4.0 * (corner(0.007) - corner(0.002)),
                0.1,
                0.2,
            ),
            // T 0.3 x 0.2, web 0.01, flange 0.02; web edge radii 0.008 (wider than half the
            // web): the web ends in a half-round end of radius 0.005.
            (
                "IFCTSHAPEPROFILEDEF(.AREA.,$,$,0.3,0.2,0.01,0.02,$,$,0.008,$,$,$)",
                0.004 + 0.0028 - 2.0 * corner(0.005),
                0.2,
                0.3,
            ),
            // U: two 0.008 fillets and two 0.004 edge radii.
            (
                "IFCUSHAPEPROFILEDEF(.AREA.,$,$,0.3,0.1,0.01,0.02,0.008,0.004,$)",
                0.004 + 0.0026 + 2.0 * corner(0.008) - 2.0 * corner(0.004),
                0.1,
                0.3,
            ),
        ];
        for (profile, area, w, h) in cases {
            let (a, lo, hi) = measure(&format!("#1={profile};"), 1);
            assert!((a / area - 1.0).abs() < 1e-3, "{profile}: {a} vs {area}");
            assert!(
                ((hi - lo) - DVec2::new(w, h)).length() < 1e-12,
                "{profile}: {lo} {hi}"
            );
        }
    }
}
