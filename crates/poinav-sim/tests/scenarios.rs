//! The three paper scenarios (SPEC.md §6) as shipped scenario files: their numbers asserted
//! from the written trace.jsonl (not from the simulator's state), the write-back read back from
//! the IFC, and determinism (every run twice gives byte-identical outputs).

use std::path::{Path, PathBuf};

use poinav_bridge::{prepare, write_back, Prepared};
use poinav_ifc::property::{property_sets, PropertyValue, Scalar};
use poinav_ifc::Model;
use poinav_poi::WriteOptions;
use poinav_sim::geometry::{polygon_gap, Obb};
use poinav_sim::{run, write_outputs, Outcome, Scenario};
use serde_json::Value;

fn scenario(name: &str) -> Scenario {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("scenarios")
        .join(format!("{name}.toml"));
    Scenario::load(&path).unwrap()
}

struct Run {
    prepared: Prepared,
    outcome: Outcome,
    trace: Vec<Value>,
    dir: tempfile::TempDir,
}

fn simulate(s: &Scenario, variant: Option<&str>) -> Run {
    let prepared = prepare(s, variant).unwrap();
    let outcome = run(s, variant, prepared.floor()).unwrap();
    let dir = tempfile::tempdir().unwrap();
    write_outputs(dir.path(), &outcome, prepared.floor()).unwrap();
    let text = std::fs::read_to_string(dir.path().join("trace.jsonl")).unwrap();
    let trace = text
        .lines()
        .map(|l| serde_json::from_str(l).unwrap())
        .collect();
    Run {
        prepared,
        outcome,
        trace,
        dir,
    }
}

fn of<'a>(trace: &'a [Value], robot: &'a str) -> impl Iterator<Item = &'a Value> + 'a {
    trace.iter().filter(move |l| l["robot"] == robot)
}

fn f(v: &Value) -> f64 {
    v.as_f64().unwrap()
}

fn roles(l: &Value) -> Vec<&str> {
    l["roles"]
        .as_array()
        .unwrap()
        .iter()
        .map(|r| r.as_str().unwrap())
        .collect()
}

fn events<'a>(trace: &'a [Value], kind: &'a str) -> impl Iterator<Item = &'a Value> + 'a {
    trace
        .iter()
        .flat_map(|l| l["events"].as_array().unwrap().iter())
        .filter(move |e| e["kind"] == kind)
}

fn texts(v: &PropertyValue) -> Vec<String> {
    let items = match v {
        PropertyValue::Single(s) => s.iter().cloned().collect(),
        PropertyValue::Enumerated(l) | PropertyValue::List(l) => l.clone(),
        _ => Vec::new(),
    };
    items
        .into_iter()
        .filter_map(|t| match t.value {
            Scalar::Text(s) | Scalar::Enum(s) => Some(s),
            _ => None,
        })
        .collect()
}

/// Door `name`'s POI properties in an IFC file: (set.property -> values).
fn door_properties(path: &PathBuf, name: &str) -> Vec<(String, Vec<String>)> {
    let model = Model::open(path).unwrap();
    let door = model
        .instances_of("IfcDoor")
        .into_iter()
        .find(|d| d.name().as_deref() == Some(name))
        .unwrap();
    property_sets(door)
        .into_iter()
        .flat_map(|s| {
            s.properties
                .iter()
                .map(|p| (format!("{}.{}", s.name, p.name), texts(&p.value)))
                .collect::<Vec<_>>()
        })
        .collect()
}

fn prop<'a>(props: &'a [(String, Vec<String>)], name: &str) -> &'a [String] {
    &props.iter().find(|p| p.0 == name).unwrap().1
}

