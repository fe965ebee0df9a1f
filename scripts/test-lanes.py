#!/usr/bin/env python3
"""Runs the workspace's tests like `cargo test --workspace`, but keeps every core busy.

`cargo test` runs its test binaries one after another; many of ours spend their time in one
thread (an IfcOpenShell process, a browser, one big model), so on a 2-core machine half the
machine idles for most of the run. This script builds every test binary once
(`cargo test --no-run`, same profile and flags), then runs the binaries, and the doc tests, on
N lanes at once (default: the number of cores), longest first (the durations of the last run
are kept in the target folder; a cold run puts the known slow ones first). Each binary runs in
its package's folder with the variables cargo sets, so it behaves as under `cargo test`.

Output: one line per finished binary with its time and result; the whole output of a failed
one. Exit status 0 when everything passed, 1 when a test failed, 2 when the build failed.

    python3 scripts/test-lanes.py [--lanes N] [--profile ci] [-- extra cargo args]
"""

import argparse
import json
import os
import subprocess
import sys
import tempfile
import threading
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent

# Slowest first when no durations are on record (measured 2026-11-27, ci profile).
KNOWN_SLOW = [
    "viewer_browser",
    "ros2_mcap",
    "viewer_storeys",
    "ids_vs_ifctester",
    "enrich_corpus",
    "round_trip",
    "export_3d_corpus",
]


def build(profile, extra):
    cmd = ["cargo", "test", *scope(extra), "--locked", "--profile", profile, "--no-run",
           "--message-format=json-render-diagnostics", *extra]
    proc = subprocess.run(cmd, cwd=ROOT, stdout=subprocess.PIPE, text=True)
    if proc.returncode != 0:
        return None
    jobs = []
    for line in proc.stdout.splitlines():
        try:
            msg = json.loads(line)
        except json.JSONDecodeError:
            continue
        if msg.get("reason") != "compiler-artifact" or not msg.get("executable"):
            continue
        if not msg["profile"].get("test"):
            continue
        target = msg["target"]
        package = msg["package_id"]
        manifest = Path(msg["manifest_path"])
        name = package_name(package, manifest)
        kind = target["kind"][0]
        label = f"{name} {target['name']}" if kind != "lib" else f"{name} (lib)"
        jobs.append({
            "label": label,
            "cmd": [msg["executable"]],
            "cwd": manifest.parent,
            "package": name,
            "manifest": manifest,
        })
    return jobs


def scope(extra):
    """`--workspace` unless the extra arguments pick packages themselves."""
    picks = any(a in ("-p", "--package") or a.startswith("--package=") for a in extra)
    return [] if picks else ["--workspace"]


def package_name(package_id, manifest):
    # `path+file:///.../crates/poinav-nav#0.1.0` or `poinav-nav 0.1.0 (path+file://...)`
    if "#" in package_id:
        tail = package_id.rsplit("#", 1)[1]
        if "@" in tail:
            return tail.split("@", 1)[0]
        return manifest.parent.name
    return package_id.split(" ", 1)[0]


def cargo_env(job, profile_dir):
    env = dict(os.environ)
    env["CARGO_MANIFEST_DIR"] = str(job["cwd"])
    env["CARGO_PKG_NAME"] = job["package"]
    env["CARGO_CRATE_NAME"] = job["package"].replace("-", "_")
    sysroot = subprocess.run(["rustc", "--print", "sysroot"], capture_output=True,
                             text=True).stdout.strip()
    libs = [str(profile_dir / "deps"), str(profile_dir), f"{sysroot}/lib"]
    if env.get("LD_LIBRARY_PATH"):
        libs.append(env["LD_LIBRARY_PATH"])
    env["LD_LIBRARY_PATH"] = ":".join(libs)
    return env


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--lanes", type=int, default=os.cpu_count() or 2)
    ap.add_argument("--profile", default="ci")
    ap.add_argument("extra", nargs="*", help="more cargo arguments (after --)")
    args = ap.parse_args()

    t0 = time.monotonic()
    jobs = build(args.profile, args.extra)
    if jobs is None:
        print("test-lanes: the build failed", file=sys.stderr)
        return 2
    target_dir = Path(os.environ.get("CARGO_TARGET_DIR", ROOT / "target"))
    profile_dir = target_dir / ("debug" if args.profile in ("dev", "test") else args.profile)
    for job in jobs:
        job["env"] = cargo_env(job, profile_dir)
    jobs.append({
        "label": "doc tests",
        "cmd": ["cargo", "test", *scope(args.extra), "--locked", "--profile", args.profile,
                "--doc", *args.extra],
        "cwd": ROOT,
        "env": dict(os.environ),
    })
    print(f"test-lanes: built {len(jobs) - 1} test binaries in {time.monotonic() - t0:.0f} s; "
          f"running them and the doc tests on {args.lanes} lanes", flush=True)

    record = profile_dir / "test-lanes-durations.json"
    try:
        last = json.loads(record.read_text())
    except (OSError, ValueError):
        last = {}

    def expected(job):
        if job["label"] in last:
            return last[job["label"]]
        name = job["label"].split(" ")[-1]
        if name in KNOWN_SLOW:
            return 1000 - KNOWN_SLOW.index(name)
        return 1.0

    queue = sorted(jobs, key=expected, reverse=True)
    lock = threading.Lock()
    failed = []
    durations = {}
    counts = {"passed": 0, "failed": 0, "ignored": 0}

    def lane():
        while True:
            with lock:
                if not queue:
                    return
                job = queue.pop(0)
            start = time.monotonic()
            with tempfile.TemporaryFile() as out:
                code = subprocess.run(job["cmd"], cwd=job["cwd"], env=job["env"], stdout=out,
                                      stderr=subprocess.STDOUT).returncode
                out.seek(0)
                text = out.read().decode("utf-8", "replace")
            took = time.monotonic() - start
            summary = [ln for ln in text.splitlines() if ln.startswith("test result:")]
            with lock:
                durations[job["label"]] = round(took, 1)
                mine = {key: 0 for key in counts}
                for ln in summary:
                    for key in counts:
                        part = [p for p in ln.split(";") if p.strip().endswith(key)]
                        if part:
                            mine[key] += int(part[0].split()[-2])
                for key in counts:
                    counts[key] += mine[key]
                state = "ok" if code == 0 else f"FAILED (exit {code})"
                tally = ", ".join(f"{n} {key}" for key, n in mine.items() if n)
                print(f"  {took:7.1f} s  {job['label']}: {state} ({tally or 'no tests'})",
                      flush=True)
                if code != 0:
                    failed.append(job["label"])
                    print(text, flush=True)

    threads = [threading.Thread(target=lane) for _ in range(max(1, args.lanes))]
    for t in threads:
        t.start()
    for t in threads:
        t.join()

    try:
        record.write_text(json.dumps(dict(sorted(durations.items())), indent=1))
    except OSError:
        pass
    print(f"test-lanes: {counts['passed']} passed, {counts['failed']} failed, "
          f"{counts['ignored']} ignored in {len(jobs)} binaries, "
          f"{time.monotonic() - t0:.0f} s in all", flush=True)
    if failed:
        print("test-lanes: failed: " + ", ".join(failed), file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
