//! The accessibility audit: for each robot profile, every door and vertical connection with
//! its status and the reason (clear width against the requirement), whether the robot's
//! centre can cross each door in the inflated grid, and every space reachable or not from the
//! entrances (exterior doors) or a named start, with the doors that block it. Written as JSON,
//! one SVG floor plan per storey and profile coloured by status, and `report.html` wrapping
//! them. Each storey is audited only where there is something to navigate (its own extent,
//! [`crate::extent`]); a storey without spaces or doors is skipped, listed in
//! [`AuditReport::skipped`] with why, and not drawn.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use poinav_io::xml::attr;
use poinav_roles::{AccessibilityStatus, RobotProfile, Role};
use serde::Serialize;

use crate::building::Building;
use crate::navigator::{NavOptions, Navigator};
use crate::route::{Blocking, NoPlace, Place, Target};
use crate::space_name::SpaceNames;
use crate::svg;
use crate::NavError;
use crate::ZoneIdx;
use poinav_floor::ElementId;

/// How to audit.
#[derive(Debug, Clone, PartialEq, Default, Serialize)]
pub struct AuditOptions {
    /// Grids, inflation, speeds.
    pub nav: NavOptions,
    /// A named start space (`Room 1` or `Room 1@Storey`); default: the entrances.
    pub start: Option<String>,
}

/// A door as audited.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct DoorAudit {
    /// Storey index.
    pub floor: usize,
    /// Storey name.
    pub floor_name: String,
    /// GlobalId.
    pub id: ElementId,
    /// Name.
    pub name: Option<String>,
    /// Clear width, metres.
    pub clear_width_m: f64,
    /// Required clear width (MinClearanceWidth), metres.
    pub required_width_m: f64,
    /// Status for the profile.
    pub status: AccessibilityStatus,
    /// Why.
    pub reason: String,
    /// The robot's centre can cross it in the inflated grid.
    pub grid_passable: bool,
    /// An entrance (a zone on one side only).
    pub exterior: bool,
    /// How an entrance is reached from outside: `ground` (its storey is at ground level) or
    /// `terrain` (a door on a storey not at ground level that opens onto the terrain); `null`
    /// for other doors.
    pub entrance: Option<crate::level::Entrance>,
    /// Names of the zones on its two sides (`outside` for none).
    pub zones: Vec<String>,
    /// The sides come from the spaces the door bounds (in IFC its IfcRelSpaceBoundary), not
    /// from geometry.
    pub sides_from_space_boundaries: bool,
    /// POI roles.
    pub roles: Vec<Role>,
    /// An opening without a door (a doorway).
    pub doorless: bool,
}

/// A vertical connection as audited.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct TransitionAudit {
    /// GlobalId.
    pub id: ElementId,
    /// Name.
    pub name: Option<String>,
    /// `stair`, `ramp`, `lift`.
    pub kind: &'static str,
    /// Storeys served.
    pub floors: Vec<String>,
    /// Clear width, metres.
    pub clear_width_m: Option<f64>,
    /// Slope, degrees.
    pub slope_deg: Option<f64>,
    /// Status for the profile.
    pub status: AccessibilityStatus,
    /// Why.
    pub reason: String,
}

/// A space as audited.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SpaceAudit {
    /// Storey index.
    pub floor: usize,
    /// Storey name.
    pub floor_name: String,
    /// GlobalId.
    pub id: ElementId,
    /// Name (Name, else LongName).
    pub name: Option<String>,
    /// Reachable from the starts.
    pub reachable: bool,
    /// Reachable, but only through RESTRICTED doors.
    pub restricted_only: bool,
    /// For unreachable spaces: the doors and transitions on the least-blocked way in.
    pub blocked_by: Vec<Blocking>,
    /// A sentence.
    pub reason: String,
    /// POI roles.
    pub roles: Vec<Role>,
}

