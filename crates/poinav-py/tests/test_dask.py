"""poinav.dask on a 2-worker LocalCluster: the corpus audited for two profiles, and the
door-width sweep of the doorway scenario with its flip widths."""

from pathlib import Path

import pytest
from conftest import PROFILES, cli_json, corpus_files

distributed = pytest.importorskip("distributed")
import poinav.dask  # noqa: E402


@pytest.fixture(scope="module")
def client():
    cluster = distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=False,
                                       dashboard_address=None)
    with distributed.Client(cluster) as c:
        yield c
    cluster.close()


def test_audit_corpus(client, tmp_path):
    # Every model, the 18 MB synthetic merge too (about 2 s of CPU in the ci profile's wheel).
    files = corpus_files()
    assert len(files) == 15
    # One profile keeps the test short (several profiles per file: test_building's audit).
    table = poinav.dask.audit_files(client, files, profiles=["paper"])
    assert len(table) == len(files)
    # Every file audits without an error: the railway's kilometres of track (meshed since
    # alignments are read) are not rasterised, since neither railway part holds a space or a
    # door (both storeys are skipped), so it has nothing to reach.
    errors = table[table["error"].notna()]
    assert errors.empty, errors
    assert set(table["profile"]) == {"paper-robot"}
    rail = table[[Path(f).name == "railway-track-ifc4x3.ifc" for f in table["file"]]]
    assert rail[["door_passages", "spaces_reachable", "spaces_unreachable"]].values.tolist() == [[0, 0, 0]]
    by = table.set_index("file")
    fzk = by.loc[str(next(f for f in files if f.name == "fzk-haus-ifc4.ifc"))]
    assert fzk[["door_passages", "full", "restricted", "blocked", "spaces_reachable"]].tolist() == [5, 2, 3, 0, 6]
    office = by.loc[str(next(f for f in files if f.name == "office-a.ifc"))]
    assert office["door_passages"] == 104 and office["full"] == 99 and office["restricted"] == 5
    assert office["spaces_reachable"] == 99
    # The synthetic merge's row counts what `poinav audit --json` reports.
    synthetic = next(f for f in files if f.name.startswith("synthetic-"))
    cli = cli_json("audit", synthetic, "-o", tmp_path / "report.html", "--json")["profiles"][0]
    statuses = [d["status"] for d in cli["doors"]]
    row = by.loc[str(synthetic)]
    assert row["door_passages"] == len(statuses) > 300
    assert row[["full", "restricted", "blocked", "pending"]].tolist() == [
        statuses.count(s) for s in ("FULL_ACCESS", "RESTRICTED", "BLOCKED", "PENDING_VALIDATION")]
    assert row["spaces_reachable"] == sum(1 for s in cli["spaces"] if s["reachable"]) > 300
    assert row["spaces_unreachable"] == sum(1 for s in cli["spaces"] if not s["reachable"])
    # The same rows without a cluster, the file sent as bytes.
    profiles = ["paper", PROFILES / "wide-cart.toml"]
    here = poinav.dask.audit_files(None, [files[0]], profiles=profiles, ship_bytes=True)
    assert len(here) == 2
    assert here["full"].iloc[1] <= here["full"].iloc[0]
    # Value for value.
    mine = here.iloc[0].drop(["file", "error"])
    theirs = table[table["file"] == str(files[0])].iloc[0].drop(["file", "error"])
    assert list(mine.index) == list(theirs.index)
    assert all(a == b for a, b in zip(mine, theirs)), (mine, theirs)


def test_door_width_sweep(client):
    widths = [0.70, 0.80, 0.90, 1.00, 1.10, 1.20, 1.30]
    profiles = ["paper", PROFILES / "compact-robot.toml", PROFILES / "wide-cart.toml"]
    sweep = poinav.dask.door_width_sweep(client, widths, profiles=profiles)
    assert len(sweep) == len(widths) * 3
    status = sweep.set_index(["profile", "width_m"])["status"]
    assert status[("paper-robot", 0.80)] == "RESTRICTED"
    assert status[("paper-robot", 1.20)] == "FULL_ACCESS"
    assert status[("wide-cart", 0.70)] == "NO_ROUTE"
    # A door exactly as wide as a profile needs is FULL_ACCESS for it (compact-robot: 0.70 m).
    assert poinav.dask.flip_widths(sweep) == {"compact-robot": 0.7, "paper-robot": 0.9, "wide-cart": 1.1}


def test_enrich_files(client):
    files = [f for f in corpus_files() if f.name in ("fzk-haus-ifc4.ifc", "office-a.ifc")]
    table = poinav.dask.enrich_files(client, files, profiles=["paper"])
    fzk = table[table["file"].str.endswith("fzk-haus-ifc4.ifc")].iloc[0]
    assert fzk["doors_full_access"] == 2 and fzk["doors_restricted"] == 3
    assert fzk["elements"] == 87
