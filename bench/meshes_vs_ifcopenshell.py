"""Benchmark poinav's element meshes against IfcOpenShell's geometry iterator.

Usage: .venv/bin/python bench/meshes_vs_ifcopenshell.py [FILE...] [--runs N] [--max-ifcopenshell S]

FILE defaults to office-a.ifc and synthetic-merged-office-duplex-ifc2x3.ifc from the corpus
(../shared/ifc, or $POINAV_SHARED/ifc). For each file, in this one run:
  (a) poinav: `cargo run --release -p poinav-geom --example mesh_timing -- FILE --runs N`
      on one thread and on the default rayon pool; the example reads the file once, then
      prints the median wall-clock time of `mesh_model` (every element but openings, and
      every space, openings cut, world coordinates) over N runs;
  (b) IfcOpenShell 0.9 in this process: ifcopenshell.open(FILE) (not timed), then its
      geometry iterator with world coordinates and default settings otherwise (openings
      subtracted) over the same products (IfcElement but IfcFeatureElementSubtraction, and
      IfcSpace, with a representation), reading every shape's vertices and faces; timed
      once on one thread and once on one thread per core (it is slow: ~9 s for office-a).
      A file whose one-thread time, estimated from the files before it by size, exceeds
      --max-ifcopenshell seconds (default 60) is not run through IfcOpenShell (said so).
Prints both times per file and the speed ratios.
Exit 0; 1 if the example fails.
"""

import argparse
import multiprocessing
import os
import re
import subprocess
import sys
import time
from pathlib import Path

import ifcopenshell
import ifcopenshell.geom

REPO = Path(__file__).resolve().parent.parent
SHARED = Path(os.environ.get("POINAV_SHARED", REPO.parent / "shared"))
DEFAULT_FILES = ["office-a.ifc", "synthetic-merged-office-duplex-ifc2x3.ifc"]


def time_poinav(path, threads, runs):
    cmd = ["cargo", "run", "--quiet", "--release", "-p", "poinav-geom", "--example", "mesh_timing",
           "--", str(path), "--runs", str(runs), "--threads", str(threads)]
    proc = subprocess.run(cmd, cwd=REPO, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    if proc.returncode != 0:
        sys.stderr.write(proc.stderr)
        raise SystemExit(1)
    m = re.search(r"median ([0-9.]+) s \((\d+) threads\)", proc.stdout)
    if not m:
        sys.stderr.write(proc.stdout)
        raise SystemExit(1)
    return float(m.group(1)), int(m.group(2)), proc.stdout.strip()


def time_ifcopenshell(f, threads):
    settings = ifcopenshell.geom.settings()
    settings.set("use-world-coords", True)
    products = [p for p in f.by_type("IfcElement") + f.by_type("IfcSpace")
                if p.Representation is not None and not p.is_a("IfcFeatureElementSubtraction")]
    start = time.perf_counter()
    shapes = 0
    it = ifcopenshell.geom.iterator(settings, f, threads, include=products)
    if it.initialize():
        while True:
            shape = it.get()
            shape.geometry.verts, shape.geometry.faces  # what a mesh consumer reads
            shapes += 1
            if not it.next():
                break
    return time.perf_counter() - start, shapes


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("files", nargs="*")
    ap.add_argument("--runs", type=int, default=5)
    ap.add_argument("--max-ifcopenshell", type=float, default=60.0)
    args = ap.parse_args()
    files = [Path(f) for f in args.files] or [SHARED / "ifc" / f for f in DEFAULT_FILES]
    cores = multiprocessing.cpu_count()
    seconds_per_mb = None
    print(f"{'file':45} {'MB':>6} {'poinav 1 thr':>13} {'poinav pool':>12} "
          f"{'IfcOS 1 thr':>12} {'IfcOS ' + str(cores) + ' thr':>12} {'ratio 1 thr':>12} {'ratio pool':>11}")
    for path in files:
        size_mb = path.stat().st_size / 1e6
        p1, _, out1 = time_poinav(path, 1, args.runs)
        pn, n, _ = time_poinav(path, 0, args.runs)
        estimate = seconds_per_mb * size_mb if seconds_per_mb else 0.0
        if estimate > args.max_ifcopenshell:
            print(f"{path.name:45} {size_mb:6.2f} {p1:12.3f}s {pn:11.3f}s "
                  f"  (IfcOpenShell not run: estimated {estimate:.0f} s > {args.max_ifcopenshell:.0f} s)")
            continue
        f = ifcopenshell.open(str(path))
        i1, shapes = time_ifcopenshell(f, 1)
        i_n, _ = time_ifcopenshell(f, cores)
        del f
        seconds_per_mb = max(seconds_per_mb or 0.0, i1 / size_mb)
        print(f"{path.name:45} {size_mb:6.2f} {p1:12.3f}s {pn:11.3f}s {i1:11.2f}s {i_n:11.2f}s "
              f"{i1 / p1:11.1f}x {i_n / pn:10.1f}x")
        print(f"    poinav: {out1}; IfcOpenShell: {shapes} shapes; poinav pool: {n} threads")
    return 0


if __name__ == "__main__":
    sys.exit(main())
