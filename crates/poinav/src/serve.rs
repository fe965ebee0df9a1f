//! `poinav serve [FILE.ifc] [--scenario S]`: prepares the building (GLB, click-to-inspect data,
//! every storey as a floor with its robots) and runs the browser viewer (`poinav-viewer`) until
//! interrupted.

use std::collections::BTreeMap;
use std::io::Write;
use std::net::{IpAddr, Ipv4Addr, SocketAddr};
use std::path::PathBuf;
use std::process::ExitCode;

use anyhow::Context;
use poinav_export::glb::GlbOptions;
use poinav_export::glb_chunks::to_glb_per_storey;
use poinav_export::scene::NO_STOREY;
use poinav_geom::{mesh_model, ModelMeshes};
use poinav_ifc::property::{property_sets, PropertyValue, Scalar, TypedScalar};
use poinav_ifc::{spatial, units, Model};
use poinav_poi::{classify, Classification};
use poinav_sim::{RobotSetup, Scenario, SimOptions};
use poinav_viewer::{ElementInfo, ModelChunk, ServerConfig, ViewStorey, Viewer};

/// Arguments of `poinav serve`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// The IFC file to show and drive in (never modified); optional with `--scenario`, whose
    /// building is then used.
    #[arg(required_unless_present = "scenario")]
    file: Option<PathBuf>,
    /// Robots (start poses, profiles, controllers) from this scenario file; without it two
    /// key-driven robots start in the largest space.
    #[arg(long)]
    scenario: Option<PathBuf>,
    /// The storey the robots drive on first (Name or GlobalId; default: the lowest with doors);
    /// the page can switch to any other storey with room for the robots.
    #[arg(long)]
    storey: Option<String>,
    /// Robot profile (default: the paper's robot).
    #[arg(long)]
    profile: Option<PathBuf>,
    /// Rule file extending the default POI rules.
    #[arg(long)]
    rules: Option<PathBuf>,
    /// Address to listen on. The default is loopback (this machine only); any other address
    /// makes the viewer reachable from the network.
    #[arg(long, default_value_t = IpAddr::V4(Ipv4Addr::LOCALHOST))]
    addr: IpAddr,
    /// Port (0 picks a free one).
    #[arg(long, default_value_t = 8080)]
    port: u16,
    /// Pages connected at once.
    #[arg(long, default_value_t = 8)]
    max_clients: usize,
    /// Record the session as a ROS 2 recording (MCAP), written here when the server stops
    /// (the storey shown first, until a page switches storey or starts again).
    #[arg(long, value_name = "FILE")]
    record: Option<PathBuf>,
}

fn text(s: &TypedScalar) -> String {
    match &s.value {
        Scalar::Text(t) => t.clone(),
        Scalar::Real(r) => format!("{r}"),
        Scalar::Integer(i) => i.to_string(),
        Scalar::Bool(b) => b.to_string(),
        Scalar::Logical(l) => l.map_or("UNKNOWN".into(), |b| b.to_string()),
        Scalar::Enum(e) => e.clone(),
        Scalar::Ref(id) => id.to_string(),
    }
}

fn value_text(v: &PropertyValue) -> String {
    let join = |l: &[TypedScalar]| l.iter().map(text).collect::<Vec<_>>().join("; ");
    match v {
        PropertyValue::Single(s) => s.as_ref().map(text).unwrap_or_default(),
        PropertyValue::Enumerated(l) | PropertyValue::List(l) => join(l),
        PropertyValue::Bounded(lo, hi) => format!(
            "{} .. {}",
            lo.as_ref().map(text).unwrap_or_default(),
            hi.as_ref().map(text).unwrap_or_default()
        ),
        PropertyValue::Complex(p) => p
            .iter()
            .map(|p| format!("{}: {}", p.name, value_text(&p.value)))
            .collect::<Vec<_>>()
            .join("; "),
        PropertyValue::Other(id) => id.to_string(),
    }
}

/// What the viewer shows of a model: one GLB per storey, the click-to-inspect data, every storey
/// as a floor (lowest first) and the index of the storey the robots drive on first.
struct Shown {
    model: Vec<ModelChunk>,
    elements: BTreeMap<String, ElementInfo>,
    floors: Vec<poinav_nav::Floor>,
    current: usize,
}

