"""Which elements IfcOpenShell meshes and poinav does not (and the reverse), per corpus file.

Usage: .venv/bin/python bench/coverage_vs_ifcopenshell.py [FILE...] [--jobs N]
       [--time-limit S] [--profile PROFILE] [--markdown]

FILE defaults to every `*.ifc` of the corpus (../shared/ifc, or $POINAV_SHARED/ifc). For each
file, in this one run:
  (a) IfcOpenShell 0.9's geometry iterator, default settings (Body representations, openings
      subtracted), world coordinates, over every product but openings
      (`IfcFeatureElementSubtraction`): tests/ifcos/meshed_guids.py, one process per file
      (--jobs at once, default 2), each given --time-limit seconds (default 600; a file past
      it is reported, not compared); the GlobalIds of the products it returns a shape for;
  (b) poinav: `cargo run --profile PROFILE -p poinav-geom --example mesh_listing -- FILE...`
      (default profile `release`), which prints, per file, the GlobalIds of the products
      `mesh_model` meshes, its failures with the reason, and the elements without any
      Representation.
Prints one row per file: IfcOpenShell meshed (elements and spaces; other products such as
sites or annotations in brackets, which poinav does not mesh), poinav meshed, meshed by
IfcOpenShell and not by poinav, and the reverse; then every element of the "not by poinav"
column with its class and poinav's reason, and the reverse ones; the last column counts
poinav's failures (products with a representation but no mesh, each with its reason). `--markdown` prints the
table as the README's.
Exit 0; 1 if the example fails.
"""

import argparse
import json
import os
import subprocess
import sys
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

REPO = Path(__file__).resolve().parent.parent
SHARED = Path(os.environ.get("POINAV_SHARED", REPO.parent / "shared"))


def ifcopenshell_meshed(path, limit):
    cmd = [sys.executable, str(REPO / "tests" / "ifcos" / "meshed_guids.py"), str(path)]
    try:
        proc = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                              timeout=limit)
    except subprocess.TimeoutExpired:
        return None, f"IfcOpenShell took more than {limit:.0f} s"
    if proc.returncode != 0:
        return None, f"IfcOpenShell failed: {proc.stderr.strip().splitlines()[-1:]}"
    return json.loads(proc.stdout)[str(path)], None


def poinav_listing(files, profile):
    cmd = ["cargo", "run", "--quiet", "--profile", profile, "-p", "poinav-geom", "--example",
           "mesh_listing", "--"] + [str(f) for f in files]
    proc = subprocess.run(cmd, cwd=REPO, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    if proc.returncode != 0:
        sys.stderr.write(proc.stderr)
        raise SystemExit(1)
    return [json.loads(line) for line in proc.stdout.splitlines() if line.strip()]


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("files", nargs="*")
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--time-limit", type=float, default=600.0)
    ap.add_argument("--profile", default="release")
    ap.add_argument("--markdown", action="store_true")
    args = ap.parse_args()
    files = [Path(f) for f in args.files] or sorted((SHARED / "ifc").glob("*.ifc"))
    with ThreadPoolExecutor(max_workers=max(1, args.jobs)) as pool:
        ours = poinav_listing(files, args.profile)
        theirs = list(pool.map(lambda f: ifcopenshell_meshed(f, args.time_limit), files))
    rows, details = [], []
    for path, listing, (ios, problem) in zip(files, ours, theirs):
        name = path.name
        meshed = listing["meshed"]  # guid -> class
        failed = listing["failed"]  # guid -> [class, reason]
        without = listing["without_representation"]  # guid -> class
        candidates = set(listing["candidates"])  # elements but openings, and spaces
        if ios is None:
            rows.append((name, None, 0, len(meshed), None, None, problem, len(failed)))
            continue
        elements = {g: c for g, c in ios.items() if g in candidates}
        other = len(ios) - len(elements)
        missing = sorted(g for g in elements if g not in meshed)
        extra = sorted(g for g in meshed if g not in ios)
        rows.append((name, len(elements), other, len(meshed), len(missing), len(extra), None,
                     len(failed)))
        for g in missing:
            reason = failed.get(g, [elements[g], "not meshed"])[1] if g in failed else (
                "no Representation" if g in without else "not a meshed product")
            details.append(f"{name}: IfcOpenShell only: {elements[g]} {g}: {reason}")
        for g in extra:
            details.append(f"{name}: poinav only: {meshed[g]} {g}")
    if args.markdown:
        print("| file | IfcOpenShell meshes | poinav meshes | IfcOpenShell only | poinav only "
              "| poinav failures |")
        print("| --- | ---: | ---: | ---: | ---: | ---: |")
        for name, ios, other, ours_n, missing, extra, problem, fails in rows:
            if problem:
                print(f"| {name} | ({problem}) | {ours_n} | | | {fails} |")
            else:
                o = f" (+{other} other)" if other else ""
                print(f"| {name} | {ios}{o} | {ours_n} | {missing} | {extra} | {fails} |")
    else:
        print(f"{'file':45} {'IfcOpenShell':>18} {'poinav':>7} {'IOS only':>9} {'poinav only':>12}"
              f" {'failures':>9}")
        for name, ios, other, ours_n, missing, extra, problem, fails in rows:
            if problem:
                print(f"{name:45} {problem}; poinav meshes {ours_n}, {fails} failures")
            else:
                o = f"{ios} (+{other})" if other else str(ios)
                print(f"{name:45} {o:>18} {ours_n:>7} {missing:>9} {extra:>12} {fails:>9}")
    for d in details:
        print(d)


if __name__ == "__main__":
    main()