/// One profile's audit.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ProfileAudit {
    /// Profile name.
    pub profile: String,
    /// Robot width, metres.
    pub robot_width_m: f64,
    /// MinClearanceWidth, metres.
    pub required_width_m: f64,
    /// Lethal inflation radius used, metres.
    pub lethal_radius_m: f64,
    /// Inflation (cost) radius used, metres.
    pub inflation_radius_m: f64,
    /// What reachability was measured from.
    pub starts: Vec<String>,
    /// Doors.
    pub doors: Vec<DoorAudit>,
    /// Stairs, ramps, lifts.
    pub transitions: Vec<TransitionAudit>,
    /// Spaces.
    pub spaces: Vec<SpaceAudit>,
}

impl ProfileAudit {
    /// Door counts: FULL_ACCESS, RESTRICTED, BLOCKED, PENDING_VALIDATION.
    pub fn door_counts(&self) -> [usize; 4] {
        let mut n = [0; 4];
        for d in &self.doors {
            n[status_index(d.status)] += 1;
        }
        n
    }

    /// Reachable and unreachable space counts.
    pub fn space_counts(&self) -> (usize, usize) {
        let r = self.spaces.iter().filter(|s| s.reachable).count();
        (r, self.spaces.len() - r)
    }
}

fn status_index(s: AccessibilityStatus) -> usize {
    match s {
        AccessibilityStatus::FullAccess => 0,
        AccessibilityStatus::Restricted => 1,
        AccessibilityStatus::Blocked => 2,
        AccessibilityStatus::PendingValidation => 3,
    }
}

/// The audit of every profile.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct AuditReport {
    /// Storey names.
    pub floors: Vec<String>,
    /// Per storey (as `floors`, when known): its elevation, the walking level used and where
    /// that comes from, and whether it is at ground level (where entrances are).
    pub levels: Vec<crate::level::FloorLevel>,
    /// What limits the audit ([`Building::diagnostics`]: storeys without spaces).
    pub warnings: Vec<String>,
    /// The elements rasterising and the graph gave up on for any profile ([`crate::bounds`]),
    /// sorted, each once; their messages are in `warnings` too.
    pub gave_up: Vec<crate::bounds::GaveUp>,
    /// The storeys with nothing to navigate (no spaces or doors), with why: not rasterised,
    /// not drawn.
    pub skipped: Vec<crate::extent::SkippedStorey>,
    /// Every other storey was rasterised and is drawn over its own extent (its spaces, doors
    /// and walls) grown by this many metres ([`crate::extent::margin`]).
    pub crop_margin_m: f64,
    /// Per profile, in the order given.
    pub profiles: Vec<ProfileAudit>,
}

/// Audits `building` for each of `profiles`.
pub fn audit(
    building: &Building,
    profiles: &[RobotProfile],
    options: &AuditOptions,
) -> Result<AuditReport, NavError> {
    audit_with_progress(building, profiles, options, &crate::progress::none)
}

/// [`audit()`], telling `progress` about each storey rasterised and the graph, per profile.
pub fn audit_with_progress(
    building: &Building,
    profiles: &[RobotProfile],
    options: &AuditOptions,
    progress: crate::progress::Progress<'_>,
) -> Result<AuditReport, NavError> {
    let mut out = Vec::new();
    let mut gave_up = Vec::new();
    let mut skipped = Vec::new();
    for p in profiles {
        let nav = Navigator::with_progress(building, p, &options.nav, progress)?;
        progress(crate::progress::Phase::Auditing, out.len(), profiles.len());
        out.push(audit_profile(&nav, options.start.as_deref())?);
        progress(crate::progress::Phase::Auditing, out.len(), profiles.len());
        skipped = nav.skipped();
        gave_up.extend(nav.gave_up);
    }
    gave_up.sort();
    gave_up.dedup();
    let mut warnings = building.diagnostics();
    warnings.extend(gave_up.iter().map(crate::bounds::GaveUp::message));
    Ok(AuditReport {
        floors: building.floors.iter().map(|f| f.name.clone()).collect(),
        levels: building.levels.clone(),
        warnings,
        gave_up,
        skipped,
        crop_margin_m: crate::extent::margin(&options.nav.grid),
        profiles: out,
    })
}

