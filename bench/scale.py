"""Every poinav command on the large benchmark models: wall time, peak memory, ratio to export glb.

Usage: .venv/bin/python bench/scale.py [MODEL...] [--poinav BIN] [--timeout S] [--keep DIR]

MODEL defaults to heavy-furnished-ft.ifc and synthetic-x8.ifc in /work/bench-models (or
$POINAV_BENCH_MODELS), written by `scripts/make-heavy-model.py` and `scripts/make-scaled-model.py`
(never committed). BIN defaults to target/release/poinav (`cargo build -p poinav --release`).
For each model, one child process per command, outputs in a temporary folder (--keep DIR keeps
them there):
  inspect       inspect --json (its storeys and spaces choose the arguments below)
  enrich        enrich -o enriched.ifc
  export glb    export glb -o model.glb
  plan          plan --all-storeys -o plan/: every storey's plan, one process
  audit         audit -o audit/report.html
  export nav2   export nav2 -o nav2
  route         route --from A@S1 --to B@S2: the first space of the lowest storey with spaces to
                the first space of the highest one (names as inspect lists them; the first
                match wins where names repeat)
  simulate      simulate scenario.toml: 2 robots, 30 simulated seconds, on the lowest storey
                with spaces, each starting at the centre of one of its first two spaces and
                routing to the other's (centres from IfcOpenShell's geometry of those spaces)
Wall time, CPU time (user + sys) and peak RSS come from the child alone (os.wait4's rusage;
IfcOpenShell runs in a child of its own, so this process stays small: a forked child's peak RSS
starts at its parent's);
the load average is printed before and after each model (the machine may be shared). A command still running
after --timeout seconds (default 600) is killed and reported as `timeout`.
Prints a markdown table per model: exit code, wall time, CPU time, peak RSS, time / export
glb's time, peak RSS / file size. Exit 0, or 1 when BIN or a model is missing.
"""

import argparse
import os
import platform
import resource
import shutil
import signal
import subprocess
import sys
import tempfile
import time
from pathlib import Path

REPO = Path(__file__).resolve().parent.parent
MODELS = Path(os.environ.get("POINAV_BENCH_MODELS", "/work/bench-models"))
DEFAULT_MODELS = ["heavy-furnished-ft.ifc", "synthetic-x8.ifc"]


def run(cmd, timeout, cwd):
    """(exit code or None on timeout, wall seconds, peak RSS bytes, stdout, CPU seconds)."""
    out = open(Path(cwd) / "stdout.txt", "wb")
    err = open(Path(cwd) / "stderr.txt", "wb")
    start = time.perf_counter()
    proc = subprocess.Popen(cmd, cwd=cwd, stdout=out, stderr=err, start_new_session=True)
    code = None
    while True:
        pid, status, usage = os.wait4(proc.pid, os.WNOHANG)
        if pid:
            code = os.waitstatus_to_exitcode(status)
            break
        if time.perf_counter() - start > timeout:
            os.killpg(proc.pid, signal.SIGKILL)
            _, status, usage = os.wait4(proc.pid, 0)
            break
        time.sleep(0.02)
    wall = time.perf_counter() - start
    proc.returncode = 0  # reaped above
    out.close()
    err.close()
    return (code, wall, usage.ru_maxrss * 1024, (Path(cwd) / "stdout.txt").read_text(errors="replace"),
            usage.ru_utime + usage.ru_stime)


def space_centres(model, spaces):
    """World XY centres (metres) of the IfcSpaces with these GlobalIds, from IfcOpenShell, in a
    child Python: Linux starts a forked child's peak RSS at its parent's, so a parent holding the
    model in IfcOpenShell (about 300 MiB for the furnished one) would inflate every later row."""
    import json

    out = subprocess.run([sys.executable, __file__, "--space-centres", str(model)] + list(spaces),
                         capture_output=True, text=True, check=True).stdout
    return {g: tuple(c) for g, c in json.loads(out).items()}


def space_centres_here(model, spaces):
    """`space_centres` in this process."""
    import ifcopenshell
    import ifcopenshell.geom

    f = ifcopenshell.open(str(model))
    settings = ifcopenshell.geom.settings()
    settings.set("use-world-coords", True)
    products = [f.by_guid(g) for g in spaces]
    it = ifcopenshell.geom.iterator(settings, f, 1, include=products)
    centres = {}
    if it.initialize():
        while True:
            shape = it.get()
            v = shape.geometry.verts
            xs, ys = v[0::3], v[1::3]
            centres[shape.guid] = ((min(xs) + max(xs)) / 2, (min(ys) + max(ys)) / 2)
            if not it.next():
                break
    return centres


def scenario(model, storey, a, b, centres, routes=True):
    def robot(name, space, goal, side):
        x, y = centres[space["guid"]]
        controller = (f'{{ kind = "route", to = "{goal["name"]}" }}' if routes
                      else f'{{ kind = "wall-follow", side = "{side}" }}')
        return (f'[[robot]]\nname = "{name}"\nstart = {{ x = {x:.3f}, y = {y:.3f}, heading_deg = 0.0 }}\n'
                f'controller = {controller}\n')

    return (f'name = "scale"\nduration_s = 30.0\n\n[building]\nifc = "{model}"\nstorey = "{storey}"\n\n'
            + robot("Robot1", a, b, "left") + "\n" + robot("Robot2", b, a, "right"))


