//! Shared helpers for the integration tests: workspace paths, the corpus, IfcOpenShell's Python.

#![allow(dead_code)]

use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};

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

/// The corpus file called `name`.
pub fn corpus_file(name: &str) -> PathBuf {
    let p = shared().join("ifc").join(name);
    assert!(p.is_file(), "corpus file {} is missing", p.display());
    p
}

/// The Python that has IfcOpenShell: `POINAV_PYTHON`, else `.venv/bin/python` at the root.
/// Panics (never skips) when it is missing: run `scripts/setup-python.sh` first.
pub fn python() -> PathBuf {
    let py = std::env::var_os("POINAV_PYTHON")
        .map(PathBuf::from)
        .unwrap_or_else(|| root().join(".venv/bin/python"));
    let ok = Command::new(&py)
        .args(["-c", "import ifcopenshell, shapely"])
        .output()
        .is_ok_and(|o| o.status.success());
    assert!(ok, "IfcOpenShell is not importable with {}: run `bash scripts/setup-python.sh` (the README's test command does)", py.display());
    py
}

/// Starts a script from `tests/ifcos/` with IfcOpenShell's Python; finish with [`json_of`].
pub fn spawn_ifcos(python: &Path, script: &str, file: &Path) -> Child {
    Command::new(python)
        .arg(root().join("tests/ifcos").join(script))
        .arg(file)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("python runs")
}

/// Waits for a script started by [`spawn_ifcos`] and parses its JSON output.
pub fn json_of(child: Child, what: &str) -> serde_json::Value {
    let out = child.wait_with_output().expect("python finishes");
    assert!(
        out.status.success(),
        "{what} failed: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    serde_json::from_slice(&out.stdout).unwrap_or_else(|e| panic!("{what} printed no JSON: {e}"))
}
