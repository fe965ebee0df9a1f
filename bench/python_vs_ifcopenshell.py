"""Benchmark the poinav wheel against IfcOpenShell's Python API, and against the same Rust
library calls without Python objects (what the wheel adds).

Usage: python bench/python_vs_ifcopenshell.py [FILE...] [--rounds N] [--ifcos-rounds M]
                                              [--no-meshes] [--no-ifcos] [--instructions]
                                              [--cli PATH]

Run it with a Python that has the poinav wheel (a release build: `maturin build --release`),
numpy and IfcOpenShell installed. FILE defaults to fzk-haus-ifc4.ifc, duplex-apartment.ifc
and office-a.ifc from the corpus ($POINAV_SHARED/ifc, else ../shared/ifc). Per file, N rounds
(default 9, after one untimed warm-up round) of the wheel and the library in turn, their order
rotated every round, so that machine noise hits all alike; then M rounds (default 3) of
IfcOpenShell, apart (its large heap, given back, made whoever ran next pay for fresh pages):

  psets    poinav      poinav.open(FILE).psets(): every IfcProduct's property sets as dicts
           rust        the same library calls in Rust, no Python objects (_native.bench_psets):
                       Model::open and property_sets of every product with a GlobalId, in
                       parallel as the wheel does, giving the same owned values (names and
                       texts as Strings) that the wheel hands to Python, then freed
           once        the Rust part of poinav.open(FILE).psets() (_native.bench_psets with
                       once=True): Model::open and each distinct property set read once, in
                       the wheel's chunks (pset_chunks::Chunks), then freed; poinav / once - 1
                       is what making the Python objects costs
           ifcos       ifcopenshell.open(FILE) + ifcopenshell.util.element.get_psets for every
                       IfcProduct (psets_only)
  meshes   poinav      poinav.open(FILE).meshes(): every element's (n, 3) float64 vertices and
                       (m, 3) uint32 triangles as numpy arrays
           rust        Model::open + mesh_model in Rust (_native.bench_meshes): the same owned
                       meshes (vertices, triangles, names) the wheel hands to numpy, then freed
           ifcos       ifcopenshell.open + the geometry iterator (world coordinates, one thread)
                       over the same elements, vertices and faces reshaped into numpy arrays
  inspect  poinav      poinav.open(FILE).inspect()          (only with --cli)
           cli         `PATH inspect FILE --json` as a subprocess, output discarded

Printed per file: the median wall time of each, "wheel" = median poinav / median rust - 1 (the
issue asks for at most 10 %), the same from the best (least disturbed) times, the median of
each round's own ratio ("pairs": the two ran back to back, so a load that changes between
rounds moves both alike), and from the
CPU time (user + sys of all the process's threads, `time.process_time`, which other programs on
a shared machine disturb much less than the wall time); for psets also poinav against "once"
(the Python objects' cost alone); the load average before and after.
The Rust calls run on all cores (rayon); psets() makes its Python objects on the calling
thread while the pool reads (each chunk of products converted as soon as it is read).

--instructions also counts the instructions of one call of each (valgrind's callgrind, one
rayon thread; the difference of 3 calls and 1 call in fresh processes): a figure the machine's
load does not move at all, though it leaves out what memory costs beyond instructions (page
faults, cache misses). Needs valgrind; takes about a minute per file and contender.
"""

import argparse
import os
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np
import poinav
from poinav import _native

REPO = Path(__file__).resolve().parent.parent
SHARED = Path(os.environ.get("POINAV_SHARED", REPO.parent / "shared"))
DEFAULT_FILES = ["fzk-haus-ifc4.ifc", "duplex-apartment.ifc", "office-a.ifc"]


def timed(fn):
    start, cpu = time.perf_counter(), time.process_time()
    out = fn()
    return (time.perf_counter() - start, time.process_time() - cpu), out


def poinav_psets(path):
    return sum(len(s) for s in poinav.open(path).psets().values())


def rust_psets(path):
    return _native.bench_psets(str(path))


def once_psets(path):
    return _native.bench_psets(str(path), once=True)


def ifcos_psets(path):
    import ifcopenshell
    import ifcopenshell.util.element
    f = ifcopenshell.open(str(path))
    return sum(len(ifcopenshell.util.element.get_psets(p, psets_only=True)) for p in f.by_type("IfcProduct"))


def poinav_meshes(path):
    return sum(len(m["triangles"]) for m in poinav.open(path).meshes())


def rust_meshes(path):
    return _native.bench_meshes(str(path))


