//! Helpers for poinav's integration tests and benchmarks (a dev-dependency only): where the
//! workspace and the corpus are, and running IfcOpenShell's Python for live comparisons.
//!
//! The corpus lives in `shared/` beside the repository (`$POINAV_SHARED` overrides it) and is
//! never copied into the repository. IfcOpenShell's Python is `$POINAV_PYTHON`, else
//! `.venv/bin/python` at the workspace root (made by `scripts/setup-python.sh`); tests that need
//! it fail, never skip, when it is missing.

use std::ffi::OsStr;
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

/// Every `.ifc` file of the public corpus, sorted; panics when the folder is missing or holds
/// fewer than 13 files.
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

/// The corpus file called `name`; panics naming the path when it is missing.
pub fn corpus_file(name: &str) -> PathBuf {
    let p = shared().join("ifc").join(name);
    assert!(
        p.is_file(),
        "corpus file {} is missing; set POINAV_SHARED to the folder holding ifc/",
        p.display()
    );
    p
}

/// The Python that imports `modules` (`"ifcopenshell, shapely"`): `POINAV_PYTHON`, else
/// `.venv/bin/python` at the root. Panics (never skips) when it cannot.
pub fn python(modules: &str) -> PathBuf {
    let py = std::env::var_os("POINAV_PYTHON")
        .map(PathBuf::from)
        .unwrap_or_else(|| root().join(".venv/bin/python"));
    let ok = Command::new(&py)
        .args(["-c", &format!("import {modules}")])
        .output()
        .is_ok_and(|o| o.status.success());
    assert!(
        ok,
        "`import {modules}` fails with {}: run `bash scripts/setup-python.sh` (the README's test command does)",
        py.display()
    );
    py
}

/// Runs `tests/ifcos/SCRIPT ARGS` with `python` and parses its JSON output.
pub fn ifcos_with(python: &Path, script: &str, args: &[&OsStr]) -> serde_json::Value {
    let out = Command::new(python)
        .arg(root().join("tests/ifcos").join(script))
        .args(args)
        .output()
        .expect("python runs");
    json_of_output(out, script)
}

/// Runs the Python code `code` (`python -c code ARGS`) and parses its JSON output.
pub fn python_json(python: &Path, code: &str, args: &[&OsStr]) -> serde_json::Value {
    let out = Command::new(python)
        .args(["-c", code])
        .args(args)
        .output()
        .expect("python runs");
    json_of_output(out, "the Python code")
}

/// Starts `tests/ifcos/SCRIPT FILE` with `python`; finish with [`json_of`].
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
    json_of_output(child.wait_with_output().expect("python finishes"), what)
}

fn json_of_output(out: std::process::Output, what: &str) -> serde_json::Value {
    assert!(
        out.status.success(),
        "{what} failed: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    serde_json::from_slice(&out.stdout).unwrap_or_else(|e| panic!("{what} printed no JSON: {e}"))
}

/// A binary PGM (P5) read back independently of the writer, by the Netpbm rules: magic,
/// width, height and maxval as whitespace-separated fields (comments from `#` to the line's
/// end), one whitespace, then the pixels row by row from the top.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Pgm {
    /// Columns.
    pub width: usize,
    /// Rows.
    pub height: usize,
    /// Largest value.
    pub maxval: u32,
    /// One byte per pixel, first row first.
    pub pixels: Vec<u8>,
}

/// Parses a binary PGM with a maxval below 256; panics on anything else (a test failure).
pub fn read_pgm(bytes: &[u8]) -> Pgm {
    let mut fields = Vec::new();
    let mut i = 0;
    while fields.len() < 4 {
        while bytes[i].is_ascii_whitespace() {
            i += 1;
        }
        if bytes[i] == b'#' {
            while bytes[i] != b'\n' {
                i += 1;
            }
            continue;
        }
        let start = i;
        while !bytes[i].is_ascii_whitespace() {
            i += 1;
        }
        fields.push(String::from_utf8(bytes[start..i].to_vec()).unwrap());
    }
    i += 1; // the single whitespace after maxval
    assert_eq!(fields[0], "P5", "not a binary PGM");
    let pgm = Pgm {
        width: fields[1].parse().unwrap(),
        height: fields[2].parse().unwrap(),
        maxval: fields[3].parse().unwrap(),
        pixels: bytes[i..].to_vec(),
    };
    assert!(pgm.maxval < 256, "two-byte pixels are not read here");
    assert_eq!(pgm.pixels.len(), pgm.width * pgm.height, "pixel count");
    pgm
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_pgm_with_a_comment_reads_back() {
        let pgm = read_pgm(b"P5\n# made by hand\n3 2\n255\n\x00\xfe\xcd\x01\x02\x03");
        assert_eq!((pgm.width, pgm.height, pgm.maxval), (3, 2, 255));
        assert_eq!(pgm.pixels, [0, 254, 205, 1, 2, 3]);
    }

    #[test]
    fn the_root_holds_the_workspace_manifest() {
        let manifest = std::fs::read_to_string(root().join("Cargo.toml")).unwrap();
        assert!(manifest.contains("[workspace]"));
        assert!(shared().ends_with("shared") || std::env::var_os("POINAV_SHARED").is_some());
    }
}
