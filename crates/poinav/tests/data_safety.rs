//! Data safety: every command that reads an IFC leaves its (read-only) inputs byte-identical, writes complete outputs and no stray temporary files, refuses to overwrite its input, fails cleanly on a missing output folder, and never leaves a partial output when killed.

mod common;

use std::ffi::{OsStr, OsString};
use std::os::unix::fs::PermissionsExt;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

/// The small corpus models (under 300 kB each) the commands run on, besides the test building.
const SMALL: [&str; 6] = [
    "ifc4-test-model.ifc",
    "ifcopenhouse-ifc4.ifc",
    "ramps-extract.ifc",
    "revit-japanese-x2.ifc",
    "wall-door-column-ifc4x3.ifc",
    "wall-opening-window-ifc4x3.ifc",
];

/// Every file below `dir` (recursive), sorted.
fn files_below(dir: &Path) -> Vec<PathBuf> {
    let mut out = Vec::new();
    let mut stack = vec![dir.to_path_buf()];
    while let Some(d) = stack.pop() {
        for e in std::fs::read_dir(&d).unwrap() {
            let p = e.unwrap().path();
            if p.is_dir() {
                stack.push(p);
            } else {
                out.push(p);
            }
        }
    }
    out.sort();
    out
}

/// The bytes of every file below `dir`, by path: the "checksum" compared before and after.
fn snapshot(dir: &Path) -> Vec<(PathBuf, Vec<u8>)> {
    files_below(dir)
        .into_iter()
        .map(|p| {
            let b = std::fs::read(&p).unwrap();
            (p, b)
        })
        .collect()
}

fn is_temp(p: &Path) -> bool {
    let name = p.file_name().unwrap().to_string_lossy();
    name.starts_with(".poinav-") && name.ends_with(".tmp")
}

/// Makes every file below `dir` 0o444 and every folder 0o555 (or back to writable).
fn set_read_only(dir: &Path, read_only: bool) {
    for f in files_below(dir) {
        let mode = if read_only { 0o444 } else { 0o644 };
        std::fs::set_permissions(&f, std::fs::Permissions::from_mode(mode)).unwrap();
    }
    let mode = if read_only { 0o555 } else { 0o755 };
    std::fs::set_permissions(dir, std::fs::Permissions::from_mode(mode)).unwrap();
}

fn os(s: impl AsRef<OsStr>) -> OsString {
    s.as_ref().to_os_string()
}

fn run(args: &[OsString]) -> (i32, String, String) {
    let refs: Vec<&OsStr> = args.iter().map(OsString::as_os_str).collect();
    let (code, out, err) = common::poinav(&refs);
    assert!(!err.contains("panicked"), "{args:?}: {err}");
    (code, out, err)
}

/// The inputs: the small corpus files and the test building, in `dir` (then made read-only),
/// plus a scenario for the test building.
fn inputs(dir: &Path) -> Vec<PathBuf> {
    std::fs::create_dir_all(dir).unwrap();
    let mut files: Vec<PathBuf> = SMALL
        .iter()
        .map(|name| {
            let to = dir.join(name);
            std::fs::copy(common::shared().join("ifc").join(name), &to).unwrap();
            to
        })
        .collect();
    let demo = dir.join("demo.ifc");
    let (code, _, err) = run(&[os("demo-building"), os("-o"), os(&demo)]);
    assert_eq!(code, 0, "{err}");
    files.push(demo);
    files
}

/// Writes a short doorway scenario whose building is `ifc`.
fn scenario(ifc: &Path, path: &Path) {
    let text = format!(
        "name = \"doorway on a copy\"\nduration_s = 0.5\n\n[building]\nifc = {:?}\n\n[poi]\nstart = \"clear\"\n\n\
         [[robot]]\nname = \"Robot2\"\nprofile = \"paper\"\nstart = {{ x = 6.2, y = 6.0, heading_deg = -90.0 }}\n\
         controller = {{ kind = \"route\", to = \"Room 2\" }}\n\n[[expect]]\nkind = \"speed-range\"\nrobot = \"Robot2\"\nat_most_m_s = 5.0\n",
        ifc.display().to_string()
    );
    std::fs::write(path, text).unwrap();
}

