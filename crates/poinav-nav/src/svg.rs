//! The audit's floor-plan drawing of one storey for one profile (SVG): spaces coloured by
//! reachability (green reachable, amber only through RESTRICTED doors, red unreachable), door
//! passages by AccessibilityStatus (a dashed outline where the inflated grid leaves no room),
//! walls, furniture and stairs, landings, names, a title, a legend and a scale bar. North-up in
//! world coordinates, lengths in metres; every shape has a `<title>` browsers show on hover.
//!
//! poinav-export's `plan_svg` draws `poinav_geom::FloorPlan`s (IFC geometry); this drawing works
//! on the plain [`Floor`] and the audit's results, which that writer does not know.

use std::fmt::Write as _;

use glam::DVec2;
use poinav_roles::AccessibilityStatus;

use crate::audit::ProfileAudit;
use crate::building::Building;
use crate::floor::{Floor, ObstacleKind};
use crate::polygon;
use poinav_io::xml::attr;

/// Fill of a door passage with this status.
pub fn status_colour(s: AccessibilityStatus) -> &'static str {
    match s {
        AccessibilityStatus::FullAccess => "#2e9d48",
        AccessibilityStatus::Restricted => "#e8a400",
        AccessibilityStatus::Blocked => "#d93025",
        AccessibilityStatus::PendingValidation => "#9e9e9e",
    }
}

const REACHABLE: &str = "#cdebd2";
const RESTRICTED_ONLY: &str = "#fbe6ad";
const UNREACHABLE: &str = "#f5c4bf";

struct View {
    lo: DVec2,
    hi: DVec2,
    margin: f64,
    top: f64,
}

impl View {
    fn pt(&self, p: DVec2) -> (f64, f64) {
        (
            p.x - self.lo.x + self.margin,
            self.hi.y - p.y + self.margin + self.top,
        )
    }

    fn path(&self, ring: &[DVec2]) -> String {
        let mut d = String::new();
        for (i, p) in ring.iter().enumerate() {
            let (x, y) = self.pt(*p);
            let _ = write!(d, "{}{:.3},{:.3}", if i == 0 { "M" } else { " L" }, x, y);
        }
        d.push_str(" Z");
        d
    }
}

/// The legend's words for the circles at the landings of stairs, ramps and lifts (filled with
/// the connection's status colour).
const LANDING_LABEL: &str = "stair/ramp/lift landing, status colour";

