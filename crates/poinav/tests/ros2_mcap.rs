//! `poinav simulate --mcap` on every shipped scenario (each variant): `tests/ros2/check_mcap.py`
//! decodes every message with `mcap` + `mcap-ros2-support` and with `rosbags`, and compares
//! topics, counts, scans, odometry and the occupancy grid with the run's trace and the Nav2
//! map `poinav_nav::write_bundle` writes for the same storey and profile. The same run
//! twice gives the same bytes; `--trace-format bin`'s trace reads back as the same lines and
//! records the same bytes.
//! `poinav serve --record` writes the live session when stopped.

mod common;

use std::ffi::OsStr;
use std::path::{Path, PathBuf};
use std::process::Command;

use poinav_nav::{Building, Nav2Options};
use poinav_sim::Scenario;

/// The Nav2 map (map.pgm, map.yaml) of the scenario variant's storey for its profile.
fn nav2_map(scenario: &Scenario, variant: Option<&str>, dir: &Path) -> (PathBuf, PathBuf) {
    let prepared = poinav_bridge::prepare(scenario, variant).unwrap();
    let profile =
        poinav_sim::scenario::load_profile(&scenario.building.profile, &scenario.dir).unwrap();
    let summary = poinav_nav::write_bundle(
        &Building::single(prepared.floor().clone()),
        &profile,
        &Nav2Options::default(),
        dir,
    )
    .unwrap();
    let folder = dir.join(&summary.storeys[0].folder);
    (folder.join("map.pgm"), folder.join("map.yaml"))
}

fn check(
    py: &Path,
    mcap: &Path,
    trace: &Path,
    map: &(PathBuf, PathBuf),
    dt: f64,
) -> serde_json::Value {
    let out = Command::new(py)
        .arg(common::root().join("tests/ros2/check_mcap.py"))
        .args([
            mcap.as_os_str(),
            trace.as_os_str(),
            map.0.as_os_str(),
            map.1.as_os_str(),
        ])
        .arg(dt.to_string())
        .output()
        .expect("python runs");
    assert!(
        out.status.success(),
        "check_mcap.py {}: {}",
        mcap.display(),
        String::from_utf8_lossy(&out.stderr)
    );
    serde_json::from_slice(&out.stdout).expect("JSON")
}

#[test]
fn every_shipped_scenario_records_ros2_messages_that_decode_and_match_the_trace() {
    let py = poinav_testkit::python("mcap, mcap_ros2, rosbags");
    let tmp = tempfile::tempdir().unwrap();
    let mut recordings = 0;
    for (name, _) in poinav_sim::SHIPPED {
        let file = common::root().join(format!("crates/poinav-sim/scenarios/{name}.toml"));
        let scenario = Scenario::load(&file).unwrap();
        let out = tmp.path().join(name);
        let target = tmp.path().join(format!("{name}.mcap"));
        let (code, stdout, stderr) = common::poinav(&[
            OsStr::new("simulate"),
            file.as_os_str(),
            OsStr::new("-o"),
            out.as_os_str(),
            OsStr::new("--mcap"),
            target.as_os_str(),
        ]);
        assert_eq!(code, 0, "{name}: {stdout}{stderr}");
        let variants: Vec<Option<String>> = match scenario.variant_names() {
            v if v.is_empty() => vec![None],
            v => v.into_iter().map(|v| Some(v.to_string())).collect(),
        };
        let several = variants.len() > 1;
        for v in &variants {
            let (mcap, trace) = match v {
                Some(v) if several => (
                    target.with_extension(format!("{v}.mcap")),
                    out.join(v).join("trace.jsonl"),
                ),
                _ => (target.clone(), out.join("trace.jsonl")),
            };
            let map = nav2_map(
                &scenario,
                v.as_deref(),
                &tmp.path().join(format!("{name}-nav2")),
            );
            let report = check(&py, &mcap, &trace, &map, scenario.dt);
            eprintln!("{name} {v:?}: {report}");
            let robots = report["robots"].as_array().unwrap().len();
            let steps = report["steps"].as_u64().unwrap();
            let want_steps = (scenario.duration_s / scenario.dt).round() as u64 + 1;
            assert_eq!(steps, want_steps, "{name} {v:?}: {report}");
            assert_eq!(robots, scenario.robots.len(), "{name} {v:?}");
            for r in report["robots"].as_array().unwrap() {
                let r = r.as_str().unwrap();
                assert_eq!(report["counts"][format!("/{r}/scan")], steps, "{name}");
                assert_eq!(report["counts"][format!("/{r}/odom")], steps, "{name}");
            }
            assert_eq!(report["counts"]["/tf"], steps);
            assert_eq!(report["counts"]["/map"], 1);
            // Five rays per robot and step, each equal to the trace's.
            assert_eq!(report["ranges_checked"], steps * robots as u64 * 5);
            // The demo building's map has free, occupied and unknown cells.
            for k in ["free", "occupied", "unknown"] {
                assert!(
                    report["map"][k].as_u64().unwrap() > 1000,
                    "{name}: {report}"
                );
            }
            assert_eq!(report["qos_map"], "durability: 1", "{name}");
            // The doorway run starts with the door PENDING_VALIDATION and the sensors set its
            // status: the markers are published again then.
            let markers = if *name == "doorway" { 2 } else { 1 };
            assert_eq!(
                report["counts"]["/poi/markers"], markers,
                "{name}: {report}"
            );
            recordings += 1;
        }
    }
    // doorway has two variants.
    assert_eq!(recordings, poinav_sim::SHIPPED.len() + 1);
}

