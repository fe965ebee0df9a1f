//! Shared helpers for the integration tests: workspace paths, the corpus, IfcOpenShell's Python.

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

/// The Python that has IfcOpenShell: `POINAV_PYTHON`, else `.venv/bin/python` at the root.
/// Panics (never skips) when it is missing: run `scripts/setup-python.sh` first.
pub fn python() -> PathBuf {
    let py = std::env::var_os("POINAV_PYTHON")
        .map(PathBuf::from)
        .unwrap_or_else(|| root().join(".venv/bin/python"));
    let ok = Command::new(&py)
        .args(["-c", "import ifcopenshell"])
        .output()
        .is_ok_and(|o| o.status.success());
    assert!(ok, "IfcOpenShell is not importable with {}: run `bash scripts/setup-python.sh` (the README's test command does)", py.display());
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

/// Runs the `poinav` binary; returns (exit code, stdout, stderr).
pub fn poinav(args: &[&std::ffi::OsStr]) -> (i32, String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_poinav"))
        .args(args)
        .output()
        .expect("poinav runs");
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

/// A running `poinav serve`, stopped when dropped.
pub struct Served {
    child: std::process::Child,
    /// `127.0.0.1:PORT`.
    pub addr: String,
}

impl Drop for Served {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

/// Starts `poinav serve ARGS --port 0` in `dir` and waits for the URL it prints; the exit
/// code when it stops without serving. Its standard output is closed after that line (the
/// server must keep running).
pub fn serve(args: &[&std::ffi::OsStr], dir: &Path) -> Result<Served, i32> {
    use std::io::BufRead;
    let mut child = Command::new(env!("CARGO_BIN_EXE_poinav"))
        .arg("serve")
        .args(args)
        .args(["--port", "0"])
        .current_dir(dir)
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::null())
        .spawn()
        .expect("poinav runs");
    let mut line = String::new();
    std::io::BufReader::new(child.stdout.take().unwrap())
        .read_line(&mut line)
        .unwrap();
    match line.trim().strip_prefix("poinav viewer: http://") {
        Some(addr) => Ok(Served {
            addr: addr.trim_end_matches('/').to_string(),
            child,
        }),
        None => Err(child.wait().unwrap().code().unwrap_or(-1)),
    }
}

/// One HTTP/1.1 GET of `path` (sent as written, not normalised): status and body.
pub fn http_get(addr: &str, path: &str) -> (u16, Vec<u8>) {
    use std::io::{Read, Write};
    let mut s = std::net::TcpStream::connect(addr).unwrap();
    write!(
        s,
        "GET {path} HTTP/1.1\r\nHost: {addr}\r\nConnection: close\r\n\r\n"
    )
    .unwrap();
    let mut buf = Vec::new();
    s.read_to_end(&mut buf).unwrap();
    let end = buf
        .windows(4)
        .position(|w| w == b"\r\n\r\n")
        .expect("an HTTP response");
    let head = String::from_utf8_lossy(&buf[..end]).to_string();
    let status = head.split_whitespace().nth(1).unwrap().parse().unwrap();
    (status, buf[end + 4..].to_vec())
}
