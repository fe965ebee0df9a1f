//! `poinav plan FILE --storey NAME -o plan.svg`: a readable floor plan of one storey;
//! `poinav plan FILE --all-storeys -o DIR`: every storey's, the model read and meshed once.

use std::collections::HashMap;
use std::path::PathBuf;
use std::process::ExitCode;

use anyhow::Context;
use poinav_export::plan_svg::{to_svg, SvgOptions};
use poinav_geom::{
    floor_plans_with_progress, mesh_model_with_progress, PlanOptions, PRODUCT_TIME_LIMIT,
};
use poinav_ifc::Model;
use poinav_poi::{classify, RuleSet};

use crate::warnings::Warning;

/// Arguments of `poinav plan`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// The IFC file (never modified).
    file: PathBuf,
    /// The storey (Name or GlobalId); default: the lowest storey with doors.
    #[arg(long, conflicts_with = "all_storeys")]
    storey: Option<String>,
    /// Every storey's plan, into the folder `-o` names (`NN-<storey>.svg`, NN its position
    /// in elevation order as in `export nav2`), from one reading and meshing of the model.
    #[arg(long)]
    all_storeys: bool,
    /// Where to write the SVG (with `--all-storeys`: the folder, created if missing).
    #[arg(short, long)]
    output: PathBuf,
    /// Robot profile whose door statuses colour the doors (default: the paper's robot).
    #[arg(long)]
    profile: Option<PathBuf>,
    /// Lowest height of the plan's band above the storey, metres.
    #[arg(long, default_value_t = 0.05)]
    band_min: f64,
    /// Highest height of the band, metres (the robot's height is a good choice).
    #[arg(long, default_value_t = 1.0)]
    band_max: f64,
}

/// Runs `poinav plan`.
pub fn run(args: &Args) -> anyhow::Result<ExitCode> {
    crate::progress::stage("reading");
    let model = Model::open(&args.file)?;
    crate::progress::stage("meshing");
    let meshes = mesh_model_with_progress(&model, PRODUCT_TIME_LIMIT, &crate::progress::tick);
    crate::progress::stage("sectioning");
    let plans = floor_plans_with_progress(
        &model,
        &meshes,
        &PlanOptions {
            band_min_m: args.band_min,
            band_max_m: args.band_max,
            ..PlanOptions::default()
        },
        &crate::progress::tick,
    );
    crate::progress::end();
    let failed = meshes.failures.len();
    let meshed = meshes.elements.len() + meshes.spaces.len();
    let uncut = crate::warnings::uncut(&model, &meshes);
    // The meshes are not needed any more: the plans hold what is drawn.
    drop(meshes);
    let chosen: Vec<usize> = if args.all_storeys {
        (0..plans.len()).collect()
    } else {
        let storeys: Vec<poinav_bridge::StoreyKey> =
            plans.iter().map(poinav_bridge::StoreyKey::of).collect();
        vec![poinav_bridge::pick(&storeys, args.storey.as_deref())?]
    };
    let mut warnings: Vec<Warning> = chosen
        .iter()
        .flat_map(|&k| plans[k].problems.iter())
        .map(|p| {
            let fallback = if p.fell_back {
                " (drawn from its footprint)"
            } else {
                " (left out)"
            };
            Warning::of(
                p.product,
                Some(p.class.clone()),
                format!("{}{fallback}", p.error),
            )
        })
        .collect();
    warnings.extend(uncut);
    crate::warnings::print(&warnings);
    crate::ensure_geometry(&args.file, meshed, failed)?;
    crate::progress::stage("classifying");
    let profile = crate::profile(args.profile.as_deref())?;
    let c = classify(&model, &RuleSet::defaults(), &profile);
    let door_status: HashMap<String, String> = c
        .elements
        .iter()
        .filter(|e| e.class == "IfcDoor")
        .filter_map(|e| {
            e.accessibility
                .as_ref()
                .map(|a| (e.global_id.clone(), a.status.label().to_string()))
        })
        .collect();
    let options = SvgOptions {
        door_status,
        ..SvgOptions::default()
    };
    if args.all_storeys {
        std::fs::create_dir_all(&args.output)
            .with_context(|| format!("creating {}", args.output.display()))?;
    }
    crate::progress::stage("writing");
    let mut written = Vec::new();
    for &k in &chosen {
        let plan = &plans[k];
        let path = if args.all_storeys {
            let name = plan.storey_name.as_deref().unwrap_or("storey");
            args.output
                .join(format!("{k:02}-{}.svg", poinav_nav::audit::slug(name)))
        } else {
            args.output.clone()
        };
        let svg = to_svg(plan, &options);
        poinav_io::write_atomic(&path, svg.as_bytes())
            .with_context(|| format!("writing {}", path.display()))?;
        written.push((k, path));
    }
    crate::progress::end();
    for (k, path) in written {
        let plan = &plans[k];
        let doorways = match plan.openings.len() {
            0 => String::new(),
            1 => "; 1 doorway without a door".to_string(),
            n => format!("; {n} doorways without a door"),
        };
        outln!(
            "wrote {}: storey {} ({} items, {} doors, {} problems{doorways})",
            path.display(),
            plan.storey_name.as_deref().unwrap_or("-"),
            plan.items.len(),
            plan.doors.len(),
            plan.problems.len()
        );
    }
    Ok(ExitCode::SUCCESS)
}
