//! Footprints agree with IfcOpenShell's triangulated geometry (run live, see
//! `tests/ifcos/product_footprints.py`): area within 2 % (our exact outlines against the area
//! inside the projected mesh's outer boundary, our convex hulls against the hull of the mesh)
//! and z-range within 1 cm, for at least 95 % of the spaces of six building models, and of
//! the doors (mostly mapped items, some scaled and nested) of every corpus file.

mod common;

use std::collections::BTreeMap;
use std::path::PathBuf;

use poinav_geom::{footprint_of, FootprintMethod, PlacementCache};
use poinav_ifc::Model;

const SPACE_FILES: [&str; 6] = [
    "office-a.ifc",
    "duplex-apartment.ifc",
    "fzk-haus-ifc4.ifc",
    "institute-var-2.ifc",
    "ifc4-test-model.ifc",
    "nested-mapped-item.ifc",
];

/// How many products agreed, and what did not.
#[derive(Default)]
struct Agreement {
    total: usize,
    area_ok: usize,
    z_ok: usize,
    both_ok: usize,
    worst_area: (f64, String),
    worst_z: (f64, String),
    per_file: BTreeMap<String, (usize, usize)>,
    failures: Vec<String>,
}

impl Agreement {
    fn report(&self, what: &str) {
        let Agreement {
            total,
            area_ok,
            z_ok,
            both_ok,
            ..
        } = self;
        eprintln!("{what} matching (area and z) per file: {:?}", self.per_file);
        eprintln!("{what}: area within 2 %: {area_ok}/{total}; z-range within 1 cm: {z_ok}/{total}; both: {both_ok}/{total}");
        eprintln!(
            "{what}: worst area error {:.2e} % ({}), worst z error {:.4} m ({})",
            100.0 * self.worst_area.0,
            self.worst_area.1,
            self.worst_z.0,
            self.worst_z.1
        );
        eprintln!("{what} not matching:\n{}", self.failures.join("\n"));
    }
}

/// Compares poinav's footprints of `classes` on `files` with IfcOpenShell's.
fn compare(files: &[PathBuf], classes: &[&str]) -> Agreement {
    let python = common::python();
    let children: Vec<_> = files
        .iter()
        .map(|f| {
            std::process::Command::new(&python)
                .arg(common::root().join("tests/ifcos/product_footprints.py"))
                .arg(f)
                .args(classes)
                .stdout(std::process::Stdio::piped())
                .stderr(std::process::Stdio::piped())
                .spawn()
                .expect("python runs")
        })
        .collect();
    let mut a = Agreement::default();
    for (file, child) in files.iter().zip(children) {
        let name = file.file_name().unwrap().to_string_lossy().into_owned();
        let model = Model::open(file).unwrap();
        let mut cache = PlacementCache::new(&model);
        let theirs = common::json_of(child, &format!("product_footprints.py {name}"));
        let mut file_ok = 0;
        let mut file_total = 0;
        for class in classes {
            for product in model.instances_of(class) {
                if product.get("Representation").is_none() {
                    continue;
                }
                a.total += 1;
                file_total += 1;
                let guid = product.global_id().unwrap();
                let r = &theirs[&guid];
                let label = format!("{name} {} {guid}", product.id());
                let ours = match footprint_of(&mut cache, product) {
                    Ok(f) => f,
                    Err(e) => {
                        a.failures.push(format!("{label}: poinav: {e}"));
                        continue;
                    }
                };
                if r.get("error").is_some() || r.is_null() {
                    a.failures.push(format!("{label}: IfcOpenShell: {r}"));
                    continue;
                }
                let reference = match ours.method {
                    FootprintMethod::Outline => r["outline_area"].as_f64().unwrap(),
                    FootprintMethod::ConvexHull => r["hull_area"].as_f64().unwrap(),
                };
                let f = &ours.footprint;
                let area_err = (f.area() - reference).abs() / reference.max(1e-9);
                let z_err = (f.z_min - r["z_min"].as_f64().unwrap())
                    .abs()
                    .max((f.z_max - r["z_max"].as_f64().unwrap()).abs());
                if area_err > a.worst_area.0 {
                    a.worst_area = (area_err, label.clone());
                }
                if z_err > a.worst_z.0 {
                    a.worst_z = (z_err, label.clone());
                }
                a.area_ok += usize::from(area_err <= 0.02);
                a.z_ok += usize::from(z_err <= 0.01);
                if area_err <= 0.02 && z_err <= 0.01 {
                    a.both_ok += 1;
                    file_ok += 1;
                } else {
                    a.failures.push(format!(
                        "{label}: {:?} area {:.4} vs {reference:.4} ({:+.2} %), z {:.4}..{:.4} vs {}..{}; {:?}",
                        ours.method,
                        f.area(),
                        100.0 * (f.area() - reference) / reference,
                        f.z_min,
                        f.z_max,
                        r["z_min"],
                        r["z_max"],
                        ours.approximations
                            .iter()
                            .map(|x| x.to_string())
                            .collect::<Vec<_>>(),
                    ));
                }
            }
        }
        a.per_file.insert(name, (file_ok, file_total));
    }
    a
}

#[test]
fn space_footprints_match_ifcopenshell() {
    let files: Vec<_> = SPACE_FILES.iter().map(|f| common::corpus_file(f)).collect();
    let a = compare(&files, &["IfcSpace"]);
    a.report("spaces");
    assert!(
        a.per_file.values().all(|v| v.1 > 0),
        "a file without spaces"
    );
    assert!(a.total >= 200, "only {} spaces", a.total);
    assert!(
        a.both_ok * 100 >= a.total * 95,
        "only {} of {} spaces match:\n{}",
        a.both_ok,
        a.total,
        a.failures.join("\n")
    );
}

#[test]
fn door_footprints_match_ifcopenshell() {
    let files: Vec<_> = common::corpus()
        .into_iter()
        .filter(|f| {
            let n = f.file_name().unwrap().to_string_lossy();
            // No doors; the merged file repeats office-a and duplex.
            !n.starts_with("railway") && !n.starts_with("ramps") && !n.starts_with("synthetic")
        })
        .collect();
    // Windows agree as well (645 of 646 when last measured; the one is IfcOpenShell 0.9
    // leaving wall-opening-window-ifc4x3.ifc's geometry in millimetres), but triangulating
    // them in IfcOpenShell takes longer than the rest of the tests together.
    let a = compare(&files, &["IfcDoor"]);
    a.report("doors");
    assert!(a.total >= 240, "only {} doors", a.total);
    assert!(
        a.both_ok * 100 >= a.total * 95,
        "only {} of {} doors match:\n{}",
        a.both_ok,
        a.total,
        a.failures.join("\n")
    );
}
