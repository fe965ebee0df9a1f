//! The compact trace (`trace.bin`, `--trace-format bin`): the JSON Lines trace's records as
//! fixed-size little-endian records, the names written once in a JSON header, and the one
//! reader of both formats ([`read_lines`]), which gives back the JSON Lines trace's lines byte
//! for byte (every number is stored as its `f64` bits and rendered by [`LineWriter`]).
//!
//! Layout: [`MAGIC`], the header's length (`u32`), the header (JSON: format, version,
//! record size, then the [`Names`] lists), then per robot and kept step a record of
//! [`RECORD_BYTES`] followed by its events (the text inside the JSON line's events array,
//! UTF-8, usually empty). A record: `step` u64, `robot` u32, mode u8, brush on u8, roles u16,
//! zone u32 (`u32::MAX`: none), events' length u32, then `t`, x, y, heading (rad), speed,
//! omega (rad/s), the command's v and omega (rad/s) and the brush angle (deg) as f64, then five
//! rays of 32 bytes: distance f64, target index u32, target kind u8 (0 none, 1 obstacle,
//! 2 robot), count of doors looked through u8, two bytes of padding, four door indices u32.

use std::io::BufRead;

use poinav_nav::ZoneIdx;

use crate::controller::{Command, Mode};
use crate::error::SimError;
use crate::events::Event;
use crate::poi_db::RoleSet;
use crate::robot::Brush;
use crate::trace::{events_json, LineWriter, Names, StepRecord};
use crate::world::{Passages, RayHit, Target};

/// The first bytes of a compact trace (a JSON Lines trace starts with `{`).
pub const MAGIC: &[u8; 8] = b"PNVTRACE";

/// The format's version in the header.
pub const VERSION: u32 = 1;

/// Bytes of one record before its events.
pub const RECORD_BYTES: usize = 96 + 5 * RAY_BYTES;

const RAY_BYTES: usize = 32;

/// The header: [`MAGIC`], its length and the JSON text naming the indices records use.
pub fn header(names: &Names) -> Vec<u8> {
    let json = serde_json::json!({
        "format": "poinav-trace-bin",
        "version": VERSION,
        "record_bytes": RECORD_BYTES,
        "robots": names.robots,
        "robot_ids": names.robot_ids,
        "obstacles": names.obstacles,
        "obstacle_classes": names.obstacle_classes,
        "doors": names.doors,
        "zones": names.zones,
    })
    .to_string();
    let mut out = MAGIC.to_vec();
    out.extend_from_slice(&(json.len() as u32).to_le_bytes());
    out.extend_from_slice(json.as_bytes());
    out
}

fn mode_code(m: Mode) -> u8 {
    match m {
        Mode::Idle => 0,
        Mode::Route => 1,
        Mode::WallFollow => 2,
        Mode::Keys => 3,
        Mode::Arrived => 4,
    }
}

fn mode_of(code: u8) -> Option<Mode> {
    Some(match code {
        0 => Mode::Idle,
        1 => Mode::Route,
        2 => Mode::WallFollow,
        3 => Mode::Keys,
        4 => Mode::Arrived,
        _ => return None,
    })
}

