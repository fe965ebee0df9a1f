//! `poinav route`, `poinav audit` and `poinav export nav2`: navigation on the building's
//! storeys (floor plans with POI roles) for robot profiles.

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use anyhow::Context;
use poinav_ifc::Model;
use poinav_nav::SpaceNames;
use poinav_nav::{
    AuditOptions, Building, FurnitureMode, GridOptions, Nav2Options, NavError, NavOptions,
    Navigator, Place, Route,
};
use poinav_poi::{classify, RobotProfile, RuleSet};

use crate::warnings::Warning;

/// How storeys are rasterised: shared by `route`, `audit` and `export nav2`.
#[derive(Debug, Clone, clap::Args)]
pub struct GridArgs {
    /// Cell size of the occupancy grids, metres.
    #[arg(long, value_name = "M", default_value_t = 0.05)]
    resolution: f64,
    /// Furniture and equipment (A-1 objects): obstacles planned around, or unknown cells left
    /// to the robot's sensors.
    #[arg(long, value_enum, default_value_t = Furniture::Obstacle)]
    furniture: Furniture,
    /// Doors and transitions PENDING_VALIDATION (no width known) count as closed instead of open.
    #[arg(long)]
    pending_closed: bool,
    /// Depth of the free apron outside each open entrance, metres (0: the outside stays unknown).
    #[arg(long, value_name = "M", default_value_t = 1.0)]
    entrance_apron: f64,
}

/// `--furniture` values.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
enum Furniture {
    /// Occupied cells, inflated like walls.
    Obstacle,
    /// Unknown cells (not entered, not inflated).
    Unknown,
}

impl GridArgs {
    /// The navigation options these arguments give (speeds and inflation by default).
    fn nav_options(&self) -> anyhow::Result<NavOptions> {
        if !(self.resolution.is_finite() && (0.005..=1.0).contains(&self.resolution)) {
            anyhow::bail!(
                "--resolution must be between 0.005 and 1 m, not {}",
                self.resolution
            );
        }
        if !(self.entrance_apron.is_finite() && (0.0..=10.0).contains(&self.entrance_apron)) {
            anyhow::bail!(
                "--entrance-apron must be between 0 and 10 m, not {}",
                self.entrance_apron
            );
        }
        Ok(NavOptions {
            grid: GridOptions {
                resolution_m: self.resolution,
                furniture: match self.furniture {
                    Furniture::Obstacle => FurnitureMode::Obstacle,
                    Furniture::Unknown => FurnitureMode::Unknown,
                },
                pending_doors_open: !self.pending_closed,
                entrance_apron_m: self.entrance_apron,
                ..GridOptions::default()
            },
            ..NavOptions::default()
        })
    }
}

/// Arguments of `poinav route`.
#[derive(Debug, clap::Args)]
pub struct RouteArgs {
    /// The IFC file (never modified).
    file: PathBuf,
    /// Start: a space's GlobalId, Name or LongName (`Room 1`; `Room 1@Level 2` on that storey;
    /// a name several spaces have is refused with the list of them), a point `x,y@Storey`
    /// (metres), or `outside` (`outside@Storey`): in front of the best open entrance.
    #[arg(long)]
    from: String,
    /// Goal, in the same forms.
    #[arg(long)]
    to: String,
    /// Robot profile (default: the paper's robot).
    #[arg(long)]
    profile: Option<PathBuf>,
    /// Print the route as JSON.
    #[arg(long)]
    json: bool,
    #[command(flatten)]
    grid: GridArgs,
}

