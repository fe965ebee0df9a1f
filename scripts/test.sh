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

bash scripts/setup-python.sh
export POINAV_PYTHON="$root/.venv/bin/python"
bash tests/js/setup.sh

cargo fmt --all --check
cargo clippy --workspace --all-targets --locked -- -D warnings
# The tests build with the `ci` profile (Cargo.toml: the dev profile's debug assertions and
# overflow checks, optimised; no debug info for dependencies), which runs the corpus tests
# several times faster than unoptimised code at a small cost in build time. test-lanes.py is
# `cargo test --workspace --locked --profile ci` with the test binaries and the doc tests run
# on as many lanes as there are cores (most of ours keep one core busy, not two).
python3 scripts/test-lanes.py --profile ci
# The Python package: the wheel (ci profile, reusing the tests' build), pytest in .venv-wheel.
bash scripts/test-python.sh

fuzz_seconds="${POINAV_FUZZ_SECONDS:-15}"
if [[ $fuzz_seconds != 0 ]]; then
    # The quick build (opt-level 1, many codegen units): fuzz.sh explains the modes.
    bash scripts/fuzz.sh "$fuzz_seconds"
fi
