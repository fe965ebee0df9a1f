#!/usr/bin/env bash
# The Python package (crates/poinav-py): builds the wheel with maturin (pinned, installed into
# .venv by setup-python.sh) with the `ci` profile (shares target/ with the workspace's tests;
# POINAV_PROFILE=dev for the unoptimised build), installs it into a fresh venv .venv-wheel
# with the pinned test packages (numpy, pandas, dask, pytest, ifcopenshell from
# requirements-test.txt), and runs pytest on crates/poinav-py/tests. Needs the corpus
# (POINAV_SHARED, default ../shared) and the `poinav` CLI, built here with the same profile,
# for the JSON comparisons.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"

bash scripts/setup-python.sh
venv="$root/.venv-wheel"
profile="${POINAV_PROFILE:-ci}"
[[ $profile == dev ]] && out_dir=debug || out_dir=$profile
wheels="$root/target/wheels"
rm -rf "$wheels"
"$root/.venv/bin/maturin" build --quiet --manifest-path crates/poinav-py/Cargo.toml \
    --profile "$profile" --interpreter "$root/.venv/bin/python" --out "$wheels"
cargo build --quiet -p poinav --locked --profile "$profile"

rm -rf "$venv"
"$root/.venv/bin/python" -m venv "$venv"
purelib='import sysconfig; print(sysconfig.get_paths()["purelib"])'
"$root/.venv/bin/python" -c "$purelib" > "$("$venv/bin/python" -c "$purelib")/_poinav_test_packages.pth"
"$venv/bin/python" -m pip install --quiet --disable-pip-version-check "$wheels"/poinav-*.whl

export POINAV_SHARED="${POINAV_SHARED:-$root/../shared}"
export POINAV_CLI="$root/target/$out_dir/poinav"
cd crates/poinav-py
"$venv/bin/python" -m pytest -q tests "$@"
