"""Benchmark poinav's meshing and GLB export against ifc-lite 28.2 (Rust, crates.io), one thread.

Usage: python3 bench/meshes_vs_ifclite.py [FILE...] [--runs N] [--ifclite-dir DIR] [--no-build]

FILE defaults to synthetic-merged-office-duplex-ifc2x3.ifc from the corpus (../shared/ifc, or
$POINAV_SHARED/ifc) and /work/bench-models/heavy-furnished-ft.ifc when it exists.

What runs, each as its own process with RAYON_NUM_THREADS=1, the two tools interleaved run by
run (poinav, ifc-lite, poinav, ...) so both see the same machine load:
  (a) poinav: `target/release/poinav export glb FILE -o OUT` (read, mesh every element with
      openings cut, classify, write the GLB with per-element metadata), built first with
      `cargo build --release -p poinav`;
  (b) ifc-lite: a tiny binary built from crates.io (ifc-lite-core, -geometry, -processing and
      -export, all exactly 28.2.0) in DIR (default target/ifclite-bench; never committed):
      `glb FILE OUT` is `ifc_lite_export::try_export_glb` with metadata, written to OUT;
      `mesh FILE` is `ifc_lite_processing::process_geometry` alone (meshes kept in memory).
Wall time and peak RSS (the child's ru_maxrss from wait4) are taken for every run; the median
of N runs (default 5) is printed per file, with the ratios ifc-lite / poinav (time: above 1
means poinav is faster; memory: above 1 means poinav uses less).
Exit 0; 1 if a build or a run fails.
"""

import argparse
import os
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

REPO = Path(__file__).resolve().parent.parent
SHARED = Path(os.environ.get("POINAV_SHARED", REPO.parent / "shared"))
DEFAULT_FILES = [SHARED / "ifc" / "synthetic-merged-office-duplex-ifc2x3.ifc",
                 Path("/work/bench-models/heavy-furnished-ft.ifc")]
IFCLITE_VERSION = "=28.2.0"

CARGO_TOML = f"""[package]
name = "ifclite-bench"
version = "0.0.0"
edition = "2021"
publish = false

[dependencies]
ifc-lite-core = "{IFCLITE_VERSION}"
ifc-lite-geometry = "{IFCLITE_VERSION}"
ifc-lite-processing = "{IFCLITE_VERSION}"
ifc-lite-export = {{ version = "{IFCLITE_VERSION}", default-features = false }}

[profile.release]
debug = false

[workspace]
"""

MAIN_RS = """//! ifc-lite 28.2 on one file: `mesh FILE` (meshes only) or `glb FILE OUT` (GLB export).
fn main() {
    let args: Vec<String> = std::env::args().collect();
    let bytes = std::fs::read(&args[2]).expect("readable file");
    match args[1].as_str() {
        "mesh" => {
            let r = ifc_lite_processing::process_geometry(&bytes);
            let tris: usize = r.meshes.iter().map(|m| m.indices.len() / 3).sum();
            println!("{} meshes, {} triangles", r.meshes.len(), tris);
        }
        "glb" => {
            let opts = ifc_lite_export::GltfOptions::default().with_include_metadata(true);
            let glb = ifc_lite_export::try_export_glb(&bytes, &opts).expect("GLB export");
            std::fs::write(&args[3], &glb).expect("write GLB");
            println!("{} bytes", glb.len());
        }
        other => panic!("unknown mode {other}"),
    }
}
"""


def build_ifclite(root):
    """Writes the tiny cargo project under `root` (if changed) and builds it; returns the binary."""
    (root / "src").mkdir(parents=True, exist_ok=True)
    for rel, text in (("Cargo.toml", CARGO_TOML), ("src/main.rs", MAIN_RS)):
        p = root / rel
        if not p.exists() or p.read_text() != text:
            p.write_text(text)
    env = dict(os.environ, CARGO_TARGET_DIR=str(root / "target"))
    proc = subprocess.run(["cargo", "build", "--release", "--quiet"], cwd=root, env=env)
    if proc.returncode != 0:
        raise SystemExit(1)
    return root / "target" / "release" / "ifclite-bench"


def build_poinav():
    proc = subprocess.run(["cargo", "build", "--release", "--quiet", "-p", "poinav"], cwd=REPO)
    if proc.returncode != 0:
        raise SystemExit(1)
    return REPO / "target" / "release" / "poinav"


def run(cmd):
    """Runs `cmd` on one thread; returns (wall seconds, peak RSS in MB)."""
    env = dict(os.environ, RAYON_NUM_THREADS="1")
    start = time.perf_counter()
    proc = subprocess.Popen(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, env=env)
    _, status, usage = os.wait4(proc.pid, 0)
    wall = time.perf_counter() - start
    err = proc.stderr.read().decode(errors="replace")
    proc.stderr.close()
    proc.returncode = os.waitstatus_to_exitcode(status)
    if proc.returncode != 0:
        sys.stderr.write(f"{' '.join(map(str, cmd))} failed ({proc.returncode}):\n{err}\n")
        raise SystemExit(1)
    return wall, usage.ru_maxrss / 1024.0


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("files", nargs="*")
    ap.add_argument("--runs", type=int, default=5)
    ap.add_argument("--ifclite-dir", type=Path, default=REPO / "target" / "ifclite-bench")
    ap.add_argument("--no-build", action="store_true", help="use the binaries already built")
    args = ap.parse_args()
    files = [Path(f) for f in args.files] or [f for f in DEFAULT_FILES if f.exists()]
    if args.no_build:
        poinav = REPO / "target" / "release" / "poinav"
        lite = args.ifclite_dir / "target" / "release" / "ifclite-bench"
    else:
        poinav = build_poinav()
        lite = build_ifclite(args.ifclite_dir)
    print(f"one thread, median of {args.runs} interleaved runs; ratio = ifc-lite / poinav")
    print(f"{'file':45} {'MB':>6} {'what':>26} {'poinav':>16} {'ifc-lite':>16} {'time ratio':>11} {'RSS ratio':>10}")
    with tempfile.TemporaryDirectory() as tmp:
        out_p, out_l = Path(tmp) / "poinav.glb", Path(tmp) / "ifclite.glb"
        for path in files:
            size_mb = path.stat().st_size / 1e6
            runs = {"poinav glb": [], "ifc-lite glb": [], "ifc-lite mesh": []}
            for _ in range(max(1, args.runs)):
                runs["poinav glb"].append(run([poinav, "export", "glb", path, "-o", out_p]))
                runs["ifc-lite glb"].append(run([lite, "glb", path, out_l]))
                runs["ifc-lite mesh"].append(run([lite, "mesh", path]))
            med = {k: (statistics.median(t for t, _ in v), statistics.median(m for _, m in v))
                   for k, v in runs.items()}
            pt, pm = med["poinav glb"]
            for what, key in (("export glb vs GLB export", "ifc-lite glb"),
                              ("export glb vs meshes only", "ifc-lite mesh")):
                lt, lm = med[key]
                print(f"{path.name:45} {size_mb:6.1f} {what:>26} {pt:6.3f}s {pm:6.0f}MB "
                      f"{lt:6.3f}s {lm:6.0f}MB {lt / pt:10.2f}x {lm / pm:9.2f}x")
            print(f"    GLB sizes: poinav {out_p.stat().st_size / 1e6:.1f} MB, "
                  f"ifc-lite {out_l.stat().st_size / 1e6:.1f} MB")
    return 0


if __name__ == "__main__":
    sys.exit(main())