#[test]
fn doorway_measures_the_clear_width_and_restricts_the_narrow_door() {
    let s = scenario("doorway");
    for (variant, width, status, narrow) in [
        ("door-0.80", 0.80, "RESTRICTED", true),
        ("door-1.20", 1.20, "FULL_ACCESS", false),
    ] {
        let r = simulate(&s, Some(variant));
        assert!(r.outcome.passed(), "{variant}: {:#?}", r.outcome.judged);
        let door = r
            .prepared
            .floor()
            .doors
            .iter()
            .find(|d| d.name.as_deref() == Some("Door Room 2"))
            .unwrap();
        assert!((door.clear_width_m - width).abs() < 1e-9);
        // From the trace: the clearance event, the roles and the status it reports.
        let c: Vec<&Value> = events(&r.trace, "clearance").collect();
        assert!(!c.is_empty(), "{variant}: no clearance measured");
        let last = c.last().unwrap();
        assert_eq!(last["door"], door.id.as_str());
        let estimate = f(&last["estimate_m"]);
        println!("{variant}: clearance estimate {estimate:.6} m, real {width:.3} m");
        assert!((estimate - width).abs() <= 0.05, "{variant}: {estimate}");
        assert_eq!(last["status"], status);
        assert_eq!(last["method"], "SENSOR_BASED");
        let door_roles: Vec<&str> = last["roles"]
            .as_array()
            .unwrap()
            .iter()
            .map(|r| r.as_str().unwrap())
            .collect();
        assert!(door_roles.contains(&"A-2"));
        assert_eq!(
            door_roles.contains(&"B-2"),
            narrow,
            "{variant}: {door_roles:?}"
        );
        let added_b2 = events(&r.trace, "role-added")
            .any(|e| e["element"] == door.id.as_str() && e["role"] == "B-2");
        assert_eq!(added_b2, narrow);
        // The +-30 degree rays first hit the corridor wall, then look through the door.
        let robot: Vec<&Value> = of(&r.trace, "Robot2").collect();
        let through = |l: &Value, k: usize| {
            l["rays"][k]["through"]
                .as_array()
                .is_some_and(|a| a.iter().any(|d| d == door.id.as_str()))
        };
        assert!(!through(robot[0], 1) && !through(robot[0], 2));
        assert!(robot.iter().any(|l| through(l, 1)) && robot.iter().any(|l| through(l, 2)));
        // Write-back: the IFC carries what the sensors found.
        let out = r.dir.path().join("written.ifc");
        let opts = WriteOptions {
            prefix: "Pset_".into(),
            timestamp: "2026-11-22T03:00:00".into(),
        };
        write_back(
            &r.prepared.model,
            &r.prepared.classification,
            &r.outcome,
            &opts,
        )
        .unwrap()
        .write(&out)
        .unwrap();
        let props = door_properties(&out, "Door Room 2");
        assert_eq!(
            prop(&props, "Pset_RobotAccessibility.AccessibilityStatus"),
            [status]
        );
        assert_eq!(
            prop(&props, "Pset_RobotAccessibility.ValidationMethod"),
            ["SENSOR_BASED"]
        );
        assert_eq!(
            prop(&props, "Pset_RobotAccessibility.LastValidated"),
            ["2026-11-22T03:00:00"]
        );
        let conditional = prop(&props, "Pset_POI_Classification.POI_ConditionalRoles");
        assert_eq!(
            conditional.contains(&"B-2".to_string()),
            narrow,
            "{conditional:?}"
        );
    }
}

#[test]
fn separation_takes_c2_below_two_metres_halves_the_speed_and_never_touches() {
    let s = scenario("separation");
    let r = simulate(&s, None);
    assert!(r.outcome.passed(), "{:#?}", r.outcome.judged);
    let a: Vec<&Value> = of(&r.trace, "Robot1").collect();
    let b: Vec<&Value> = of(&r.trace, "Robot2").collect();
    assert_eq!(a.len(), b.len());
    let pos = |l: &Value| glam::DVec2::new(f(&l["x"]), f(&l["y"]));
    let dt = 1.0 / 60.0;
    let (mut first_below, mut min_gap) = (None, f64::INFINITY);
    let mut c2_speeds = Vec::new();
    let mut onset: [Option<f64>; 2] = [None, None];
    let mut top = 0.0f64;
    for (la, lb) in a.iter().zip(&b) {
        let t = f(&la["t"]);
        let d = pos(la).distance(pos(lb));
        if d < 2.0 {
            first_below.get_or_insert(t);
            assert!(
                roles(la).contains(&"C-2") && roles(lb).contains(&"C-2"),
                "t={t} d={d}"
            );
        } else {
            assert!(
                !roles(la).contains(&"C-2") && !roles(lb).contains(&"C-2"),
                "t={t} d={d}"
            );
        }
        for (k, l) in [la, lb].into_iter().enumerate() {
            top = top.max(f(&l["speed"]));
            if roles(l).contains(&"C-2") {
                let since = *onset[k].get_or_insert(t);
                // Braking 5.0 -> 2.5 m/s at 100 N / 5 kg = 20 m/s² takes 0.125 s.
                if t - since >= 0.15 - 1e-9 {
                    c2_speeds.push(f(&l["speed"]));
                }
            } else {
                onset[k] = None;
            }
        }
        let boxes =
            [la, lb].map(|l| Obb::new(pos(l), f(&l["heading_deg"]).to_radians(), 0.4, 0.35));
        min_gap = min_gap.min(polygon_gap(&boxes[0].corners(), &boxes[1].corners()));
    }
    let first_below = first_below.expect("the robots come closer than 2.0 m");
    let (lo, hi) = c2_speeds
        .iter()
        .fold((f64::INFINITY, 0.0f64), |(lo, hi), v| {
            (lo.min(*v), hi.max(*v))
        });
    println!(
        "separation: C-2 from t={first_below:.3} s; speeds during C-2 {lo:.4}..{hi:.4} m/s over {} samples; min gap {min_gap:.3} m; top speed {top:.4}",
        c2_speeds.len()
    );
    assert!(c2_speeds.len() > 40);
    assert!(lo >= 2.45 && hi <= 2.55, "{lo}..{hi}");
    assert!((top - 5.0).abs() < 1e-5, "{top}");
    assert!(min_gap > 0.0, "{min_gap}");
    assert_eq!(events(&r.trace, "contact").count(), 0);
    // Both robots switched C-2 on in the step the distance first fell below 2.0 m.
    let on: Vec<f64> = events(&r.trace, "robot-role")
        .filter(|e| e["on"] == true)
        .map(|e| f(&e["distance_m"]))
        .collect();
    assert_eq!(on.len(), 2);
    assert!(on.iter().all(|d| *d < 2.0 && *d > 2.0 - 10.0 * dt * 1.5));
    // The corridor's record got C-2 (R5) and lost it again.
    assert!(events(&r.trace, "role-added").any(|e| e["name"] == "Corridor" && e["role"] == "C-2"));
    assert!(events(&r.trace, "role-removed").any(|e| e["name"] == "Corridor" && e["role"] == "C-2"));
}