/// What the viewer shows of `model`: its GLB and click-to-inspect data from `meshes`, and the
/// floors of `building` (the bridge's, [`poinav_bridge::building`]) with `current` first.
fn shown(
    model: &Model,
    classification: &Classification,
    mut meshes: ModelMeshes,
    building: poinav_nav::Building,
    storeys: &[poinav_bridge::StoreyKey],
    current: usize,
) -> Shown {
    let unit = units::length_unit(model);
    let structure = spatial::spatial_structure(model, &unit);
    let storey_name = |id| {
        structure
            .storeys
            .iter()
            .find(|s| Some(s.id) == id)
            .and_then(|s| s.name.clone())
    };
    let mut elements = BTreeMap::new();
    for e in meshes.elements.iter().chain(&meshes.spaces) {
        if e.global_id.is_empty() {
            continue;
        }
        let mut info = ElementInfo {
            global_id: e.global_id.clone(),
            class: e.class.clone(),
            name: e.name.clone(),
            storey: storey_name(e.storey),
            ..ElementInfo::default()
        };
        if let Some(c) = classification.get(e.product) {
            let roles =
                |r: &[poinav_poi::Role]| r.iter().map(|r| r.label()).collect::<Vec<_>>().join(";");
            info.poi
                .insert("POI_Category".into(), c.category.label().into());
            info.poi
                .insert("POI_Type".into(), c.poi_type.label().into());
            info.poi
                .insert("POI_PrimaryRoles".into(), roles(&c.primary));
            info.poi
                .insert("POI_ConditionalRoles".into(), roles(&c.conditional));
            if let Some(a) = &c.accessibility {
                info.poi
                    .insert("AccessibilityStatus".into(), a.status.label().into());
            }
        }
        if let Some(entity) = model.entity(e.product) {
            for set in property_sets(entity) {
                let props = set
                    .properties
                    .iter()
                    .map(|p| (p.name.clone(), value_text(&p.value)))
                    .collect();
                info.property_sets.insert(set.name.clone(), props);
            }
        }
        elements.insert(e.global_id.clone(), info);
    }
    // One GLB per storey, so the page draws the simulated storey before the rest arrives.
    let model = to_glb_per_storey(
        &structure.storeys,
        &mut meshes.elements,
        Some(classification),
        GlbOptions::COMPACT,
    )
    .into_iter()
    .map(|c| {
        let storey = c.storey.map(|g| &structure.storeys[g]);
        ModelChunk {
            storey: storey.and_then(|s| floor_of(storeys, s)),
            name: storey.map_or(NO_STOREY.to_string(), |s| s.label()),
            elevation_m: storey
                .and_then(|s| s.elevation_m)
                .filter(|e| e.is_finite())
                .unwrap_or(0.0),
            elements: c.elements,
            glb: c.glb,
        }
    })
    .collect();
    Shown {
        model,
        elements,
        floors: building.floors,
        current,
    }
}

/// The floor of `storey` among the bridge's `storeys`: by GlobalId, else by name.
fn floor_of(storeys: &[poinav_bridge::StoreyKey], storey: &spatial::Storey) -> Option<usize> {
    storeys
        .iter()
        .position(|k| k.global_id.is_some() && k.global_id == storey.global_id)
        .or_else(|| {
            storeys
                .iter()
                .position(|k| k.name.is_some() && k.name == storey.name)
        })
}

fn scenario_robots(s: &Scenario) -> (Vec<RobotSetup>, SimOptions) {
    (
        s.robots.iter().map(|r| r.setup.clone()).collect(),
        SimOptions {
            dt: s.dt,
            start: s.start,
            behaviour: s.behaviour.clone(),
            ..SimOptions::default()
        },
    )
}