/// The drawing of storey `floor_index` of `building` for the audit `audit`.
pub fn audit_svg(
    building: &Building,
    floor_index: usize,
    floor: &Floor,
    audit: &ProfileAudit,
) -> String {
    let (lo, hi) = floor.bounds().unwrap_or((DVec2::ZERO, DVec2::splat(1.0)));
    let size = (hi - lo).max(DVec2::splat(1.0));
    let unit = (0.04 * size.max_element()).clamp(0.25, 2.0);
    let margin = 1.5 * unit;
    let top = 2.0 * unit;
    let legend_h = 3.6 * unit;
    let view = View {
        lo,
        hi,
        margin,
        top,
    };
    let (w, h) = (
        size.x + 2.0 * margin,
        size.y + 2.0 * margin + top + legend_h,
    );
    let scale_px = 1400.0 / w.max(h);
    let mut s = String::new();
    let _ = writeln!(
        s,
        "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<svg xmlns=\"http://www.w3.org/2000/svg\" viewBox=\"0 0 {w:.3} {h:.3}\" width=\"{:.0}\" height=\"{:.0}\" font-family=\"sans-serif\">",
        w * scale_px,
        h * scale_px
    );
    let _ = writeln!(
        s,
        "<rect x=\"0\" y=\"0\" width=\"{w:.3}\" height=\"{h:.3}\" fill=\"white\"/>"
    );
    let title = format!(
        "{} - {} (width {:.2} m, needs {:.2} m)",
        floor.name, audit.profile, audit.robot_width_m, audit.required_width_m
    );
    let title_fs =
        (0.9 * unit).min((w - 2.0 * margin) / (0.62 * title.chars().count().max(1) as f64));
    let _ = writeln!(
        s,
        "<text x=\"{margin:.3}\" y=\"{:.3}\" font-size=\"{title_fs:.3}\" font-weight=\"bold\">{}</text>",
        1.3 * unit,
        attr(&title)
    );

    // Spaces.
    s.push_str("<g id=\"spaces\" stroke=\"#9a9a9a\">\n");
    for space in audit.spaces.iter().filter(|sp| sp.floor == floor_index) {
        let Some(z) = floor.zones.iter().find(|z| z.id == space.id) else {
            continue;
        };
        let fill = if !space.reachable {
            UNREACHABLE
        } else if space.restricted_only {
            RESTRICTED_ONLY
        } else {
            REACHABLE
        };
        let _ = writeln!(
            s,
            "<path d=\"{}\" fill=\"{fill}\" stroke-width=\"{:.3}\" data-global-id=\"{}\"><title>{}: {}</title></path>",
            view.path(&z.ring),
            0.02 * unit,
            attr(&z.id),
            attr(space.name.as_deref().unwrap_or(&space.id)),
            attr(&space.reason)
        );
    }
    s.push_str("</g>\n");

    // Obstacles.
    s.push_str("<g id=\"obstacles\">\n");
    for o in &floor.obstacles {
        let (fill, opacity) = match o.kind {
            ObstacleKind::Structure => ("#303030", 1.0),
            ObstacleKind::Furniture => ("#8d6e4f", 0.7),
            ObstacleKind::DoorLeaf => ("#a0a0a0", 0.8),
            ObstacleKind::Transition => ("#b59a6a", 0.9),
            ObstacleKind::Unknown => ("#9e9e9e", 0.6),
        };
        let d: Vec<String> = o.rings.iter().map(|r| view.path(r)).collect();
        let _ = writeln!(
            s,
            "<path d=\"{}\" fill=\"{fill}\" fill-opacity=\"{opacity}\" data-global-id=\"{}\" data-class=\"{}\"><title>{} {}</title></path>",
            d.join(" "),
            attr(&o.id),
            attr(&o.class),
            attr(&o.class),
            attr(&o.id)
        );
    }
    s.push_str("</g>\n");

    // Doors.
    s.push_str("<g id=\"doors\">\n");
    for d in audit.doors.iter().filter(|d| d.floor == floor_index) {
        let Some(door) = floor.doors.iter().find(|x| x.id == d.id) else {
            continue;
        };
        let ring = if door.ring.len() >= 3 {
            door.ring.clone()
        } else {
            let (c, r) = (door.center, 0.25 * unit);
            polygon::rect(c.x - r, c.y - r, c.x + r, c.y + r)
        };
        let dash = if d.grid_passable {
            String::new()
        } else {
            format!(
                " stroke=\"black\" stroke-width=\"{:.3}\" stroke-dasharray=\"{:.3}\"",
                0.03 * unit,
                0.08 * unit
            )
        };
        let _ = writeln!(
            s,
            "<path d=\"{}\" fill=\"{}\"{dash} data-global-id=\"{}\"><title>{}: {} - {}{}</title></path>",
            view.path(&ring),
            status_colour(d.status),
            attr(&d.id),
            attr(d.name.as_deref().unwrap_or(&d.id)),
            d.status.label(),
            attr(&d.reason),
            if d.grid_passable {
                ""
            } else {
                "; no free path in the inflated grid"
            }
        );
    }
    s.push_str("</g>\n");

    // Landings of stairs, ramps and lifts.
    s.push_str("<g id=\"landings\">\n");
    for (c, t) in building.connections.iter().zip(&audit.transitions) {
        for l in c.landings.iter().filter(|l| l.floor == floor_index) {
            let (x, y) = view.pt(l.point);
            let _ = writeln!(
                s,
                "<circle cx=\"{x:.3}\" cy=\"{y:.3}\" r=\"{:.3}\" fill=\"{}\" stroke=\"black\" stroke-width=\"{:.3}\"><title>{} {}: {} - {}</title></circle>",
                0.3 * unit,
                status_colour(t.status),
                0.02 * unit,
                c.kind.label(),
                attr(c.label()),
                t.status.label(),
                attr(&t.reason)
            );
        }
    }
    s.push_str("</g>\n");

    // Names.
    s.push_str("<g id=\"names\" text-anchor=\"middle\" fill=\"#202020\">\n");
    for z in &floor.zones {
        let Some(p) = polygon::interior_point(&z.ring) else {
            continue;
        };
        let (lo, hi) = polygon::bounds(&z.ring).unwrap_or((p, p));
        let fs = (0.45 * unit).min(0.18 * (hi - lo).min_element().max(0.5));
        let (x, y) = view.pt(p);
        let name = z.name.as_deref().or(z.long_name.as_deref()).unwrap_or("");
        let _ = writeln!(
            s,
            "<text x=\"{x:.3}\" y=\"{y:.3}\" font-size=\"{fs:.3}\">{}</text>",
            attr(name)
        );
    }
    s.push_str("</g>\n");

    // Legend and scale bar.
    let ly = margin + top + size.y + margin + 0.6 * unit;
    let box_w = 0.6 * unit;
    let items: [(&str, &str); 7] = [
        (REACHABLE, "space reachable"),
        (RESTRICTED_ONLY, "only via RESTRICTED"),
        (UNREACHABLE, "space unreachable"),
        (
            status_colour(AccessibilityStatus::FullAccess),
            "FULL_ACCESS",
        ),
        (status_colour(AccessibilityStatus::Restricted), "RESTRICTED"),
        (status_colour(AccessibilityStatus::Blocked), "BLOCKED"),
        (
            status_colour(AccessibilityStatus::PendingValidation),
            "PENDING",
        ),
    ];
    // Spaces on the first row, door statuses on the second.
    let step = (w - 2.0 * margin) / 4.0;
    let longest = items.iter().map(|i| i.1.len()).max().unwrap_or(1) as f64;
    let legend_fs = (0.4 * unit).min((step - 1.5 * box_w) / (0.6 * longest));
    for (i, (fill, label)) in items.iter().enumerate() {
        let (col, row) = if i < 3 { (i, 0.0) } else { (i - 3, 1.0) };
        let x = margin + col as f64 * step;
        let ly = ly + row * 0.9 * unit;
        let _ = writeln!(
            s,
            "<rect x=\"{x:.3}\" y=\"{ly:.3}\" width=\"{box_w:.3}\" height=\"{box_w:.3}\" fill=\"{fill}\" stroke=\"#666\" stroke-width=\"{:.3}\"/><text x=\"{:.3}\" y=\"{:.3}\" font-size=\"{legend_fs:.3}\">{label}</text>",
            0.02 * unit,
            x + 1.3 * box_w,
            ly + 0.8 * box_w,
        );
    }
    // The landings' marker: a circle in its connection's status colour.
    let x = margin + 3.0 * step;
    let landing_fs = (0.4 * unit).min((step - 1.5 * box_w) / (0.6 * LANDING_LABEL.len() as f64));
    let _ = writeln!(
        s,
        "<circle cx=\"{:.3}\" cy=\"{:.3}\" r=\"{:.3}\" fill=\"white\" stroke=\"black\" stroke-width=\"{:.3}\"/><text x=\"{:.3}\" y=\"{:.3}\" font-size=\"{landing_fs:.3}\">{LANDING_LABEL}</text>",
        x + box_w / 2.0,
        ly + box_w / 2.0,
        0.3 * unit,
        0.02 * unit,
        x + 1.3 * box_w,
        ly + 0.8 * box_w,
    );
    let bar = nice_length(size.x / 4.0);
    let by = ly + 2.2 * unit;
    let _ = writeln!(
        s,
        "<rect x=\"{margin:.3}\" y=\"{by:.3}\" width=\"{bar:.3}\" height=\"{:.3}\" fill=\"black\"/><text x=\"{:.3}\" y=\"{:.3}\" font-size=\"{:.3}\">{bar} m</text>",
        0.15 * unit,
        margin + bar + 0.3 * unit,
        by + 0.3 * unit,
        0.4 * unit
    );
    s.push_str("</svg>\n");
    s
}

/// 1, 2 or 5 times a power of ten, at most `x`.
fn nice_length(x: f64) -> f64 {
    let x = x.max(0.1);
    let p = 10f64.powf(x.log10().floor());
    for m in [5.0, 2.0, 1.0] {
        if m * p <= x {
            return m * p;
        }
    }
    p
}