def bench_model(poinav, model, timeout, work):
    import json

    rows = []
    size = model.stat().st_size

    def row(name, cmd, budget=timeout):
        d = work / name.replace(" ", "-")
        d.mkdir(parents=True, exist_ok=True)
        code, wall, rss, out, cpu = run([str(poinav)] + cmd, budget, d)
        note = ""
        if code:
            lines = (d / "stderr.txt").read_text(errors="replace").strip().splitlines()
            note = lines[-1] if lines else ""
        rows.append({"name": name, "code": code, "wall": wall, "cpu": cpu, "rss": rss, "note": note})
        return code, out

    code, out = row("inspect", ["inspect", str(model), "--json"])
    info = json.loads(out) if code == 0 else {"storeys": [], "spaces": []}
    row("enrich", ["enrich", str(model), "-o", str(work / "enriched.ifc")])
    row("export glb", ["export", "glb", str(model), "-o", str(work / "model.glb")])

    # plan: every storey in one process (the model read and meshed once).
    storeys = info["storeys"]
    code, out = row("plan", ["plan", str(model), "--all-storeys", "-o", str(work / "plan")])
    written = out.count("wrote ")
    rows[-1]["name"] = f"plan ({written} of {len(storeys)} storeys, --all-storeys)"

    row("audit", ["audit", str(model), "-o", str(work / "audit" / "report.html")])
    row("export nav2", ["export", "nav2", str(model), "-o", str(work / "nav2")])

    by_storey = {}
    for sp in info["spaces"]:
        if sp.get("name") and sp.get("storey_id") is not None:
            by_storey.setdefault(sp["storey_id"], []).append(sp)
    elev = {s["id"]: (s.get("elevation_m") or 0.0) for s in storeys}
    with_spaces = sorted(by_storey, key=lambda i: (elev.get(i, 0.0), i))
    if with_spaces:
        lo, hi = by_storey[with_spaces[0]], by_storey[with_spaces[-1]]
        row("route", ["route", str(model), "--from", f"{lo[0]['name']}@{lo[0]['storey']}",
                      "--to", f"{hi[0]['name']}@{hi[0]['storey']}"])
    if with_spaces and len(lo) >= 2:
        a, b = lo[0], lo[1]
        centres = space_centres(model, [a["guid"], b["guid"]])
        if a["guid"] in centres and b["guid"] in centres:
            path = work / "scenario.toml"
            path.write_text(scenario(model, a["storey"], a, b, centres))
            code, _ = row("simulate", ["simulate", str(path), "-o", str(work / "sim")])
            if code == 2:  # no route between the two spaces: the robots follow walls instead
                path.write_text(scenario(model, a["storey"], a, b, centres, routes=False))
                row("simulate (wall-following)", ["simulate", str(path), "-o", str(work / "sim-walls")])
    glb = next(r for r in rows if r["name"] == "export glb")
    print(f"\n### {model.name} ({size / 1e6:.1f} MB)\n")
    print("| command | exit | wall time | CPU time | peak RSS | time / export glb | peak RSS / file size |")
    print("|---|---|---|---|---|---|---|")
    for r in rows:
        timed_out = r["code"] is None
        wall = f"timeout ({r['wall']:.0f} s)" if timed_out else f"{r['wall']:.2f} s"
        ratio = "-" if timed_out or glb["code"] is None else f"{r['wall'] / glb['wall']:.1f}x"
        if timed_out and glb["code"] is not None:
            ratio = f"> {r['wall'] / glb['wall']:.0f}x"
        print(f"| {r['name']} | {'-' if timed_out else r['code']} | {wall} | {r['cpu']:.2f} s | "
              f"{r['rss'] / 2**20:.0f} MiB | {ratio} | {r['rss'] / size:.1f}x |")
    notes = [f"- {r['name']} (exit {r['code']}): {r['note']}" for r in rows if r["code"] and r["note"]]
    if notes:
        print("\n" + "\n".join(notes))
    sys.stdout.flush()


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("models", nargs="*", type=Path)
    ap.add_argument("--poinav", type=Path, default=REPO / "target" / "release" / "poinav")
    ap.add_argument("--timeout", type=float, default=600.0)
    ap.add_argument("--keep", type=Path, help="keep the outputs in this folder")
    args = ap.parse_args()
    models = args.models or [MODELS / m for m in DEFAULT_MODELS]
    missing = [str(p) for p in [args.poinav] + models if not p.is_file()]
    if missing:
        sys.stderr.write("missing: " + ", ".join(missing) +
                         " (build with `cargo build -p poinav --release`; make the models with "
                         "scripts/make-heavy-model.py and scripts/make-scaled-model.py)\n")
        return 1
    version = subprocess.run([str(args.poinav), "--version"], capture_output=True, text=True).stdout.strip()
    print(f"{time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())}, {version} ({args.poinav}), "
          f"{os.cpu_count()} cores, {os.sysconf('SC_PAGE_SIZE') * os.sysconf('SC_PHYS_PAGES') / 2**30:.0f} GiB, "
          f"{platform.machine()}, timeout {args.timeout:.0f} s per command")
    resource.setrlimit(resource.RLIMIT_CORE, (0, 0))
    for model in models:
        work = Path(tempfile.mkdtemp(prefix="poinav-scale-"))
        try:
            before = os.getloadavg()
            bench_model(args.poinav, model.resolve(), args.timeout, work)
            after = os.getloadavg()
            print(f"\nload average (1, 5, 15 min) before: {before[0]:.2f} {before[1]:.2f} {before[2]:.2f}, "
                  f"after: {after[0]:.2f} {after[1]:.2f} {after[2]:.2f}")
            sys.stdout.flush()
        finally:
            if args.keep:
                dest = args.keep / model.stem
                shutil.rmtree(dest, ignore_errors=True)
                shutil.move(str(work), dest)
            else:
                shutil.rmtree(work, ignore_errors=True)
    return 0


if __name__ == "__main__":
    if sys.argv[1:2] == ["--space-centres"]:
        import json

        print(json.dumps(space_centres_here(Path(sys.argv[2]), sys.argv[3:])))
        sys.exit(0)
    sys.exit(main())
