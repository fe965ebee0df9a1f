"""Model.building: storeys, occupancy grids as numpy, routes and the audit against
`poinav route --json` and `poinav audit --json`."""

import numpy as np
import poinav
import pytest
from conftest import CORPUS, PROFILES, cli_json


@pytest.fixture(scope="module")
def fzk_building(fzk):
    return fzk.building()


def test_storeys_and_grid(fzk_building):
    b = fzk_building
    assert b.profile == "paper-robot"
    assert [s["name"] for s in b.storeys] == ["Erdgeschoss", "Dachgeschoss"]
    assert b.storeys[0]["zones"] == 6 and b.storeys[0]["doors"] == 5
    g = b.grid("Erdgeschoss")
    cells = np.asarray(g)
    assert cells.dtype == np.uint8 and cells.ndim == 2
    assert g.shape == cells.shape
    assert set(np.unique(cells)) == {g.FREE, g.OCCUPIED, g.UNKNOWN}
    assert g.resolution == 0.05
    assert g.clearance_m.shape == cells.shape and g.clearance_m.dtype == np.float32
    # The grid covers the house (about 12 x 10 m) with an unknown border.
    h, w = cells.shape
    assert 10.0 < w * g.resolution < 20.0 and 8.0 < h * g.resolution < 20.0
    free_m2 = (cells == 0).sum() * g.resolution**2
    assert 40.0 < free_m2 < 160.0
    assert (np.asarray(b.grid(0)) == cells).all()
    coarse = b.grid(0, resolution=0.1)
    assert abs(coarse.shape[1] * 0.1 - w * 0.05) < 0.2
    with pytest.raises(poinav.PoinavError, match="Erdgeschoss"):
        b.grid("Keller")
    with pytest.raises(poinav.PoinavError, match="resolution"):
        b.grid(0, resolution=5.0)


def test_route_equals_cli(fzk_building):
    mine = fzk_building.route("outside", "Wohnen")
    cli = cli_json("route", CORPUS / "fzk-haus-ifc4.ifc", "--from", "outside", "--to", "Wohnen", "--json")
    assert mine["length_m"] == pytest.approx(cli["length_m"], abs=1e-9)
    assert mine["time_s"] == pytest.approx(cli["time_s"], abs=1e-9)
    assert [l["floor_name"] for l in mine["legs"]] == [l["floor_name"] for l in cli["legs"]]
    assert 2.0 < mine["length_m"] < 30.0


def test_routes_reuse_the_prepared_navigator(fzk):
    b = fzk.building()
    assert b.navigators_built == 0
    first = b.route("outside", "Wohnen")
    assert b.navigators_built == 1
    # The second route, and the other way, rasterise nothing and answer the same.
    assert b.route("outside", "Wohnen") == first
    back = b.route("Wohnen", "outside")
    assert back["length_m"] == pytest.approx(first["length_m"], abs=0.5)
    assert b.navigators_built == 1
    # The grid of a prepared storey is the route's grid, equal to a fresh building's.
    fresh = fzk.building().grid("Erdgeschoss")
    kept = b.grid("Erdgeschoss")
    assert b.navigators_built == 1
    assert (np.asarray(kept) == np.asarray(fresh)).all()
    assert (kept.clearance_m == fresh.clearance_m).all() and kept.origin == fresh.origin
    # Other options: another navigator, kept beside the first.
    coarse = b.route("outside", "Wohnen", resolution=0.1)
    assert b.navigators_built == 2
    assert coarse["length_m"] == pytest.approx(first["length_m"], abs=0.5)
    assert b.route("outside", "Wohnen") == first
    assert b.route("outside", "Wohnen", resolution=0.1) == coarse
    assert b.navigators_built == 2
    # No route is an answer of the kept navigator too.
    with pytest.raises(poinav.NoRouteError):
        b.route("outside", "Galerie")
    assert b.navigators_built == 2


def test_routes_from_threads_share_one_navigator(fzk):
    # The GIL is released while routing: threads wait for the one navigator, none rebuilds it.
    from concurrent.futures import ThreadPoolExecutor

    b = fzk.building()
    with ThreadPoolExecutor(4) as pool:
        routes = list(pool.map(lambda _: b.route("outside", "Wohnen"), range(8)))
    assert b.navigators_built == 1
    assert all(r == routes[0] for r in routes)
    assert routes[0]["length_m"] == pytest.approx(fzk.building().route("outside", "Wohnen")["length_m"])


def test_no_route_and_unknown_place(fzk_building):
    with pytest.raises(poinav.NoRouteError):
        fzk_building.route("outside", "Galerie")  # upstairs, by a spiral stair only
    with pytest.raises(poinav.PoinavError, match="Nowhere"):
        fzk_building.route("outside", "Nowhere")


@pytest.mark.parametrize("name", ["fzk-haus-ifc4.ifc", "duplex-apartment.ifc"])
def test_audit_equals_cli(name, tmp_path):
    profiles = [PROFILES / "paper-robot.toml", PROFILES / "wide-cart.toml"]
    b = poinav.open(CORPUS / name).building(profiles[0])
    mine = b.audit(profiles=profiles)
    args = []
    for p in profiles:
        args += ["--profile", p]
    cli = cli_json("audit", CORPUS / name, "-o", tmp_path / "report.html", "--json", *args)
    assert mine["profiles"] == cli["profiles"]
    assert mine["floors"] == cli["floors"]
    assert [p["profile"] for p in mine["profiles"]] == ["paper-robot", "wide-cart"]