/// Appends the record of `r` at time `t` and its `events` to `out`.
pub fn record_into(out: &mut Vec<u8>, r: &StepRecord, t: f64, events: &[&Event]) {
    let text = if events.is_empty() {
        String::new()
    } else {
        events_json(events)
    };
    let mut b = [0u8; RECORD_BYTES];
    b[0..8].copy_from_slice(&r.step.to_le_bytes());
    b[8..12].copy_from_slice(&r.robot.to_le_bytes());
    b[12] = mode_code(r.mode);
    b[13] = u8::from(r.brush.on);
    b[14..16].copy_from_slice(&r.roles.0.to_le_bytes());
    // No zone is u32::MAX in the file.
    let zone = r.zone.map_or(u32::MAX, |z| z.get() as u32);
    b[16..20].copy_from_slice(&zone.to_le_bytes());
    b[20..24].copy_from_slice(&(text.len() as u32).to_le_bytes());
    let nums = [
        t,
        r.pos.x,
        r.pos.y,
        r.heading,
        r.speed,
        r.omega,
        r.action.v,
        r.action.omega,
        r.brush.angle_deg,
    ];
    for (k, v) in nums.iter().enumerate() {
        b[24 + 8 * k..32 + 8 * k].copy_from_slice(&v.to_le_bytes());
    }
    for (k, ray) in r.rays.iter().enumerate() {
        let o = 96 + k * RAY_BYTES;
        b[o..o + 8].copy_from_slice(&ray.dist.to_le_bytes());
        let (kind, index) = match ray.target {
            Target::None => (0u8, 0u32),
            Target::Obstacle(i) => (1, i),
            Target::Robot(i) => (2, i),
        };
        b[o + 8..o + 12].copy_from_slice(&index.to_le_bytes());
        b[o + 12] = kind;
        let doors = ray.passages.doors();
        b[o + 13] = doors.len() as u8;
        for (n, d) in doors.iter().enumerate() {
            b[o + 16 + 4 * n..o + 20 + 4 * n].copy_from_slice(&d.to_le_bytes());
        }
    }
    out.extend_from_slice(&b);
    out.extend_from_slice(text.as_bytes());
}

fn u32_at(b: &[u8], o: usize) -> u32 {
    u32::from_le_bytes(b[o..o + 4].try_into().expect("4 bytes"))
}

fn f64_at(b: &[u8], o: usize) -> f64 {
    f64::from_le_bytes(b[o..o + 8].try_into().expect("8 bytes"))
}

/// Decodes a record (its events' length and its time beside it); `None` when it names a
/// mode, target kind or index the header does not have.
fn decode(b: &[u8; RECORD_BYTES], names: &Names) -> Option<(StepRecord, f64, usize)> {
    let robot = u32_at(b, 8);
    if robot as usize >= names.robots.len() {
        return None;
    }
    let zone = match u32_at(b, 16) {
        u32::MAX => None,
        z if (z as usize) < names.zones.len() => Some(ZoneIdx::new(z as usize)),
        _ => return None,
    };
    let mut rays = [RayHit::NONE; 5];
    for (k, ray) in rays.iter_mut().enumerate() {
        let o = 96 + k * RAY_BYTES;
        let index = u32_at(b, o + 8);
        ray.dist = f64_at(b, o);
        ray.target = match b[o + 12] {
            0 => Target::None,
            1 if (index as usize) < names.obstacles.len() => Target::Obstacle(index),
            2 if (index as usize) < names.robot_ids.len() => Target::Robot(index),
            _ => return None,
        };
        let n = b[o + 13] as usize;
        if n > Passages::CAP {
            return None;
        }
        let doors: Vec<u32> = (0..n).map(|i| u32_at(b, o + 16 + 4 * i)).collect();
        if doors.iter().any(|&d| d as usize >= names.doors.len()) {
            return None;
        }
        ray.passages = Passages::of_doors(&doors);
    }
    let num = |k: usize| f64_at(b, 24 + 8 * k);
    let record = StepRecord {
        step: u64::from_le_bytes(b[0..8].try_into().expect("8 bytes")),
        robot,
        pos: glam::DVec2::new(num(1), num(2)),
        heading: num(3),
        speed: num(4),
        omega: num(5),
        action: Command {
            v: num(6),
            omega: num(7),
        },
        rays,
        roles: RoleSet(u16::from_le_bytes([b[14], b[15]])),
        mode: mode_of(b[12])?,
        zone,
        brush: Brush {
            on: b[13] != 0,
            angle_deg: num(8),
            ..Brush::paper()
        },
    };
    Some((record, num(0), u32_at(b, 20) as usize))
}

enum Source<R> {
    Jsonl(R),
    Bin { read: R, writer: LineWriter },
}

/// The lines of a trace in either format (see [`read_lines`]).
#[allow(missing_debug_implementations)]
pub struct TraceLines<R> {
    source: Source<R>,
    name: String,
    /// Names of the compact trace's header (empty for JSON Lines).
    names: Names,
    done: bool,
}

