//! A storey's floor plan ([`poinav_geom::FloorPlan`]) as a readable SVG drawing: spaces light
//! with their Name and LongName, walls and columns dark, furniture, stairs and windows in
//! their own colours, door frames, leaves and clear passages (coloured by AccessibilityStatus
//! when given), a title, a legend and a scale bar in metres.
//!
//! The drawing is north-up in project coordinates (world +Y up, the file's project north, not
//! `TrueNorth`): SVG user units are metres with Y negated, and the `viewBox` fits the plan
//! with a margin. Each region is a `<path>` carrying the element's GlobalId and class
//! (`data-global-id`, `data-class`) and a `<title>` that browsers show on hover.

use std::collections::HashMap;
use std::fmt::Write as _;

use glam::DVec2;
use poinav_geom::floor_plan::{FloorPlan, PlanItem};
use poinav_geom::region::Region;
use poinav_geom::PlanItemKind;
use poinav_io::xml;

/// How to draw a plan.
#[derive(Debug, Clone, PartialEq)]
pub struct SvgOptions {
    /// The drawing's larger side in pixels (the `width`/`height` attributes); lengths inside are
    /// metres.
    pub size_px: f64,
    /// White space around the plan, metres (at least 3 % of the plan's larger side).
    pub margin_m: f64,
    /// AccessibilityStatus label (`FULL_ACCESS`, `RESTRICTED`, `BLOCKED`,
    /// `PENDING_VALIDATION`) per door GlobalId: door passages are coloured by it.
    pub door_status: HashMap<String, String>,
    /// Write spaces' names.
    pub space_names: bool,
}

impl Default for SvgOptions {
    fn default() -> Self {
        SvgOptions {
            size_px: 1600.0,
            margin_m: 1.0,
            door_status: HashMap::new(),
            space_names: true,
        }
    }
}

/// Fill, stroke and stroke width (metres) of a kind.
fn style(kind: PlanItemKind) -> (&'static str, &'static str, f64) {
    match kind {
        PlanItemKind::Space => ("#f3f0e6", "#c9c2ad", 0.02),
        PlanItemKind::Stair => ("#e3d3b4", "#8a6d3b", 0.02),
        PlanItemKind::Ramp => ("#e8ddc0", "#8a7a3b", 0.02),
        PlanItemKind::Furniture => ("#c8b49a", "#6e5a40", 0.015),
        PlanItemKind::Obstacle => ("#8c8c8c", "#555555", 0.01),
        PlanItemKind::Column => ("#3a3a3a", "#1a1a1a", 0.01),
        PlanItemKind::Wall => ("#2f2f2f", "#1a1a1a", 0.01),
        PlanItemKind::Window => ("#a9d3f0", "#3f7fae", 0.015),
        PlanItemKind::DoorOpening => ("#cdb8f0", "#6a4fb0", 0.015),
        PlanItemKind::DoorFrame => ("#6b4a2b", "#3d2914", 0.01),
        PlanItemKind::DoorLeaf => ("#d08a3c", "#7a4a16", 0.015),
    }
}

/// Fill of a door passage with this AccessibilityStatus.
fn status_fill(status: &str) -> Option<&'static str> {
    match status {
        "FULL_ACCESS" => Some("#5cbf6e"),
        "RESTRICTED" => Some("#f0b429"),
        "BLOCKED" => Some("#e0463b"),
        "PENDING_VALIDATION" => Some("#b0b0b0"),
        _ => None,
    }
}

