//! Floor plan drawings: one SVG per storey of every corpus model, well-formed XML with every
//! space's name, a scale bar, a path per item and door passages coloured by status.
//! `POINAV_PLAN_SVG_DIR=DIR` keeps the drawings there to look at.

mod common;

use std::collections::{BTreeSet, HashMap};

use poinav_export::plan_svg::{to_svg, SvgOptions};
use poinav_geom::{floor_plans, FloorPlan, PlanItemKind, PlanOptions};
use poinav_ifc::Model;

/// Checks one drawing; returns the number of `<path>`s with a GlobalId.
fn check(svg: &str, plan: &FloorPlan, what: &str) -> usize {
    let doc = roxmltree::Document::parse(svg).unwrap_or_else(|e| panic!("{what}: not XML: {e}"));
    let root = doc.root_element();
    assert_eq!(root.tag_name().name(), "svg", "{what}");
    assert_eq!(
        root.tag_name().namespace(),
        Some("http://www.w3.org/2000/svg")
    );
    let view: Vec<f64> = root
        .attribute("viewBox")
        .unwrap()
        .split(' ')
        .map(|v| v.parse().unwrap())
        .collect();
    assert_eq!(view.len(), 4);
    assert!(view[2] > 0.0 && view[3] > 0.0);
    // The plan fits the view box (Y negated).
    if let Some((lo, hi)) = plan.bounds {
        assert!(view[0] <= lo.x && view[0] + view[2] >= hi.x, "{what}");
        assert!(view[1] <= -hi.y && view[1] + view[3] >= -lo.y, "{what}");
    }
    let texts: BTreeSet<String> = doc
        .descendants()
        .filter(|n| n.is_text())
        .filter_map(|n| n.text())
        .map(|t| t.trim().to_string())
        .collect();
    for space in plan.items_of(PlanItemKind::Space) {
        for name in [&space.name, &space.long_name].into_iter().flatten() {
            if !name.trim().is_empty() {
                assert!(
                    texts.contains(name.trim()),
                    "{what}: space name {name:?} missing"
                );
            }
        }
    }
    let bar = doc
        .descendants()
        .find(|n| n.attribute("class") == Some("scale-bar"))
        .unwrap_or_else(|| panic!("{what}: no scale bar"));
    assert!(bar
        .descendants()
        .any(|n| n.text().is_some_and(|t| t.ends_with(" m"))));
    assert!(bar.children().filter(|n| n.has_tag_name("rect")).count() >= 2);
    let paths = doc
        .descendants()
        .filter(|n| n.has_tag_name("path") && n.attribute("data-global-id").is_some())
        .count();
    assert_eq!(paths, plan.items.len(), "{what}: one path per item");
    paths
}

#[test]
fn every_storey_of_the_corpus_draws() {
    let keep = std::env::var_os("POINAV_PLAN_SVG_DIR").map(std::path::PathBuf::from);
    let tmp = tempfile::tempdir().unwrap();
    let dir = keep.clone().unwrap_or_else(|| tmp.path().to_path_buf());
    std::fs::create_dir_all(&dir).unwrap();
    let mut drawings = 0;
    let mut spaces = 0;
    for file in common::corpus() {
        let model = Model::open(&file).unwrap();
        let stem = file.file_stem().unwrap().to_string_lossy().to_string();
        for (i, plan) in floor_plans(&model, &PlanOptions::default())
            .iter()
            .enumerate()
        {
            let svg = to_svg(plan, &SvgOptions::default());
            let what = format!("{stem} {:?}", plan.storey_name);
            check(&svg, plan, &what);
            let out = dir.join(format!("{stem}-{i}.svg"));
            std::fs::write(&out, &svg).unwrap();
            drawings += 1;
            spaces += plan.items_of(PlanItemKind::Space).count();
        }
    }
    println!(
        "{drawings} drawings, {spaces} spaces named, in {}",
        dir.display()
    );
    // The railway has no storeys: one plan for each of the two railway parts holding track.
    assert_eq!(drawings, 56);
}

#[test]
fn doors_are_coloured_by_status() {
    let model = Model::open(common::shared().join("ifc/fzk-haus-ifc4.ifc")).unwrap();
    let plans = floor_plans(&model, &PlanOptions::default());
    let plan = &plans[0];
    let mut status = HashMap::new();
    for (i, d) in plan.doors.iter().enumerate() {
        let s = if i == 0 { "BLOCKED" } else { "FULL_ACCESS" };
        status.insert(d.global_id.clone(), s.to_string());
    }
    let options = SvgOptions {
        door_status: status,
        ..SvgOptions::default()
    };
    let svg = to_svg(plan, &options);
    check(&svg, plan, "fzk-haus");
    let doc = roxmltree::Document::parse(&svg).unwrap();
    let openings: Vec<_> = doc
        .descendants()
        .filter(|n| n.attribute("class") == Some("door-opening"))
        .flat_map(|g| g.children().filter(|n| n.has_tag_name("path")))
        .collect();
    assert_eq!(openings.len(), 5);
    let fills: Vec<_> = openings.iter().map(|p| p.attribute("fill")).collect();
    assert_eq!(fills.iter().filter(|f| **f == Some("#e0463b")).count(), 1);
    assert_eq!(fills.iter().filter(|f| **f == Some("#5cbf6e")).count(), 4);
    let legend: Vec<&str> = doc
        .descendants()
        .filter(|n| n.attribute("class") == Some("legend"))
        .flat_map(|g| g.descendants().filter_map(|n| n.text()))
        .collect();
    assert!(legend.contains(&"door blocked") && legend.contains(&"door full access"));
    assert!(legend.contains(&"wall") && legend.contains(&"space"));
}

#[test]
fn the_test_building_draws_with_its_rooms_and_door_statuses() {
    let spec = poinav_author::DemoBuilding::default();
    let bytes = poinav_author::demo_building(&spec, "2026-01-01T00:00:00").unwrap();
    let model = Model::from_bytes("demo.ifc", bytes).unwrap();
    let plans = floor_plans(&model, &PlanOptions::default());
    let plan = &plans[0];
    // Room 2's 0.80 m door is RESTRICTED for the paper's robot, the others FULL_ACCESS.
    let status: HashMap<String, String> = plan
        .doors
        .iter()
        .map(|d| {
            let s = if d.clear_width_m < 0.9 {
                "RESTRICTED"
            } else {
                "FULL_ACCESS"
            };
            (d.global_id.clone(), s.to_string())
        })
        .collect();
    let options = SvgOptions {
        door_status: status,
        ..SvgOptions::default()
    };
    let svg = to_svg(plan, &options);
    check(&svg, plan, "demo building");
    for room in [
        "Room 1", "Room 2", "Room 3", "Room 4", "Room 5", "Room 6", "Corridor",
    ] {
        assert!(svg.contains(&format!(">{room}<")), "{room}");
    }
    assert_eq!(
        svg.matches(r##"fill="#f0b429""##).count(),
        2,
        "one door and the legend"
    );
    if let Some(dir) = std::env::var_os("POINAV_PLAN_SVG_DIR") {
        std::fs::write(std::path::Path::new(&dir).join("demo-building.svg"), &svg).unwrap();
    }
}
