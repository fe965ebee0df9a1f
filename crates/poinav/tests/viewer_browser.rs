//! The viewer end to end in Debian's Chromium (headless), driven by Playwright
//! (tests/js/viewer-e2e.mjs): `poinav serve` on the drive scenario, the page loads without
//! console errors, the screenshot shows the building, keys drive the robots, the forward ray
//! turns red at a wall, the camera key switches views, a click inspects a wall, POI colours,
//! and a `poinav simulate` trace plays to its end. Needs node, tests/js/node_modules and
//! /usr/bin/chromium (tests/js/setup.sh installs them). With POINAV_UPDATE_SCREENSHOT=1 the
//! screenshot replaces docs/viewer.png (the README's).

mod common;

use std::ffi::OsStr;
use std::process::Command;

#[test]
fn viewer_in_chromium() {
    let root = common::root();
    let bin = env!("CARGO_BIN_EXE_poinav");
    let tmp = tempfile::tempdir().unwrap();
    let sim = Command::new(bin)
        .args([
            "simulate",
            "crates/poinav-sim/scenarios/separation.toml",
            "-o",
        ])
        .arg(tmp.path().join("separation"))
        .current_dir(&root)
        .output()
        .unwrap();
    assert!(
        sim.status.success(),
        "{}",
        String::from_utf8_lossy(&sim.stderr)
    );
    let trace = tmp.path().join("separation/trace.jsonl");

    let server = common::serve(
        &[
            OsStr::new("--scenario"),
            OsStr::new("crates/poinav-sim/scenarios/drive.toml"),
        ],
        &root,
    )
    .expect("poinav serve starts");
    let url = format!("http://{}/", server.addr);
    assert!(url.starts_with("http://127.0.0.1:"), "{url}");

    let out = tmp.path().join("e2e");
    let (report, ok) = common::browser_report(
        "viewer-e2e.mjs",
        &[OsStr::new(&url), out.as_os_str(), trace.as_os_str()],
        &out,
    );
    assert_eq!(report["failures"], serde_json::json!([]), "{report:#}");
    assert!(ok, "{report:#}");
    let m = |check: &str, key: &str| report["checks"][check]["measured"][key].clone();
    let checks = report["checks"].as_object().unwrap();
    assert_eq!(checks.len(), 14, "{report:#}");
    assert!(checks.values().all(|c| c["ok"] == true));
    assert!(m("building covers the view", "coverage").as_f64().unwrap() > 0.08);
    assert!(m("building loaded", "elements").as_u64().unwrap() >= 17);
    assert!(m("ArrowUp moves Robot1", "moved_m").as_f64().unwrap() > 0.3);
    assert_eq!(
        m("ArrowUp moves Robot1", "robot2_moved_m").as_f64(),
        Some(0.0)
    );
    assert_eq!(m("forward ray red at the wall", "colour"), "#ef4444");
    assert_eq!(m("forward ray red at the wall", "hitClass"), "IfcWall");
    assert_eq!(m("camera key switches to top-down", "camera"), "top");
    assert_eq!(m("POI colours doors by status", "status"), "RESTRICTED");
    assert_eq!(m("playback reaches the end", "ended"), true);
    assert_eq!(m("playback reaches the end", "end"), 4.5);

    let png = std::fs::read(out.join("viewer.png")).unwrap();
    assert_eq!(&png[..8], b"\x89PNG\r\n\x1a\n");
    assert!(png.len() > 20_000, "screenshot only {} bytes", png.len());
    if std::env::var_os("POINAV_UPDATE_SCREENSHOT").is_some() {
        std::fs::write(root.join("docs/viewer.png"), &png).unwrap();
    }
}