def ifcos_meshes(path):
    import ifcopenshell
    import ifcopenshell.geom
    f = ifcopenshell.open(str(path))
    settings = ifcopenshell.geom.settings()
    settings.set("use-world-coords", True)
    products = [p for p in f.by_type("IfcElement")
                if p.Representation is not None and not p.is_a("IfcFeatureElementSubtraction")]
    if not products:
        return 0
    it = ifcopenshell.geom.iterator(settings, f, 1, include=products)
    triangles = 0
    if it.initialize():
        while True:
            g = it.get().geometry
            np.asarray(g.verts, dtype=np.float64).reshape(-1, 3)
            triangles += len(np.asarray(g.faces, dtype=np.uint32).reshape(-1, 3))
            if not it.next():
                break
    return triangles


CALLS = {
    ("psets", "poinav"): poinav_psets,
    ("psets", "rust"): rust_psets,
    ("psets", "once"): once_psets,
    ("psets", "ifcos"): ifcos_psets,
    ("meshes", "poinav"): poinav_meshes,
    ("meshes", "rust"): rust_meshes,
    ("meshes", "ifcos"): ifcos_meshes,
}


def cli_inspect(cli, path):
    subprocess.run([cli, "inspect", str(path), "--json"], stdout=subprocess.DEVNULL, check=True)


def bench(path, rounds, kinds, ifcos_rounds, cli):
    # The wheel and the library in turn, their order rotated every round, so that each runs
    # as often first as later (the first after a group pays for the other kind's freed
    # memory); IfcOpenShell apart afterwards: run between them, whoever came next paid for
    # the pages its large heap had given back.
    pairs = [((kind, "poinav"), (kind, "rust")) + (((kind, "once"),) if kind == "psets" else ())
             for kind in kinds]
    tasks = {k: (lambda fn: lambda: fn(path))(CALLS[k]) for pair in pairs for k in pair}
    if cli:
        pairs.append((("inspect", "poinav"), ("inspect", "cli")))
        tasks[("inspect", "poinav")] = lambda: poinav.open(path).inspect()
        tasks[("inspect", "cli")] = lambda: cli_inspect(cli, path)
    times = {k: [] for k in tasks}
    cpus = {k: [] for k in tasks}
    counts = {}

    def run(k, keep):
        (t, c), n = timed(tasks[k])
        if keep:
            times[k].append(t)
            cpus[k].append(c)
        counts[k] = n

    for r in range(rounds + 1):
        for group in pairs:
            s = r % len(group)
            for k in group[s:] + group[:s]:
                run(k, r > 0)
    if ifcos_rounds:
        for kind in kinds:
            k = (kind, "ifcos")
            tasks[k], times[k], cpus[k] = (lambda fn: lambda: fn(path))(CALLS[k]), [], []
            for r in range(ifcos_rounds + 1):
                run(k, r > 0)
    return times, cpus, counts


