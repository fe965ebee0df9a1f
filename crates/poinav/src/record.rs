//! `poinav serve --record FILE`: the live simulation's states, as the pages get them, written
//! as trace lines while the server runs, then turned into a ROS 2 recording
//! (`poinav_mcap`) when it stops. Only the storey shown first is recorded, until a page
//! switches storey or starts again; paused steps are recorded once; states a slow recorder
//! skipped are missing (it writes to a buffered file, so it does not fall behind in practice).
//! The states have no turn rate: it is the heading's change since the robot's previous
//! recorded step.

use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};
use std::sync::Arc;

use anyhow::Context;
use poinav_nav::Floor;
use poinav_poi::RobotProfile;
use serde_json::{json, Value};
use tokio::sync::broadcast;

/// Trace lines being written from the live states.
pub struct LiveTrace {
    file: BufWriter<tempfile::NamedTempFile>,
    storey: Option<u64>,
    last_step: Option<u64>,
    stopped: bool,
    dt: f64,
    headings: std::collections::BTreeMap<String, (u64, f64)>,
}

impl LiveTrace {
    /// A trace in a temporary file beside `target`, of a simulation stepped every `dt` s.
    pub fn new(target: &Path, dt: f64) -> anyhow::Result<LiveTrace> {
        let dir = match target.parent() {
            Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
            _ => PathBuf::from("."),
        };
        let tmp = tempfile::Builder::new()
            .prefix(&format!(".poinav-{}-", std::process::id()))
            .suffix(".tmp")
            .tempfile_in(&dir)
            .with_context(|| format!("--record: cannot write in {}", dir.display()))?;
        Ok(LiveTrace {
            file: BufWriter::new(tmp),
            storey: None,
            last_step: None,
            stopped: false,
            dt,
            headings: std::collections::BTreeMap::new(),
        })
    }

    /// Takes in one state (the viewer's `{"type":"state",...}` JSON).
    pub fn add(&mut self, state: &str) -> std::io::Result<()> {
        let Ok(v) = serde_json::from_str::<Value>(state) else {
            return Ok(());
        };
        let (Some(step), Some(storey)) = (v["step"].as_u64(), v["storey"].as_u64()) else {
            return Ok(());
        };
        if self.stopped || self.last_step == Some(step) {
            return Ok(());
        }
        if *self.storey.get_or_insert(storey) != storey || self.last_step.is_some_and(|l| step < l)
        {
            self.stopped = true;
            return Ok(());
        }
        self.last_step = Some(step);
        let empty = Vec::new();
        let events = v["events"].as_array().unwrap_or(&empty);
        for r in v["robots"].as_array().unwrap_or(&empty) {
            let name = r["name"].as_str().unwrap_or_default();
            let mine: Vec<&Value> = events
                .iter()
                .filter(|e| e["robot"].as_str() == Some(name))
                .collect();
            let rays: Vec<Value> = r["rays"]
                .as_array()
                .unwrap_or(&empty)
                .iter()
                .map(|ray| json!({"deg": ray["deg"], "d": ray["d"]}))
                .collect();
            let heading = r["heading_deg"].as_f64().unwrap_or(0.0);
            let omega = match self.headings.insert(name.to_string(), (step, heading)) {
                Some((s0, h0)) if step > s0 => {
                    let turn = (heading - h0 + 540.0).rem_euclid(360.0) - 180.0;
                    turn / ((step - s0) as f64 * self.dt)
                }
                _ => 0.0,
            };
            let line = json!({
                "step": step,
                "robot": name,
                "x": r["x"],
                "y": r["y"],
                "heading_deg": r["heading_deg"],
                "speed": r["speed"],
                "omega_deg_s": omega,
                "rays": rays,
                "events": mine,
            });
            serde_json::to_writer(&mut self.file, &line)?;
            self.file.write_all(b"\n")?;
        }
        Ok(())
    }

    /// Writes the recording of what was taken in to `target`.
    pub fn finish(
        self,
        target: &Path,
        floor: &Floor,
        profile: &RobotProfile,
        dt: f64,
    ) -> anyhow::Result<poinav_mcap::RecordSummary> {
        let tmp = self
            .file
            .into_inner()
            .map_err(|e| anyhow::anyhow!("--record: {}", e.error()))?;
        let map = poinav_mcap::storey_map(floor, profile, &poinav_nav::Nav2Options::default())?;
        let scene = poinav_mcap::Scene {
            floor,
            profile,
            map: &map,
            dt,
        };
        Ok(poinav_mcap::write_recording(tmp.path(), &scene, target)?)
    }
}

/// Records every state `rx` gets into `trace` until the channel closes.
pub async fn record_states(
    mut rx: broadcast::Receiver<Arc<str>>,
    trace: Arc<std::sync::Mutex<LiveTrace>>,
) {
    loop {
        match rx.recv().await {
            Ok(state) => {
                let mut t = trace.lock().unwrap_or_else(|e| e.into_inner());
                if t.add(&state).is_err() {
                    t.stopped = true;
                }
            }
            Err(broadcast::error::RecvError::Lagged(_)) => {}
            Err(broadcast::error::RecvError::Closed) => return,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn state(step: u64, storey: u64, heading: f64) -> String {
        json!({"type": "state", "step": step, "storey": storey, "robots": [
            {"name": "R", "x": 1.0, "y": 2.0, "heading_deg": heading, "speed": 0.5,
             "rays": [{"deg": 0.0, "d": 1.25, "hit": null}]}
        ], "events": [{"kind": "brush", "on": true, "robot": "R"}, {"kind": "x", "robot": "S"}]})
        .to_string()
    }

    #[test]
    fn states_become_trace_lines_once_per_step_on_the_first_storey() {
        let tmp = tempfile::tempdir().unwrap();
        let mut t = LiveTrace::new(&tmp.path().join("x.mcap"), 0.5).unwrap();
        t.add(&state(1, 0, 170.0)).unwrap();
        t.add(&state(1, 0, 170.0)).unwrap(); // paused: the same step again
        t.add(&state(2, 0, -170.0)).unwrap(); // +20 degrees across 180 in 0.5 s
        t.add(&state(3, 1, 0.0)).unwrap(); // another storey: recording stops
        t.add(&state(4, 0, 0.0)).unwrap();
        let file = t.file.into_inner().unwrap();
        let text = std::fs::read_to_string(file.path()).unwrap();
        let lines: Vec<Value> = text
            .lines()
            .map(|l| serde_json::from_str(l).unwrap())
            .collect();
        assert_eq!(lines.len(), 2);
        assert_eq!(lines[0]["omega_deg_s"], 0.0);
        assert!((lines[1]["omega_deg_s"].as_f64().unwrap() - 40.0).abs() < 1e-9);
        assert_eq!(lines[1]["rays"], json!([{"deg": 0.0, "d": 1.25}]));
        // Each robot's line carries its own events only.
        assert_eq!(
            lines[0]["events"],
            json!([{"kind": "brush", "on": true, "robot": "R"}])
        );
    }
}
