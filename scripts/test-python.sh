#!/usr/bin/env bash
# The Python package (crates/poinav-py): builds the wheel with maturin (pinned, installed into
# .venv by setup-python.sh) with the `ci` profile (shares target/ with the workspace's tests;
# POINAV_PROFILE=dev for the unoptimised build), installs it into its own venv .venv-wheel as a
# user would, with its declared dependencies and the `dask` extra, pinned by
# requirements-test.txt, plus pytest and IfcOpenShell; then runs pytest on
# crates/poinav-py/tests. .venv-wheel is made afresh (always in CI's clean clone) when it is
# missing or requirements-test.txt or pyproject.toml changed; otherwise only the wheel is
# reinstalled. Needs the corpus (POINAV_SHARED, default ../shared) and the `poinav` CLI, built
# here with the same profile, for the JSON comparisons.
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

wheel="$(ls "$wheels"/poinav-*.whl)"
# .venv's pip installs into .venv-wheel (made without pip of its own: ensurepip costs seconds).
pip=("$root/.venv/bin/python" -m pip --python "$venv/bin/python" install --quiet
     --disable-pip-version-check --no-compile)
stamp="$venv/.poinav-test-venv.sha256"
want="$(cat scripts/requirements-test.txt crates/poinav-py/pyproject.toml | sha256sum | cut -d' ' -f1)"
if [[ -x "$venv/bin/python" && "$(cat "$stamp" 2>/dev/null)" == "$want" ]]; then
    "${pip[@]}" --force-reinstall --no-deps "$wheel"
else
    rm -rf "$venv"
    "$root/.venv/bin/python" -m venv --without-pip "$venv"
    # What `pip install poinav[dask]` brings (numpy, pandas, dask, distributed), at the pins.
    "${pip[@]}" -c scripts/requirements-test.txt "$wheel[dask]" pytest ifcopenshell
    echo "$want" > "$stamp"
fi

export POINAV_SHARED="${POINAV_SHARED:-$root/../shared}"
export POINAV_CLI="$root/target/$out_dir/poinav"
cd crates/poinav-py
"$venv/bin/python" -m pytest -q tests "$@"
