//! Shared helpers for the integration tests: workspace paths, the corpus and IfcOpenShell's
//! Python (from `poinav-testkit`), running the `poinav` binary and `poinav serve`.

#![allow(dead_code, unused_imports)]

use std::path::{Path, PathBuf};
use std::process::Command;

pub use poinav_testkit::{corpus, root, shared};

/// The Python that has IfcOpenShell (panics, never skips, when it is missing).
pub fn python() -> PathBuf {
    poinav_testkit::python("ifcopenshell")
}

/// Runs a script from `tests/ifcos/` with IfcOpenShell's Python and parses its JSON output.
pub fn ifcos(script: &str, args: &[&std::ffi::OsStr]) -> serde_json::Value {
    poinav_testkit::ifcos_with(&python(), script, args)
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

/// Runs the browser test `tests/js/SCRIPT ARGS...` with node and reads the report it writes
/// to `OUT/report.json` (panics with what node printed when there is none), with whether node
/// exited successfully. `OUT` is one of `ARGS`.
pub fn browser_report(
    script: &str,
    args: &[&std::ffi::OsStr],
    out: &Path,
) -> (serde_json::Value, bool) {
    let run = Command::new("node")
        .arg(root().join("tests/js").join(script))
        .args(args)
        .output()
        .expect("node must be installed (tests/js/setup.sh)");
    let report = std::fs::read(out.join("report.json")).unwrap_or_else(|e| {
        panic!(
            "no report ({e}); node said:\n{}\n{}",
            String::from_utf8_lossy(&run.stdout),
            String::from_utf8_lossy(&run.stderr)
        )
    });
    (
        serde_json::from_slice(&report).unwrap(),
        run.status.success(),
    )
}
