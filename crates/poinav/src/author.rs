//! `poinav demo-building` and `poinav patch door-width`: write the paper's test building and
//! change a door's width for the design-iteration loop.

use std::path::PathBuf;
use std::process::ExitCode;

use anyhow::Context;
use poinav_author::DemoBuilding;
use poinav_ifc::timestamp::{iso8601_utc, now_or_source_date_epoch};

/// Arguments of `poinav demo-building`.
#[derive(Debug, clap::Args)]
pub struct DemoBuildingArgs {
    /// Width of the door into Room 2, metres (the paper's first design: 0.80).
    #[arg(long, default_value_t = 0.80)]
    door_width: f64,
    /// Width of every other door, metres.
    #[arg(long, default_value_t = 1.0)]
    other_door_width: f64,
    /// Rooms on each side of the corridor.
    #[arg(long, default_value_t = 3)]
    rooms_per_side: usize,
    /// Where to write the IFC.
    #[arg(short, long)]
    output: PathBuf,
}

/// Design patches.
#[derive(Debug, clap::Subcommand)]
pub enum Patch {
    /// Set a door's OverallWidth and resize its opening and leaf geometry to match.
    DoorWidth(DoorWidthArgs),
}

/// Arguments of `poinav patch door-width`.
#[derive(Debug, clap::Args)]
pub struct DoorWidthArgs {
    /// The IFC file to change (never modified).
    input: PathBuf,
    /// Where to write the changed copy.
    #[arg(short, long)]
    output: PathBuf,
    /// The door: its GlobalId, or its Name when that is unique.
    #[arg(long)]
    door: String,
    /// The new width in metres.
    #[arg(long)]
    width: f64,
}

fn timestamp() -> String {
    iso8601_utc(now_or_source_date_epoch())
}

/// Runs `poinav demo-building`.
pub fn demo_building(args: &DemoBuildingArgs) -> anyhow::Result<ExitCode> {
    let spec = DemoBuilding {
        room2_door_width_m: args.door_width,
        door_width_m: args.other_door_width,
        rooms_per_side: args.rooms_per_side,
        ..DemoBuilding::default()
    };
    let bytes = poinav_author::demo_building(&spec, &timestamp())?;
    poinav_io::write_atomic(&args.output, &bytes)
        .with_context(|| format!("writing {}", args.output.display()))?;
    let layout = spec.layout();
    outln!(
        "wrote {}: {} rooms and a corridor, {:.2} x {:.2} m inside; Room 2 door {:.2} m, other doors {:.2} m",
        args.output.display(),
        layout.rooms.len(),
        spec.length_m(),
        spec.depth_m(),
        spec.room2_door_width_m,
        spec.door_width_m
    );
    Ok(ExitCode::SUCCESS)
}

/// Runs `poinav patch door-width`.
pub fn door_width(args: &DoorWidthArgs) -> anyhow::Result<ExitCode> {
    let model = poinav_ifc::Model::open(&args.input)?;
    let (editor, patch) =
        poinav_author::patch_door_width(&model, &args.door, args.width, &timestamp())?;
    editor.write(&args.output)?;
    let old = patch
        .old_width_m
        .map_or("none".to_string(), |w| format!("{w:.3} m"));
    outln!(
        "door {} ({}): width {} -> {:.3} m; {} profile(s) resized; wrote {}",
        patch.global_id,
        patch.door,
        old,
        patch.new_width_m,
        patch.profiles.len(),
        args.output.display()
    );
    let warnings: Vec<crate::warnings::Warning> = patch
        .warnings
        .iter()
        .map(|w| crate::warnings::Warning::plain(w.to_string()))
        .collect();
    crate::warnings::print(&warnings);
    Ok(ExitCode::SUCCESS)
}
