#!/usr/bin/env bash
# The test command: installs what the tests need (IfcOpenShell in .venv), then runs the
# formatting and lint gates, the generated-code freshness check and every test.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"

if [[ ! -d ../shared/ifc && -z "${POINAV_SHARED:-}" ]]; then
    echo "test.sh: the corpus (../shared/ifc) is missing; set POINAV_SHARED" >&2
    exit 2
fi

bash scripts/setup-python.sh
export POINAV_PYTHON="$root/.venv/bin/python"

cargo fmt --all --check
cargo clippy --workspace --all-targets --locked -- -D warnings
cargo test --workspace --locked
