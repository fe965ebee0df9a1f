//! The viewer on the corpus's multi-storey buildings in Debian's Chromium (headless), driven by
//! Playwright (tests/js/viewer-storeys.mjs): `poinav serve FILE` without a scenario; from
//! straight above the robots' rays and the doors' colours show on the simulated storey (the
//! storeys above are cut away), switching the storey moves the robots and the section plane,
//! ArrowUp drives Robot1 at least 1 m in 2.5 s without touching Robot2, the building arrives one
//! GLB per storey with the simulated storey's first, is drawn in few draw calls, is not redrawn
//! while nothing moves, frames where only robots moved show what a whole drawing shows, and
//! X-ray leaves the storey cut. Prints the first-frame time, the simulated storey's and the
//! building's load times, the frame rate while Robot1 drives, the time one frame takes
//! (everything, and only the robots moved) and the load average per model. Needs node,
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
    assert_eq!(checks.len(), 12, "{report:#}");
    assert!(checks.values().all(|c| c["ok"] == true));
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
    assert_eq!(
        m("no frames while nothing moves", "frames").as_u64(),
        Some(0)
    );
    let f = |key: &str| report[key].as_f64().unwrap_or(f64::NAN);
    eprintln!(
        "{model}: first frame {:.0} ms, simulated storey loaded in {:.0} ms (drawn at {:.0} ms), \
         building loaded in {:.0} ms (drawn at {:.0} ms), {:.1} frames/s while Robot1 drives, \
         a frame takes {:.0} ms ({:.0} ms when only robots move), {} draw calls, load average {}",
        f("first_frame_ms"),
        f("storey_ms"),
        f("storey_frame_ms"),
        f("building_ms"),
        f("building_frame_ms"),
        f("frames_per_s"),
        f("render_ms"),
        f("robots_ms"),
        report["draw_calls"],
        report["load_average"]
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