/// Runs `poinav serve`.
pub fn run(args: &Args) -> anyhow::Result<ExitCode> {
    let profile = crate::profile(args.profile.as_deref())?;
    let rules = crate::rules(args.rules.as_deref())?;
    let scenario = args.scenario.as_deref().map(Scenario::load).transpose()?;
    let storey = args
        .storey
        .as_deref()
        .or(scenario.as_ref().and_then(|s| s.building.storey.as_deref()));
    let (model, classification, made, title) = match (&args.file, &scenario) {
        (Some(file), _) => {
            let model = Model::open(file)?;
            let c = classify(&model, &rules, &profile);
            let stages = poinav_bridge::Stages::of(&model);
            let made = poinav_bridge::building(&model, &c, &stages);
            let current = poinav_bridge::pick(&made.storeys, storey)?;
            let title = file.display().to_string();
            (
                model,
                c,
                (made.building, made.storeys, current, Some(stages.meshes)),
                title,
            )
        }
        (None, Some(s)) => {
            // The floors `poinav simulate` runs the scenario on, not another recipe's.
            let (p, meshes) = poinav_bridge::prepare_with_meshes(s, None)?;
            let current = match args.storey.as_deref() {
                Some(name) => poinav_bridge::pick(&p.storeys, Some(name))?,
                None => p.current,
            };
            let title = format!("{} (scenario building)", s.name);
            (
                p.model,
                p.classification,
                (p.building, p.storeys, current, meshes),
                title,
            )
        }
        (None, None) => anyhow::bail!("give an IFC file or --scenario"),
    };
    let (building, storey_keys, current, meshes) = made;
    let meshes = meshes.unwrap_or_else(|| mesh_model(&model));
    crate::warnings::print(&crate::warnings::uncut(&model, &meshes));
    let Shown {
        model,
        elements,
        floors,
        current,
    } = shown(
        &model,
        &classification,
        meshes,
        building,
        &storey_keys,
        current,
    );
    let (scenario_setups, options, source) = match &scenario {
        Some(s) => {
            let (r, o) = scenario_robots(s);
            (
                Some(r),
                o,
                format!("robots of scenario `{}` ({})", s.name, s.file),
            )
        }
        None => (
            None,
            SimOptions::default(),
            "two robots in the largest space".to_string(),
        ),
    };
    // The POI database (and the doors' colours) hold the enrichment's statuses: for the
    // profile the floors were classified for.
    let options = SimOptions {
        poi_profile: classification.profile.clone(),
        ..options
    };
    // The scenario's robots drive on its storey; every other storey (and every storey without
    // a scenario) gets two key-driven robots where there is room for them.
    let mut scenario_setups = scenario_setups;
    let storeys: Vec<ViewStorey> = floors
        .into_iter()
        .enumerate()
        .map(
            |(i, floor)| match scenario_setups.take_if(|_| i == current) {
                Some(robots) => ViewStorey::new(floor, robots),
                None => match poinav_viewer::default_robots(&floor, &profile) {
                    Ok(robots) => ViewStorey::new(floor, robots),
                    Err(e) => {
                        let reason = e.to_string();
                        ViewStorey::unplaced(floor, reason)
                    }
                },
            },
        )
        .collect();
    if let Some(reason) = &storeys[current].unplaced {
        anyhow::bail!("{reason}");
    }
    let recording = match &args.record {
        Some(target) => Some((
            std::sync::Arc::new(std::sync::Mutex::new(crate::record::LiveTrace::new(
                target, options.dt,
            )?)),
            storeys[current].floor.clone(),
            options.dt,
        )),
        None => None,
    };
    let viewer = Viewer {
        title,
        model,
        elements,
        storeys,
        current,
        options,
        source,
    };
    let config = ServerConfig {
        addr: SocketAddr::new(args.addr, args.port),
        max_clients: args.max_clients.max(1),
        ..ServerConfig::default()
    };
    let runtime = tokio::runtime::Builder::new_multi_thread()
        .worker_threads(2)
        .enable_all()
        .build()
        .context("starting the server runtime")?;
    runtime.block_on(async {
        let bound = poinav_viewer::bind(config, viewer).await?;
        let addr = bound.local_addr();
        // The server keeps running when nobody reads its output any more (`| head -1`, a
        // closed terminal): write errors are ignored rather than panicking in println!.
        let mut out = std::io::stdout();
        let _ = writeln!(out, "poinav viewer: http://{addr}/");
        let _ = writeln!(
            out,
            "  Robot1: arrow keys, Robot2: W A S D, C: camera; Ctrl+C stops the server"
        );
        let _ = out.flush();
        if !addr.ip().is_loopback() {
            let _ = writeln!(
                std::io::stderr(),
                "warning: listening on {}, reachable from the network; WebXR on another device needs HTTPS",
                addr.ip()
            );
        }
        let recorder = recording.as_ref().map(|(trace, _, _)| {
            tokio::spawn(crate::record::record_states(
                bound.subscribe(),
                trace.clone(),
            ))
        });
        let served = bound
            .run_until(async {
                let _ = tokio::signal::ctrl_c().await;
            })
            .await;
        if let Some(task) = recorder {
            task.abort();
            let _ = task.await;
        }
        served
    })?;
    if let (Some(target), Some((trace, floor, dt))) = (&args.record, recording) {
        let trace = std::sync::Arc::into_inner(trace)
            .context("--record: the recorder is still running")?
            .into_inner()
            .unwrap_or_else(|e| e.into_inner());
        let summary = trace.finish(target, &floor, &profile, dt)?;
        outln!(
            "wrote ROS 2 recording to {} ({} steps, {} messages)",
            target.display(),
            summary.steps,
            summary.total()
        );
    }
    Ok(ExitCode::SUCCESS)
}
