//! SVG plots of a run: trajectories on the floor plan (zones, walls, doors coloured by their
//! status after the run, each robot's path and final footprint), speed over time, and the
//! distance between robots over time with the zones' separation thresholds. They draw what
//! [`crate::samples::PlotSamples`] kept during the run (every step up to 3000 points per line,
//! fewer for many robots), not the trace.

use std::fmt::Write;

use glam::DVec2;
use poinav_io::xml::attr;
use poinav_nav::{polygon, DoorIdx, Floor};
use poinav_roles::AccessibilityStatus;

use crate::geometry::Obb;
use crate::poi_db::Element;
use crate::run::Outcome;
use poinav_io::number::fixed;

/// Robot colours in order (Robot1 red, Robot2 blue as in the paper's figures).
pub const COLOURS: [&str; 8] = [
    "#d62728", "#1f77b4", "#2ca02c", "#9467bd", "#ff7f0e", "#8c564b", "#e377c2", "#17becf",
];

fn colour(i: usize) -> &'static str {
    COLOURS[i % COLOURS.len()]
}

fn f(v: f64) -> String {
    fixed(v, 2)
}

/// Trajectories on the floor plan.
pub fn trajectories(outcome: &Outcome, floor: &Floor) -> String {
    let data = &outcome.data;
    let (lo, hi) = floor.bounds().unwrap_or((DVec2::ZERO, DVec2::ONE));
    let (scale, margin) = (50.0, 20.0);
    let px = |p: DVec2| (margin + (p.x - lo.x) * scale, margin + (hi.y - p.y) * scale);
    let width = (hi.x - lo.x) * scale + 2.0 * margin;
    let height =
        (hi.y - lo.y) * scale + 2.0 * margin + 20.0 * (data.names.robots.len().min(8) as f64 + 1.0);
    let mut s = String::new();
    let _ = writeln!(
        s,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{}" height="{}" viewBox="0 0 {} {}" font-family="sans-serif">"#,
        f(width),
        f(height),
        f(width),
        f(height)
    );
    let _ = writeln!(s, r#"<rect width="100%" height="100%" fill="white"/>"#);
    let poly = |ring: &[DVec2]| -> String {
        ring.iter()
            .map(|p| {
                let (x, y) = px(*p);
                format!("{},{}", f(x), f(y))
            })
            .collect::<Vec<_>>()
            .join(" ")
    };
    for z in &floor.zones {
        let _ = writeln!(
            s,
            r##"<polygon points="{}" fill="#f3f3f3" stroke="#bbbbbb" stroke-width="1"/>"##,
            poly(&z.ring)
        );
        let (x, y) = px(polygon::centroid(&z.ring).unwrap_or_default());
        let label = z.name.as_deref().unwrap_or(&z.id);
        let _ = writeln!(
            s,
            r##"<text x="{}" y="{}" font-size="11" fill="#888888" text-anchor="middle">{}</text>"##,
            f(x),
            f(y),
            attr(label)
        );
    }
    for o in &floor.obstacles {
        for ring in &o.rings {
            let _ = writeln!(s, r##"<polygon points="{}" fill="#555555"/>"##, poly(ring));
        }
    }
    for (i, d) in floor.doors.iter().enumerate() {
        let rec = data.db.get(data.db.index(Element::Door(DoorIdx::new(i))));
        let status = rec
            .accessibility
            .as_ref()
            .map_or(AccessibilityStatus::PendingValidation, |a| a.status);
        let fill = match status {
            AccessibilityStatus::FullAccess => "#4caf50",
            AccessibilityStatus::Restricted => "#ff9800",
            AccessibilityStatus::Blocked => "#f44336",
            AccessibilityStatus::PendingValidation => "#9e9e9e",
        };
        let _ = writeln!(
            s,
            r#"<polygon points="{}" fill="{fill}" fill-opacity="0.8"><title>{} {}</title></polygon>"#,
            poly(&d.ring),
            attr(d.name.as_deref().unwrap_or(&d.id)),
            status.label()
        );
    }
    let samples = &outcome.samples;
    for (i, name) in data.names.robots.iter().enumerate() {
        let mine: Vec<_> = samples.of(i).collect();
        let last = samples.last(i);
        let pts: Vec<String> = mine
            .iter()
            .copied()
            .chain(last)
            .map(|r| {
                let (x, y) = px(r.pos);
                format!("{},{}", f(x), f(y))
            })
            .collect();
        let c = colour(i);
        let _ = writeln!(
            s,
            r#"<polyline points="{}" fill="none" stroke="{c}" stroke-width="2"><title>{}</title></polyline>"#,
            pts.join(" "),
            attr(name)
        );
        if let (Some(first), Some(last)) = (mine.first(), last) {
            let (x, y) = px(first.pos);
            let _ = writeln!(
                s,
                r#"<circle cx="{}" cy="{}" r="4" fill="{c}"/>"#,
                f(x),
                f(y)
            );
            let (hl, hw) = data.sizes[i];
            let b = Obb::new(last.pos, last.heading, hl, hw);
            let _ = writeln!(
                s,
                r#"<polygon points="{}" fill="{c}" fill-opacity="0.35" stroke="{c}"/>"#,
                poly(&b.corners())
            );
        }
        let ly = (hi.y - lo.y) * scale + 2.0 * margin + 16.0 * (i as f64 + 1.0);
        if i < 8 {
            let _ = writeln!(
                s,
                r#"<rect x="{}" y="{}" width="18" height="4" fill="{c}"/><text x="{}" y="{}" font-size="12">{}</text>"#,
                f(margin),
                f(ly - 4.0),
                f(margin + 24.0),
                f(ly),
                attr(name)
            );
        }
    }
    s.push_str("</svg>\n");
    s
}

/// A line chart (its points come thinned by [`crate::samples::PlotSamples`]).
struct Series {
    name: String,
    colour: &'static str,
    points: Vec<(f64, f64)>,
}

fn chart(
    title: &str,
    y_label: &str,
    series: &[Series],
    hlines: &[(f64, String)],
    x_max: f64,
) -> String {
    let (w, h, left, right, top, bottom) = (900.0, 360.0, 60.0, 20.0, 30.0, 50.0);
    let y_max = series
        .iter()
        .flat_map(|s| s.points.iter().map(|p| p.1))
        .chain(hlines.iter().map(|l| l.0))
        .filter(|v| v.is_finite())
        .fold(1.0f64, f64::max)
        * 1.1;
    let x_max = x_max.max(1e-9);
    let px = |x: f64, y: f64| {
        (
            left + x / x_max * (w - left - right),
            top + (1.0 - y.min(y_max) / y_max) * (h - top - bottom),
        )
    };
    let mut s = String::new();
    let _ = writeln!(
        s,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{w}" height="{h}" viewBox="0 0 {w} {h}" font-family="sans-serif">"#
    );
    let _ = writeln!(s, r#"<rect width="100%" height="100%" fill="white"/>"#);
    let _ = writeln!(
        s,
        r#"<text x="{}" y="20" font-size="14" text-anchor="middle">{}</text>"#,
        f(w / 2.0),
        attr(title)
    );
    let nice = |max: f64| -> f64 {
        let raw = max / 8.0;
        let p = 10f64.powf(raw.log10().floor());
        [1.0, 2.0, 5.0, 10.0]
            .iter()
            .map(|m| m * p)
            .find(|v| *v >= raw)
            .unwrap_or(p * 10.0)
    };
    let (xs, ys) = (nice(x_max), nice(y_max));
    let mut x = 0.0;
    while x <= x_max + 1e-9 {
        let (a, b) = px(x, 0.0);
        let _ = writeln!(
            s,
            r##"<line x1="{}" y1="{}" x2="{}" y2="{}" stroke="#eeeeee"/><text x="{}" y="{}" font-size="11" text-anchor="middle">{}</text>"##,
            f(a),
            f(top),
            f(a),
            f(b),
            f(a),
            f(b + 16.0),
            fixed(x, 3)
        );
        x += xs;
    }
    let mut y = 0.0;
    while y <= y_max + 1e-9 {
        let (a, b) = px(0.0, y);
        let _ = writeln!(
            s,
            r##"<line x1="{}" y1="{}" x2="{}" y2="{}" stroke="#eeeeee"/><text x="{}" y="{}" font-size="11" text-anchor="end">{}</text>"##,
            f(a),
            f(b),
            f(w - right),
            f(b),
            f(a - 6.0),
            f(b + 4.0),
            fixed(y, 3)
        );
        y += ys;
    }
    let (ox, oy) = px(0.0, 0.0);
    let _ = writeln!(
        s,
        r#"<line x1="{}" y1="{}" x2="{}" y2="{}" stroke="black"/><line x1="{}" y1="{}" x2="{}" y2="{}" stroke="black"/>"#,
        f(ox),
        f(oy),
        f(w - right),
        f(oy),
        f(ox),
        f(oy),
        f(ox),
        f(top)
    );
    let _ = writeln!(
        s,
        r#"<text x="{}" y="{}" font-size="12" text-anchor="middle">time (s)</text>"#,
        f((left + w - right) / 2.0),
        f(h - 10.0)
    );
    let _ = writeln!(
        s,
        r#"<text x="14" y="{}" font-size="12" text-anchor="middle" transform="rotate(-90 14 {})">{}</text>"#,
        f(h / 2.0),
        f(h / 2.0),
        attr(y_label)
    );
    for (v, label) in hlines {
        let (a, b) = px(0.0, *v);
        let _ = writeln!(
            s,
            r##"<line x1="{}" y1="{}" x2="{}" y2="{}" stroke="#555555" stroke-dasharray="6 4"/><text x="{}" y="{}" font-size="11" text-anchor="end">{}</text>"##,
            f(a),
            f(b),
            f(w - right),
            f(b),
            f(w - right - 4.0),
            f(b - 4.0),
            attr(label)
        );
    }
    for (k, se) in series.iter().enumerate() {
        let pts: Vec<String> = se
            .points
            .iter()
            .filter(|p| p.1.is_finite())
            .map(|&(x, y)| {
                let (a, b) = px(x, y);
                format!("{},{}", f(a), f(b))
            })
            .collect();
        let _ = writeln!(
            s,
            r#"<polyline points="{}" fill="none" stroke="{}" stroke-width="1.5"/>"#,
            pts.join(" "),
            se.colour
        );
        if k < 8 {
            let ly = top + 16.0 * (k as f64 + 1.0);
            let _ = writeln!(
                s,
                r#"<rect x="{}" y="{}" width="18" height="4" fill="{}"/><text x="{}" y="{}" font-size="12">{}</text>"#,
                f(w - right - 150.0),
                f(ly - 4.0),
                se.colour,
                f(w - right - 126.0),
                f(ly),
                attr(&se.name)
            );
        }
    }
    s.push_str("</svg>\n");
    s
}

/// Speed over time, one line per robot.
pub fn speed(outcome: &Outcome) -> String {
    let data = &outcome.data;
    let series: Vec<Series> = data
        .names
        .robots
        .iter()
        .enumerate()
        .map(|(i, name)| Series {
            name: name.clone(),
            colour: colour(i),
            points: outcome
                .samples
                .of(i)
                .map(|r| (r.step as f64 * data.dt, r.speed))
                .collect(),
        })
        .collect();
    chart(
        "Speed",
        "speed (m/s)",
        &series,
        &[],
        data.steps as f64 * data.dt,
    )
}

/// Centre distance between robots over time (every pair up to 8 robots, else each robot's
/// nearest neighbour), with each C-1 zone's MinInterRobotSeparation.
pub fn distance(outcome: &Outcome, floor: &Floor) -> String {
    let data = &outcome.data;
    let n = data.names.robots.len();
    let mut series = Vec::new();
    if n >= 2 {
        let steps: Vec<_> = outcome.samples.steps().collect();
        if n <= 8 {
            for a in 0..n {
                for b in a + 1..n {
                    series.push(Series {
                        name: format!("{} - {}", data.names.robots[a], data.names.robots[b]),
                        colour: colour(series.len()),
                        points: steps
                            .iter()
                            .map(|s| (s[a].step as f64 * data.dt, s[a].pos.distance(s[b].pos)))
                            .collect(),
                    });
                }
            }
        } else {
            for a in 0..n.min(8) {
                series.push(Series {
                    name: format!("{} nearest", data.names.robots[a]),
                    colour: colour(a),
                    points: steps
                        .iter()
                        .map(|s| {
                            let d = (0..n)
                                .filter(|&b| b != a)
                                .map(|b| s[a].pos.distance(s[b].pos))
                                .fold(f64::INFINITY, f64::min);
                            (s[a].step as f64 * data.dt, d)
                        })
                        .collect(),
                });
            }
        }
    }
    let mut seps: Vec<f64> = floor
        .zones
        .iter()
        .filter_map(|z| z.coordination.map(|c| c.0))
        .collect();
    seps.sort_by(f64::total_cmp);
    seps.dedup();
    let lines: Vec<(f64, String)> = seps
        .iter()
        .map(|v| (*v, format!("MinInterRobotSeparation {} m", fixed(*v, 3))))
        .collect();
    chart(
        "Distance between robots",
        "centre distance (m)",
        &series,
        &lines,
        data.steps as f64 * data.dt,
    )
}