/// Checks that a written output is complete: re-read by its own reader or format rules.
fn assert_complete(path: &Path) {
    let bytes = std::fs::read(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let ext = path.extension().and_then(OsStr::to_str).unwrap_or("");
    match ext {
        "ifc" => {
            let m = poinav_ifc::Model::open(path).unwrap();
            assert!(!m.is_empty(), "{}", path.display());
            assert!(
                bytes.trim_ascii_end().ends_with(b"END-ISO-10303-21;"),
                "{}",
                path.display()
            );
        }
        "glb" => {
            assert_eq!(&bytes[..4], b"glTF");
            let len = u32::from_le_bytes(bytes[8..12].try_into().unwrap()) as usize;
            assert_eq!(len, bytes.len(), "{}", path.display());
        }
        "fbx" => {
            assert!(bytes.starts_with(b"Kaydara FBX Binary  \0"));
            // FBX 7.4 ends with a 16-byte footer magic after the padding.
            assert!(bytes.len() > 200, "{}", path.display());
        }
        "svg" => assert!(
            bytes.trim_ascii_end().ends_with(b"</svg>"),
            "{}",
            path.display()
        ),
        "html" => assert!(
            bytes.trim_ascii_end().ends_with(b"</html>"),
            "{}",
            path.display()
        ),
        "json" | "geojson" => {
            serde_json::from_slice::<serde_json::Value>(&bytes)
                .unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        }
        "jsonl" => {
            for line in bytes.split(|&b| b == b'\n').filter(|l| !l.is_empty()) {
                serde_json::from_slice::<serde_json::Value>(line).unwrap();
            }
        }
        "csv" => {
            let mut r = csv::Reader::from_reader(&bytes[..]);
            let n = r.headers().unwrap().len();
            for rec in r.records() {
                assert_eq!(rec.unwrap().len(), n, "{}", path.display());
            }
        }
        "ids" => assert!(
            bytes.trim_ascii_end().ends_with(b"</ids:ids>"),
            "{}",
            path.display()
        ),
        "pgm" => assert!(bytes.starts_with(b"P5"), "{}", path.display()),
        _ => assert!(!bytes.is_empty(), "{}", path.display()),
    }
}

/// Every command that reads an IFC, for one input, writing below `out`.
fn commands(input: &Path, out: &Path, is_demo: bool) -> Vec<(&'static str, Vec<OsString>)> {
    let i = os(input);
    let mut cmds = vec![
        ("inspect", vec![os("inspect"), i.clone(), os("--json")]),
        (
            "enrich",
            vec![
                os("enrich"),
                i.clone(),
                os("-o"),
                os(out.join("enriched.ifc")),
                os("--csv"),
                os(out.join("enriched.csv")),
                os("--ids"),
                os(out.join("enriched.ids")),
            ],
        ),
        (
            "plan",
            vec![os("plan"), i.clone(), os("-o"), os(out.join("plan.svg"))],
        ),
        (
            "export glb",
            vec![
                os("export"),
                os("glb"),
                i.clone(),
                os("-o"),
                os(out.join("model.glb")),
            ],
        ),
        (
            "export fbx",
            vec![
                os("export"),
                os("fbx"),
                i.clone(),
                os("-o"),
                os(out.join("model.fbx")),
            ],
        ),
        (
            "export nav2",
            vec![
                os("export"),
                os("nav2"),
                i.clone(),
                os("-o"),
                os(out.join("nav2")),
            ],
        ),
        (
            "route",
            vec![
                os("route"),
                i.clone(),
                os("--from"),
                os("Room 1"),
                os("--to"),
                os("Room 3"),
                os("--json"),
            ],
        ),
        (
            "audit",
            vec![
                os("audit"),
                i.clone(),
                os("-o"),
                os(out.join("audit/report.html")),
            ],
        ),
    ];
    if is_demo {
        cmds.push((
            "patch door-width",
            vec![
                os("patch"),
                os("door-width"),
                i.clone(),
                os("-o"),
                os(out.join("wide.ifc")),
                os("--door"),
                os("Door Room 2"),
                os("--width"),
                os("1.20"),
            ],
        ));
    }
    cmds
}

/// `poinav serve FILE`, asked for the building's first part, then stopped: the GLB's size, or
/// the exit code when the server does not start.
fn serve_once(input: &Path) -> Result<usize, i32> {
    let server = common::serve(&[input.as_os_str()], Path::new("."))?;
    let (status, glb) = common::http_get(&server.addr, "/api/model/0.glb");
    assert_eq!(
        (status, &glb[..4]),
        (200, &b"glTF"[..]),
        "{}",
        input.display()
    );
    Ok(glb.len())
}

#[test]
fn every_command_leaves_read_only_inputs_identical_and_writes_complete_outputs() {
    let tmp = tempfile::tempdir().unwrap();
    let in_dir = tmp.path().join("in");
    let files = inputs(&in_dir);
    let demo = files.last().unwrap().clone();
    let scen = in_dir.join("doorway-copy.toml");
    scenario(&demo, &scen);
    set_read_only(&in_dir, true);
    let before = snapshot(&in_dir);

    for input in &files {
        let stem = input.file_stem().unwrap().to_string_lossy().into_owned();
        let is_demo = input == &demo;
        let out = tmp.path().join("out").join(&stem);
        std::fs::create_dir_all(&out).unwrap();
        for (what, args) in commands(input, &out, is_demo) {
            let (code, stdout, stderr) = run(&args);
            // The test building supports every command; corpus models may have no rooms to
            // route between (exit 2 names them) but never crash.
            if is_demo || !matches!(what, "route") {
                assert_eq!(code, 0, "{what} {stem}: {stdout}\n{stderr}");
            } else {
                assert!(matches!(code, 0..=2), "{what} {stem}: {stderr}");
            }
            if what == "inspect" || what == "route" {
                serde_json::from_str::<serde_json::Value>(&stdout)
                    .map(|_| ())
                    .or_else(|e| if code == 0 { Err(e) } else { Ok(()) })
                    .unwrap_or_else(|e| panic!("{what} {stem}: stdout is not JSON: {e}"));
            }
            assert_eq!(
                snapshot(&in_dir),
                before,
                "{what} changed an input ({stem})"
            );
        }
        let written = files_below(&out);
        assert!(written.len() >= 10, "{stem}: {written:?}");
        for f in &written {
            assert!(!is_temp(f), "stray temporary file {}", f.display());
            assert_complete(f);
        }
    }

    // serve reads its input, serves it and writes nothing: started on every input, asked for
    // the building, stopped. Models without spaces have nowhere to put robots: exit 2.
    for input in &files {
        let served = serve_once(input);
        assert!(
            matches!(served, Ok(n) if n > 1000) || served == Err(2),
            "serve {}: {served:?}",
            input.display()
        );
        assert_eq!(
            snapshot(&in_dir),
            before,
            "serve changed {}",
            input.display()
        );
    }

    // simulate on an IFC copy, with the sensors' findings written back to another copy.
    let out = tmp.path().join("out/simulate");
    let (code, stdout, stderr) = run(&[
        os("simulate"),
        os(&scen),
        os("-o"),
        os(&out),
        os("--write-back"),
        os(out.join("written-back.ifc")),
    ]);
    assert_eq!(code, 0, "simulate: {stdout}\n{stderr}");
    assert_eq!(snapshot(&in_dir), before, "simulate changed an input");
    let written = files_below(&out);
    assert!(
        written.iter().any(|f| f.ends_with("summary.json"))
            && written.iter().any(|f| f.ends_with("written-back.ifc")),
        "{written:?}"
    );
    for f in &written {
        assert!(!is_temp(f), "stray temporary file {}", f.display());
        assert_complete(f);
    }
    // Nothing was added beside the inputs either.
    assert_eq!(files_below(&in_dir).len(), before.len());
    set_read_only(&in_dir, false);
}

#[test]
fn writing_over_the_input_is_refused_and_leaves_it_unchanged() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path().join("in");
    let files = inputs(&dir);
    let demo = files.last().unwrap().clone();
    let small = dir.join("wall-opening-window-ifc4x3.ifc");
    let before = snapshot(&dir);
    // The same file under another spelling of its path is refused too.
    let dotted = dir.join("../in/wall-opening-window-ifc4x3.ifc");
    for args in [
        vec![os("enrich"), os(&small), os("-o"), os(&small)],
        vec![os("enrich"), os(&small), os("-o"), os(&dotted)],
        vec![
            os("patch"),
            os("door-width"),
            os(&demo),
            os("-o"),
            os(&demo),
            os("--door"),
            os("Door Room 2"),
            os("--width"),
            os("1.20"),
        ],
    ] {
        let (code, stdout, stderr) = run(&args);
        assert_eq!(code, 2, "{args:?}: {stdout}");
        assert!(
            stderr.contains("refusing to overwrite the input file"),
            "{args:?}: {stderr}"
        );
        assert_eq!(snapshot(&dir), before, "{args:?}");
    }
}