#[test]
fn wall_following_keeps_half_a_metre_and_reaches_the_room() {
    let s = scenario("wall-following");
    let r = simulate(&s, None);
    assert!(r.outcome.passed(), "{:#?}", r.outcome.judged);
    let north_wall_face = r
        .prepared
        .floor()
        .zones
        .iter()
        .find(|z| z.name.as_deref() == Some("Corridor"))
        .unwrap()
        .ring[2]
        .y;
    let (mut odo, mut prev) = (0.0, None::<glam::DVec2>);
    let (mut rays, mut lateral) = (Vec::new(), Vec::new());
    for l in of(&r.trace, "Robot1") {
        let p = glam::DVec2::new(f(&l["x"]), f(&l["y"]));
        if let Some(q) = prev {
            odo += p.distance(q);
        }
        prev = Some(p);
        if odo < 1.0 || l["mode"] != "wall-follow" {
            continue;
        }
        lateral.push(north_wall_face - p.y);
        let ray = &l["rays"][3];
        assert_eq!(ray["deg"], 90);
        if ray["class"] == "IfcWall" && ray.get("through").is_none() {
            rays.push(f(&ray["d"]));
            assert!(roles(l).contains(&"A-3"));
        }
    }
    let stats = |v: &[f64]| {
        let (lo, hi) = v.iter().fold((f64::INFINITY, 0.0f64), |(lo, hi), x| {
            (lo.min(*x), hi.max(*x))
        });
        let mean = v.iter().sum::<f64>() / v.len() as f64;
        (lo, hi, mean)
    };
    let (lo, hi, mean) = stats(&rays);
    let (plo, phi, _) = stats(&lateral);
    println!(
        "wall following: +90 ray {lo:.4}..{hi:.4} m (mean {mean:.4}, {} samples); pose lateral {plo:.4}..{phi:.4} m over {} steps",
        rays.len(),
        lateral.len()
    );
    assert!(rays.len() > 50);
    assert!(lo >= 0.45 && hi <= 0.55);
    assert!(
        plo >= 0.45 && phi <= 0.55,
        "the heading is held across door gaps too"
    );
    assert_eq!(
        events(&r.trace, "arrived")
            .filter(|e| e["name"] == "Room 6")
            .count(),
        1
    );
    assert_eq!(events(&r.trace, "contact").count(), 0);
}

#[test]
fn every_shipped_scenario_runs_twice_to_identical_bytes() {
    for (name, _) in poinav_sim::SHIPPED {
        let s = scenario(name);
        let variants: Vec<Option<&str>> = if s.variants.is_empty() {
            vec![None]
        } else {
            s.variants.iter().map(|v| Some(v.name.as_str())).collect()
        };
        for v in variants {
            let a = simulate(&s, v);
            let b = simulate(&s, v);
            for file in [
                "trace.jsonl",
                "summary.json",
                "trajectories.svg",
                "speed.svg",
                "distance.svg",
            ] {
                let x = std::fs::read(a.dir.path().join(file)).unwrap();
                let y = std::fs::read(b.dir.path().join(file)).unwrap();
                assert!(x == y, "{name} {v:?}: {file} differs between runs");
            }
            assert!(a.outcome.passed(), "{name} {v:?}");
        }
    }
}

#[test]
fn shipped_scenarios_match_the_files() {
    for (name, text) in poinav_sim::SHIPPED {
        let path = Path::new(env!("CARGO_MANIFEST_DIR")).join(format!("scenarios/{name}.toml"));
        assert_eq!(std::fs::read_to_string(path).unwrap(), *text);
    }
}
