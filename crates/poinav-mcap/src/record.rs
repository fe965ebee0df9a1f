//! Writing a recording: reads a simulation trace (`trace.jsonl`, one line per step and
//! robot, see `poinav_sim::trace`) line by line and streams ROS 2 messages into an MCAP file
//! (profile `ros2`, schemas `ros2msg`, messages `cdr`, uncompressed chunks), published
//! atomically at the end. Log time = publish time = header stamp = [`START_NS`] + step × dt.
//!
//! Topics: `/map` (`nav_msgs/msg/OccupancyGrid`, once at the start) and `/poi/markers`
//! (`visualization_msgs/msg/MarkerArray`, at the start and again at each step where a door's
//! status changed), both latched (transient-local QoS in `offered_qos_profiles`); `/tf`
//! (`tf2_msgs/msg/TFMessage`, one per step: `map` → `odom` identity, `odom` →
//! `<robot>/base_link` per robot); per robot `/<robot>/scan` (`sensor_msgs/msg/LaserScan`)
//! and `/<robot>/odom` (`nav_msgs/msg/Odometry`), one per trace line; `/poi/events`
//! (`std_msgs/msg/String`, one JSON object per event: the trace's event fields plus `step`,
//! `t` and `robot`).

use std::collections::BTreeMap;
use std::io::{BufRead, BufReader, Write};
use std::path::Path;

use mcap::records::MessageHeader;
use poinav_nav::door_status::classified_status;
use poinav_nav::Floor;
use poinav_roles::RobotProfile;
use serde::Deserialize;
use serde_json::Value;

use crate::error::McapError;
use crate::map::StoreyMap;
use crate::markers::floor_markers;
use crate::msgs::{self, LaserScan, OccupancyGrid, Odometry, Pose2, Stamp, Transform};
use crate::schema::{self, Schema};

/// Log time of step 0: 2025-01-01T00:00:00Z in nanoseconds (fixed, so equal runs give equal
/// files).
pub const START_NS: u64 = 1_735_689_600_000_000_000;

/// The scan's first beam, degrees (the sensor's rays are at 0, ±30 and ±90 degrees).
pub const SCAN_MIN_DEG: f64 = -90.0;
/// Degrees between beams; the ±60 degree beams have no ray and are NaN.
pub const SCAN_STEP_DEG: f64 = 30.0;
/// Beams per scan.
pub const SCAN_BEAMS: usize = 7;
/// The sensor's range, metres (`range_max`).
pub const RANGE_MAX_M: f32 = 5.0;

/// The ROS 2 distribution whose message definitions the recordings use.
pub const ROS_DISTRO: &str = "jazzy";

/// What a recording shows besides the trace.
#[derive(Debug, Clone, Copy)]
pub struct Scene<'a> {
    /// The storey the robots ran on (markers).
    pub floor: &'a Floor,
    /// The profile of the run's POI database (the enrichment's): the doors' statuses before
    /// the run changes them.
    pub profile: &'a RobotProfile,
    /// Its map (`/map`).
    pub map: &'a StoreyMap,
    /// The simulation's step, seconds.
    pub dt: f64,
}

/// What was written.
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub struct RecordSummary {
    /// Robot names, in trace order, with their ROS names (topic prefix and frame).
    pub robots: Vec<(String, String)>,
    /// Steps recorded.
    pub steps: u64,
    /// Messages per topic.
    pub messages: BTreeMap<String, u64>,
}

impl RecordSummary {
    /// Every message.
    pub fn total(&self) -> u64 {
        self.messages.values().sum()
    }
}

#[derive(Deserialize)]
struct Ray {
    deg: f64,
    d: Option<f64>,
}

#[derive(Deserialize)]
struct Line {
    step: u64,
    robot: String,
    x: f64,
    y: f64,
    heading_deg: f64,
    speed: f64,
    omega_deg_s: f64,
    rays: Vec<Ray>,
    #[serde(default)]
    events: Vec<serde_json::Map<String, Value>>,
}

/// A ROS graph name for a robot: letters, digits and `_` kept, anything else `_`, `r_` before
/// a leading digit (or an empty name), and `_2`, `_3`, ... when an earlier robot took it.
pub fn ros_name(name: &str, taken: &[(String, String)]) -> String {
    let mut s: String = name
        .chars()
        .map(|c| if c.is_ascii_alphanumeric() { c } else { '_' })
        .collect();
    if s.is_empty() || s.starts_with(|c: char| c.is_ascii_digit()) {
        s.insert_str(0, "r_");
    }
    let base = s.clone();
    let mut k = 2;
    while taken.iter().any(|(_, r)| *r == s) {
        s = format!("{base}_{k}");
        k += 1;
    }
    s
}

