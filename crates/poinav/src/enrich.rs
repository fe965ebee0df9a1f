//! `poinav enrich`: classify every element with the POI rules and write the enriched IFC,
//! the semantic CSV and the IDS, with a summary per robot profile.

use std::collections::BTreeMap;
use std::path::PathBuf;
use std::process::ExitCode;

use poinav_ifc::Model;
use poinav_poi::{classify, AccessibilityStatus, Classification, RobotProfile, WriteOptions};
use serde::Serialize;

/// Arguments of `poinav enrich`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// The IFC file to enrich (never modified).
    input: PathBuf,
    /// Where to write the enriched IFC.
    #[arg(short, long)]
    output: PathBuf,
    /// Robot profile file (TOML); repeat to evaluate several. The first is written into the IFC.
    /// Default: the paper's robot (0.90 m clear width).
    #[arg(long = "profile")]
    profiles: Vec<PathBuf>,
    /// Rule file (TOML) extending the default rules, or replacing them with `mode = "replace"`.
    #[arg(long)]
    rules: Option<PathBuf>,
    /// Also write the semantic CSV here.
    #[arg(long)]
    csv: Option<PathBuf>,
    /// Also write an IDS (buildingSMART IDS 1.0) describing what the enriched model contains.
    #[arg(long)]
    ids: Option<PathBuf>,
    /// Prefix of the three property set names. `Pset_` (the paper's names) is reserved by
    /// buildingSMART; use e.g. `POINAV_` for names no IDS audit flags.
    #[arg(long, default_value = "Pset_")]
    pset_prefix: String,
    /// Print the summary as JSON.
    #[arg(long)]
    json: bool,
}

#[derive(Debug, Serialize)]
struct ProfileSummary {
    name: String,
    min_clearance_width_m: f64,
    doors: BTreeMap<&'static str, usize>,
    transitions: BTreeMap<&'static str, usize>,
    spaces: BTreeMap<&'static str, usize>,
}

#[derive(Debug, Serialize)]
struct Corridor {
    guid: String,
    name: Option<String>,
    long_name: Option<String>,
    rule: String,
}

#[derive(Debug, Serialize)]
struct Summary {
    input: String,
    output: String,
    schema: &'static str,
    length_unit_m: f64,
    timestamp: String,
    pset_prefix: String,
    elements: usize,
    instances_added: usize,
    rules: BTreeMap<String, usize>,
    categories: BTreeMap<&'static str, usize>,
    roles: BTreeMap<&'static str, usize>,
    conditional_roles: BTreeMap<&'static str, usize>,
    corridors: Vec<Corridor>,
    profiles: Vec<ProfileSummary>,
}

fn statuses(
    c: &Classification,
    filter: impl Fn(&poinav_poi::Classified) -> bool,
) -> BTreeMap<&'static str, usize> {
    let mut m: BTreeMap<&'static str, usize> = AccessibilityStatus::ALL
        .iter()
        .map(|s| (s.label(), 0))
        .collect();
    for e in c.elements.iter().filter(|e| filter(e)) {
        if let Some(a) = &e.accessibility {
            *m.entry(a.status.label()).or_default() += 1;
        }
    }
    m
}

fn profile_summary(c: &Classification) -> ProfileSummary {
    ProfileSummary {
        name: c.profile.name.clone(),
        min_clearance_width_m: c.profile.min_clearance_width(),
        doors: statuses(c, |e| e.class == "IfcDoor"),
        transitions: statuses(c, |e| e.poi_type == poinav_poi::PoiType::TransitionElement),
        spaces: statuses(c, |e| e.class == "IfcSpace"),
    }
}