/// Arguments of `poinav audit`.
#[derive(Debug, clap::Args)]
pub struct AuditArgs {
    /// The IFC file (never modified).
    file: PathBuf,
    /// Robot profiles to audit (repeat; default: the paper's robot).
    #[arg(long = "profile")]
    profiles: Vec<PathBuf>,
    /// Where to write the HTML report; audit.json and one SVG per profile and storey go beside it.
    #[arg(short, long)]
    output: PathBuf,
    /// Measure reachability from this space (GlobalId, Name or LongName, `@Storey` optional)
    /// instead of from the entrances (exterior doors); `outside` is the entrances.
    #[arg(long)]
    start: Option<String>,
    /// Exit with code 1 unless these spaces (named as for --start) are reachable for every
    /// profile; an unknown or ambiguous name exits 2.
    #[arg(long, num_args = 1..)]
    require_reachable: Vec<String>,
    /// Print the audit as JSON.
    #[arg(long)]
    json: bool,
    /// Also write BCF issues (a `.bcf` zip) to this file: one topic per door, stair, ramp or
    /// lift BLOCKED or RESTRICTED for a profile and per unreachable space, each with the
    /// element selected, a camera on it and a plan snapshot. Dated SOURCE_DATE_EPOCH when set,
    /// else the IFC file's modification time, so the same model gives the same bytes.
    #[arg(long, value_name = "FILE")]
    bcf: Option<PathBuf>,
    /// BCF version of --bcf.
    #[arg(long, value_enum, default_value_t = BcfVersionArg::V3_0, requires = "bcf")]
    bcf_version: BcfVersionArg,
    #[command(flatten)]
    grid: GridArgs,
}

/// `--bcf-version` values.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
enum BcfVersionArg {
    /// BCF 3.0.
    #[value(name = "3.0")]
    V3_0,
    /// BCF 2.1.
    #[value(name = "2.1")]
    V2_1,
}

impl From<BcfVersionArg> for poinav_bcf::BcfVersion {
    fn from(v: BcfVersionArg) -> Self {
        match v {
            BcfVersionArg::V3_0 => poinav_bcf::BcfVersion::V3_0,
            BcfVersionArg::V2_1 => poinav_bcf::BcfVersion::V2_1,
        }
    }
}

/// Arguments of `poinav export nav2`.
#[derive(Debug, clap::Args)]
pub struct Nav2Args {
    /// The IFC file (never modified).
    file: PathBuf,
    /// Output folder (one sub-folder per storey, a README on loading it).
    #[arg(short, long)]
    output: PathBuf,
    /// Robot profile (default: the paper's robot).
    #[arg(long)]
    profile: Option<PathBuf>,
    /// Print what was written as JSON (storeys, map sizes, mask and graph counts, files).
    #[arg(long)]
    json: bool,
    #[command(flatten)]
    grid: GridArgs,
}

/// The building's storeys as floors, classified for `profile`, and warnings: the stairs,
/// ramps and lifts left out (with why), the elements meshed without an opening or boolean
/// operand ([`crate::warnings::uncut`]) and what else limits navigation
/// ([`Building::diagnostics`]).
pub fn building(file: &Path, profile: &RobotProfile) -> anyhow::Result<(Building, Vec<Warning>)> {
    let (building, warnings, _) = load(file, profile)?;
    Ok((building, warnings))
}

/// [`building`] with its warnings printed; refuses a model that gave no geometry at all
/// unless `--allow-empty` ([`crate::ensure_geometry`]).
fn checked_building(
    file: &Path,
    profile: &RobotProfile,
) -> anyhow::Result<(Building, Vec<Warning>)> {
    let (building, warnings, (meshed, failed)) = load(file, profile)?;
    crate::warnings::print(&warnings);
    crate::ensure_geometry(file, meshed, failed)?;
    Ok((building, warnings))
}

