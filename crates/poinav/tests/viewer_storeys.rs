//! The viewer on the corpus's multi-storey buildings in Debian's Chromium (headless), driven by
//! Playwright (tests/js/viewer-storeys.mjs): `poinav serve FILE` without a scenario; from
//! straight above the robots' rays and the doors' colours show on the simulated storey (the
//! storeys above are cut away), switching the storey moves the robots and the section plane, and
//! ArrowUp drives Robot1 at least 1 m in 2.5 s without touching Robot2. Prints the first-frame
//! time, the building's load time and the frame rate per model. Needs node,
//! tests/js/node_modules and /usr/bin/chromium (tests/js/setup.sh installs them).

mod common;

use std::ffi::OsStr;
use std::sync::Mutex;

/// One browser and one server at a time: each is heavy on a small machine.
static ONE_AT_A_TIME: Mutex<()> = Mutex::new(());

fn viewer_on(model: &str) {
    let _turn = ONE_AT_A_TIME.lock().unwrap_or_else(|e| e.into_inner());
    let root = common::root();
    let file = poinav_testkit::corpus_file(model);
    let server = common::serve(&[file.as_os_str()], &root).expect("poinav serve starts");
    let url = format!("http://{}/", server.addr);
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("storeys");
    let (report, ok) = common::browser_report(
        "viewer-storeys.mjs",
        &[OsStr::new(&url), out.as_os_str()],
        &out,
    );
    assert_eq!(
        report["failures"],
        serde_json::json!([]),
        "{model}: {report:#}"
    );
    assert!(ok, "{report:#}");
    let checks = report["checks"].as_object().unwrap();
    assert_eq!(checks.len(), 7, "{report:#}");
    let m = |check: &str, key: &str| report["checks"][check]["measured"][key].clone();
    assert!(m("rays visible from above", "ray_pixels").as_u64().unwrap() > 50);
    assert!(
        m("ArrowUp drives Robot1 without touching Robot2", "moved_m")
            .as_f64()
            .unwrap()
            >= 1.0
    );
    assert_eq!(
        m(
            "ArrowUp drives Robot1 without touching Robot2",
            "robot2_moved_m"
        )
        .as_f64(),
        Some(0.0)
    );
    eprintln!(
        "{model}: first frame {:.0} ms, building loaded in {:.0} ms, {:.1} frames/s",
        report["first_frame_ms"].as_f64().unwrap_or(f64::NAN),
        report["building_ms"].as_f64().unwrap_or(f64::NAN),
        report["frames_per_s"].as_f64().unwrap_or(f64::NAN)
    );
}

#[test]
fn viewer_on_fzk_haus() {
    viewer_on("fzk-haus-ifc4.ifc");
}

#[test]
fn viewer_on_duplex_apartment() {
    viewer_on("duplex-apartment.ifc");
}

#[test]
fn viewer_on_office_a() {
    viewer_on("office-a.ifc");
}