#[test]
fn an_output_in_a_missing_folder_fails_cleanly_and_leaves_nothing() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path().join("in");
    let files = inputs(&dir);
    let demo = files.last().unwrap().clone();
    let out = tmp.path().join("out");
    std::fs::create_dir(&out).unwrap();
    let missing = out.join("no/such/folder");
    let before = snapshot(&dir);
    let d = os(&demo);
    let cases: Vec<(PathBuf, Vec<OsString>)> = [
        ("x.ifc", vec![os("enrich"), d.clone()]),
        ("x.glb", vec![os("export"), os("glb"), d.clone()]),
        ("x.fbx", vec![os("export"), os("fbx"), d.clone()]),
        ("x.svg", vec![os("plan"), d.clone()]),
    ]
    .into_iter()
    .map(|(name, mut args)| {
        let target = missing.join(name);
        args.extend([os("-o"), os(&target)]);
        (target, args)
    })
    .chain(std::iter::once({
        let target = missing.join("wide.ifc");
        (
            target.clone(),
            vec![
                os("patch"),
                os("door-width"),
                d.clone(),
                os("-o"),
                os(&target),
                os("--door"),
                os("Door Room 2"),
                os("--width"),
                os("1.20"),
            ],
        )
    }))
    .collect();
    for (target, args) in cases {
        let (code, stdout, stderr) = run(&args);
        assert_eq!(code, 2, "{args:?}: {stdout}");
        let first = stderr.lines().next().unwrap_or("");
        assert!(
            first.starts_with("error: ")
                && first.contains(&target.display().to_string())
                && (first.contains("No such file or directory")
                    || first.contains("does not exist")),
            "{args:?}: {stderr}"
        );
        assert!(
            files_below(&out).is_empty(),
            "{args:?} left {:?}",
            files_below(&out)
        );
        assert!(!out.join("no").exists());
        assert_eq!(snapshot(&dir), before);
    }
}