/// [`building`], and how many products were meshed and how many failed.
fn load(
    file: &Path,
    profile: &RobotProfile,
) -> anyhow::Result<(Building, Vec<Warning>, (usize, usize))> {
    use crate::progress::{stage, tick};
    stage("reading");
    let model = Model::open(file)?;
    stage("classifying");
    let c = classify(&model, &RuleSet::defaults(), profile);
    stage("meshing");
    let meshes =
        poinav_geom::mesh_model_with_progress(&model, poinav_geom::PRODUCT_TIME_LIMIT, &tick);
    stage("sectioning");
    let plans = poinav_geom::floor_plans_with_progress(
        &model,
        &meshes,
        &poinav_geom::PlanOptions::default(),
        &tick,
    );
    let stages = poinav_bridge::Stages { meshes, plans };
    let made = poinav_bridge::building(&model, &c, &stages);
    crate::progress::end();
    let building = made.building;
    let meshes = stages.meshes;
    let warnings = crate::warnings::of_building(&model, &made.dropped, &meshes.uncut, &building);
    let meshed = meshes.elements.len() + meshes.spaces.len();
    Ok((building, warnings, (meshed, meshes.failures.len())))
}

/// Progress of rasterising, the graph and writing, as stages of the CLI's progress.
fn nav_progress(phase: poinav_nav::Phase, done: usize, total: usize) {
    crate::progress::phase(phase.label(), done, total);
}

/// Runs `poinav route`.
pub fn route(args: &RouteArgs) -> anyhow::Result<ExitCode> {
    let options = args.grid.nav_options()?;
    let profile = crate::profile(args.profile.as_deref())?;
    let (building, mut warnings) = checked_building(&args.file, &profile)?;
    let nav = Navigator::with_progress(&building, &profile, &options, &nav_progress)?;
    let gave_up = crate::warnings::gave_up(&nav.gave_up);
    crate::warnings::print(&gave_up);
    warnings.extend(gave_up);
    crate::progress::stage("routing");
    let from: Place = args.from.parse()?;
    let to: Place = args.to.parse()?;
    let route = nav.route(&from, &to);
    crate::progress::end();
    match route {
        Ok(r) => {
            if args.json {
                let mut json = serde_json::to_value(&r)?;
                json["warnings"] = crate::warnings::to_json(&warnings);
                outln!("{}", serde_json::to_string_pretty(&json)?);
            } else {
                for line in route_text(&r) {
                    outln!("{line}");
                }
            }
            Ok(ExitCode::SUCCESS)
        }
        // The answer is no (exit 1); a place that does not exist or is ambiguous is bad input (2).
        Err(e @ (NavError::Unreachable(_) | NavError::NoRoom(_))) => {
            errln!("error: {e}");
            Ok(ExitCode::from(1))
        }
        Err(e) => Err(e.into()),
    }
}

/// The route as text: length and time (the same as the JSON's), then per storey its length
/// and time and every door and doorway passed, and between storeys the stair, ramp or lift
/// taken with its time.
pub fn route_text(r: &Route) -> Vec<String> {
    let mut out = vec![format!(
        "{} -> {} for {}: {:.2} m, {:.1} s",
        r.from, r.to, r.profile, r.length_m, r.time_s
    )];
    for (k, leg) in r.legs.iter().enumerate() {
        out.push(format!(
            "  on {}: {:.2} m, {:.1} s",
            leg.floor_name,
            leg.length_m,
            leg.travel_time_s + leg.turn_time_s
        ));
        for d in &leg.doors {
            out.push(format!(
                "    through {} {} ({}, {:.2} m)",
                if d.doorless { "doorway" } else { "door" },
                d.name.as_deref().unwrap_or(&d.id),
                d.status.label(),
                d.clear_width_m
            ));
        }
        if let Some(c) = r.connections.get(k) {
            out.push(format!(
                "  {} {} from {} to {}: {:.1} s ({})",
                c.kind,
                c.name.as_deref().unwrap_or(&c.id),
                c.from_floor,
                c.to_floor,
                c.time_s,
                c.status.label()
            ));
        }
    }
    out
}

