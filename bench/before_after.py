"""Two builds of poinav on the same commands, interleaved: is any command slower after a change?

Usage: python3 bench/before_after.py --before BIN --after BIN [--rounds N] [MODEL...]

Issue 16's check ("no command gets slower by more than 5 %: inspect, enrich, export glb, export
nav2 on office-a and the 17.9 MB file, simulation steps"). BIN are two `poinav` release binaries,
e.g. the one built from the commit before a refactor (`git worktree add /tmp/before REV && cd
/tmp/before && cargo build --release -p poinav`) and target/release/poinav. MODEL defaults to
office-a.ifc and synthetic-merged-office-duplex-ifc2x3.ifc in $POINAV_SHARED/ifc (default
../shared/ifc). For each model: `inspect --json`, `enrich -o`, `export glb -o`, `export nav2 -o`,
`plan --all-storeys -o`, `audit -o`;
then the simulation: `simulate` of a crowd scenario written here (24 robots routing between the
rooms of a 4-rooms-per-side test building, 60 simulated seconds, full JSON Lines trace) and of
the shipped `doorway.toml`.

Each round runs every command once with each binary, one right after the other (which goes
first alternates by round), each in a child process whose CPU time (user + sys, os.wait4's
rusage) and wall time are kept; outputs go to a temporary folder. Prints a markdown table: the
median CPU and wall time of each side, after/before, and `ok` when the CPU ratio is at most
1.05 (CPU time, since a shared machine stretches wall time; the load average is printed before
and after). Exit 0, or 2 when a binary or model is missing or a command fails.
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
DEFAULT_MODELS = ["office-a.ifc", "synthetic-merged-office-duplex-ifc2x3.ifc"]


def crowd_scenario(rooms=4, seconds=60.0):
    """24 robots, three in each room, each routing to a room across the corridor."""
    s = (f'name = "crowd"\nduration_s = {seconds}\n[building]\n'
         f'demo = {{ rooms_per_side = {rooms} }}\n')
    k = 0
    for side in range(2):
        for i in range(rooms):
            x0, y0 = i * 4.2, (0.0 if side == 0 else 6.8)
            heading = 90.0 if side == 0 else -90.0
            for dx, dy in [(1.0, 1.0), (3.0, 1.0), (2.0, 2.8)]:
                k += 1
                room = side * rooms + i
                to = (room + rooms + k % 2) % (2 * rooms)
                s += (f'[[robot]]\nname = "R{k}"\n'
                      f'start = {{ x = {x0 + dx}, y = {y0 + dy}, heading_deg = {heading} }}\n'
                      f'controller = {{ kind = "route", to = "Room {to + 1}" }}\n')
    return s


def run(cmd, cwd):
    """(exit code, wall seconds, CPU seconds, last stderr line) of one child process."""
    start = time.perf_counter()
    with open(Path(cwd) / "stderr.txt", "wb") as err:
        proc = subprocess.Popen(cmd, cwd=cwd, stdout=subprocess.DEVNULL, stderr=err)
        _, status, usage = os.wait4(proc.pid, 0)
    wall = time.perf_counter() - start
    proc.returncode = os.waitstatus_to_exitcode(status)
    lines = (Path(cwd) / "stderr.txt").read_text(errors="replace").strip().splitlines()
    return proc.returncode, wall, usage.ru_utime + usage.ru_stime, lines[-1] if lines else ""


def commands(models, work):
    out = []
    for m in models:
        short = m.stem[:24]
        out += [
            (f"inspect {short}", lambda o, m=m: ["inspect", str(m), "--json"]),
            (f"enrich {short}", lambda o, m=m: ["enrich", str(m), "-o", str(o / "enriched.ifc")]),
            (f"export glb {short}", lambda o, m=m: ["export", "glb", str(m), "-o", str(o / "m.glb")]),
            (f"export nav2 {short}", lambda o, m=m: ["export", "nav2", str(m), "-o", str(o / "nav2")]),
            (f"plan {short}", lambda o, m=m: ["plan", str(m), "--all-storeys", "-o", str(o / "plans")]),
            (f"audit {short}", lambda o, m=m: ["audit", str(m), "-o", str(o / "audit" / "report.html")]),
        ]
    crowd = work / "crowd.toml"
    crowd.write_text(crowd_scenario())
    doorway = REPO / "crates/poinav-sim/scenarios/doorway.toml"
    out += [
        ("simulate crowd (24 robots, 60 s)", lambda o: ["simulate", str(crowd), "-o", str(o / "sim")]),
        ("simulate doorway.toml", lambda o: ["simulate", str(doorway), "-o", str(o / "sim")]),
    ]
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--before", required=True, type=Path)
    ap.add_argument("--after", required=True, type=Path)
    ap.add_argument("--rounds", type=int, default=5)
    ap.add_argument("models", nargs="*")
    a = ap.parse_args()
    models = [Path(m) if "/" in m else SHARED / "ifc" / m for m in (a.models or DEFAULT_MODELS)]
    for p in [a.before, a.after] + models:
        if not p.exists():
            print(f"missing: {p}", file=sys.stderr)
            return 2
    bins = {"before": a.before.resolve(), "after": a.after.resolve()}
    print(f"load average before: {os.getloadavg()}")
    with tempfile.TemporaryDirectory(prefix="poinav-before-after-") as tmp:
        work = Path(tmp)
        cmds = commands(models, work)
        times = {(name, side): [] for name, _ in cmds for side in bins}
        for r in range(a.rounds):
            order = ["before", "after"] if r % 2 == 0 else ["after", "before"]
            for name, args in cmds:
                for side in order:
                    o = work / side / name.replace(" ", "-")
                    o.mkdir(parents=True, exist_ok=True)
                    code, wall, cpu, last = run([str(bins[side])] + args(o), o)
                    if code != 0:
                        print(f"{name} ({side}) exit {code}: {last}", file=sys.stderr)
                        return 2
                    times[(name, side)].append((cpu, wall))
    print(f"load average after: {os.getloadavg()}")
    print(f"\n{a.rounds} rounds, medians; before = {bins['before']}, after = {bins['after']}\n")
    print("| command | CPU before | CPU after | after/before | wall before | wall after | within 5 % |")
    print("|---|---|---|---|---|---|---|")
    for name, _ in cmds:
        cb = statistics.median(c for c, _ in times[(name, "before")])
        ca = statistics.median(c for c, _ in times[(name, "after")])
        wb = statistics.median(w for _, w in times[(name, "before")])
        wa = statistics.median(w for _, w in times[(name, "after")])
        ratio = ca / cb if cb > 0 else float("nan")
        print(f"| {name} | {cb:.3f} s | {ca:.3f} s | {ratio:.3f} | {wb:.3f} s | {wa:.3f} s | "
              f"{'ok' if ratio <= 1.05 else 'SLOWER'} |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