/// The `offered_qos_profiles` channel metadata rosbag2 writes (integer enums of rmw: history
/// 1 keep-last, reliability 1 reliable, durability 1 transient-local or 2 volatile, liveliness
/// 1 automatic; zero durations are the defaults).
pub fn qos_profile(latched: bool) -> String {
    let (depth, durability) = if latched { (1, 1) } else { (10, 2) };
    format!(
        "- history: 1\n  depth: {depth}\n  reliability: 1\n  durability: {durability}\n  deadline:\n    sec: 0\n    nsec: 0\n  lifespan:\n    sec: 0\n    nsec: 0\n  liveliness: 1\n  liveliness_lease_duration:\n    sec: 0\n    nsec: 0\n  avoid_ros_namespace_conventions: false"
    )
}

struct Out<W: Write + std::io::Seek> {
    w: mcap::Writer<W>,
    path: std::path::PathBuf,
    schemas: BTreeMap<&'static str, u16>,
    channels: Vec<(String, u32)>,
    summary: RecordSummary,
}

impl<W: Write + std::io::Seek> Out<W> {
    fn err(&self, source: mcap::McapError) -> McapError {
        McapError::Mcap {
            path: self.path.clone(),
            source,
        }
    }

    fn channel(&mut self, topic: &str, schema: Schema, latched: bool) -> Result<u16, McapError> {
        let sid = match self.schemas.get(schema.name) {
            Some(&id) => id,
            None => {
                let id = self
                    .w
                    .add_schema(schema.name, "ros2msg", schema.text.as_bytes())
                    .map_err(|e| self.err(e))?;
                self.schemas.insert(schema.name, id);
                id
            }
        };
        let meta = BTreeMap::from([("offered_qos_profiles".to_string(), qos_profile(latched))]);
        let id = self
            .w
            .add_channel(sid, topic, "cdr", &meta)
            .map_err(|e| self.err(e))?;
        while self.channels.len() <= id as usize {
            self.channels.push((String::new(), 0));
        }
        self.channels[id as usize] = (topic.to_string(), 0);
        self.summary.messages.insert(topic.to_string(), 0);
        Ok(id)
    }

    fn write(&mut self, channel: u16, stamp: Stamp, data: &[u8]) -> Result<(), McapError> {
        let (topic, seq) = &mut self.channels[channel as usize];
        *seq += 1;
        let header = MessageHeader {
            channel_id: channel,
            sequence: *seq,
            log_time: stamp,
            publish_time: stamp,
        };
        *self.summary.messages.entry(topic.clone()).or_default() += 1;
        self.w
            .write_to_known_channel(&header, data)
            .map_err(|e| self.err(e))
    }
}

/// Per-step state: what the step's `/tf` holds and whether the markers must be republished.
struct Step {
    step: u64,
    transforms: Vec<(String, Pose2)>,
    statuses_changed: bool,
}

/// Each door's status when the run started, where the run changed it: the `from` of its first
/// `status-changed` event (a scenario may start every door PENDING_VALIDATION whatever the
/// floor says).
fn initial_statuses(
    trace: &mut dyn BufRead,
    trace_name: &str,
) -> Result<BTreeMap<String, String>, McapError> {
    let mut first = BTreeMap::new();
    let mut text = String::new();
    let mut lineno = 0u64;
    loop {
        text.clear();
        let n = trace.read_line(&mut text).map_err(|e| McapError::Io {
            path: trace_name.into(),
            source: e,
        })?;
        if n == 0 {
            return Ok(first);
        }
        lineno += 1;
        if !text.contains("\"status-changed\"") {
            continue;
        }
        let line: Line = serde_json::from_str(&text).map_err(|e| McapError::Trace {
            name: trace_name.to_string(),
            line: lineno,
            message: e.to_string(),
        })?;
        for ev in &line.events {
            if ev.get("kind").and_then(Value::as_str) != Some("status-changed") {
                continue;
            }
            if let (Some(Value::String(id)), Some(Value::String(from))) =
                (ev.get("element"), ev.get("from"))
            {
                first.entry(id.clone()).or_insert_with(|| from.clone());
            }
        }
    }
}