def instructions(kind, who, path):
    """Instructions of one call (callgrind: 3 calls less 1 call, fresh processes)."""
    total = {}
    with tempfile.TemporaryDirectory() as tmp:
        for n in (1, 3):
            out = Path(tmp) / f"cg-{n}.out"
            env = dict(os.environ, RAYON_NUM_THREADS="1")
            subprocess.run(["valgrind", "--tool=callgrind", f"--callgrind-out-file={out}",
                            sys.executable, __file__, "--one", kind, who, str(n), str(path)],
                           env=env, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
            total[n] = next(int(line.split()[1]) for line in out.read_text().splitlines()
                            if line.startswith(("summary:", "totals:")))
    return (total[3] - total[1]) / 2


def pct(a, b):
    return 100 * (a / b - 1)


def paired(times, a, b):
    """The median of the rounds' own ratios a / b - 1 (in %): the two ran one after the
    other in each round, so a load that changes between rounds moves both alike."""
    return 100 * (statistics.median(x / y for x, y in zip(times[a], times[b])) - 1)


def main():
    if len(sys.argv) > 1 and sys.argv[1] == "--one":
        kind, who, n, path = sys.argv[2:6]
        for _ in range(int(n)):
            CALLS[(kind, who)](Path(path))
        return 0
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("files", nargs="*")
    ap.add_argument("--rounds", type=int, default=9)
    ap.add_argument("--no-meshes", action="store_true")
    ap.add_argument("--ifcos-rounds", type=int, default=3, help="IfcOpenShell's rounds (default 3)")
    ap.add_argument("--no-ifcos", action="store_true", help="leave IfcOpenShell out (faster)")
    ap.add_argument("--instructions", action="store_true", help="also count instructions (valgrind)")
    ap.add_argument("--cli", help="a poinav binary to compare inspect with")
    args = ap.parse_args()
    if args.instructions and not shutil.which("valgrind"):
        ap.error("--instructions needs valgrind")
    files = [Path(f) for f in args.files] or [SHARED / "ifc" / f for f in DEFAULT_FILES]
    kinds = ("psets",) + (() if args.no_meshes else ("meshes",))
    versions = f"numpy {np.__version__}, Python {sys.version.split()[0]}"
    if not args.no_ifcos:
        import ifcopenshell
        versions = f"IfcOpenShell {ifcopenshell.version}, " + versions
    print(f"poinav {poinav.__version__} (wheel), {versions}; {os.cpu_count()} cores; "
          f"median of {args.rounds} rounds" + ("" if args.no_ifcos else f" ({args.ifcos_rounds} for IfcOpenShell)"))
    for path in files:
        load = os.getloadavg()[0]
        times, cpus, counts = bench(path, max(1, args.rounds), kinds,
                                    0 if args.no_ifcos else max(1, args.ifcos_rounds), args.cli)
        load = f"{load:.1f}-{os.getloadavg()[0]:.1f}"
        med = {k: statistics.median(v) for k, v in times.items()}
        best = {k: min(v) for k, v in times.items()}
        cpu = {k: statistics.median(v) for k, v in cpus.items()}
        size = path.stat().st_size / 1e6
        print(f"\n{path.name} ({size:.2f} MB), load average {load}")
        print(f"  {'':7} {'poinav s':>9} {'rust s':>8} {'wheel':>7} {'(best)':>7} {'(pairs)':>7} "
              f"{'CPU poinav':>11} {'CPU rust':>9} {'wheel':>7}"
              + ("" if args.no_ifcos else f" {'ifcos s':>8} {'vs ifcos':>9}"))
        for kind in kinds:
            p, r = (kind, "poinav"), (kind, "rust")
            line = (f"  {kind:7} {med[p]:9.4f} {med[r]:8.4f} {pct(med[p], med[r]):+6.1f}% "
                    f"{pct(best[p], best[r]):+6.1f}% {paired(times, p, r):+6.1f}% "
                    f"{cpu[p]:11.4f} {cpu[r]:9.4f} {pct(cpu[p], cpu[r]):+6.1f}%")
            if not args.no_ifcos:
                i = (kind, "ifcos")
                line += f" {med[i]:8.4f} {med[i] / med[p]:8.1f}x"
            print(line)
            o = (kind, "once")
            if o in med:
                print(f"  {'':7} {'once s':>9} {med[o]:8.4f} {pct(med[p], med[o]):+6.1f}% "
                      f"{pct(best[p], best[o]):+6.1f}% {paired(times, p, o):+6.1f}% "
                      f"{'CPU once':>11} {cpu[o]:9.4f} "
                      f"{pct(cpu[p], cpu[o]):+6.1f}%   (poinav against its own Rust part)")
        if args.instructions:
            for kind in kinds:
                ip = instructions(kind, "poinav", path)
                ir = instructions(kind, "rust", path)
                line = (f"  {kind:7} instructions per call: poinav {ip / 1e6:.1f} M, rust {ir / 1e6:.1f} M, "
                        f"wheel {pct(ip, ir):+.1f}%")
                if (kind, "once") in CALLS:
                    io = instructions(kind, "once", path)
                    line += f"; once {io / 1e6:.1f} M, poinav {pct(ip, io):+.1f}% over it"
                print(line)
        if ("inspect", "cli") in med:
            print(f"  inspect  poinav {med[('inspect', 'poinav')]:.4f} s, "
                  f"CLI subprocess {med[('inspect', 'cli')]:.4f} s")
        line = (f"  counts: psets poinav {counts[('psets', 'poinav')]}, rust {counts[('psets', 'rust')]}, "
                f"once {counts[('psets', 'once')]}")
        if ("psets", "ifcos") in counts:
            line += f", ifcos {counts[('psets', 'ifcos')]}"
        if "meshes" in kinds:
            line += f"; triangles poinav {counts[('meshes', 'poinav')]}, rust {counts[('meshes', 'rust')]}"
            if ("meshes", "ifcos") in counts:
                line += f", ifcos {counts[('meshes', 'ifcos')]}"
        print(line)
    return 0


if __name__ == "__main__":
    sys.exit(main())