/// The plan as an SVG document (UTF-8 text).
pub fn to_svg(plan: &FloorPlan, options: &SvgOptions) -> String {
    let (lo, hi) = plan.bounds.unwrap_or((DVec2::ZERO, DVec2::splat(1.0)));
    let size = (hi - lo).max(DVec2::splat(1.0));
    let m = options.margin_m.max(0.03 * size.max_element());
    // Room above for the title, below for the scale bar and the legend.
    let unit = 0.06 * size.max_element().max(8.0);
    let title_h = unit;
    let entries = legend_entries(plan, options);
    let legend_x = lo.x + (size.x * 0.35).min(unit * 6.0);
    let col_w = unit * 2.8;
    let per_row = (((hi.x + m - legend_x) / col_w).floor() as usize).max(1);
    let rows = entries.len().div_ceil(per_row);
    let foot_h = (unit * 0.45 * rows as f64 + unit * 0.8).max(2.2 * unit);
    let x0 = lo.x - m;
    let y0 = -hi.y - m - title_h;
    let w = size.x + 2.0 * m;
    let h = size.y + 2.0 * m + title_h + foot_h;
    let scale = options.size_px / w.max(h);
    let mut s = String::with_capacity(64 * 1024);
    let _ = writeln!(s, r#"<?xml version="1.0" encoding="UTF-8"?>"#);
    let _ = writeln!(
        s,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{}" height="{}" viewBox="{} {} {} {}">"#,
        num(w * scale),
        num(h * scale),
        num(x0),
        num(y0),
        num(w),
        num(h)
    );
    let storey = plan.storey_name.as_deref().unwrap_or("(unnamed storey)");
    let _ = writeln!(
        s,
        "<title>{} (elevation {:.2} m, plan band {:.2}-{:.2} m)</title>",
        xml::attr(storey),
        plan.elevation_m,
        plan.band.0 - plan.elevation_m,
        plan.band.1 - plan.elevation_m
    );
    let _ = writeln!(
        s,
        r#"<rect x="{}" y="{}" width="{}" height="{}" fill="white"/>"#,
        num(x0),
        num(y0),
        num(w),
        num(h)
    );
    for kind in PlanItemKind::ALL {
        let items: Vec<&PlanItem> = plan.items_of(kind).collect();
        if items.is_empty() {
            continue;
        }
        let (fill, stroke, sw) = style(kind);
        let _ = writeln!(
            s,
            r#"<g class="{}" fill="{fill}" stroke="{stroke}" stroke-width="{}" stroke-linejoin="round" fill-rule="evenodd">"#,
            kind.label(),
            num(sw)
        );
        for item in items {
            let status = options.door_status.get(&item.global_id);
            let own_fill = match kind {
                PlanItemKind::DoorOpening => status.and_then(|st| status_fill(st)),
                _ => None,
            };
            let _ = write!(
                s,
                r#"<path data-global-id="{}" data-class="{}""#,
                xml::attr(&item.global_id),
                xml::attr(&item.class)
            );
            if let Some(f) = own_fill {
                let _ = write!(s, r#" fill="{f}""#);
            }
            let _ = write!(
                s,
                r#" d="{}"><title>{}"#,
                path(&item.regions),
                xml::attr(&item.class)
            );
            for text in [&item.name, &item.long_name].into_iter().flatten() {
                let _ = write!(s, " {}", xml::attr(text));
            }
            if let Some(st) = status {
                let _ = write!(s, " ({})", xml::attr(st));
            }
            let _ = writeln!(s, "</title></path>");
        }
        let _ = writeln!(s, "</g>");
    }
    if options.space_names {
        labels(&mut s, plan);
    }
    let title = format!(
        "{}  -  elevation {:.2} m, band {:.2}-{:.2} m",
        storey,
        plan.elevation_m,
        plan.band.0 - plan.elevation_m,
        plan.band.1 - plan.elevation_m
    );
    let _ = writeln!(
        s,
        r##"<text class="title" x="{}" y="{}" font-family="sans-serif" font-size="{}" fill="#222">{}</text>"##,
        num(lo.x),
        num(-hi.y - m - title_h * 0.3),
        // Half the title band high, narrower when the text would be wider than the drawing.
        num((title_h * 0.5).min(w / (0.56 * title.chars().count().max(1) as f64))),
        xml::attr(&title)
    );
    scale_bar(
        &mut s,
        DVec2::new(lo.x, -lo.y + m + unit * 0.5),
        size.x,
        unit,
    );
    legend(
        &mut s,
        &entries,
        DVec2::new(legend_x, -lo.y + m + unit * 0.4),
        unit,
        per_row,
        col_w,
    );
    let _ = writeln!(s, "</svg>");
    s
}

/// Names of spaces, each where its text can be largest, at most 0.45 m high and never
/// smaller than 0.12 m.
fn labels(s: &mut String, plan: &FloorPlan) {
    let _ = writeln!(
        s,
        r##"<g class="space-names" font-family="sans-serif" fill="#4a4536" text-anchor="middle">"##
    );
    for item in plan.items_of(PlanItemKind::Space) {
        let mut lines: Vec<&String> = [&item.name, &item.long_name]
            .into_iter()
            .flatten()
            .filter(|t| !t.trim().is_empty())
            .collect();
        lines.dedup_by(|a, b| a.trim() == b.trim());
        if lines.is_empty() {
            continue;
        }
        let longest = lines
            .iter()
            .map(|l| l.chars().count())
            .max()
            .unwrap_or(1)
            .max(2);
        let Some((at, font)) = item
            .regions
            .iter()
            .map(|r| label_spot(r, longest, lines.len()))
            .max_by(|a, b| a.1.total_cmp(&b.1))
        else {
            continue;
        };
        let top = at.y + 0.55 * font * (lines.len() as f64 - 1.0);
        let _ = write!(
            s,
            r#"<text data-global-id="{}" x="{}" y="{}" font-size="{}">"#,
            xml::attr(&item.global_id),
            num(at.x),
            num(-top + 0.35 * font),
            num(font)
        );
        for (i, line) in lines.iter().enumerate() {
            let _ = write!(
                s,
                r#"<tspan x="{}" dy="{}">{}</tspan>"#,
                num(at.x),
                if i == 0 {
                    "0".to_string()
                } else {
                    num(font * 1.1)
                },
                xml::attr(line.trim())
            );
        }
        let _ = writeln!(s, "</text>");
    }
    let _ = writeln!(s, "</g>");
}

/// Where in `r` a text of `lines` lines of `chars` characters can be largest (about 0.6 em
/// wide per character, 1.1 em per line), and that font size: the centroid or a point of a
/// grid, whichever leaves the most room along and across.
fn label_spot(r: &Region, chars: usize, lines: usize) -> (DVec2, f64) {
    let fit = |p: DVec2| {
        if !r.contains(p) {
            return 0.0;
        }
        let across = free_run(r, p, DVec2::X);
        let up = free_run(r, p, DVec2::Y);
        (0.9 * across / (0.6 * chars as f64))
            .min(0.8 * up / (1.15 * lines as f64))
            .min(0.45)
    };
    let c = r.centroid();
    let mut best = (c, fit(c));
    let (lo, hi) = r.bounds();
    let n = 16;
    for i in 1..n {
        for j in 1..n {
            let p = lo + (hi - lo) * DVec2::new(i as f64 / n as f64, j as f64 / n as f64);
            let f = fit(p);
            // The centroid unless a point fits a clearly larger text.
            if f > best.1 * 1.2 {
                best = (p, f);
            }
        }
    }
    (best.0, best.1.max(0.12))
}

/// Twice the distance from `p` to the nearest crossing of `r`'s boundary along the line
/// through `p` with direction `dir` (either way): the room a text centred on `p` has.
fn free_run(r: &Region, p: DVec2, dir: DVec2) -> f64 {
    let mut near = f64::INFINITY;
    for ring in r.rings() {
        let n = ring.len();
        for i in 0..n {
            let (a, b) = (ring[i], ring[(i + 1) % n]);
            if let Some((t, u)) = poinav_geom::polygon::line_crossing(p, dir, a, b) {
                if (0.0..=1.0).contains(&u) {
                    near = near.min(t.abs());
                }
            }
        }
    }
    2.0 * near
}

/// A scale bar of a round length, about a fifth of the plan's width, at `at` (SVG units).
fn scale_bar(s: &mut String, at: DVec2, width: f64, unit: f64) {
    let target = (width / 5.0).max(0.5);
    let len = [
        0.5, 1.0, 2.0, 5.0, 10.0, 20.0, 50.0, 100.0, 200.0, 500.0, 1000.0,
    ]
    .into_iter()
    .rfind(|l| *l <= target)
    .unwrap_or(0.5);
    let h = unit * 0.25;
    let font = unit * 0.35;
    let _ = writeln!(
        s,
        r##"<g class="scale-bar" font-family="sans-serif" font-size="{}" fill="#222">"##,
        num(font)
    );
    let segments = 5;
    for i in 0..segments {
        let x = at.x + len * i as f64 / segments as f64;
        let fill = if i % 2 == 0 { "#222" } else { "white" };
        let _ = writeln!(
            s,
            r##"<rect x="{}" y="{}" width="{}" height="{}" fill="{fill}" stroke="#222" stroke-width="{}"/>"##,
            num(x),
            num(at.y),
            num(len / segments as f64),
            num(h),
            num(h * 0.1)
        );
    }
    let fmt_len = |l: f64| {
        if l.fract() == 0.0 {
            format!("{l:.0}")
        } else {
            format!("{l}")
        }
    };
    let _ = writeln!(
        s,
        r#"<text x="{}" y="{}" text-anchor="middle">0</text><text x="{}" y="{}" text-anchor="middle">{} m</text>"#,
        num(at.x),
        num(at.y + h + font * 1.1),
        num(at.x + len),
        num(at.y + h + font * 1.1),
        fmt_len(len)
    );
    // North arrow, left of the bar: project north is up.
    let n = DVec2::new(at.x + len + unit * 1.2, at.y + h);
    let a = unit * 0.6;
    let _ = writeln!(
        s,
        r##"<path class="north" d="M {} {} L {} {} L {} {} Z" fill="#222"/><text x="{}" y="{}" text-anchor="middle">N</text>"##,
        num(n.x),
        num(n.y - a),
        num(n.x + a * 0.3),
        num(n.y),
        num(n.x - a * 0.3),
        num(n.y),
        num(n.x),
        num(n.y + font * 1.1)
    );
    let _ = writeln!(s, "</g>");
}

/// Legend entries: the kinds the plan has, and the door statuses used.
fn legend_entries(plan: &FloorPlan, options: &SvgOptions) -> Vec<(String, &'static str)> {
    let mut entries: Vec<(String, &'static str)> = PlanItemKind::ALL
        .into_iter()
        .filter(|k| plan.items_of(*k).next().is_some())
        .map(|k| (k.label().replace('-', " "), style(k).0))
        .collect();
    let mut statuses: Vec<&str> = plan
        .doors
        .iter()
        .filter_map(|d| options.door_status.get(&d.global_id))
        .map(String::as_str)
        .collect();
    statuses.sort_unstable();
    statuses.dedup();
    for st in statuses {
        if let Some(f) = status_fill(st) {
            entries.push((format!("door {}", st.to_lowercase().replace('_', " ")), f));
        }
    }
    entries
}

/// Swatches with labels, `per_row` to a row.
fn legend(
    s: &mut String,
    entries: &[(String, &'static str)],
    at: DVec2,
    unit: f64,
    per_row: usize,
    col_w: f64,
) {
    let font = unit * 0.3;
    let sw = unit * 0.3;
    let _ = writeln!(
        s,
        r##"<g class="legend" font-family="sans-serif" font-size="{}" fill="#222">"##,
        num(font)
    );
    for (i, (label, fill)) in entries.iter().enumerate() {
        let p = at
            + DVec2::new(
                (i % per_row) as f64 * col_w,
                (i / per_row) as f64 * unit * 0.45,
            );
        let _ = writeln!(
            s,
            r##"<rect x="{}" y="{}" width="{}" height="{}" fill="{fill}" stroke="#555" stroke-width="{}"/><text x="{}" y="{}">{}</text>"##,
            num(p.x),
            num(p.y),
            num(sw),
            num(sw),
            num(sw * 0.05),
            num(p.x + sw * 1.3),
            num(p.y + sw * 0.85),
            xml::attr(label)
        );
    }
    let _ = writeln!(s, "</g>");
}

/// SVG path data of regions, Y negated: one closed subpath per ring.
fn path(regions: &[Region]) -> String {
    let mut d = String::new();
    for r in regions {
        for ring in r.rings() {
            for (i, p) in ring.iter().enumerate() {
                let _ = write!(
                    d,
                    "{}{} {} ",
                    if i == 0 { "M" } else { "L" },
                    num(p.x),
                    num(-p.y)
                );
            }
            d.push_str("Z ");
        }
    }
    d.trim_end().to_string()
}

/// A number to the millimetre, without trailing zeros (`poinav_io::number::fixed`, as the
/// simulator's traces and plots write theirs).
fn num(v: f64) -> String {
    poinav_io::number::fixed(v, 3)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_and_escapes() {
        assert_eq!(num(1.0), "1");
        assert_eq!(num(-0.0001), "0");
        assert_eq!(num(2.5004), "2.5");
        assert_eq!(num(-3.1226), "-3.123");
    }
}
