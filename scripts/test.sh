#!/usr/bin/env bash
# The test command: installs what the tests need (IfcOpenShell in .venv; the glTF validator
# from npm and assimp from Debian), then runs the formatting and lint gates, the
# generated-code freshness check, every test, and each fuzz target for a short bounded time
# (POINAV_FUZZ_SECONDS per target, default 15; 0 skips fuzzing).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"

if [[ ! -d ../shared/ifc && -z "${POINAV_SHARED:-}" ]]; then
    echo "test.sh: the corpus (../shared/ifc) is missing; set POINAV_SHARED" >&2
    exit 2
fi

# The set-up waits on the network (pip, npm, apt), the builds on the cores: they run side by
# side. Each set-up job writes a log under target/test-setup/, shown when it ends.
logs="$root/target/test-setup"
mkdir -p "$logs"
declare -A jobs=()
start() {
    local name=$1
    shift
    "$@" > "$logs/$name.log" 2>&1 &
    jobs[$name]=$!
}
join() {
    local name=$1 status=0
    wait "${jobs[$name]}" || status=$?
    sed "s/^/[$name] /" "$logs/$name.log"
    if ((status != 0)); then
        echo "test.sh: set-up step '$name' failed (exit $status)" >&2
        exit "$status"
    fi
}
# Python: .venv (IfcOpenShell and the other reference tools), then .venv-wheel's dependencies.
start python bash -c 'bash scripts/setup-python.sh && bash scripts/test-python.sh --deps-only'
start js bash tests/js/setup.sh
export POINAV_PYTHON="$root/.venv/bin/python"

cargo fmt --all --check
# Lint and build in one pass: clippy's driver compiles our crates (cargo hands it every
# workspace crate as RUSTC_WORKSPACE_WRAPPER, as `cargo clippy` does, and it passes
# dependencies to rustc unlinted), so the lints (`-D warnings`, over every target: libraries,
# binaries, tests, benchmarks, examples) cost no separate check build of the dependencies.
# `cargo clippy --workspace --all-targets -- -D warnings` is the same gate by itself. Every
# later build of the workspace here keeps the same variables, so it reuses this one.
export RUSTC_WORKSPACE_WRAPPER="$(command -v clippy-driver)"
export CLIPPY_ARGS="-D__CLIPPY_HACKERY__warnings__CLIPPY_HACKERY__"
# The tests' build first, while the set-up may still be downloading.
cargo test --workspace --all-targets --locked --profile ci --no-run --quiet
join python
join js
# The tests build with the `ci` profile (Cargo.toml: the dev profile's debug assertions and
# overflow checks, optimised; no debug info for dependencies), which runs the corpus tests
# several times faster than unoptimised code at a small cost in build time. test-lanes.py is
# `cargo test --workspace --locked --profile ci` with the test binaries and the doc tests run
# on as many lanes as there are cores (most of ours keep one core busy, not two).
python3 scripts/test-lanes.py --profile ci
# The CLI that build made (for the integration tests) serves the Python tests' comparisons.
export POINAV_CLI="$root/target/ci/poinav"
# The Python package: the wheel (ci profile, reusing the tests' build), pytest in .venv-wheel.
# maturin builds the extension by itself (`-p poinav-py`, whose features differ from the test
# build's): it would not reuse that build either way, so it skips the lints.
env -u RUSTC_WORKSPACE_WRAPPER -u CLIPPY_ARGS bash scripts/test-python.sh

fuzz_seconds="${POINAV_FUZZ_SECONDS:-15}"
if [[ $fuzz_seconds != 0 ]]; then
    # The quick build (opt-level 1, many codegen units): fuzz.sh explains the modes.
    env -u RUSTC_WORKSPACE_WRAPPER -u CLIPPY_ARGS bash scripts/fuzz.sh "$fuzz_seconds"
fi