/// Audits one prepared profile.
pub fn audit_profile(nav: &Navigator<'_>, start: Option<&str>) -> Result<ProfileAudit, NavError> {
    let b = nav.building;
    let t = &nav.topology;
    let zone_label = |floor: usize, z: Option<ZoneIdx>| -> String {
        match z {
            Some(k) => t.nodes[t.zone_nodes[floor][k.get()]].label().to_string(),
            None => "outside".into(),
        }
    };
    let doors: Vec<DoorAudit> = t
        .doors
        .iter()
        .map(|s| {
            let d = &b.floors[s.floor].doors[s.door.get()];
            let (status, reason) = nav.status[s.node].clone();
            DoorAudit {
                floor: s.floor,
                floor_name: b.floors[s.floor].name.clone(),
                id: d.id.clone(),
                name: d.name.clone(),
                clear_width_m: d.clear_width_m,
                required_width_m: nav.profile.min_clearance_width(),
                status,
                reason,
                grid_passable: nav.grid_passable[s.node],
                exterior: s.exterior(),
                entrance: s.entrance(),
                zones: s.zones.iter().map(|z| zone_label(s.floor, *z)).collect(),
                sides_from_space_boundaries: s.from_spaces,
                doorless: d.doorless,
                roles: d.roles.clone(),
            }
        })
        .collect();
    let transitions: Vec<TransitionAudit> = b
        .connections
        .iter()
        .map(|c| {
            let (status, reason) = c.status(&nav.profile);
            TransitionAudit {
                id: c.id.clone(),
                name: c.name.clone(),
                kind: c.kind.label(),
                floors: c
                    .landings
                    .iter()
                    .filter_map(|l| b.floors.get(l.floor).map(|f| f.name.clone()))
                    .collect(),
                clear_width_m: c.clear_width_m,
                slope_deg: c.slope_deg,
                status,
                reason,
            }
        })
        .collect();

    // Where reachability starts.
    let (starts, start_labels): (Vec<usize>, Vec<String>) = match start {
        // `outside`: the entrances (unless a space has that name).
        Some(s)
            if matches!(
                s.parse::<Place>(),
                Ok(Place {
                    target: Target::Outside,
                    ..
                })
            ) && t.zone_node(b, "outside", None).is_none() =>
        {
            let floor = match s.parse::<Place>().ok().and_then(|p| p.floor) {
                Some(f) => Some(b.find_storey(&f)?),
                None => None,
            };
            let entrances: Vec<usize> = t
                .doors
                .iter()
                .filter(|d| d.exterior() && floor.is_none_or(|f| f == d.floor))
                .map(|d| d.node)
                .collect();
            let labels = entrances.iter().map(|&n| entrance_label(nav, n)).collect();
            (entrances, labels)
        }
        Some(s) => {
            let place: Place = s
                .parse()
                .map_err(|e: NoPlace| NavError::Invalid(e.to_string()))?;
            let Target::Zone(name) = &place.target else {
                return Err(NavError::Invalid(format!(
                    "the audit's start must be a space, not a point: `{s}`"
                )));
            };
            let floor = place
                .floor
                .as_deref()
                .map(|f| b.find_storey(f))
                .transpose()?;
            let space = b.find_space(name, floor, place.floor.as_deref())?;
            let node = t.zone_nodes[space.floor][space.zone.get()];
            (vec![node], vec![s.to_string()])
        }
        None => {
            let entrances = t.entrances();
            let labels = entrances.iter().map(|&n| entrance_label(nav, n)).collect();
            (entrances, labels)
        }
    };
    let open_starts: Vec<usize> = starts.iter().copied().filter(|&n| nav.open[n]).collect();
    let (dist, _) = t.search(
        &open_starts,
        |n| nav.open[n].then_some(0.0),
        |x, y| nav.connection_cost(x, y),
    );
    let (dist_full, _) = t.search(
        &open_starts,
        |n| (nav.open[n] && nav.status[n].0 != AccessibilityStatus::Restricted).then_some(0.0),
        |x, y| nav.connection_cost(x, y),
    );
    let mut spaces = Vec::new();
    for (fi, f) in b.floors.iter().enumerate() {
        for (k, z) in f.zones.iter().enumerate() {
            let node = t.zone_nodes[fi][k];
            let label = t.nodes[node].label().to_string();
            // A space that is itself a vertical connection (a lift shaft) is entered at the
            // connection's landings, not through doors of its own.
            if let Some(ci) = b.connections.iter().position(|c| c.id == z.id) {
                let c = &b.connections[ci];
                let landings = t.landing_nodes.get(ci).map_or(&[][..], |l| &l[..]);
                let reachable = landings.iter().any(|&n| dist[n].is_finite());
                let restricted_only =
                    reachable && !landings.iter().any(|&n| dist_full[n].is_finite());
                let (status, why) = c.status(&nav.profile);
                spaces.push(SpaceAudit {
                    floor: fi,
                    floor_name: f.name.clone(),
                    id: z.id.clone(),
                    name: Some(label),
                    reachable,
                    restricted_only,
                    blocked_by: Vec::new(),
                    reason: format!(
                        "the {} {} itself, entered at its landings ({}); {}: {why}",
                        c.kind.label(),
                        c.label(),
                        if reachable {
                            "reachable"
                        } else {
                            "not reachable"
                        },
                        status.label()
                    ),
                    roles: z.roles.clone(),
                });
                continue;
            }
            let reachable = dist[node].is_finite();
            let restricted_only = reachable && !dist_full[node].is_finite();
            let (blocked_by, reason) = if reachable {
                let r = if restricted_only {
                    "reachable only through RESTRICTED doors".to_string()
                } else {
                    "reachable".to_string()
                };
                (Vec::new(), r)
            } else if starts.is_empty() {
                (
                    Vec::new(),
                    "no entrance (a door with a space on one side only) found: name a start space"
                        .to_string(),
                )
            } else {
                match nav.blocking(&starts, node) {
                    Some(bl) if !bl.is_empty() => {
                        let names: Vec<String> = bl.iter().map(|x| x.to_string()).collect();
                        (bl, format!("blocked by {}", names.join(", ")))
                    }
                    Some(_) => (
                        Vec::new(),
                        "no free path for the robot in the inflated grid".to_string(),
                    ),
                    None => (
                        Vec::new(),
                        "not connected to the start by any door, opening or vertical connection"
                            .to_string(),
                    ),
                }
            };
            spaces.push(SpaceAudit {
                floor: fi,
                floor_name: f.name.clone(),
                id: z.id.clone(),
                name: Some(label),
                reachable,
                restricted_only,
                blocked_by,
                reason,
                roles: z.roles.clone(),
            });
        }
    }
    Ok(ProfileAudit {
        profile: nav.profile.name.clone(),
        robot_width_m: nav.profile.width_m,
        required_width_m: nav.profile.min_clearance_width(),
        lethal_radius_m: nav.floors.first().map_or(0.0, |f| f.grid.lethal_radius_m),
        inflation_radius_m: nav
            .floors
            .first()
            .map_or(0.0, |f| f.grid.inflation_radius_m),
        starts: start_labels,
        doors,
        transitions,
        spaces,
    })
}

