//! Temporary exploration (removed before handing in).
use poinav_ifc::Model;
use poinav_poi::{classify, RobotProfile, RuleSet, WriteOptions};
use std::time::Instant;

#[test]
fn explore() {
    let out = std::path::Path::new("/tmp/idsx");
    std::fs::create_dir_all(out).unwrap();
    let mut files: Vec<_> = std::fs::read_dir("/work/shared/ifc")
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|x| x == "ifc"))
        .collect();
    files.sort();
    for f in files {
        let t = Instant::now();
        let model = Model::open(&f).unwrap();
        let c = classify(&model, &RuleSet::defaults(), &RobotProfile::paper());
        for prefix in ["Pset_", "POINAV_"] {
            let opts = WriteOptions {
                prefix: prefix.into(),
                timestamp: "2026-11-22T02:30:00".into(),
            };
            let stem = f.file_stem().unwrap().to_string_lossy().to_string();
            let ifc = out.join(format!("{stem}.{prefix}.ifc"));
            poinav_poi::write_enrichment(&model, &c, &opts)
                .unwrap()
                .write(&ifc)
                .unwrap();
            poinav_export::ids::write_ids(
                &out.join(format!("{stem}.{prefix}.ids")),
                &model,
                &c,
                &opts,
            )
            .unwrap();
        }
        eprintln!(
            "{} {} elements {:?}",
            f.display(),
            c.elements.len(),
            t.elapsed()
        );
    }
}
