//! World placements of every IfcSpace, IfcDoor and IfcWall on every corpus file agree with
//! IfcOpenShell's `get_local_placement` (run live): translations within 1e-6 m, rotation
//! entries within 1e-9.

mod common;

use std::collections::BTreeMap;

use poinav_geom::PlacementCache;
use poinav_ifc::Model;

const CLASSES: [&str; 3] = ["IfcSpace", "IfcDoor", "IfcWall"];

/// The world matrix as IfcOpenShell prints it: row-major 4x4.
fn row_major(t: &glam::DAffine3) -> [f64; 16] {
    let m = t.matrix3;
    let mut out = [0.0; 16];
    for r in 0..3 {
        out[4 * r] = m.x_axis[r];
        out[4 * r + 1] = m.y_axis[r];
        out[4 * r + 2] = m.z_axis[r];
        out[4 * r + 3] = t.translation[r];
    }
    out[15] = 1.0;
    out
}

#[test]
fn placements_match_ifcopenshell_on_every_corpus_file() {
    let python = common::python();
    let files = common::corpus();
    // IfcOpenShell runs for all files at once while poinav computes.
    let children: Vec<_> = files
        .iter()
        .map(|f| common::spawn_ifcos(&python, "placements.py", f))
        .collect();
    let mut problems = Vec::new();
    let mut per_file = BTreeMap::new();
    let (mut worst_t, mut worst_r) = (0.0f64, 0.0f64);
    for (file, child) in files.iter().zip(children) {
        let name = file.file_name().unwrap().to_string_lossy().into_owned();
        let model = Model::open(file).unwrap();
        let mut cache = PlacementCache::new(&model);
        let mut ours = BTreeMap::new();
        for class in CLASSES {
            for e in model.instances_of(class) {
                ours.insert(e.global_id().unwrap(), cache.product(e));
            }
        }
        let theirs = common::json_of(child, &format!("placements.py {name}"));
        let theirs = theirs.as_object().unwrap();
        assert_eq!(ours.len(), theirs.len(), "{name}: element count");
        let mut matched = 0;
        for (guid, reference) in theirs {
            let Some(mine) = ours.get(guid) else {
                problems.push(format!("{name}: {guid} not found by poinav"));
                continue;
            };
            let (Some(reference), Ok(mine)) = (reference.as_array(), mine) else {
                problems.push(format!(
                    "{name}: {guid}: IfcOpenShell {reference}, poinav {mine:?}"
                ));
                continue;
            };
            let mine = row_major(mine);
            let mut ok = true;
            for (i, r) in reference.iter().enumerate() {
                let d = (r.as_f64().unwrap() - mine[i]).abs();
                if i % 4 == 3 && i < 12 {
                    worst_t = worst_t.max(d);
                    ok &= d <= 1e-6;
                } else {
                    worst_r = worst_r.max(d);
                    ok &= d <= 1e-9;
                }
            }
            if ok {
                matched += 1;
            } else {
                problems.push(format!(
                    "{name}: {guid}: IfcOpenShell {reference:?}, poinav {mine:?}"
                ));
            }
        }
        per_file.insert(name, (matched, theirs.len()));
    }
    let total: usize = per_file.values().map(|v| v.1).sum();
    eprintln!("placements matched per file (matched, total): {per_file:?}");
    eprintln!("worst translation error {worst_t:e} m, worst rotation entry error {worst_r:e}");
    assert!(total > 1500, "only {total} elements checked");
    assert!(problems.is_empty(), "{}", problems.join("\n"));
}
