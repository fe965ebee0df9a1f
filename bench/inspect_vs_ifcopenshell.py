"""Benchmark `poinav inspect --json` against IfcOpenShell reading the same file.

Usage: .venv/bin/python bench/inspect_vs_ifcopenshell.py FILE [--poinav PATH] [--runs N]

Times, as the median of N runs (default 5, after one untimed warm-up each):
  (a) `PATH inspect FILE --json` end to end as a subprocess, wall clock, output
      discarded (PATH defaults to target/release/poinav in the repo);
  (b) IfcOpenShell in this process: ifcopenshell.open(FILE) plus by_type for
      IfcWall, IfcDoor, IfcWindow, IfcSpace, IfcSlab, IfcBuildingStorey
      (interpreter start and import are not timed).
Prints both medians, the file size, poinav's MB/s and the speed ratio.
Exit 0; 1 if poinav fails on the file; 2 if the poinav binary does not exist.
"""

import argparse
import os
import shutil
import statistics
import subprocess
import sys
import time
from pathlib import Path

import ifcopenshell

REPO = Path(__file__).resolve().parent.parent
CLASSES = ["IfcWall", "IfcDoor", "IfcWindow", "IfcSpace", "IfcSlab", "IfcBuildingStorey"]


def time_poinav(binary, path):
    cmd = [binary, "inspect", path, "--json"]
    start = time.perf_counter()
    proc = subprocess.run(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    elapsed = time.perf_counter() - start
    if proc.returncode != 0:
        sys.stderr.write(proc.stderr.decode(errors="replace"))
        raise SystemExit(f"error: {' '.join(cmd)} exited with {proc.returncode}")
    return elapsed


def time_ifcopenshell(path):
    start = time.perf_counter()
    f = ifcopenshell.open(path)
    for cls in CLASSES:
        f.by_type(cls)
    elapsed = time.perf_counter() - start
    del f
    return elapsed


def median_of(fn, runs):
    fn()  # warm-up: page cache, lazy loading
    return statistics.median(fn() for _ in range(runs))


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("file")
    ap.add_argument("--poinav", default=str(REPO / "target" / "release" / "poinav"))
    ap.add_argument("--runs", type=int, default=5)
    args = ap.parse_args()

    binary = args.poinav if os.path.exists(args.poinav) else shutil.which(args.poinav)
    if not binary or not os.access(binary, os.X_OK):
        print(f"error: poinav binary not found at {args.poinav} "
              "(build it with `cargo build --release`, or pass --poinav PATH)", file=sys.stderr)
        return 2
    if not os.path.isfile(args.file):
        print(f"error: no such file: {args.file}", file=sys.stderr)
        return 2
    runs = max(1, args.runs)

    size_mb = os.path.getsize(args.file) / 1e6
    t_poinav = median_of(lambda: time_poinav(binary, args.file), runs)
    t_ios = median_of(lambda: time_ifcopenshell(args.file), runs)

    print(f"file: {args.file} ({size_mb:.2f} MB), median of {runs} runs")
    print(f"  {'':40} {'seconds':>9} {'MB/s':>9}")
    print(f"  {'poinav inspect --json (subprocess)':40} {t_poinav:9.4f} {size_mb / t_poinav:9.1f}")
    print(f"  {'IfcOpenShell open+by_type (in-process)':40} {t_ios:9.4f} {size_mb / t_ios:9.1f}")
    if t_poinav <= t_ios:
        print(f"poinav is {t_ios / t_poinav:.1f}x faster than IfcOpenShell open+by_type")
    else:
        print(f"poinav is {t_poinav / t_ios:.1f}x slower than IfcOpenShell open+by_type")
    return 0


if __name__ == "__main__":
    sys.exit(main())