impl<R> TraceLines<R> {
    fn err(&mut self, message: String) -> Option<Result<String, SimError>> {
        self.done = true;
        Some(Err(SimError::Io {
            path: self.name.clone(),
            message,
        }))
    }

    /// The names the compact trace's header holds (empty lists for a JSON Lines trace).
    pub fn names(&self) -> &Names {
        &self.names
    }
}

/// Reads the trace `read` holds, JSON Lines or compact (told apart by [`MAGIC`]), as JSON Lines
/// (without their newlines): a compact trace's lines are those the JSON Lines trace of the same
/// run holds, byte for byte. `name` names the trace in errors.
pub fn read_lines<R: BufRead>(mut read: R, name: &str) -> Result<TraceLines<R>, SimError> {
    let io = |message: String| SimError::Io {
        path: name.to_string(),
        message,
    };
    let head = read.fill_buf().map_err(|e| io(e.to_string()))?;
    // (A reader may hand out fewer bytes than the magic at first: a prefix of it counts.)
    let compact = !head.is_empty() && (head.starts_with(MAGIC) || MAGIC.starts_with(head));
    if !compact {
        return Ok(TraceLines {
            source: Source::Jsonl(read),
            name: name.to_string(),
            names: Names::default(),
            done: false,
        });
    }
    let mut start = [0u8; 12];
    read.read_exact(&mut start)
        .map_err(|e| io(format!("compact trace header: {e}")))?;
    let len = u32::from_le_bytes(start[8..12].try_into().expect("4 bytes")) as usize;
    let mut json = vec![0u8; len];
    read.read_exact(&mut json)
        .map_err(|e| io(format!("compact trace header: {e}")))?;
    let v: serde_json::Value =
        serde_json::from_slice(&json).map_err(|e| io(format!("compact trace header: {e}")))?;
    if v["version"] != VERSION || v["record_bytes"] != RECORD_BYTES {
        return Err(io(format!(
            "compact trace version {} with records of {} bytes (this reader: {VERSION}, {RECORD_BYTES})",
            v["version"], v["record_bytes"]
        )));
    }
    let list = |key: &str| -> Result<Vec<String>, SimError> {
        serde_json::from_value(v[key].clone())
            .map_err(|e| io(format!("compact trace header `{key}`: {e}")))
    };
    let names = Names {
        robots: list("robots")?,
        robot_ids: list("robot_ids")?,
        obstacles: list("obstacles")?,
        obstacle_classes: list("obstacle_classes")?,
        doors: list("doors")?,
        zones: list("zones")?,
    };
    if names.obstacle_classes.len() != names.obstacles.len() {
        return Err(io("compact trace header: obstacles without classes".into()));
    }
    Ok(TraceLines {
        source: Source::Bin {
            read,
            writer: LineWriter::new(&names),
        },
        name: name.to_string(),
        names,
        done: false,
    })
}

/// [`read_lines`] of the file at `path`.
pub fn read_file(
    path: &std::path::Path,
) -> Result<TraceLines<std::io::BufReader<std::fs::File>>, SimError> {
    let name = path.display().to_string();
    let file = std::fs::File::open(path).map_err(|e| SimError::Io {
        path: name.clone(),
        message: e.to_string(),
    })?;
    read_lines(std::io::BufReader::with_capacity(1 << 16, file), &name)
}

impl<R: BufRead> Iterator for TraceLines<R> {
    type Item = Result<String, SimError>;

