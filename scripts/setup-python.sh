#!/usr/bin/env bash
# Create/refresh the repo-local Python venv (.venv) with the pinned IfcOpenShell
# tools from scripts/requirements-test.txt, used by tests/ifcos/ and bench/.
# Idempotent: does nothing (fast) when the venv already matches the requirements.
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
venv="$root/.venv"
req="$root/scripts/requirements-test.txt"
stamp="$venv/.requirements-test.sha256"

if [[ ! -x "$venv/bin/python" ]]; then
    python3 -m venv "$venv"
fi

want="$(sha256sum "$req" | cut -d' ' -f1)"
have="$(cat "$stamp" 2>/dev/null || true)"
if [[ "$want" == "$have" ]] && "$venv/bin/python" -c 'import ifcopenshell, ifctester' 2>/dev/null; then
    exit 0
fi

"$venv/bin/python" -m pip install --quiet --disable-pip-version-check -r "$req"
"$venv/bin/python" -c 'import ifcopenshell, ifctester'
echo "$want" > "$stamp"
echo "setup-python: .venv ready ($("$venv/bin/python" -c 'import ifcopenshell; print("ifcopenshell", ifcopenshell.version)'))"
