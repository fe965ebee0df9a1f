"""Shared fixtures: the corpus (POINAV_SHARED), the poinav CLI (POINAV_CLI, else the
workspace's debug build) and a helper running it with --json."""

import json
import os
import subprocess
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[3]
SHARED = Path(os.environ.get("POINAV_SHARED", REPO.parent / "shared"))
CORPUS = SHARED / "ifc"
CLI = Path(os.environ.get("POINAV_CLI", REPO / "target" / "debug" / "poinav"))
SCENARIOS = REPO / "crates" / "poinav-sim" / "scenarios"
PROFILES = REPO / "examples" / "profiles"

# Small and medium buildings for the calls that mesh (debug builds are slow on big models).
BUILDINGS = ["fzk-haus-ifc4.ifc", "duplex-apartment.ifc", "ifc4-test-model.ifc", "wall-door-column-ifc4x3.ifc"]


def corpus_files():
    files = sorted(CORPUS.glob("*.ifc"))
    assert files, f"no IFC files in {CORPUS} (set POINAV_SHARED)"
    return files


def cli_json(*args, ok=(0,)):
    assert CLI.exists(), f"the poinav CLI is missing at {CLI} (cargo build -p poinav, or POINAV_CLI)"
    proc = subprocess.run([str(CLI), "--quiet", *map(str, args)], capture_output=True, text=True)
    assert proc.returncode in ok, proc.stderr
    return json.loads(proc.stdout)


@pytest.fixture(scope="session")
def fzk():
    import poinav

    return poinav.open(CORPUS / "fzk-haus-ifc4.ifc")
