#!/usr/bin/env bash
# The Python package (crates/poinav-py): builds the wheel with maturin (pinned, installed into
# .venv by setup-python.sh) with the `ci` profile (shares target/ with the workspace's tests;
# POINAV_PROFILE=dev for the unoptimised build), installs it into its own venv .venv-wheel as a
# user would, with its declared dependencies and the `dask` extra, pinned by
# requirements-test.txt, plus pytest and IfcOpenShell; then runs pytest on
# crates/poinav-py/tests. .venv-wheel is made afresh (always in CI's clean clone) when it is
# missing or requirements-test.txt or pyproject.toml changed; otherwise only the wheel is
# reinstalled; `--deps-only` prepares .venv-wheel's dependencies and stops. Needs the corpus
# (POINAV_SHARED, default ../shared) and the `poinav` CLI, built here with the same profile,
# for the JSON comparisons.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"

bash scripts/setup-python.sh
venv="$root/.venv-wheel"
# .venv's pip installs into .venv-wheel (made without pip of its own: ensurepip costs seconds).
pip=("$root/.venv/bin/python" -m pip --python "$venv/bin/python" install --quiet
     --disable-pip-version-check --no-compile)
stamp="$venv/.poinav-test-venv.sha256"
want="$(cat scripts/requirements-test.txt crates/poinav-py/pyproject.toml | sha256sum | cut -d' ' -f1)"

if [[ ${1:-} == --deps-only ]]; then
    # Only .venv-wheel's dependencies (network-bound; scripts/test.sh runs this while the
    # Rust builds keep the cores busy): what pyproject.toml declares for the package and its
    # `dask` extra, pytest and IfcOpenShell, at the pins. The wheel comes later.
    [[ -x "$venv/bin/python" && "$(cat "$stamp" 2>/dev/null)" == "$want" ]] && exit 0
    rm -rf "$venv"
    "$root/.venv/bin/python" -m venv --without-pip "$venv"
    mapfile -t deps < <("$root/.venv/bin/python" - <<'PY'
import tomllib
project = tomllib.load(open("crates/poinav-py/pyproject.toml", "rb"))["project"]
for d in project["dependencies"] + project["optional-dependencies"]["dask"]:
    print(d)
PY
)
    "${pip[@]}" -c scripts/requirements-test.txt "${deps[@]}" pytest ifcopenshell
    echo "$want" > "$stamp"
    exit 0
fi
profile="${POINAV_PROFILE:-ci}"
[[ $profile == dev ]] && out_dir=debug || out_dir=$profile
wheels="$root/target/wheels"
rm -rf "$wheels"
"$root/.venv/bin/maturin" build --quiet --manifest-path crates/poinav-py/Cargo.toml \
    --profile "$profile" --interpreter "$root/.venv/bin/python" --out "$wheels"
# The CLI for the JSON comparisons: scripts/test.sh passes the one its test build made
# (POINAV_CLI); a build of `-p poinav` alone would resolve other features than the test build
# (dev-dependencies turn some on) and compile the whole graph again.
if [[ -z ${POINAV_CLI:-} ]]; then
    cargo build --quiet -p poinav --locked --profile "$profile"
    export POINAV_CLI="$root/target/$out_dir/poinav"
fi

wheel="$(ls "$wheels"/poinav-*.whl)"
if [[ -x "$venv/bin/python" && "$(cat "$stamp" 2>/dev/null)" == "$want" ]]; then
    # The dependencies are in place (from an earlier run or from --deps-only): pip resolves
    # the wheel's requirements as for a user, finds them satisfied and adds the wheel.
    "${pip[@]}" -c scripts/requirements-test.txt "$wheel[dask]"
    "${pip[@]}" --force-reinstall --no-deps "$wheel"
else
    rm -rf "$venv"
    "$root/.venv/bin/python" -m venv --without-pip "$venv"
    # What `pip install poinav[dask]` brings (numpy, pandas, dask, distributed), at the pins.
    "${pip[@]}" -c scripts/requirements-test.txt "$wheel[dask]" pytest ifcopenshell
    echo "$want" > "$stamp"
fi

export POINAV_SHARED="${POINAV_SHARED:-$root/../shared}"
cd crates/poinav-py
"$venv/bin/python" -m pytest -q tests "$@"