    fn next(&mut self) -> Option<Self::Item> {
        if self.done {
            return None;
        }
        let (read, writer) = match &mut self.source {
            Source::Jsonl(read) => {
                let mut line = String::new();
                return match read.read_line(&mut line) {
                    Ok(0) => {
                        self.done = true;
                        None
                    }
                    Ok(_) => {
                        if line.ends_with('\n') {
                            line.pop();
                        }
                        Some(Ok(line))
                    }
                    Err(e) => self.err(e.to_string()),
                };
            }
            Source::Bin { read, writer } => (read, writer),
        };
        match read.fill_buf() {
            Ok([]) => {
                self.done = true;
                return None;
            }
            Ok(_) => {}
            Err(e) => return self.err(e.to_string()),
        }
        let mut b = [0u8; RECORD_BYTES];
        if let Err(e) = read.read_exact(&mut b) {
            return self.err(format!("truncated record: {e}"));
        }
        let Some((record, t, events_len)) = decode(&b, &self.names) else {
            return self.err("a record names an index its header does not have".into());
        };
        let mut events = vec![0u8; events_len];
        if let Err(e) = read.read_exact(&mut events) {
            return self.err(format!("truncated events: {e}"));
        }
        let mut out = Vec::with_capacity(1100 + events_len);
        writer.line_with(&mut out, &record, t, |out| out.extend_from_slice(&events));
        match String::from_utf8(out) {
            Ok(line) => Some(Ok(line)),
            Err(_) => self.err("events are not UTF-8".into()),
        }
    }
}

/// The lines of a trace in either format as a JSON Lines byte stream, each line with its
/// newline (see [`TraceLines::into_jsonl`]): what a reader of `trace.jsonl` takes, so one
/// reader serves both formats (`poinav simulate --trace-format bin --mcap`).
#[allow(missing_debug_implementations)]
pub struct JsonlStream<R> {
    lines: TraceLines<R>,
    line: Vec<u8>,
    at: usize,
}

impl<R> TraceLines<R> {
    /// These lines as a JSON Lines byte stream; an error reading them is an
    /// [`std::io::Error`] whose source is the [`SimError`].
    pub fn into_jsonl(self) -> JsonlStream<R> {
        JsonlStream {
            lines: self,
            line: Vec::new(),
            at: 0,
        }
    }
}

impl<R: BufRead> std::io::Read for JsonlStream<R> {
    fn read(&mut self, out: &mut [u8]) -> std::io::Result<usize> {
        let have = self.fill_buf()?;
        let n = have.len().min(out.len());
        out[..n].copy_from_slice(&have[..n]);
        self.consume(n);
        Ok(n)
    }
}

impl<R: BufRead> BufRead for JsonlStream<R> {
    fn fill_buf(&mut self) -> std::io::Result<&[u8]> {
        if self.at == self.line.len() {
            match self.lines.next() {
                None => return Ok(&[]),
                Some(Err(e)) => return Err(std::io::Error::other(e)),
                Some(Ok(line)) => {
                    self.line.clear();
                    self.line.extend_from_slice(line.as_bytes());
                    self.line.push(b'\n');
                    self.at = 0;
                }
            }
        }
        Ok(&self.line[self.at..])
    }