/// Runs `poinav audit`.
pub fn audit(args: &AuditArgs) -> anyhow::Result<ExitCode> {
    let nav = args.grid.nav_options()?;
    let profiles: Vec<RobotProfile> = if args.profiles.is_empty() {
        vec![RobotProfile::paper()]
    } else {
        args.profiles
            .iter()
            .map(|p| RobotProfile::load(p))
            .collect::<Result<_, _>>()?
    };
    // Statuses come from each profile's own width rule; the floors carry the first profile's roles.
    let (building, warnings) = checked_building(&args.file, &profiles[0])?;
    if let Some(dir) = args.output.parent().filter(|d| d.is_file()) {
        anyhow::bail!(
            "cannot write {}: {} is a file, not a folder",
            args.output.display(),
            dir.display()
        );
    }
    // Unknown or ambiguous spaces are bad input: refused before anything is written.
    for want in &args.require_reachable {
        building.select_space(want)?;
    }
    crate::progress::stage("auditing");
    let grid_options = nav.grid.clone();
    let mut report = poinav_nav::audit::audit_with_progress(
        &building,
        &profiles,
        &AuditOptions {
            nav,
            start: args.start.clone(),
        },
        &nav_progress,
    )?;
    // Its warnings name them too; the summary here groups them.
    crate::warnings::print(&crate::warnings::gave_up(&report.gave_up));
    // The report lists the left-out connections too (diagnostics are in it already).
    let dropped: Vec<String> = warnings
        .iter()
        .map(Warning::line)
        .filter(|w| !report.warnings.contains(w))
        .collect();
    report.warnings.splice(0..0, dropped);
    let dir = args
        .output
        .parent()
        .filter(|p| !p.as_os_str().is_empty())
        .unwrap_or(Path::new("."));
    crate::progress::stage("writing");
    let files = poinav_nav::audit::write_report(&report, &building, dir)?;
    let written = dir.join("report.html");
    if written != args.output {
        std::fs::rename(&written, &args.output)
            .with_context(|| format!("writing {}", args.output.display()))?;
    }
    let bcf = match &args.bcf {
        Some(path) => Some((
            path,
            write_bcf(args, path, &report, &building, &profiles, grid_options)?,
        )),
        None => None,
    };
    crate::progress::end();
    if args.json {
        let mut json = report.to_json();
        if let Some((path, topics)) = &bcf {
            json["bcf"] = bcf_json(path, args.bcf_version, topics);
        }
        outln!("{}", serde_json::to_string_pretty(&json)?);
    } else {
        for p in &report.profiles {
            let [full, restricted, blocked, pending] = p.door_counts();
            let (reachable, unreachable) = p.space_counts();
            let doorways = p.doors.iter().filter(|d| d.doorless).count();
            outln!(
                "{}: {} door passages ({} doors, {doorways} doorways): {full} full, {restricted} restricted, {blocked} blocked, {pending} pending; spaces {reachable} reachable, {unreachable} not",
                p.profile,
                p.doors.len(),
                p.doors.len() - doorways,
            );
            for d in &p.doors {
                if d.entrance == Some(poinav_nav::Entrance::Terrain) {
                    outln!(
                        "  entrance from the terrain: {} door {} (storey not at ground level)",
                        d.floor_name,
                        d.name.as_deref().unwrap_or(&d.id)
                    );
                }
            }
            for t in &p.transitions {
                if t.status == poinav_poi::AccessibilityStatus::PendingValidation {
                    outln!(
                        "  {} {} is PENDING_VALIDATION: {}",
                        t.kind,
                        t.name.as_deref().unwrap_or(&t.id),
                        t.reason
                    );
                }
            }
        }
        for k in &report.skipped {
            outln!("  {}", k.line());
        }
        outln!(
            "wrote {} and {} more files in {}",
            args.output.display(),
            files.len().saturating_sub(1),
            dir.display()
        );
        if let Some((path, topics)) = &bcf {
            outln!("wrote {} BCF topics to {}", topics.len(), path.display());
        }
    }
    let failures = report.unreachable_required(&building, &args.require_reachable)?;
    for f in &failures {
        errln!("error: {f}");
    }
    Ok(if failures.is_empty() {
        ExitCode::SUCCESS
    } else {
        ExitCode::from(1)
    })
}