/// How the report names an entrance (door node `node`) among the starts: `Level 1 door 184606
/// into 101 ENTRY`: the storey, the door's name (for a Revit-style `Family:Type:Id` name its
/// last part, else the GlobalId's first 8 characters when it has none) and the space it leads
/// into (Name and LongName); `, from the terrain` ends the label of a door on a storey not at
/// ground level that opens onto the terrain ([`crate::level::Entrance::Terrain`]).
pub fn entrance_label(nav: &Navigator<'_>, node: usize) -> String {
    let t = &nav.topology;
    let n = &t.nodes[node];
    let floor = &nav.building.floors[n.floor];
    let door = short_name(n.name.as_deref(), &n.element);
    let sides = t.doors.iter().find(|d| d.node == node);
    let into = sides
        .and_then(|d| d.zones.iter().flatten().next())
        .map(|&z| {
            let z = &floor.zones[z.get()];
            let words: Vec<&str> = [z.name.as_deref(), z.long_name.as_deref()]
                .into_iter()
                .flatten()
                .collect();
            if words.is_empty() {
                format!(" into {}", z.id)
            } else {
                format!(" into {}", words.join(" "))
            }
        })
        .unwrap_or_default();
    let terrain = if sides.and_then(|d| d.entrance()) == Some(crate::level::Entrance::Terrain) {
        ", from the terrain"
    } else {
        ""
    };
    format!("{} door {door}{into}{terrain}", floor.name)
}

