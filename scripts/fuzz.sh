#!/usr/bin/env bash
# Builds the libFuzzer targets in fuzz/ and runs each for a bounded time (default 30 s each).
# Usage: scripts/fuzz.sh [SECONDS_PER_TARGET] [TARGET...]   (POINAV_FUZZ_SEED, default 1)
#
# No cargo-fuzz needed: the build is plain `cargo build` with the instrumentation flags
# cargo-fuzz 0.13 passes for `-s none` (SanitizerCoverage: inline 8-bit counters, PC table,
# compare tracing, stack depth; `--cfg fuzzing`), on the stable toolchain. Targets and corpora
# keep cargo-fuzz's layout, so `cargo fuzz run -s none TARGET` works too where it is installed.
#
# Build modes (POINAV_FUZZ_BUILD):
#   quick (default): optimised (opt-level 1) with many codegen units: a short build for the
#                    short runs of scripts/test.sh; executions are about as fast as the full
#                    mode's for these targets' inputs.
#   full:            what `cargo fuzz build -O` builds (opt-level 3, one codegen unit): for
#                    long runs.
#   dev:             unoptimised, with debug assertions and overflow checks in every crate.
# Seeds: fuzz/seeds/<target>/ (ours) plus, for the IFC targets, the small corpus files from
# ../shared/ifc copied into a temporary corpus folder (never into the repository).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root/fuzz"
seconds="${1:-30}"
shift || true
targets=("$@")
[[ ${#targets[@]} -gt 0 ]] || targets=(step_reader step_string rules_loader scenario_loader enrichment)

triple="$(rustc -vV | sed -n 's/^host: //p')"
flags=(-Cpasses=sancov-module -Cllvm-args=-sanitizer-coverage-level=4
    -Cllvm-args=-sanitizer-coverage-inline-8bit-counters -Cllvm-args=-sanitizer-coverage-pc-table
    -Cllvm-args=-sanitizer-coverage-trace-compares -Cllvm-args=-simplifycfg-branch-fold-threshold=0
    --cfg fuzzing -Clink-dead-code)
[[ $triple == *-linux-* ]] && flags+=(-Cllvm-args=-sanitizer-coverage-stack-depth)
build=(--release)
out=release
case "${POINAV_FUZZ_BUILD:-quick}" in
    quick) export CARGO_PROFILE_RELEASE_OPT_LEVEL=1 CARGO_PROFILE_RELEASE_CODEGEN_UNITS=16 \
        CARGO_PROFILE_RELEASE_DEBUG=line-tables-only
        # Our crates and the small dependencies their parsers lean on optimised, the rest
        # not: the build's time goes to manifold-rust, i_overlay, toml and regex, a short
        # run's to our parsers.
        build+=(--config 'profile.release.package."*".opt-level=0')
        for c in poinav-io poinav-ifc poinav-geom poinav-roles poinav-poi poinav-author \
            poinav-nav poinav-sim memchr hashbrown foldhash rustc-hash smallvec rayon \
            rayon-core crossbeam-deque crossbeam-epoch crossbeam-utils glam serde_json ryu \
            itoa libfuzzer-sys; do
            build+=(--config "profile.release.package.$c.opt-level=1")
        done ;;
    full) flags+=(-Ccodegen-units=1) ;;
    dev) build=(); out=debug; flags+=(-Cdebug-assertions) ;;
    *) echo "fuzz.sh: POINAV_FUZZ_BUILD is quick, full or dev" >&2; exit 2 ;;
esac
# fuzz/ is its own workspace: bring its lock file's entries for our crates up to date with
# theirs (a new dependency of a poinav crate), without moving any registry version.
cargo update --workspace --offline --quiet
# --target keeps the flags away from build scripts and proc macros (as cargo-fuzz does).
RUSTFLAGS="${flags[*]} ${RUSTFLAGS:-}" CARGO_FUZZ=1 \
    cargo build --locked --bins --target "$triple" "${build[@]}"
bin="$root/fuzz/target/$triple/$out"

shared="${POINAV_SHARED:-$root/../shared}"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
run() {
    local t=$1 corpus="$work/$1"
    mkdir -p "$corpus" "$root/fuzz/artifacts/$t"
    cp "seeds/$t"/* "$corpus/"
    if [[ $t == step_reader || $t == enrichment ]]; then
        for f in "$shared"/ifc/wall-opening-window-ifc4x3.ifc "$shared"/ifc/ramps-extract.ifc; do
            [[ -f $f ]] && cp "$f" "$corpus/"
        done
    fi
    # A fixed seed: every run explores the same inputs first, so CI is reproducible. A crash
    # exits non-zero and leaves its input in fuzz/artifacts/<target>/.
    "$bin/$t" "$corpus" -artifact_prefix="$root/fuzz/artifacts/$t/" -seed="${POINAV_FUZZ_SEED:-1}" \
        -max_total_time="$seconds" -max_len=65536 -timeout=10 -rss_limit_mb=2048 \
        > "$work/$t.log" 2>&1
}
# Each libFuzzer run uses one core: as many targets at once as there are cores
# (POINAV_FUZZ_JOBS), each reported with the last lines of its log when it ends.
jobs="${POINAV_FUZZ_JOBS:-$(nproc)}"
failed=()
pending=("${targets[@]}")
declare -A pid_of=()
while ((${#pending[@]} || ${#pid_of[@]})); do
    while ((${#pending[@]})) && ((${#pid_of[@]} < jobs)); do
        t=${pending[0]}
        pending=("${pending[@]:1}")
        echo "fuzz: $t for ${seconds}s"
        run "$t" &
        pid_of[$t]=$!
    done
    for t in "${!pid_of[@]}"; do
        if ! kill -0 "${pid_of[$t]}" 2>/dev/null; then
            if wait "${pid_of[$t]}"; then
                echo "fuzz: $t done"
                tail -n 3 "$work/$t.log"
            else
                echo "fuzz: $t FAILED"
                tail -n 40 "$work/$t.log"
                failed+=("$t")
            fi
            unset "pid_of[$t]"
        fi
    done
    sleep 1
done
if ((${#failed[@]})); then
    echo "fuzz: failed: ${failed[*]}" >&2
    exit 1
fi
