//! `poinav demo`: the main job end to end on the paper's test building: write it, enrich it,
//! run the three validation scenarios, apply the design change (widen the Room 2 door,
//! re-enrich), export 3D, navigate both designs (routes, accessibility audit, Nav2 bundle) and
//! write an HTML report with the plots.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

use anyhow::Context;
use poinav_author::DemoBuilding;
use poinav_ifc::{spatial, units, Model};
use poinav_io::{write_atomic, xml::attr};
use poinav_poi::{
    classify, write_enrichment, AccessibilityStatus, RobotProfile, RuleSet, WriteOptions,
};
use poinav_sim::Scenario;

use crate::simulate::{report, run_scenario, VariantRun};

/// Arguments of `poinav demo`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// Output folder.
    #[arg(short, long, default_value = "out/demo")]
    output: PathBuf,
}

/// The scenario files shipped with poinav-sim, built into the binary.
const SCENARIOS: [(&str, &str); 3] = [
    (
        "doorway",
        include_str!("../../poinav-sim/scenarios/doorway.toml"),
    ),
    (
        "separation",
        include_str!("../../poinav-sim/scenarios/separation.toml"),
    ),
    (
        "wall-following",
        include_str!("../../poinav-sim/scenarios/wall-following.toml"),
    ),
];

struct Step {
    title: String,
    detail: String,
}

fn enrich_file(
    input: &Path,
    output: &Path,
    opts: &WriteOptions,
) -> anyhow::Result<(usize, String)> {
    let model = Model::open(input)?;
    let c = classify(&model, &RuleSet::defaults(), &RobotProfile::paper());
    write_enrichment(&model, &c, opts)?.write(output)?;
    let door2 = c
        .elements
        .iter()
        .find(|e| e.name.as_deref() == Some("Door Room 2"));
    let status = door2
        .map(|d| {
            let s = d
                .accessibility
                .as_ref()
                .map_or(AccessibilityStatus::PendingValidation, |a| a.status);
            let roles: Vec<&str> = d
                .primary
                .iter()
                .chain(&d.conditional)
                .map(|r| r.label())
                .collect();
            format!("Door Room 2: {} ({})", s.label(), roles.join(" + "))
        })
        .unwrap_or_default();
    Ok((c.elements.len(), status))
}