/// Writes `--bcf`: the audit's failures as BCF topics.
fn write_bcf(
    args: &AuditArgs,
    path: &Path,
    report: &poinav_nav::AuditReport,
    building: &Building,
    profiles: &[RobotProfile],
    grid: GridOptions,
) -> anyhow::Result<Vec<poinav_bcf::Issue>> {
    crate::progress::stage("writing BCF");
    // Reproducible: SOURCE_DATE_EPOCH, else the model's modification time.
    let created_s = std::env::var("SOURCE_DATE_EPOCH")
        .ok()
        .and_then(|v| v.trim().parse::<i64>().ok())
        .or_else(|| {
            let modified = std::fs::metadata(&args.file).ok()?.modified().ok()?;
            let secs = modified.duration_since(std::time::UNIX_EPOCH).ok()?;
            i64::try_from(secs.as_secs()).ok()
        })
        .unwrap_or(0);
    let options = poinav_bcf::BcfOptions {
        version: args.bcf_version.into(),
        grid,
        model: args
            .file
            .file_name()
            .map(|n| n.to_string_lossy().into_owned()),
        created_s,
    };
    Ok(poinav_bcf::write_bcf(
        path, report, building, profiles, &options,
    )?)
}

/// What `--bcf` wrote, for `--json`.
fn bcf_json(
    path: &Path,
    version: BcfVersionArg,
    topics: &[poinav_bcf::Issue],
) -> serde_json::Value {
    serde_json::json!({
        "file": path.display().to_string(),
        "version": poinav_bcf::BcfVersion::from(version).label(),
        "topics": topics.iter().map(|t| serde_json::json!({
            "guid": t.guid,
            "profile": t.profile_name,
            "kind": t.kind.label(),
            "element": t.element,
            "status": t.status,
            "title": t.title,
        })).collect::<Vec<_>>(),
    })
}

/// Runs `poinav export nav2`.
pub fn nav2(args: &Nav2Args) -> anyhow::Result<ExitCode> {
    let nav = args.grid.nav_options()?;
    let profile = crate::profile(args.profile.as_deref())?;
    let (building, mut warnings) = checked_building(&args.file, &profile)?;
    let options = Nav2Options {
        nav,
        ..Nav2Options::default()
    };
    let summary = poinav_nav::write_bundle_with_progress(
        &building,
        &profile,
        &options,
        &args.output,
        &nav_progress,
    )?;
    crate::progress::end();
    let gave_up = crate::warnings::gave_up(&summary.gave_up);
    crate::warnings::print(&gave_up);
    warnings.extend(gave_up);
    if args.json {
        let mut json = serde_json::to_value(&summary)?;
        json["warnings"] = crate::warnings::to_json(&warnings);
        outln!("{}", serde_json::to_string_pretty(&json)?);
        return Ok(ExitCode::SUCCESS);
    }
    outln!(
        "wrote a Nav2 bundle for {} to {}: {} storey{}, {} files",
        profile.name,
        args.output.display(),
        summary.storeys.len(),
        if summary.storeys.len() == 1 { "" } else { "s" },
        summary.files.len()
    );
    for s in &summary.storeys {
        outln!(
            "  {}/ ({}): map {} x {} cells, origin ({:.2}, {:.2}); keepout {} cells, speed limit {} cells; route graph {} nodes, {} edges",
            s.folder,
            s.floor,
            s.width,
            s.height,
            s.origin[0],
            s.origin[1],
            s.keepout_cells,
            s.speed_cells,
            s.graph_nodes,
            s.graph_edges
        );
    }
    for k in &summary.skipped {
        outln!("  {}", k.line());
    }
    Ok(ExitCode::SUCCESS)
}