/// A door's name for lists: the name, the last part of a Revit-style `Family:Type:Id` name,
/// else the first 8 characters of the GlobalId.
fn short_name(name: Option<&str>, id: &str) -> String {
    let name = name.map(str::trim).filter(|n| !n.is_empty());
    match name.map(|n| n.rsplit(':').next().unwrap_or(n).trim()) {
        Some(n) if !n.is_empty() => n.to_string(),
        _ => id.chars().take(8).collect(),
    }
}

impl AuditReport {
    /// Messages for every `required` space (a GlobalId, Name or LongName, `@Storey` optional,
    /// selecting one space of `building`, as [`crate::SpaceNames::select_space`]) that some profile
    /// cannot reach; empty when all are reachable. An unknown or ambiguous name is an error.
    pub fn unreachable_required(
        &self,
        building: &Building,
        required: &[String],
    ) -> Result<Vec<String>, NavError> {
        let mut out = Vec::new();
        for want in required {
            let space = building.select_space(want)?;
            let id = &building.space(space).id;
            for p in &self.profiles {
                let hit = p
                    .spaces
                    .iter()
                    .find(|s| s.floor == space.floor && &s.id == id);
                if let Some(s) = hit.filter(|s| !s.reachable) {
                    out.push(format!(
                        "{}: {want} is unreachable: {}",
                        p.profile, s.reason
                    ));
                }
            }
        }
        Ok(out)
    }

    /// As JSON.
    pub fn to_json(&self) -> serde_json::Value {
        serde_json::to_value(self).unwrap_or(serde_json::Value::Null)
    }
}

/// A file name part from free text: lower case letters, digits and dashes.
pub fn slug(text: &str) -> String {
    let mut s = String::new();
    for c in text.chars().flat_map(char::to_lowercase) {
        if c.is_alphanumeric() {
            s.push(c);
        } else if !s.ends_with('-') && !s.is_empty() {
            s.push('-');
        }
    }
    while s.ends_with('-') {
        s.pop();
    }
    if s.is_empty() {
        s.push('x');
    }
    s
}

fn write(path: &Path, bytes: &[u8]) -> Result<(), NavError> {
    poinav_io::write_atomic(path, bytes).map_err(|source| NavError::Write {
        path: path.to_path_buf(),
        source,
    })
}

/// The file name of the drawing of storey `floor` for profile `p` (`paper-robot-00-ground-floor.svg`).
pub fn drawing_name(report: &AuditReport, p: usize, floor: usize) -> String {
    format!(
        "{}-{floor:02}-{}.svg",
        slug(&report.profiles[p].profile),
        slug(&report.floors[floor])
    )
}

