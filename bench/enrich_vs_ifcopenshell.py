"""Benchmark `poinav enrich` against IfcOpenShell adding the same property sets.

Usage: .venv/bin/python bench/enrich_vs_ifcopenshell.py FILE [--poinav PATH] [--runs N]

Times, as the median of N runs (default 3, after one untimed warm-up each):
  (a) `PATH enrich FILE -o TMP.ifc --csv TMP.csv` end to end as a subprocess, wall clock,
      with SOURCE_DATE_EPOCH set (taken from the environment, else 1700000000) so every run
      writes the same time stamp (PATH defaults to target/release/poinav in the repo);
  (b) IfcOpenShell in this process: ifcopenshell.open(FILE); for every row of the CSV that
      poinav wrote (read once, before timing: same elements, same values) look the element
      up with by_guid and add Pset_POI_Classification, plus Pset_RobotAccessibility when the
      row has an AccessibilityStatus and Pset_RobotCoordination when it has
      MaxSimultaneousRobots, each with ifcopenshell.api.pset.add_pset + edit_pset; then
      f.write(TMP2.ifc). Open + add + write is timed; interpreter start and import are not.
      If the IfcOpenShell warm-up takes longer than 120 s, it is timed once only (said so).
Prints both medians, the file size, the number of elements enriched, the instances each side
added and the speed ratio.

What the IfcOpenShell side writes, and how it differs from poinav (same values throughout):
  - Enumerated values (POI_Category, POI_Type, AccessibilityStatus, ValidationMethod,
    CoordinationProtocol, AppliesTo): poinav writes IfcPropertyEnumeratedValue pointing at a
    shared IfcPropertyEnumeration (PEnum_*). edit_pset builds enumerated values only from a
    property set template, and IFC2X3 has no templates, so the closest api equivalent is used:
    a plain string, which edit_pset writes as IfcPropertySingleValue(IfcLabel).
  - Role lists (POI_PrimaryRoles, POI_ConditionalRoles): edit_pset builds lists only from a
    template too, so an IfcPropertyListValue of IfcLabel is created with create_entity and
    passed through edit_pset (which accepts IfcProperty instances), as poinav writes it. An
    empty conditional list is left out in IFC2X3 (ListValues is mandatory) and written with
    ListValues `$` in IFC4+, as poinav does.
  - Lengths are passed as IfcPositiveLengthMeasure (a bare float would become IfcReal),
    MaxSimultaneousRobots as int (IfcInteger), LastValidated as a string (IfcLabel) in IFC2X3
    and as IfcDateTime in IFC4+, all as poinav writes them.
  - poinav shares identical sets: one IfcPropertySet and one IfcRelDefinesByProperties per
    distinct set, reusing the file's IfcOwnerHistory. add_pset makes one set and one relation
    per element and, with the api's default owner settings, a new IfcOwnerHistory per set
    (mandatory in IFC2X3; in IFC4+ when the file has a user and an application).
  - The set Description is set to poinav's marker ("poinav POI enrichment") on both sides.
Exit 0; 1 if poinav fails on the file or a CSV GlobalId is not in it; 2 if the poinav binary
or FILE does not exist.
"""

import argparse
import csv
import os
import re
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import ifcopenshell
import ifcopenshell.api.pset

REPO = Path(__file__).resolve().parent.parent
MARKER = "poinav POI enrichment"
SLOW_S = 120.0


def time_poinav(binary, path, out_ifc, out_csv, env):
    cmd = [binary, "enrich", path, "-o", out_ifc, "--csv", out_csv]
    start = time.perf_counter()
    proc = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, env=env)
    elapsed = time.perf_counter() - start
    if proc.returncode != 0:
        sys.stderr.write(proc.stderr.decode(errors="replace"))
        raise SystemExit(f"error: {' '.join(cmd)} exited with {proc.returncode}")
    return elapsed, proc.stdout.decode(errors="replace")


def read_rows(csv_path):
    """The CSV as plain Python values: lengths as float, counts as int, roles as lists."""
    num = lambda s: float(s) if s else None  # noqa: E731
    roles = lambda s: [x for x in s.split(";") if x]  # noqa: E731
    rows = []
    with open(csv_path, newline="", encoding="utf-8") as fh:
        for r in csv.DictReader(fh):
            row = {
                "guid": r["GlobalId"],
                "category": r["POI_Category"],
                "type": r["POI_Type"],
                "primary": roles(r["POI_PrimaryRoles"]),
                "conditional": roles(r["POI_ConditionalRoles"]),
                "access": None,
                "coord": None,
            }
            if r["AccessibilityStatus"]:
                row["access"] = (num(r["MinClearanceWidth"]), num(r["MinClearanceHeight"]),
                                 r["AccessibilityStatus"], r["ValidationMethod"],
                                 r["LastValidated"])
            if r["MaxSimultaneousRobots"]:
                row["coord"] = (int(r["MaxSimultaneousRobots"]), num(r["MinInterRobotSeparation"]),
                                r["CoordinationProtocol"], r["AppliesTo"])
            rows.append(row)
    return rows


def add_set(f, element, name, properties):
    pset = ifcopenshell.api.pset.add_pset(f, product=element, name=name)
    pset.Description = MARKER
    ifcopenshell.api.pset.edit_pset(f, pset=pset, properties=properties)