/// Writes the recording of the trace file `trace` and `scene` to `out` (written to a
/// temporary file beside it, renamed at the end). The trace is read twice: once for the
/// doors' starting statuses, once for the messages.
pub fn write_recording(
    trace: &Path,
    scene: &Scene<'_>,
    out: &Path,
) -> Result<RecordSummary, McapError> {
    let open = || -> Result<Box<dyn BufRead>, std::io::Error> {
        Ok(Box::new(BufReader::new(std::fs::File::open(trace)?)))
    };
    write_recording_from(&open, trace, scene, out)
}

/// [`write_recording`] of the JSON Lines trace `open` opens (called twice, each time from its
/// start), `trace` naming it in errors: another format read as JSON Lines (the simulator's
/// compact trace through `poinav_sim::trace_bin::TraceLines::into_jsonl`).
pub fn write_recording_from(
    open: &dyn Fn() -> Result<Box<dyn BufRead>, std::io::Error>,
    trace: &Path,
    scene: &Scene<'_>,
    out: &Path,
) -> Result<RecordSummary, McapError> {
    let trace_name = trace.display().to_string();
    let open = || {
        open().map_err(|e| McapError::Io {
            path: trace.to_path_buf(),
            source: e,
        })
    };
    let start = initial_statuses(&mut open()?, &trace_name)?;
    let mut reader = open()?;
    let io = |e: std::io::Error| McapError::Io {
        path: out.to_path_buf(),
        source: e,
    };
    let file = poinav_io::AtomicFile::create(out).map_err(io)?;
    let opts = mcap::WriteOptions::new()
        .profile("ros2")
        .library("poinav-mcap")
        .compression(None);
    let w = opts.create(file).map_err(|e| McapError::Mcap {
        path: out.to_path_buf(),
        source: e,
    })?;
    let mut o = Out {
        w,
        path: out.to_path_buf(),
        schemas: BTreeMap::new(),
        channels: Vec::new(),
        summary: RecordSummary::default(),
    };
    record(&mut o, &mut reader, &trace_name, scene, start)?;
    o.w.finish().map_err(|e| o.err(e))?;
    o.w.into_inner().commit().map_err(io)?;
    Ok(o.summary)
}