/// Writes `audit.json`, one SVG per profile and storey (but the skipped ones, drawn over the
/// extent audited) and `report.html` into `dir` (created if missing). Returns the files
/// written.
pub fn write_report(
    report: &AuditReport,
    building: &Building,
    dir: &Path,
) -> Result<Vec<PathBuf>, NavError> {
    std::fs::create_dir_all(dir).map_err(|source| NavError::Write {
        path: dir.to_path_buf(),
        source,
    })?;
    let mut files = Vec::new();
    let json = serde_json::to_string_pretty(report).unwrap_or_default() + "\n";
    let p = dir.join("audit.json");
    write(&p, json.as_bytes())?;
    files.push(p);
    let mut drawings = Vec::new();
    for (pi, pa) in report.profiles.iter().enumerate() {
        for (fi, floor) in building.floors.iter().enumerate() {
            if crate::extent::nothing_to_navigate(floor).is_some() {
                continue;
            }
            let floor = crate::extent::cropped(floor, report.crop_margin_m);
            let text = svg::audit_svg(building, fi, &floor, pa);
            let p = dir.join(drawing_name(report, pi, fi));
            write(&p, text.as_bytes())?;
            files.push(p);
            drawings.push((pi, fi, text));
        }
    }
    let html = report_html(report, &drawings);
    let p = dir.join("report.html");
    write(&p, html.as_bytes())?;
    files.push(p);
    Ok(files)
}

