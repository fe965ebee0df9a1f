//! A recording of a hand-written two-step trace on a one-room floor, read back with the `mcap`
//! crate: topics, counts, log times, the scan's beams, the map's cells, markers published
//! again when the door's status changes, byte-identical output, and a bad trace line named.

use std::collections::BTreeMap;
use std::path::Path;

use glam::DVec2;
use poinav_mcap::{storey_map, write_recording, McapError, Scene, START_NS};
use poinav_nav::polygon::rect;
use poinav_nav::{Floor, FloorDoor, FloorObstacle, FloorZone, Nav2Options, ObstacleKind};
use poinav_roles::{RobotProfile, Role};

/// A 4 x 3 m room with 0.1 m walls and a 1 m door in the south wall.
fn floor() -> Floor {
    let wall = |id: &str, r| FloorObstacle {
        id: id.into(),
        class: "IfcWall".into(),
        kind: ObstacleKind::Structure,
        rings: vec![r],
        roles: vec![Role::PathGuidance],
    };
    Floor {
        name: "Ground".into(),
        obstacles: vec![
            wall("n", rect(-0.1, 3.0, 4.1, 3.1)),
            wall("w", rect(-0.1, -0.1, 0.0, 3.0)),
            wall("e", rect(4.0, -0.1, 4.1, 3.0)),
            wall("s1", rect(-0.1, -0.1, 1.5, 0.0)),
            wall("s2", rect(2.5, -0.1, 4.1, 0.0)),
        ],
        doors: vec![FloorDoor {
            id: "door1".into(),
            name: Some("Door 1".into()),
            ring: rect(1.5, -0.1, 2.5, 0.0),
            center: DVec2::new(2.0, -0.05),
            clear_width_m: 1.0,
            classified_width_m: Some(1.0),
            blocked: None,
            roles: vec![Role::Transition],
            spaces: Some(vec!["room".into()]),
            doorless: false,
            terrain: false,
        }],
        zones: vec![FloorZone {
            id: "room".into(),
            name: Some("Room".into()),
            long_name: None,
            ring: rect(0.0, 0.0, 4.0, 3.0),
            roles: vec![Role::Destination],
            coordination: None,
        }],
        ..Floor::default()
    }
}

const TRACE: &str = r#"{"step":0,"t":0,"robot":"R 1","x":2,"y":1.5,"heading_deg":90,"speed":0,"omega_deg_s":0,"cmd":{"v":0,"omega_deg_s":0},"mode":"route","zone":"Room","roles":[],"brush":{"on":false,"angle_deg":0},"rays":[{"deg":0,"d":1.5,"hit":"n","class":"IfcWall"},{"deg":30,"d":1.732051,"hit":"n","class":"IfcWall"},{"deg":-30,"d":1.732051,"hit":"n","class":"IfcWall"},{"deg":90,"d":2,"hit":"w","class":"IfcWall"},{"deg":-90,"d":2,"hit":"e","class":"IfcWall"}],"events":[]}
{"step":1,"t":0.016667,"robot":"R 1","x":2,"y":1.45,"heading_deg":-90,"speed":3,"omega_deg_s":12.5,"cmd":{"v":3,"omega_deg_s":0},"mode":"route","zone":"Room","roles":[],"brush":{"on":false,"angle_deg":0},"rays":[{"deg":0,"d":5,"hit":null},{"deg":30,"d":1.7,"hit":"s1","class":"IfcWall"},{"deg":-30,"d":1.7,"hit":"s2","class":"IfcWall"},{"deg":90,"d":2,"hit":"e","class":"IfcWall"},{"deg":-90,"d":2,"hit":"w","class":"IfcWall"}],"events":[{"kind":"status-changed","element":"door1","name":"Door 1","from":"PENDING_VALIDATION","to":"RESTRICTED"}]}
"#;

fn record(dir: &Path, trace: &str, name: &str) -> Result<Vec<u8>, McapError> {
    let floor = floor();
    let profile = RobotProfile::paper();
    let map = storey_map(&floor, &profile, &Nav2Options::default()).unwrap();
    let scene = Scene {
        floor: &floor,
        profile: &profile,
        map: &map,
        dt: 1.0 / 60.0,
    };
    let t = dir.join(format!("{name}.jsonl"));
    std::fs::write(&t, trace).unwrap();
    let out = dir.join(format!("{name}.mcap"));
    let summary = write_recording(&t, &scene, &out)?;
    assert_eq!(summary.steps, 2);
    assert_eq!(summary.robots, [("R 1".to_string(), "R_1".to_string())]);
    Ok(std::fs::read(out).unwrap())
}

/// Reads `n` little-endian f32 after skipping a header with `frame` (stamp 8, string).
fn scan_ranges(data: &[u8], frame: &str) -> Vec<f32> {
    let mut at = 4 + 8 + 4 + frame.len() + 1;
    at = 4 + (at - 4).div_ceil(4) * 4;
    at += 7 * 4; // angle_min .. range_max
    let n = u32::from_le_bytes(data[at..at + 4].try_into().unwrap()) as usize;
    (0..n)
        .map(|k| {
            let p = at + 4 + 4 * k;
            f32::from_le_bytes(data[p..p + 4].try_into().unwrap())
        })
        .collect()
}