    fn consume(&mut self, n: usize) {
        self.at = (self.at + n).min(self.line.len());
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{TraceFormat, TraceOut};

    fn traced(file: &str, variant: Option<&str>, every: u64, format: TraceFormat) -> Vec<u8> {
        let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("scenarios");
        let scenario = crate::Scenario::load(&dir.join(file)).unwrap();
        let floor = crate::test_floor::prepared(&scenario, variant);
        let mut buf = Vec::new();
        let out = TraceOut {
            writer: &mut buf,
            every,
            name: "t".into(),
            format,
        };
        crate::run_with(&scenario, variant, &floor, Some(out)).unwrap();
        buf
    }

    #[test]
    fn a_compact_trace_streams_as_the_bytes_of_the_json_lines_trace() {
        use std::io::Read;
        let jsonl = traced("doorway.toml", Some("door-0.80"), 1, TraceFormat::Jsonl);
        let bin = traced("doorway.toml", Some("door-0.80"), 1, TraceFormat::Bin);
        assert!(
            bin.len() < jsonl.len() / 2,
            "{} vs {}",
            bin.len(),
            jsonl.len()
        );
        for source in [&bin, &jsonl] {
            let mut out = Vec::new();
            read_lines(source.as_slice(), "t")
                .unwrap()
                .into_jsonl()
                .read_to_end(&mut out)
                .unwrap();
            assert!(out == jsonl, "{} vs {} bytes", out.len(), jsonl.len());
        }
        // A damaged record is an I/O error carrying the trace's name.
        let cut = &bin[..bin.len() - 7];
        let mut out = Vec::new();
        let e = read_lines(cut, "cut.bin")
            .unwrap()
            .into_jsonl()
            .read_to_end(&mut out)
            .unwrap_err();
        assert!(e.to_string().contains("cut.bin"), "{e}");
        assert!(e.to_string().contains("truncated"), "{e}");
    }

    fn lines(bytes: &[u8]) -> Vec<String> {
        read_lines(bytes, "t")
            .unwrap()
            .collect::<Result<_, _>>()
            .unwrap()
    }

    /// Two shipped scenarios in full and thinned (rays through doors, hits on robots, events):
    /// the compact trace read back is the JSON Lines trace, line for line and byte for byte.
    #[test]
    fn compact_trace_reads_back_as_the_json_lines_trace() {
        let mut checked = 0;
        for (file, variant, every) in [
            ("doorway.toml", Some("door-0.80"), 1),
            ("yield.toml", None, 1),
            ("yield.toml", None, 7),
        ] {
            let jsonl = traced(file, variant, every, TraceFormat::Jsonl);
            let bin = traced(file, variant, every, TraceFormat::Bin);
            assert!(bin.starts_with(MAGIC));
            let want: Vec<String> = std::str::from_utf8(&jsonl)
                .unwrap()
                .lines()
                .map(str::to_string)
                .collect();
            assert!(want.len() > 100, "{file}: {} lines", want.len());
            assert_eq!(
                lines(&jsonl),
                want,
                "{file}: the JSON Lines read as they are"
            );
            let got = lines(&bin);
            assert_eq!(got.len(), want.len(), "{file}");
            for (k, (g, w)) in got.iter().zip(&want).enumerate() {
                assert_eq!(g, w, "{file} line {k}");
            }
            assert!(
                bin.len() * 2 < jsonl.len(),
                "{file}: {} bytes compact, {} as JSON Lines",
                bin.len(),
                jsonl.len()
            );
            if every == 1 {
                assert!(want.iter().any(|l| l.contains("\"through\":[")));
                assert!(want.iter().any(|l| !l.ends_with("\"events\":[]}")));
            }
            checked += got.len();
        }
        assert!(checked > 1000, "{checked} lines");
    }

    #[test]
    fn damaged_compact_traces_are_errors_naming_the_trace() {
        let bin = traced("yield.toml", None, 1, TraceFormat::Bin);
        let all = lines(&bin).len();
        // Cut inside the last record (no events at the end of this run).
        let header = 12 + u32::from_le_bytes(bin[8..12].try_into().unwrap()) as usize;
        let cut = &bin[..bin.len() - 10];
        let read: Vec<_> = read_lines(cut, "cut.bin").unwrap().collect();
        assert_eq!(read.len(), all);
        assert!(read[..all - 1].iter().all(Result::is_ok));
        let e = read[all - 1].as_ref().unwrap_err().to_string();
        assert!(e.starts_with("cut.bin: truncated record"), "{e}");
        // A robot index the header does not have.
        let mut bad = bin.clone();
        bad[header + 8..header + 12].copy_from_slice(&999u32.to_le_bytes());
        let e = read_lines(&bad[..], "bad.bin")
            .unwrap()
            .next()
            .unwrap()
            .unwrap_err()
            .to_string();
        assert!(e.contains("index its header does not have"), "{e}");
        // A header of another version.
        let mut other = bin[..header].to_vec();
        let text = String::from_utf8(other[12..].to_vec()).unwrap();
        let text = text.replacen("\"version\":1", "\"version\":9", 1);
        other.truncate(8);
        other.extend_from_slice(&(text.len() as u32).to_le_bytes());
        other.extend_from_slice(text.as_bytes());
        let e = read_lines(&other[..], "v9.bin").err().unwrap().to_string();
        assert!(e.contains("version 9"), "{e}");
    }
}