/// Runs `poinav demo`.
pub fn run(args: &Args) -> anyhow::Result<ExitCode> {
    let out = &args.output;
    std::fs::create_dir_all(out).with_context(|| format!("creating {}", out.display()))?;
    let stamp =
        poinav_ifc::timestamp::iso8601_utc(poinav_ifc::timestamp::now_or_source_date_epoch());
    let opts = WriteOptions {
        prefix: "Pset_".into(),
        timestamp: stamp.clone(),
    };
    let mut steps = Vec::new();

    // 1. The test building, first design (0.80 m door into Room 2).
    let spec = DemoBuilding::default();
    let building = out.join("test-building.ifc");
    write_atomic(&building, &poinav_author::demo_building(&spec, &stamp)?)?;
    steps.push(Step {
        title: "Test building".into(),
        detail: format!(
            "{} rooms and a corridor, Room 2 door {:.2} m: test-building.ifc",
            spec.layout().rooms.len(),
            spec.room2_door_width_m
        ),
    });

    // 2. Enrichment.
    let enriched = out.join("test-building.poi.ifc");
    let (n, door) = enrich_file(&building, &enriched, &opts)?;
    steps.push(Step {
        title: "POI enrichment".into(),
        detail: format!("{n} elements classified; {door}: test-building.poi.ifc"),
    });

    // 3. 3D export.
    let model = Model::open(&enriched)?;
    let meshes = poinav_geom::mesh_model(&model);
    crate::warnings::print(&crate::warnings::uncut(&model, &meshes));
    let structure = spatial::spatial_structure(&model, &units::length_unit(&model));
    let c = classify(&model, &RuleSet::defaults(), &RobotProfile::paper());
    let scene = poinav_export::SceneInput {
        storeys: &structure.storeys,
        elements: &meshes.elements,
        poi: Some(&c),
    };
    poinav_export::glb::write_glb(&out.join("test-building.glb"), &scene)?;
    steps.push(Step {
        title: "3D export".into(),
        detail: format!("{} elements: test-building.glb", meshes.elements.len()),
    });

    // 4. The three validation scenarios.
    let mut all = true;
    let mut sections = String::new();
    outln!("scenarios:");
    for (name, text) in SCENARIOS {
        let scenario = Scenario::from_toml(text, &format!("{name}.toml"), out)?;
        let runs = run_scenario(&scenario, None, &out.join(name))?;
        all &= report(name, &runs);
        sections.push_str(&scenario_html(name, &runs, out));
        if name == "doorway" {
            if let Some(first) = runs.first() {
                let back = out.join("doorway-sensor-findings.ifc");
                poinav_bridge::write_back(
                    &first.building.model,
                    &first.building.classification,
                    &first.outcome,
                    &opts,
                )?
                .write(&back)?;
                steps.push(Step { title: "Sensor write-back".into(), detail: "doorway findings (B-2, RESTRICTED, SENSOR_BASED) written into doorway-sensor-findings.ifc".into() });
            }
        }
    }

    // 5. Design iteration: widen the door, re-enrich.
    let source = Model::open(&building)?;
    let (editor, patch) = poinav_author::patch_door_width(&source, "Door Room 2", 1.20, &stamp)?;
    let wide = out.join("test-building-wide.ifc");
    editor.write(&wide)?;
    let (_, door) = enrich_file(&wide, &out.join("test-building-wide.poi.ifc"), &opts)?;
    steps.push(Step {
        title: "Design iteration".into(),
        detail: format!(
            "Room 2 door {:.2} -> {:.2} m ({} profiles resized); re-enriched: {door}",
            patch.old_width_m.unwrap_or(0.0),
            patch.new_width_m,
            patch.profiles.len()
        ),
    });

    // 6. Navigation on both designs: the same route, the audit, the Nav2 bundle of the
    // widened one.
    let paper = RobotProfile::paper();
    let mut times = Vec::new();
    for (design, file, dir, bundle) in [
        ("first design", &building, "navigation", false),
        ("widened design", &wide, "navigation-wide", true),
    ] {
        let dir = out.join(dir);
        std::fs::create_dir_all(&dir).with_context(|| format!("creating {}", dir.display()))?;
        let (b, _) = crate::navigate::building(file, &paper)?;
        let nav = poinav_nav::Navigator::new(&b, &paper, &poinav_nav::NavOptions::default())?;
        let from: poinav_nav::Place = "Room 1".parse()?;
        let to: poinav_nav::Place = "Room 2".parse()?;
        let route = nav.route(&from, &to)?;
        let mut json = serde_json::to_string_pretty(&route)?;
        json.push('\n');
        write_atomic(&dir.join("route-room1-room2.json"), json.as_bytes())?;
        let report = poinav_nav::audit(
            &b,
            std::slice::from_ref(&paper),
            // The test building has no exterior door: reachability from the corridor.
            &poinav_nav::AuditOptions {
                start: Some("Corridor".into()),
                ..poinav_nav::AuditOptions::default()
            },
        )?;
        poinav_nav::audit::write_report(&report, &b, &dir)?;
        let p = &report.profiles[0];
        let [full, restricted, blocked, _] = p.door_counts();
        let (reachable, unreachable) = p.space_counts();
        let doors: Vec<&str> = route
            .doors
            .iter()
            .map(|d| d.name.as_deref().unwrap_or(&d.id))
            .collect();
        let mut detail = format!(
            "Room 1 -> Room 2 {:.2} m in {:.1} s through {}; audit: doors {full} full, {restricted} restricted, {blocked} blocked, spaces reachable from the corridor {reachable}, not {unreachable}: {}/report.html",
            route.length_m,
            route.time_s,
            doors.join(", "),
            dir.file_name().unwrap_or_default().to_string_lossy()
        );
        if bundle {
            let summary = poinav_nav::write_bundle(
                &b,
                &paper,
                &poinav_nav::Nav2Options::default(),
                &out.join("nav2"),
            )?;
            write!(
                detail,
                "; Nav2 bundle ({} storey, route graph {} nodes): nav2/",
                summary.storeys.len(),
                summary.storeys.iter().map(|s| s.graph_nodes).sum::<usize>()
            )?;
        }
        times.push(route.time_s);
        steps.push(Step {
            title: format!("Navigation, {design}"),
            detail,
        });
    }
    if let [before, after] = times[..] {
        steps.push(Step {
            title: "Design check".into(),
            detail: format!(
                "Room 1 -> Room 2 for the paper robot: {before:.1} s with the 0.80 m door (B-2, half speed through it), {after:.1} s with the 1.20 m one"
            ),
        });
    }

    let html = report_html(&steps, &sections, all, &stamp);
    let report_path = out.join("report.html");
    write_atomic(&report_path, html.as_bytes())?;
    for s in &steps {
        outln!("{}: {}", s.title, s.detail);
    }
    outln!(
        "demo: {} — open {}",
        if all {
            "every expectation holds"
        } else {
            "SOME EXPECTATIONS FAILED"
        },
        report_path.display()
    );
    Ok(if all {
        ExitCode::SUCCESS
    } else {
        ExitCode::from(1)
    })
}