fn record<W: Write + std::io::Seek>(
    o: &mut Out<W>,
    trace: &mut dyn BufRead,
    trace_name: &str,
    scene: &Scene<'_>,
    mut statuses: BTreeMap<String, String>,
) -> Result<(), McapError> {
    let stamp_of = |step: u64| START_NS + (step as f64 * scene.dt * 1e9).round() as u64;
    // What rosbag2's MCAP plugin reads: with a `rosbag2` record that has no
    // `serialized_metadata` it takes the channels' QoS profiles in the integer form of
    // metadata versions up to 8, which Humble and Jazzy both read.
    let meta = mcap::records::Metadata {
        name: "rosbag2".into(),
        metadata: BTreeMap::from([("ROS_DISTRO".to_string(), ROS_DISTRO.to_string())]),
    };
    o.w.write_metadata(&meta).map_err(|e| o.err(e))?;
    let map_ch = o.channel("/map", schema::occupancy_grid(), true)?;
    let markers_ch = o.channel("/poi/markers", schema::marker_array(), true)?;
    let tf_ch = o.channel("/tf", schema::tf_message(), false)?;
    let events_ch = o.channel("/poi/events", schema::string(), false)?;

    let m = scene.map;
    let grid = OccupancyGrid {
        stamp: START_NS,
        frame: "map",
        resolution: m.resolution_m as f32,
        width: m.width as u32,
        height: m.height as u32,
        origin: Pose2 {
            x: m.origin.x,
            y: m.origin.y,
            yaw: 0.0,
        },
        data: &m.data,
    }
    .encode();
    o.write(map_ch, START_NS, &grid)?;
    let bytes = msgs::marker_array(
        START_NS,
        "map",
        &floor_markers(scene.floor, scene.profile, &statuses),
    );
    o.write(markers_ch, START_NS, &bytes)?;

    // Per robot: ROS name, frame, scan and odom channels.
    let mut robots: BTreeMap<String, (String, String, u16, u16)> = BTreeMap::new();
    let mut cur: Option<Step> = None;
    let mut text = String::new();
    let mut lineno = 0u64;
    let bad = |line: u64, message: String| McapError::Trace {
        name: trace_name.to_string(),
        line,
        message,
    };
    loop {
        text.clear();
        let n = trace.read_line(&mut text).map_err(|e| McapError::Io {
            path: trace_name.into(),
            source: e,
        })?;
        lineno += 1;
        let line: Option<Line> = if n == 0 {
            None
        } else if text.trim().is_empty() {
            continue;
        } else {
            Some(serde_json::from_str(&text).map_err(|e| bad(lineno, e.to_string()))?)
        };
        // A new step (or the end) closes the current one: its /tf, its markers.
        let next_step = line.as_ref().map(|l| l.step);
        if let Some(s) = cur.as_ref().filter(|s| Some(s.step) != next_step) {
            let stamp = stamp_of(s.step);
            let mut tfs = vec![Transform {
                stamp,
                parent: "map",
                child: "odom",
                pose: Pose2 {
                    x: 0.0,
                    y: 0.0,
                    yaw: 0.0,
                },
            }];
            tfs.extend(s.transforms.iter().map(|(frame, pose)| Transform {
                stamp,
                parent: "odom",
                child: frame,
                pose: *pose,
            }));
            o.write(tf_ch, stamp, &msgs::tf_message(&tfs))?;
            if s.statuses_changed {
                let bytes = msgs::marker_array(
                    stamp,
                    "map",
                    &floor_markers(scene.floor, scene.profile, &statuses),
                );
                o.write(markers_ch, stamp, &bytes)?;
            }
            o.summary.steps += 1;
            cur = None;
        }
        let Some(line) = line else { break };
        if cur.is_none() {
            cur = Some(Step {
                step: line.step,
                transforms: Vec::new(),
                statuses_changed: false,
            });
        }
        let s = cur.as_mut().expect("set above");
        if !robots.contains_key(&line.robot) {
            let ros = ros_name(&line.robot, &o.summary.robots);
            o.summary.robots.push((line.robot.clone(), ros.clone()));
            let scan = o.channel(&format!("/{ros}/scan"), schema::laser_scan(), false)?;
            let odom = o.channel(&format!("/{ros}/odom"), schema::odometry(), false)?;
            robots.insert(
                line.robot.clone(),
                (ros.clone(), format!("{ros}/base_link"), scan, odom),
            );
        }
        let (_, frame, scan_ch, odom_ch) = &robots[&line.robot];
        let stamp = stamp_of(line.step);
        let mut ranges = [f32::NAN; SCAN_BEAMS];
        for r in &line.rays {
            let k = (r.deg - SCAN_MIN_DEG) / SCAN_STEP_DEG;
            if !(k >= 0.0 && k <= (SCAN_BEAMS - 1) as f64 && k.fract() == 0.0) {
                return Err(bad(
                    lineno,
                    format!(
                        "a ray at {} degrees is not on the scan's 30 degree grid",
                        r.deg
                    ),
                ));
            }
            ranges[k as usize] = r.d.map_or(f32::NAN, |d| d as f32);
        }
        let scan = LaserScan {
            stamp,
            frame,
            angle_min: SCAN_MIN_DEG.to_radians() as f32,
            increment: SCAN_STEP_DEG.to_radians() as f32,
            scan_time: scene.dt as f32,
            range_max: RANGE_MAX_M,
            ranges: &ranges,
        }
        .encode();
        o.write(*scan_ch, stamp, &scan)?;
        let pose = Pose2 {
            x: line.x,
            y: line.y,
            yaw: line.heading_deg.to_radians(),
        };
        let odom = Odometry {
            stamp,
            frame: "odom",
            child: frame,
            pose,
            speed: line.speed,
            omega: line.omega_deg_s.to_radians(),
        }
        .encode();
        o.write(*odom_ch, stamp, &odom)?;
        s.transforms.push((frame.clone(), pose));
        for ev in line.events {
            let kind = ev.get("kind").and_then(Value::as_str).unwrap_or("");
            let door_status = match kind {
                "status-changed" => ev.get("element").zip(ev.get("to")),
                "clearance" => ev.get("door").zip(ev.get("status")),
                _ => None,
            };
            if let Some((Value::String(id), Value::String(to))) = door_status {
                let now = statuses.get(id).map(String::as_str).or_else(|| {
                    let d = scene.floor.doors.iter().find(|d| &d.id == id)?;
                    Some(classified_status(d, scene.profile).0.label())
                });
                if now.is_some_and(|now| now != to) {
                    statuses.insert(id.clone(), to.clone());
                    s.statuses_changed = true;
                }
            }
            let mut obj = ev;
            obj.insert("step".into(), Value::from(line.step));
            let t = (line.step as f64 * scene.dt * 1e6).round() / 1e6;
            obj.insert("t".into(), Value::from(t));
            obj.insert("robot".into(), Value::from(line.robot.clone()));
            let json = serde_json::to_string(&obj).expect("events are JSON");
            o.write(events_ch, stamp, &msgs::string(&json))?;
        }
    }
    Ok(())
}
