#!/usr/bin/env bash
# Builds the cargo-fuzz targets and runs each for a bounded time (default 30 s each).
# Usage: scripts/fuzz.sh [SECONDS_PER_TARGET] [TARGET...]   (POINAV_FUZZ_SEED, default 1)
# POINAV_FUZZ_DEV=1 builds without optimisation (with overflow checks): a much shorter build for
# short smoke runs (scripts/test.sh); long runs keep the default optimised build.
# Seeds: fuzz/seeds/<target>/ (ours) plus, for the IFC targets, the small corpus files from
# ../shared/ifc copied into a temporary corpus folder (never into the repository).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root/fuzz"
seconds="${1:-30}"
shift || true
targets=("$@")
[[ ${#targets[@]} -gt 0 ]] || targets=(step_reader step_string rules_loader scenario_loader enrichment)

if ! command -v cargo-fuzz >/dev/null 2>&1; then
    cargo install cargo-fuzz --version 0.13.2 --locked
fi
# No sanitizer: the project forbids unsafe code and this keeps to the stable toolchain.
mode=(-O)
[[ ${POINAV_FUZZ_DEV:-0} == 1 ]] && mode=(--dev)
cargo fuzz build -s none "${mode[@]}"

shared="${POINAV_SHARED:-$root/../shared}"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
for t in "${targets[@]}"; do
    corpus="$work/$t"
    mkdir -p "$corpus"
    cp "seeds/$t"/* "$corpus/"
    if [[ $t == step_reader || $t == enrichment ]]; then
        for f in "$shared"/ifc/wall-opening-window-ifc4x3.ifc "$shared"/ifc/ramps-extract.ifc; do
            [[ -f $f ]] && cp "$f" "$corpus/"
        done
    fi
    echo "fuzz: $t for ${seconds}s"
    # A fixed seed: every run explores the same inputs first, so CI is reproducible.
    cargo fuzz run -s none "${mode[@]}" "$t" "$corpus" -- -seed="${POINAV_FUZZ_SEED:-1}" -max_total_time="$seconds" -max_len=65536 -timeout=10 -rss_limit_mb=2048 2>&1 | tail -n 3
done