fn report_html(report: &AuditReport, drawings: &[(usize, usize, String)]) -> String {
    let mut h = String::new();
    h.push_str(
        "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<title>poinav accessibility audit</title>\n<style>\n\
body{font-family:system-ui,sans-serif;margin:2em;color:#222}\n\
table{border-collapse:collapse;margin:0.5em 0 1.5em}\n\
td,th{border:1px solid #ccc;padding:0.25em 0.6em;text-align:left;font-size:0.9em}\n\
th{background:#f2f2f2}\n\
.FULL_ACCESS{background:#d7f0dc}.RESTRICTED{background:#fdecc0}.BLOCKED{background:#f8d0cc}.PENDING_VALIDATION{background:#e6e6e6}\n\
.no{background:#f8d0cc}.yes{background:#d7f0dc}.amber{background:#fdecc0}\n\
figure{margin:1em 0}svg{max-width:100%;height:auto;border:1px solid #ddd}\n\
</style>\n</head>\n<body>\n<h1>Accessibility audit</h1>\n",
    );
    let _ = writeln!(
        h,
        "<p>Storeys: {}. Profiles: {}.</p>",
        attr(&report.floors.join(", ")),
        attr(
            &report
                .profiles
                .iter()
                .map(|p| p.profile.as_str())
                .collect::<Vec<_>>()
                .join(", ")
        )
    );
    for k in &report.skipped {
        let _ = writeln!(
            h,
            "<p class=\"skipped\">Storey {} is skipped: {}.</p>",
            attr(&k.floor),
            attr(&k.reason)
        );
    }
    if !report.warnings.is_empty() {
        h.push_str("<ul class=\"warnings\">\n");
        for w in &report.warnings {
            let _ = writeln!(h, "<li>{}</li>", attr(w));
        }
        h.push_str("</ul>\n");
    }
    for (pi, p) in report.profiles.iter().enumerate() {
        let [full, restricted, blocked, pending] = p.door_counts();
        let (reach, unreach) = p.space_counts();
        let doorways = p.doors.iter().filter(|d| d.doorless).count();
        let _ = writeln!(h, "<section>\n<h2>Profile {}</h2>", attr(&p.profile));
        let _ = writeln!(
            h,
            "<p>Robot width {:.3} m, required clear width {:.3} m; grid inflated by {:.3} m (lethal) to {:.3} m (cost). Reachability from: {}.</p>",
            p.robot_width_m,
            p.required_width_m,
            p.lethal_radius_m,
            p.inflation_radius_m,
            if p.starts.is_empty() {
                "nothing (no entrance found)".to_string()
            } else {
                attr(&p.starts.join(", "))
            }
        );
        let _ = writeln!(
            h,
            "<p>Door passages: {} ({} doors, {doorways} doorways, openings without a door): {full} FULL_ACCESS, {restricted} RESTRICTED, {blocked} BLOCKED, {pending} PENDING_VALIDATION. Spaces: {reach} reachable, {unreach} unreachable. In the drawings, circles mark the landings of stairs, ramps and lifts, filled with the connection's status colour.</p>",
            p.doors.len(),
            p.doors.len() - doorways
        );
        for c in &p.transitions {
            if c.status == AccessibilityStatus::PendingValidation {
                let _ = writeln!(
                    h,
                    "<p class=\"PENDING_VALIDATION\">The {} {} is PENDING_VALIDATION: {}.</p>",
                    c.kind,
                    attr(c.name.as_deref().unwrap_or(&c.id)),
                    attr(&c.reason)
                );
            }
        }
        for (dp, fi, text) in drawings {
            if *dp == pi {
                let _ = writeln!(
                    h,
                    "<figure>\n{}\n<figcaption>{} for {}</figcaption>\n</figure>",
                    text.replacen("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n", "", 1),
                    attr(&report.floors[*fi]),
                    attr(&p.profile)
                );
            }
        }
        h.push_str("<h3>Doors</h3>\n<table>\n<tr><th>storey</th><th>door</th><th>clear width</th><th>required</th><th>status</th><th>reason</th><th>free path in grid</th><th>between</th></tr>\n");
        for d in &p.doors {
            let _ = writeln!(
                h,
                "<tr><td>{}</td><td>{}</td><td>{:.3} m</td><td>{:.3} m</td><td class=\"{}\">{}</td><td>{}</td><td class=\"{}\">{}</td><td>{}</td></tr>",
                attr(&d.floor_name),
                attr(d.name.as_deref().unwrap_or(&d.id)),
                d.clear_width_m,
                d.required_width_m,
                d.status.label(),
                d.status.label(),
                attr(&d.reason),
                if d.grid_passable { "yes" } else { "no" },
                if d.grid_passable { "yes" } else { "no" },
                attr(&d.zones.join(" | "))
            );
        }
        h.push_str("</table>\n");
        if !p.transitions.is_empty() {
            h.push_str("<h3>Stairs, ramps and lifts</h3>\n<table>\n<tr><th>name</th><th>kind</th><th>storeys</th><th>status</th><th>reason</th></tr>\n");
            for c in &p.transitions {
                let _ = writeln!(
                    h,
                    "<tr><td>{}</td><td>{}</td><td>{}</td><td class=\"{}\">{}</td><td>{}</td></tr>",
                    attr(c.name.as_deref().unwrap_or(&c.id)),
                    c.kind,
                    attr(&c.floors.join(", ")),
                    c.status.label(),
                    c.status.label(),
                    attr(&c.reason)
                );
            }
            h.push_str("</table>\n");
        }
        h.push_str("<h3>Spaces</h3>\n<table>\n<tr><th>storey</th><th>space</th><th>reachable</th><th>reason</th></tr>\n");
        for s in &p.spaces {
            let class = if !s.reachable {
                "no"
            } else if s.restricted_only {
                "amber"
            } else {
                "yes"
            };
            let _ = writeln!(
                h,
                "<tr><td>{}</td><td>{}</td><td class=\"{class}\">{}</td><td>{}</td></tr>",
                attr(&s.floor_name),
                attr(s.name.as_deref().unwrap_or(&s.id)),
                if s.reachable { "yes" } else { "no" },
                attr(&s.reason)
            );
        }
        h.push_str("</table>\n</section>\n");
    }
    h.push_str("</body>\n</html>\n");
    h
}