#[test]
fn a_recording_is_byte_identical_run_to_run_and_needs_a_trace() {
    let tmp = tempfile::tempdir().unwrap();
    let file = common::root().join("crates/poinav-sim/scenarios/separation.toml");
    let mut bytes = Vec::new();
    for k in 0..2 {
        let target = tmp.path().join(format!("run{k}.mcap"));
        let (code, stdout, stderr) = common::poinav(&[
            OsStr::new("simulate"),
            file.as_os_str(),
            OsStr::new("-o"),
            tmp.path().join(format!("out{k}")).as_os_str(),
            OsStr::new("--mcap"),
            target.as_os_str(),
        ]);
        assert_eq!(code, 0, "{stdout}{stderr}");
        assert!(stdout.contains("wrote ROS 2 recording"), "{stdout}");
        bytes.push(std::fs::read(&target).unwrap());
    }
    assert_eq!(bytes[0], bytes[1]);
    assert_eq!(&bytes[0][..8], b"\x89MCAP0\r\n");
    let (code, _, stderr) = common::poinav(&[
        OsStr::new("simulate"),
        file.as_os_str(),
        OsStr::new("-o"),
        tmp.path().join("out").as_os_str(),
        OsStr::new("--no-trace"),
        OsStr::new("--mcap"),
        tmp.path().join("x.mcap").as_os_str(),
    ]);
    assert_eq!(code, 2, "{stderr}");
    assert!(stderr.contains("--no-trace"), "{stderr}");
    // The compact trace: trace.bin instead of trace.jsonl, read back as the same lines; no
    // recording from it.
    let out = tmp.path().join("out0");
    let (code, stdout, stderr) = common::poinav(&[
        OsStr::new("simulate"),
        file.as_os_str(),
        OsStr::new("-o"),
        out.as_os_str(),
        OsStr::new("--trace-format"),
        OsStr::new("bin"),
    ]);
    assert_eq!(code, 0, "{stdout}{stderr}");
    assert!(!out.join("trace.jsonl").exists());
    let jsonl = std::fs::read_to_string(tmp.path().join("out1/trace.jsonl")).unwrap();
    let bin = poinav_sim::trace_bin::read_file(&out.join("trace.bin"))
        .unwrap()
        .collect::<Result<Vec<String>, _>>()
        .unwrap();
    assert!(bin.len() > 500, "{} lines", bin.len());
    assert_eq!(bin, jsonl.lines().collect::<Vec<_>>());
    // The recording made from the compact trace is the one made from the JSON Lines trace,
    // byte for byte.
    let from_bin = tmp.path().join("from-bin.mcap");
    let (code, stdout, stderr) = common::poinav(&[
        OsStr::new("simulate"),
        file.as_os_str(),
        OsStr::new("-o"),
        out.as_os_str(),
        OsStr::new("--trace-format"),
        OsStr::new("bin"),
        OsStr::new("--mcap"),
        from_bin.as_os_str(),
    ]);
    assert_eq!(code, 0, "{stdout}{stderr}");
    assert!(stdout.contains("wrote ROS 2 recording"), "{stdout}");
    let from_bin = std::fs::read(&from_bin).unwrap();
    assert!(from_bin.len() > 10_000, "{} bytes", from_bin.len());
    assert!(
        from_bin == bytes[0],
        "{} vs {} bytes",
        from_bin.len(),
        bytes[0].len()
    );
}

#[test]
fn serve_record_writes_the_live_session_when_stopped() {
    use std::io::{BufRead, Read};
    let py = poinav_testkit::python("mcap, mcap_ros2");
    let tmp = tempfile::tempdir().unwrap();
    let scenario = common::root().join("crates/poinav-sim/scenarios/separation.toml");
    let target = tmp.path().join("live.mcap");
    let mut child = Command::new(env!("CARGO_BIN_EXE_poinav"))
        .arg("serve")
        .arg("--scenario")
        .arg(&scenario)
        .args(["--port", "0", "--record"])
        .arg(&target)
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    let mut stdout = std::io::BufReader::new(child.stdout.take().unwrap());
    let mut line = String::new();
    stdout.read_line(&mut line).unwrap();
    assert!(line.starts_with("poinav viewer: http://"), "{line}");
    std::thread::sleep(std::time::Duration::from_secs(2));
    let killed = Command::new("kill")
        .args(["-INT", &child.id().to_string()])
        .status()
        .unwrap();
    assert!(killed.success());
    let deadline = std::time::Instant::now() + std::time::Duration::from_secs(60);
    let status = loop {
        if let Some(s) = child.try_wait().unwrap() {
            break s;
        }
        assert!(std::time::Instant::now() < deadline, "serve did not stop");
        std::thread::sleep(std::time::Duration::from_millis(100));
    };
    let mut rest = String::new();
    stdout.read_to_string(&mut rest).unwrap();
    assert!(status.success(), "{status}: {rest}");
    assert!(rest.contains("wrote ROS 2 recording to"), "{rest}");
    let script = r#"
import json, sys
from collections import Counter
from mcap.reader import make_reader
from mcap_ros2.decoder import DecoderFactory
with open(sys.argv[1], "rb") as f:
    r = make_reader(f, decoder_factories=[DecoderFactory()])
    print(json.dumps(Counter(c.topic for _, c, _, _ in r.iter_decoded_messages())))
"#;
    let out = Command::new(&py)
        .args(["-c", script])
        .arg(&target)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let counts: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    // About 2 s at 60 Hz (the machine may be slow): one scan, odometry and /tf per step.
    let steps = counts["/tf"].as_u64().unwrap();
    assert!(steps >= 30, "{counts}");
    for r in ["Robot1", "Robot2"] {
        assert_eq!(counts[format!("/{r}/scan")], steps, "{counts}");
        assert_eq!(counts[format!("/{r}/odom")], steps, "{counts}");
    }
    assert_eq!(counts["/map"], 1);
    assert_eq!(counts["/poi/markers"], 1);
}
