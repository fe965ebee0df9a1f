#!/usr/bin/env bash
# The main job end to end: builds poinav in release mode and runs `poinav demo` (the paper's
# test building: enrichment, the three validation scenarios, design iteration, routes, audit,
# Nav2 bundle, GLB, report) into
# out/demo/; then inspects and enriches every model of the corpus into out/demo/corpus/: per
# model the inspect report (.json), the enriched IFC (.poi.ifc), the semantic CSV (.csv), the
# IDS (.ids), the enrichment summary (.enrich.json), a floor plan of its first storey (.svg) and
# the accessibility audit for the paper's robot (.audit/report.html), plus a summary table.
# A plan or audit that fails is reported (its messages in .plan.log, .audit/log), not hidden.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"
shared="${POINAV_SHARED:-$root/../shared}"
out="$root/out/demo"
mkdir -p "$out"

cargo build --release --locked -p poinav
bin="$root/target/release/poinav"
"$bin" demo -o "$out"
out="$out/corpus"
mkdir -p "$out"
echo

printf '%-44s %-12s %8s %7s %7s %7s %6s %8s %9s %9s\n' file schema "unit(m)" storeys spaces doors diag enriched corridors restricted | tee "$out/summary.txt"
for f in "$shared"/ifc/*.ifc; do
    name="$(basename "$f" .ifc)"
    "$bin" inspect "$f" --json > "$out/$name.json"
    "$bin" enrich "$f" -o "$out/$name.poi.ifc" --csv "$out/$name.csv" --ids "$out/$name.ids" --json > "$out/$name.enrich.json"
    # Plan and audit may fail on models without a building (railway): say so, keep going; their
    # messages are in the .log files.
    "$bin" plan "$f" -o "$out/$name.svg" > /dev/null 2> "$out/$name.plan.log" \
        || echo "demo: plan of $name failed (exit $?), see $out/$name.plan.log" >&2
    mkdir -p "$out/$name.audit"
    "$bin" audit "$f" -o "$out/$name.audit/report.html" > /dev/null 2> "$out/$name.audit/log" \
        || echo "demo: audit of $name failed (exit $?), see $out/$name.audit/log" >&2
    python3 - "$out/$name.json" "$out/$name.enrich.json" "$name" <<'PY' | tee -a "$out/summary.txt"
import json, sys
r = json.load(open(sys.argv[1]))
e = json.load(open(sys.argv[2]))
doors = e["profiles"][0]["doors"]
print(f"{sys.argv[3]:<44} {r['schema']:<12} {r['length_unit_m']:>8g} {len(r['storeys']):>7} {len(r['spaces']):>7} {len(r['doors']):>7} {r['diagnostics']:>6} {e['elements']:>8} {len(e['corridors']):>9} {doors['RESTRICTED']:>9}")
PY
done
echo
"$bin" enrich "$shared/ifc/office-a.ifc" -o "$out/office-a.poi.ifc"
echo
echo "demo: report in ${out%/corpus}/report.html, corpus outputs in $out"
echo "demo: drive the robots in the browser with"
echo "  $bin serve --scenario crates/poinav-sim/scenarios/drive.toml   # then open http://127.0.0.1:8080/"