/// `poinav enrich IN -o OUT` with a fixed time stamp.
fn enrich_cmd(input: &Path, output: &Path) -> Command {
    let mut c = Command::new(env!("CARGO_BIN_EXE_poinav"));
    c.env("SOURCE_DATE_EPOCH", "0")
        .arg("enrich")
        .arg(input)
        .arg("-o")
        .arg(output)
        .stdout(Stdio::null())
        .stderr(Stdio::null());
    c
}

/// Kills `poinav enrich` of the 17.9 MB file at several moments: the visible output is either
/// missing or complete and equal to an uninterrupted run's, never partial. A SIGKILL between
/// the temporary file's creation and its rename can leave a hidden `.poinav-<pid>-*.tmp` beside
/// the target (nothing can clean up after SIGKILL); nothing else may appear, and the next write
/// into that folder removes it (its process is gone).
#[test]
fn an_interrupted_enrich_never_leaves_a_partial_output() {
    let tmp = tempfile::tempdir().unwrap();
    let input = tmp.path().join("synthetic.ifc");
    std::fs::copy(
        common::shared().join("ifc/synthetic-merged-office-duplex-ifc2x3.ifc"),
        &input,
    )
    .unwrap();
    std::fs::set_permissions(&input, std::fs::Permissions::from_mode(0o444)).unwrap();
    let original = std::fs::read(&input).unwrap();

    let reference = tmp.path().join("reference.ifc");
    let start = Instant::now();
    assert!(enrich_cmd(&input, &reference).status().unwrap().success());
    let full = start.elapsed();
    let expected = std::fs::read(&reference).unwrap();
    poinav_ifc::Model::open(&reference).unwrap();

    // Fixed delays and fractions of a whole run (the write happens at the end).
    let mut delays: Vec<Duration> = [20, 60, 120]
        .into_iter()
        .map(Duration::from_millis)
        .collect();
    delays.extend([0.5, 0.8, 0.9, 0.95, 1.0, 1.5].map(|f| full.mul_f64(f)));
    let (mut complete, mut absent, mut leftovers) = (0, 0, 0);
    let mut untidy = Vec::new();
    for (k, delay) in delays.iter().enumerate() {
        let dir = tmp.path().join(format!("run-{k}"));
        std::fs::create_dir(&dir).unwrap();
        let out = dir.join("out.ifc");
        let mut child = enrich_cmd(&input, &out).spawn().unwrap();
        std::thread::sleep(*delay);
        let _ = child.kill();
        let _ = child.wait();
        if out.exists() {
            let got = std::fs::read(&out).unwrap();
            assert!(
                got == expected,
                "killed after {delay:?}: {} is partial ({} of {} bytes)",
                out.display(),
                got.len(),
                expected.len()
            );
            poinav_ifc::Model::open(&out).unwrap();
            complete += 1;
        } else {
            absent += 1;
        }
        for f in files_below(&dir) {
            if f != out {
                assert!(is_temp(&f), "unexpected file {}", f.display());
                leftovers += 1;
                untidy.push(dir.clone());
            }
        }
        assert_eq!(std::fs::read(&input).unwrap(), original);
    }
    // Also a planted leftover of a process that no longer exists (pid above Linux's 2^22).
    let planted = tmp.path().join("planted");
    std::fs::create_dir(&planted).unwrap();
    std::fs::write(planted.join(".poinav-99999999-AbC123.tmp"), b"partial").unwrap();
    untidy.push(planted);
    untidy.dedup();
    for dir in &untidy {
        let out = dir.join("out.ifc");
        assert!(enrich_cmd(&input, &out).status().unwrap().success());
        assert_eq!(
            files_below(dir),
            std::slice::from_ref(&out),
            "stale temporary files stay"
        );
        assert!(std::fs::read(&out).unwrap() == expected);
    }
    eprintln!(
        "uninterrupted run {full:?}; {complete} complete, {absent} absent, {leftovers} hidden temporary files left by SIGKILL"
    );
    assert_eq!(complete + absent, delays.len());
}

