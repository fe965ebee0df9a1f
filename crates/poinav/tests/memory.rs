//! Resource limits: `poinav inspect --json` on generated ~50 MB and ~200 MB models (office-a.ifc repeated with offset ids) stays under 3x the file size in peak memory, reports exactly copies x office-a's counts, and takes time proportional to size.

mod common;

use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

use serde_json::Value;

/// office-a.ifc split into its header (through `DATA;`) and DATA body cut at every `#id`
/// outside strings: `text[0] id[0] text[1] id[1] ... text[n]`.
struct Template {
    header: Vec<u8>,
    texts: Vec<Vec<u8>>,
    ids: Vec<u64>,
    max_id: u64,
}

fn template() -> Template {
    let bytes = std::fs::read(common::shared().join("ifc/office-a.ifc")).unwrap();
    // Line ends may be CRLF: the body starts after `DATA;`'s line end, ends at `ENDSEC;`.
    let data = find(&bytes, b"\nDATA;").expect("DATA;");
    let start = data + bytes[data + 1..].iter().position(|&b| b == b'\n').unwrap() + 2;
    let end = rfind(&bytes, b"\nENDSEC;").expect("ENDSEC;") + 1;
    let body = &bytes[start..end];
    let (mut texts, mut ids) = (Vec::new(), Vec::new());
    let (mut i, mut from, mut in_string) = (0, 0, false);
    while i < body.len() {
        match body[i] {
            b'\'' => in_string = !in_string,
            b'#' if !in_string => {
                let digits = body[i + 1..]
                    .iter()
                    .take_while(|b| b.is_ascii_digit())
                    .count();
                if digits > 0 {
                    texts.push(body[from..=i].to_vec());
                    let n = std::str::from_utf8(&body[i + 1..i + 1 + digits]).unwrap();
                    ids.push(n.parse().unwrap());
                    i += digits;
                    from = i + 1;
                }
            }
            _ => {}
        }
        i += 1;
    }
    texts.push(body[from..].to_vec());
    let max_id = *ids.iter().max().unwrap();
    Template {
        header: bytes[..start].to_vec(),
        texts,
        ids,
        max_id,
    }
}

fn find(hay: &[u8], needle: &[u8]) -> Option<usize> {
    hay.windows(needle.len()).position(|w| w == needle)
}

fn rfind(hay: &[u8], needle: &[u8]) -> Option<usize> {
    hay.windows(needle.len()).rposition(|w| w == needle)
}

/// Writes `copies` copies of office-a's DATA section, ids offset per copy, through a
/// buffered writer; returns the file size.
fn generate(t: &Template, copies: u64, path: &Path) -> u64 {
    let mut w = BufWriter::with_capacity(1 << 20, std::fs::File::create(path).unwrap());
    w.write_all(&t.header).unwrap();
    for c in 0..copies {
        let offset = c * (t.max_id + 1);
        for (text, id) in t.texts.iter().zip(&t.ids) {
            w.write_all(text).unwrap();
            write!(w, "{}", id + offset).unwrap();
        }
        w.write_all(t.texts.last().unwrap()).unwrap();
    }
    w.write_all(b"ENDSEC;\nEND-ISO-10303-21;\n").unwrap();
    w.into_inner().unwrap().sync_all().unwrap();
    std::fs::metadata(path).unwrap().len()
}

/// One measured run: stdout, wall time, peak resident set in bytes.
struct Measured {
    stdout: Vec<u8>,
    time: Duration,
    peak_rss: u64,
}

/// Runs `poinav inspect FILE --json` and measures its peak RSS: with GNU time (`%M`) when
/// `/usr/bin/time` exists, else by polling `VmHWM` in `/proc/PID/status` every 2 ms (a lower
/// bound missing at most the last poll interval's growth).
fn inspect_measured(file: &Path, dir: &Path) -> Measured {
    let bin = env!("CARGO_BIN_EXE_poinav");
    let gnu_time = Path::new("/usr/bin/time").exists();
    let rss_file = dir.join("rss.txt");
    let stdout_file = dir.join("stdout.json");
    let mut cmd = if gnu_time {
        let mut c = Command::new("/usr/bin/time");
        c.arg("-f").arg("%M").arg("-o").arg(&rss_file).arg(bin);
        c
    } else {
        Command::new(bin)
    };
    cmd.arg("inspect")
        .arg(file)
        .arg("--json")
        .stdout(std::fs::File::create(&stdout_file).unwrap())
        .stderr(Stdio::inherit());
    let start = Instant::now();
    let mut child = cmd.spawn().expect("poinav runs");
    let mut polled_kb = 0u64;
    let status = loop {
        if let Some(status) = child.try_wait().unwrap() {
            break status;
        }
        if !gnu_time {
            let status = std::fs::read_to_string(format!("/proc/{}/status", child.id()));
            if let Some(kb) = status.ok().as_deref().and_then(vm_hwm_kb) {
                polled_kb = polled_kb.max(kb);
            }
        }
        std::thread::sleep(Duration::from_millis(2));
    };
    let time = start.elapsed();
    assert!(status.success(), "inspect failed: {status}");
    let kb = if gnu_time {
        let text = std::fs::read_to_string(&rss_file).unwrap();
        text.lines().last().unwrap().trim().parse().unwrap()
    } else {
        polled_kb
    };
    assert!(kb > 0, "no peak RSS measured");
    Measured {
        stdout: std::fs::read(&stdout_file).unwrap(),
        time,
        peak_rss: kb * 1024,
    }
}