def label_list(f, name, values, ifc2x3):
    """IfcPropertyListValue of IfcLabel, or None when IFC2X3 cannot hold an empty list."""
    if not values and ifc2x3:
        return None
    items = [f.create_entity("IfcLabel", v) for v in values] or None
    return f.create_entity("IfcPropertyListValue", Name=name, ListValues=items)


def enrich_ifcopenshell(path, rows, out_path):
    """Open, add the sets of every row with ifcopenshell.api, write; returns (seconds, added)."""
    start = time.perf_counter()
    f = ifcopenshell.open(path)
    before = f.get_max_id()
    ifc2x3 = f.schema == "IFC2X3"
    length = lambda v: f.create_entity("IfcPositiveLengthMeasure", v)  # noqa: E731
    for row in rows:
        element = f.by_guid(row["guid"])
        props = {"POI_Category": row["category"], "POI_Type": row["type"],
                 "POI_PrimaryRoles": label_list(f, "POI_PrimaryRoles", row["primary"], ifc2x3)}
        conditional = label_list(f, "POI_ConditionalRoles", row["conditional"], ifc2x3)
        if conditional is not None:
            props["POI_ConditionalRoles"] = conditional
        add_set(f, element, "Pset_POI_Classification", props)
        if row["access"]:
            width, height, status, method, validated = row["access"]
            add_set(f, element, "Pset_RobotAccessibility", {
                "MinClearanceWidth": length(width),
                "MinClearanceHeight": length(height),
                "AccessibilityStatus": status,
                "ValidationMethod": method,
                "LastValidated": validated if ifc2x3 else f.create_entity("IfcDateTime", validated),
            })
        if row["coord"]:
            robots, separation, protocol, applies_to = row["coord"]
            add_set(f, element, "Pset_RobotCoordination", {
                "MaxSimultaneousRobots": robots,
                "MinInterRobotSeparation": length(separation),
                "CoordinationProtocol": protocol,
                "AppliesTo": applies_to,
            })
    f.write(out_path)
    elapsed = time.perf_counter() - start
    added = f.get_max_id() - before
    del f
    return elapsed, added


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("file")
    ap.add_argument("--poinav", default=str(REPO / "target" / "release" / "poinav"))
    ap.add_argument("--runs", type=int, default=3)
    args = ap.parse_args()

    binary = args.poinav if os.path.exists(args.poinav) else shutil.which(args.poinav)
    if not binary or not os.access(binary, os.X_OK):
        print(f"error: poinav binary not found at {args.poinav} "
              "(build it with `cargo build --release -p poinav`, or pass --poinav PATH)",
              file=sys.stderr)
        return 2
    if not os.path.isfile(args.file):
        print(f"error: no such file: {args.file}", file=sys.stderr)
        return 2
    runs = max(1, args.runs)
    size_mb = os.path.getsize(args.file) / 1e6
    env = dict(os.environ, SOURCE_DATE_EPOCH=os.environ.get("SOURCE_DATE_EPOCH", "1700000000"))

    with tempfile.TemporaryDirectory(prefix="poinav-enrich-bench-") as tmp:
        out_ifc, out_csv = os.path.join(tmp, "poinav.ifc"), os.path.join(tmp, "poinav.csv")
        out_ios = os.path.join(tmp, "ifcopenshell.ifc")

        _, summary = time_poinav(binary, args.file, out_ifc, out_csv, env)  # warm-up
        t_poinav = statistics.median(
            time_poinav(binary, args.file, out_ifc, out_csv, env)[0] for _ in range(runs))
        m = re.search(r"(\d+) instances added", summary)
        poinav_added = m.group(1) if m else "?"

        rows = read_rows(out_csv)  # before any IfcOpenShell timing
        try:
            warm, ios_added = enrich_ifcopenshell(args.file, rows, out_ios)  # warm-up
        except RuntimeError as e:  # by_guid: a GlobalId of the CSV is not in the file
            print(f"error: IfcOpenShell: {e}", file=sys.stderr)
            return 1
        ios_runs = 1 if warm > SLOW_S else runs
        t_ios = statistics.median(
            enrich_ifcopenshell(args.file, rows, out_ios)[0] for _ in range(ios_runs))

    n_access = sum(1 for r in rows if r["access"])
    n_coord = sum(1 for r in rows if r["coord"])
    print(f"file: {args.file} ({size_mb:.2f} MB)")
    print(f"elements enriched: {len(rows)} (Pset_POI_Classification {len(rows)}, "
          f"Pset_RobotAccessibility {n_access}, Pset_RobotCoordination {n_coord})")
    note = "" if ios_runs == runs else f", warm-up took {warm:.0f} s > {SLOW_S:.0f} s"
    print(f"  {'':46} {'seconds':>9} {'runs':>5} {'added':>8}")
    print(f"  {'poinav enrich -o --csv (subprocess)':46} {t_poinav:9.3f} {runs:5} "
          f"{poinav_added:>8}")
    print(f"  {'IfcOpenShell open + api + write (in-process)':46} {t_ios:9.3f} {ios_runs:5} "
          f"{ios_added:>8}")
    print(f"  (median of the runs after one warm-up; added = IFC instances written"
          f"{note}; IfcOpenShell warm-up {warm:.3f} s)")
    if t_poinav <= t_ios:
        print(f"poinav enrich is {t_ios / t_poinav:.1f}x faster than IfcOpenShell "
              "(open + api + write)")
    else:
        print(f"poinav enrich is {t_poinav / t_ios:.1f}x slower than IfcOpenShell "
              "(open + api + write)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