#[test]
fn enrich_writes_no_output_when_another_output_cannot_be_written() {
    let dir = tempfile::tempdir().unwrap();
    let input = common::shared().join("ifc/wall-opening-window-ifc4x3.ifc");
    let ifc = dir.path().join("ok.ifc");
    let csv = dir.path().join("no/such/x.csv");
    let (code, _, err) = common::poinav(&[
        OsStr::new("enrich"),
        input.as_os_str(),
        OsStr::new("-o"),
        ifc.as_os_str(),
        OsStr::new("--csv"),
        csv.as_os_str(),
    ]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("does not exist"), "{err}");
    assert!(
        !ifc.exists(),
        "the IFC must not be written when the CSV cannot be"
    );
    assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 0);
}

/// `poinav inspect x --json | head -c 10`: the reader stops early; poinav ends quietly with exit
/// code 0, no panic (println! panics on a closed pipe).
#[test]
fn a_closed_stdout_ends_the_command_quietly() {
    use std::io::Read;
    let file = common::shared().join("ifc/synthetic-merged-office-duplex-ifc2x3.ifc");
    let mut child = Command::new(env!("CARGO_BIN_EXE_poinav"))
        .args([os("inspect"), os(&file), os("--json")])
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let mut head = [0u8; 10];
    child.stdout.take().unwrap().read_exact(&mut head).unwrap();
    assert_eq!(head[0], b'{');
    let out = child.wait_with_output().unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(!stderr.contains("panicked"), "{stderr}");
    assert_eq!(out.status.code(), Some(0), "{stderr}");
}
