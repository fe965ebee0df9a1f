"""Model.enrich: the summary against `poinav enrich --json`, the table, and what `write`
writes read back with IfcOpenShell."""

import ifcopenshell
import ifcopenshell.util.element
import poinav
import pytest
from conftest import BUILDINGS, CORPUS, PROFILES, cli_json

SAME = ["schema", "length_unit_m", "pset_prefix", "elements", "rules", "categories", "roles",
        "conditional_roles", "corridors", "profiles"]


@pytest.mark.parametrize("name", BUILDINGS + ["office-a.ifc", "institute-var-2.ifc"])
def test_summary_equals_cli(name, tmp_path):
    profiles = ["paper", PROFILES / "wide-cart.toml"]
    e = poinav.open(CORPUS / name).enrich(profiles=profiles)
    mine = e.write(tmp_path / "py.ifc")
    cli = cli_json("enrich", CORPUS / name, "-o", tmp_path / "cli.ifc", "--profile",
                   PROFILES / "paper-robot.toml", "--profile", PROFILES / "wide-cart.toml", "--json")
    for key in SAME:
        assert mine[key] == cli[key], key
    assert mine["instances_added"] == cli["instances_added"]
    assert e.summary["profiles"] == cli["profiles"]
    assert e.profiles == ["paper-robot", "wide-cart"]


def one(v):
    """An enumerated value (a list of one) as its item."""
    return v[0] if isinstance(v, (list, tuple)) and len(v) == 1 else v


def test_write_reads_back_in_ifcopenshell(fzk, tmp_path):
    e = fzk.enrich()
    out, csv, ids = tmp_path / "fzk.poi.ifc", tmp_path / "fzk.csv", tmp_path / "fzk.ids"
    summary = e.write(out, csv=csv, ids=ids)
    assert summary["output"] == str(out)
    assert summary["instances_added"] > 0
    assert csv.read_bytes().splitlines()[0].startswith(b"GlobalId,IfcClass")
    assert b"<ids" in ids.read_bytes()
    df = e.to_dataframe()
    assert len(df) == summary["elements"] == 87
    f = ifcopenshell.open(str(out))
    doors = 0
    for row in df[df["IfcClass"] == "IfcDoor"].itertuples():
        psets = ifcopenshell.util.element.get_psets(f.by_guid(row.GlobalId))
        acc = psets["Pset_RobotAccessibility"]
        assert one(acc["AccessibilityStatus"]) == row.AccessibilityStatus
        assert one(psets["Pset_POI_Classification"]["POI_Category"]) == row.POI_Category
        doors += 1
    assert doors == 5
    # poinav reads the sets it wrote back as IfcOpenShell does, value for value.
    back = poinav.open(out).psets("IfcDoor")
    assert len(back) == 5
    for gid, sets in back.items():
        theirs = ifcopenshell.util.element.get_psets(f.by_guid(gid), psets_only=True)
        for name in ("Pset_RobotAccessibility", "Pset_POI_Classification"):
            assert sets[name] == theirs[name], (gid, name)
    statuses = sorted(df[df["IfcClass"] == "IfcDoor"]["AccessibilityStatus"])
    assert statuses == ["FULL_ACCESS"] * 2 + ["RESTRICTED"] * 3
    # The input is never the output.
    with pytest.raises(poinav.PoinavError):
        e.write(CORPUS / "fzk-haus-ifc4.ifc")


def test_enrich_rejects_bad_profile_and_rules(fzk, tmp_path):
    with pytest.raises(poinav.PoinavError, match="nope.toml"):
        fzk.enrich(profiles=[tmp_path / "nope.toml"])
    bad = tmp_path / "bad.toml"
    bad.write_text("name = 'x'\nwidth_m = -1\n")
    with pytest.raises(poinav.PoinavError):
        fzk.enrich(profiles=[bad])
    with pytest.raises(poinav.PoinavError):
        fzk.enrich(rules=bad)