fn vm_hwm_kb(status: &str) -> Option<u64> {
    let line = status.lines().find(|l| l.starts_with("VmHWM:"))?;
    line.split_whitespace().nth(1)?.parse().ok()
}

/// The time of the 17.9 MB synthetic file (best of 3, one warm-up).
fn reference_time(dir: &Path) -> (u64, Duration) {
    let file = common::shared().join("ifc/synthetic-merged-office-duplex-ifc2x3.ifc");
    let size = std::fs::metadata(&file).unwrap().len();
    inspect_measured(&file, dir);
    let best = (0..3)
        .map(|_| inspect_measured(&file, dir).time)
        .min()
        .unwrap();
    (size, best)
}

/// Generates `copies` copies, inspects them and checks memory, counts and time.
fn check(copies: u64) {
    // One at a time: the two tests would otherwise share the cores and skew the timings.
    static SERIAL: std::sync::Mutex<()> = std::sync::Mutex::new(());
    let _serial = SERIAL.lock().unwrap_or_else(|e| e.into_inner());
    let tmp = tempfile::tempdir().unwrap();
    let t = template();
    let file: PathBuf = tmp.path().join(format!("office-a-x{copies}.ifc"));
    let size = generate(&t, copies, &file);

    let one = inspect_measured(&common::shared().join("ifc/office-a.ifc"), tmp.path());
    let one: Value = serde_json::from_slice(&one.stdout).unwrap();
    let (ref_size, ref_time) = reference_time(tmp.path());

    let run = inspect_measured(&file, tmp.path());
    let r: Value = serde_json::from_slice(&run.stdout).unwrap();
    let ratio = run.peak_rss as f64 / size as f64;
    let time_ratio = run.time.as_secs_f64() / ref_time.as_secs_f64();
    eprintln!(
        "{copies} copies: {:.1} MB, peak RSS {:.1} MB ({ratio:.2}x the file), {:.2} s; \
         reference {:.1} MB in {:.3} s; time ratio {time_ratio:.1} for a size ratio {:.1}",
        size as f64 / 1e6,
        run.peak_rss as f64 / 1e6,
        run.time.as_secs_f64(),
        ref_size as f64 / 1e6,
        ref_time.as_secs_f64(),
        size as f64 / ref_size as f64,
    );

    // Exactly `copies` times office-a: instances, every class count, storeys, spaces, doors.
    assert_eq!(r["diagnostics"], 0, "{:?}", r["diagnostic_list"]);
    assert_eq!(
        r["instances"].as_u64().unwrap(),
        copies * one["instances"].as_u64().unwrap()
    );
    let (counts, one_counts) = (
        r["counts"].as_object().unwrap(),
        one["counts"].as_object().unwrap(),
    );
    assert_eq!(counts.len(), one_counts.len());
    for (class, n) in one_counts {
        assert_eq!(
            counts[class].as_u64().unwrap(),
            copies * n.as_u64().unwrap(),
            "{class}"
        );
    }
    for key in ["storeys", "spaces", "doors"] {
        assert_eq!(
            r[key].as_array().unwrap().len() as u64,
            copies * one[key].as_array().unwrap().len() as u64,
            "{key}"
        );
    }

    assert!(
        ratio < 3.0,
        "peak RSS {} bytes is {ratio:.2}x the {size}-byte file",
        run.peak_rss
    );
    // Proportional to size: no worse than 2x the per-byte time of the 17.9 MB file (plus a
    // second for noise on shared cores).
    let bound = ref_time.as_secs_f64() * (size as f64 / ref_size as f64) * 2.0 + 1.0;
    assert!(
        run.time.as_secs_f64() < bound,
        "{:.2} s for {size} bytes; bound {bound:.2} s from {:.3} s for {ref_size} bytes",
        run.time.as_secs_f64(),
        ref_time.as_secs_f64()
    );
}

#[test]
fn inspect_of_a_50_mb_model_stays_under_3x_its_size_in_memory() {
    check(12);
}

#[test]
fn inspect_of_a_200_mb_model_stays_under_3x_its_size_in_memory() {
    check(49);
}