fn scenario_html(name: &str, runs: &[VariantRun], out: &Path) -> String {
    let mut h = String::new();
    for r in runs {
        let title = match &r.variant {
            Some(v) => format!("{name} — {v}"),
            None => name.to_string(),
        };
        let _ = write!(h, "<section><h2>{}</h2><table><tr><th>expectation</th><th>expected</th><th>measured</th><th></th></tr>", attr(&title));
        for j in &r.outcome.judged {
            let _ = write!(
                h,
                "<tr><td>{}</td><td>{}</td><td><code>{}</code></td><td class=\"{}\">{}</td></tr>",
                attr(j.kind),
                attr(&j.expected),
                attr(&j.measured.to_string()),
                if j.pass { "pass" } else { "fail" },
                if j.pass { "PASS" } else { "FAIL" }
            );
        }
        h.push_str("</table><div class=\"plots\">");
        let rel = r.dir.strip_prefix(out).unwrap_or(&r.dir);
        for plot in ["trajectories.svg", "speed.svg", "distance.svg"] {
            if r.dir.join(plot).exists() {
                let _ = write!(
                    h,
                    "<img src=\"{}\" alt=\"{plot}\">",
                    attr(&rel.join(plot).to_string_lossy())
                );
            }
        }
        h.push_str("</div></section>");
    }
    h
}

fn report_html(steps: &[Step], sections: &str, all: bool, stamp: &str) -> String {
    let mut h = String::from(
        "<!doctype html><html><head><meta charset=\"utf-8\"><title>poinav demo</title><style>\
         body{font-family:system-ui,sans-serif;margin:2em;max-width:1100px}table{border-collapse:collapse;margin:.5em 0}\
         td,th{border:1px solid #ccc;padding:.25em .5em;text-align:left;font-size:90%}.pass{color:#070;font-weight:bold}\
         .fail{color:#b00;font-weight:bold}.plots img{max-width:100%;width:520px;border:1px solid #ddd;margin:.25em}\
         </style></head><body><h1>poinav demo: the paper's test building</h1>",
    );
    let _ = write!(
        h,
        "<p>Generated {stamp}. Overall: <span class=\"{}\">{}</span></p><ol>",
        if all { "pass" } else { "fail" },
        if all {
            "every expectation holds"
        } else {
            "some expectations failed"
        }
    );
    for s in steps {
        let _ = write!(h, "<li><b>{}</b>: {}</li>", attr(&s.title), attr(&s.detail));
    }
    h.push_str("</ol>");
    h.push_str(sections);
    h.push_str("</body></html>\n");
    h
}
