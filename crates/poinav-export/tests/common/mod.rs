//! Shared helpers for poinav-export's integration tests: workspace paths, the corpus, and
//! IfcOpenShell's Python (copied from `crates/poinav/tests/common`, which this crate cannot see).

#![allow(dead_code)]

use std::path::{Path, PathBuf};
use std::process::Command;

/// The workspace root.
pub fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../..")
        .canonicalize()
        .expect("workspace root")
}

/// `shared/` beside the repository (override with `POINAV_SHARED`).
pub fn shared() -> PathBuf {
    std::env::var_os("POINAV_SHARED")
        .map(PathBuf::from)
        .unwrap_or_else(|| root().join("../shared"))
}

/// Every `.ifc` file of the public corpus, sorted.
pub fn corpus() -> Vec<PathBuf> {
    let dir = shared().join("ifc");
    let mut files: Vec<PathBuf> = std::fs::read_dir(&dir)
        .unwrap_or_else(|e| panic!("corpus folder {} is missing: {e}", dir.display()))
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|x| x == "ifc"))
        .collect();
    files.sort();
    assert!(
        files.len() >= 13,
        "expected the 15-file corpus in {}",
        dir.display()
    );
    files
}

/// The Python with IfcOpenShell and ifctester: `POINAV_PYTHON`, else `.venv/bin/python` at the
/// root. Panics (never skips) when either is missing: run `scripts/setup-python.sh` first.
pub fn python() -> PathBuf {
    let py = std::env::var_os("POINAV_PYTHON")
        .map(PathBuf::from)
        .unwrap_or_else(|| root().join(".venv/bin/python"));
    let ok = Command::new(&py)
        .args(["-c", "import ifcopenshell, ifctester.ids"])
        .output()
        .is_ok_and(|o| o.status.success());
    assert!(
        ok,
        "IfcOpenShell and ifctester are not importable with {}: run `bash scripts/setup-python.sh` \
         (the README's test command does)",
        py.display()
    );
    py
}

/// Runs a script from `tests/ifcos/` with IfcOpenShell's Python and parses its JSON output.
pub fn ifcos(script: &str, args: &[&std::ffi::OsStr]) -> serde_json::Value {
    let out = Command::new(python())
        .arg(root().join("tests/ifcos").join(script))
        .args(args)
        .output()
        .expect("python runs");
    assert!(
        out.status.success(),
        "{script} failed: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    serde_json::from_slice(&out.stdout).unwrap_or_else(|e| panic!("{script} printed no JSON: {e}"))
}