/// Runs `poinav enrich`.
pub fn run(args: &Args) -> anyhow::Result<ExitCode> {
    let rules = crate::rules(args.rules.as_deref())?;
    let profiles = if args.profiles.is_empty() {
        vec![RobotProfile::paper()]
    } else {
        args.profiles
            .iter()
            .map(|p| RobotProfile::load(p))
            .collect::<Result<Vec<_>, _>>()?
    };
    // All outputs or none: refuse before writing anything when a folder is missing.
    for out in [Some(&args.output), args.csv.as_ref(), args.ids.as_ref()]
        .into_iter()
        .flatten()
    {
        let dir = out
            .parent()
            .filter(|d| !d.as_os_str().is_empty())
            .unwrap_or(std::path::Path::new("."));
        anyhow::ensure!(
            dir.is_dir(),
            "cannot write {}: the folder {} does not exist",
            out.display(),
            dir.display()
        );
        anyhow::ensure!(
            !out.is_dir(),
            "cannot write {}: it is a folder; name a file (e.g. {})",
            out.display(),
            out.join("model.poi.ifc").display()
        );
    }
    crate::progress::stage("reading");
    let model = Model::open(&args.input)?;
    crate::progress::stage("classifying");
    let classifications: Vec<Classification> = profiles
        .iter()
        .map(|p| classify(&model, &rules, p))
        .collect();
    let primary = &classifications[0];
    crate::progress::stage("writing");
    let timestamp = poinav_poi::iso8601_utc(poinav_poi::now_or_source_date_epoch());
    let opts = WriteOptions {
        prefix: args.pset_prefix.clone(),
        timestamp: timestamp.clone(),
    };
    let editor = poinav_poi::write_enrichment(&model, primary, &opts)?;
    // The error names the file and the cause.
    editor.write(&args.output)?;
    let metres = poinav_ifc::units::length_unit(&model).metres_per_unit;
    if let Some(csv) = &args.csv {
        poinav_export::semantic_csv::write_csv(csv, primary, metres, &timestamp)?;
    }
    if let Some(ids) = &args.ids {
        poinav_export::ids::write_ids(ids, &model, primary, &opts)?;
    }
    crate::progress::end();

    let mut summary = Summary {
        input: args.input.display().to_string(),
        output: args.output.display().to_string(),
        schema: model.schema().name(),
        length_unit_m: metres,
        timestamp,
        pset_prefix: args.pset_prefix.clone(),
        elements: primary.elements.len(),
        instances_added: editor.added_count(),
        rules: BTreeMap::new(),
        categories: BTreeMap::new(),
        roles: BTreeMap::new(),
        conditional_roles: BTreeMap::new(),
        corridors: Vec::new(),
        profiles: classifications.iter().map(profile_summary).collect(),
    };
    for e in &primary.elements {
        *summary.rules.entry(e.rule.clone()).or_default() += 1;
        *summary.categories.entry(e.category.label()).or_default() += 1;
        for r in &e.primary {
            *summary.roles.entry(r.label()).or_default() += 1;
        }
        for r in &e.conditional {
            *summary.conditional_roles.entry(r.label()).or_default() += 1;
        }
        if e.primary.contains(&poinav_poi::Role::MultiRobotZone) {
            summary.corridors.push(Corridor {
                guid: e.global_id.clone(),
                name: e.name.clone(),
                long_name: model.entity(e.id).and_then(|s| s.get_str("LongName")),
                rule: e.rule.clone(),
            });
        }
    }
    if args.json {
        outln!("{}", serde_json::to_string_pretty(&summary)?);
    } else {
        print_summary(&summary);
    }
    Ok(ExitCode::SUCCESS)
}

fn print_summary(s: &Summary) {
    outln!(
        "enriched {} -> {} ({}, unit {} m)",
        s.input,
        s.output,
        s.schema,
        s.length_unit_m
    );
    let sets = poinav_poi::pset_names(&s.pset_prefix);
    outln!(
        "  {} elements, {} instances added, property sets {}, {}, {}",
        s.elements,
        s.instances_added,
        sets.classification,
        sets.accessibility,
        sets.coordination
    );
    let join = |m: &BTreeMap<&str, usize>| {
        m.iter()
            .map(|(k, v)| format!("{k} {v}"))
            .collect::<Vec<_>>()
            .join(", ")
    };
    outln!("  roles:       {}", join(&s.roles));
    outln!(
        "  conditional: {}",
        if s.conditional_roles.is_empty() {
            "none".into()
        } else {
            join(&s.conditional_roles)
        }
    );
    outln!(
        "  rules:       {}",
        s.rules
            .iter()
            .map(|(k, v)| format!("{k} {v}"))
            .collect::<Vec<_>>()
            .join(", ")
    );
    for p in &s.profiles {
        outln!(
            "  profile {} (needs {:.2} m): doors {}; spaces {}",
            p.name,
            p.min_clearance_width_m,
            join(&p.doors),
            join(&p.spaces)
        );
    }
    outln!("  corridors found: {}", s.corridors.len());
    for c in &s.corridors {
        outln!(
            "    {} {} {}  ({})",
            c.guid,
            c.name.as_deref().unwrap_or("-"),
            c.long_name.as_deref().unwrap_or(""),
            c.rule
        );
    }
}