#[test]
fn a_two_step_trace_becomes_ros2_messages() {
    let tmp = tempfile::tempdir().unwrap();
    let bytes = record(tmp.path(), TRACE, "a").unwrap();
    let again = record(tmp.path(), TRACE, "b").unwrap();
    assert_eq!(bytes, again, "same inputs, same bytes");

    let mut by_topic: BTreeMap<String, Vec<(u64, Vec<u8>)>> = BTreeMap::new();
    for m in mcap::MessageStream::new(&bytes).unwrap() {
        let m = m.unwrap();
        let schema = m.channel.schema.as_ref().unwrap();
        assert_eq!(schema.encoding, "ros2msg");
        assert_eq!(m.channel.message_encoding, "cdr");
        let qos = &m.channel.metadata["offered_qos_profiles"];
        let latched = m.channel.topic == "/map" || m.channel.topic == "/poi/markers";
        assert_eq!(
            qos.contains("durability: 1"),
            latched,
            "{}",
            m.channel.topic
        );
        assert_eq!(m.log_time, m.publish_time);
        by_topic
            .entry(m.channel.topic.clone())
            .or_default()
            .push((m.log_time, m.data.into_owned()));
    }
    let counts: BTreeMap<&str, usize> = by_topic
        .iter()
        .map(|(t, v)| (t.as_str(), v.len()))
        .collect();
    assert_eq!(
        counts,
        BTreeMap::from([
            ("/R_1/odom", 2),
            ("/R_1/scan", 2),
            ("/map", 1),
            ("/poi/events", 1),
            ("/poi/markers", 2),
            ("/tf", 2),
        ])
    );
    // Step 1 at 1/60 s, rounded to the nanosecond.
    let scans = &by_topic["/R_1/scan"];
    assert_eq!(scans[0].0, START_NS);
    assert_eq!(scans[1].0, START_NS + 16_666_667);
    // Beams -90, -60, -30, 0, 30, 60, 90 degrees: trace rays -90 (2), -30, 0, 30, 90.
    let r = scan_ranges(&scans[1].1, "R_1/base_link");
    assert_eq!(r.len(), 7);
    assert_eq!([r[0], r[2], r[3], r[4], r[6]], [2.0, 1.7, 5.0, 1.7, 2.0]);
    assert!(r[1].is_nan() && r[5].is_nan());
    let r0 = scan_ranges(&scans[0].1, "R_1/base_link");
    assert_eq!(r0[3], 1.5);
    assert_eq!(r0[2], 1.732051f64 as f32);
    // The map: the grid's cells as 0 / 100 / -1, after the header and MapMetaData.
    let map = &by_topic["/map"][0].1;
    let floor = floor();
    let m = storey_map(&floor, &RobotProfile::paper(), &Nav2Options::default()).unwrap();
    let cells = m.width * m.height;
    assert!(cells > 1000);
    let data = &map[map.len() - cells..];
    let count = u32::from_le_bytes(
        map[map.len() - cells - 4..map.len() - cells]
            .try_into()
            .unwrap(),
    );
    assert_eq!(count as usize, cells);
    let data: Vec<i8> = data.iter().map(|&b| b as i8).collect();
    assert_eq!(data, m.data);
    for v in [0i8, 100, -1] {
        assert!(data.contains(&v), "{v}");
    }
    // The event as JSON with step, t and robot.
    let ev = &by_topic["/poi/events"][0].1;
    let text = std::str::from_utf8(&ev[8..ev.len() - 1]).unwrap();
    let json: serde_json::Value = serde_json::from_str(text).unwrap();
    assert_eq!(json["kind"], "status-changed");
    assert_eq!(json["robot"], "R 1");
    assert_eq!(json["step"], 1);
    assert_eq!(json["t"], 0.016667);
    // The markers start with the door PENDING_VALIDATION (the run's starting status, not the
    // floor's) and show it RESTRICTED from step 1.
    let markers = &by_topic["/poi/markers"];
    assert_eq!(markers[1].0, START_NS + 16_666_667);
    let has = |b: &[u8], s: &str| b.windows(s.len()).any(|w| w == s.as_bytes());
    assert!(has(&markers[0].1, "Door 1 PENDING_VALIDATION"));
    assert!(has(&markers[1].1, "Door 1 RESTRICTED"));
}

#[test]
fn a_bad_trace_line_is_named() {
    let tmp = tempfile::tempdir().unwrap();
    let broken = TRACE.replace(r#"{"deg":30,"d":1.7,"#, r#"{"deg":45,"d":1.7,"#);
    let err = record(tmp.path(), &broken, "bad").unwrap_err().to_string();
    assert!(
        err.contains("bad.jsonl:2:") && err.contains("45 degrees"),
        "{err}"
    );
    let err = record(tmp.path(), "{\"step\":0}\n", "short")
        .unwrap_err()
        .to_string();
    assert!(
        err.contains("short.jsonl:1:") && err.contains("missing field"),
        "{err}"
    );
    assert!(!tmp.path().join("bad.mcap").exists());
}
