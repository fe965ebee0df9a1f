"""poinav.open, inspect, storeys, doors, psets and meshes against the CLI's JSON and
IfcOpenShell on the corpus."""

import math
from concurrent.futures import ThreadPoolExecutor

import ifcopenshell
import ifcopenshell.util.element
import ifcopenshell.util.unit
import numpy as np
import poinav
import pytest
from conftest import BUILDINGS, CORPUS, cli_json, corpus_files


@pytest.mark.parametrize("path", corpus_files(), ids=lambda p: p.name)
def test_inspect_equals_cli_json(path):
    model = poinav.open(path)
    mine = model.inspect()
    cli = cli_json("inspect", path, "--json")
    assert mine == cli
    assert model.schema == cli["schema"]
    assert len(model) == cli["instances"]
    assert model.doors == cli["doors"]
    assert model.storeys == cli["storeys"]


@pytest.mark.parametrize("path", corpus_files(), ids=lambda p: p.name)
def test_counts_and_door_widths_equal_ifcopenshell(path):
    model = poinav.open(path)
    f = ifcopenshell.open(str(path))
    for cls in ["IfcWall", "IfcDoor", "IfcWindow", "IfcSpace", "IfcSlab", "IfcBuildingStorey"]:
        assert model.count(cls) == len(f.by_type(cls)), cls
    scale = ifcopenshell.util.unit.calculate_unit_scale(f)
    theirs = {d.GlobalId: d.OverallWidth * scale for d in f.by_type("IfcDoor") if d.OverallWidth is not None}
    mine = {d["guid"]: d["overall_width_m"] for d in model.doors if d["overall_width_m"] is not None}
    assert mine.keys() == theirs.keys()
    for gid, w in theirs.items():
        assert math.isclose(mine[gid], w, rel_tol=1e-9, abs_tol=1e-9), gid


def same_value(mine, theirs):
    """A property value as poinav and IfcOpenShell give it: floats to 1e-9, lists and bounded
    (lower, upper) tuples item by item, complex values (dicts) key by key but for `id`."""
    if isinstance(theirs, float):
        return isinstance(mine, float) and math.isclose(mine, theirs, rel_tol=1e-9, abs_tol=1e-12)
    if isinstance(theirs, (list, tuple)):
        return (type(mine) is type(theirs) and len(mine) == len(theirs)
                and all(same_value(a, b) for a, b in zip(mine, theirs)))
    if isinstance(theirs, dict):
        keys = set(theirs) - {"id"}
        return (isinstance(mine, dict) and set(mine) - {"id"} == keys
                and all(same_value(mine[k], theirs[k]) for k in keys))
    return mine == theirs


@pytest.mark.parametrize("name", ["fzk-haus-ifc4.ifc", "duplex-apartment.ifc", "ifc4-test-model.ifc"])
def test_psets_equal_ifcopenshell(name):
    model = poinav.open(CORPUS / name)
    mine = model.psets()
    f = ifcopenshell.open(str(CORPUS / name))
    products = f.by_type("IfcProduct")
    assert len(mine) == len(products)
    compared = 0
    for p in products:
        # poinav reads IfcPropertySets; IfcOpenShell adds predefined sets (door linings, ...).
        theirs = {k: v for k, v in ifcopenshell.util.element.get_psets(p, psets_only=True).items()
                  if f.by_id(v["id"]).is_a("IfcPropertySet")}
        got = mine[p.GlobalId]
        assert set(got) == set(theirs), p.GlobalId
        for set_name, props in theirs.items():
            assert got[set_name]["id"] == props["id"]
            assert set(got[set_name]) == set(props), (p.GlobalId, set_name)
            for k, v in props.items():
                assert same_value(got[set_name][k], v), (p.GlobalId, set_name, k, got[set_name][k], v)
                compared += 1
    assert compared > 100


def test_psets_shared_by_products_are_separate_dicts():
    # duplex: 2,329 sets of 1,459 distinct #ids; a set's later products get copies of the
    # first one's dict, which must not be the same object.
    path = CORPUS / "duplex-apartment.ifc"
    psets = poinav.open(path).psets()
    # The benchmark's Rust sides read as many sets: per product (the library's
    # property_sets) and each distinct set once (what psets() reads).
    assert poinav._native.bench_psets(str(path)) == 2329 == poinav._native.bench_psets(str(path), once=True)
    by_id = {}
    for sets in psets.values():
        for props in sets.values():
            by_id.setdefault(props["id"], []).append(props)
    shared = [dicts for dicts in by_id.values() if len(dicts) > 1]
    assert sum(len(d) for d in by_id.values()) == 2329 and len(by_id) == 1459
    assert len(shared) > 100
    for first, *others in shared:
        for other in others:
            assert other == first and other is not first
    first, second = shared[0][:2]
    first["poinav-test"] = 1.0
    assert "poinav-test" not in second


def test_psets_called_from_threads_at_once():
    # psets() reads on the shared rayon pool while each calling thread makes its dicts from
    # the chunks read so far (duplex: 295 products in chunks of 148, 74, 37, 18 and 18, sets
    # shared across chunks); five callers at once must each get the whole, same result.
    model = poinav.open(CORPUS / "duplex-apartment.ifc")
    want = model.psets()
    with ThreadPoolExecutor(5) as pool:
        got = list(pool.map(model.psets, ["IfcProduct"] * 4 + ["IfcDoor"]))
    assert len(want) == 295 and sum(len(s) for s in want.values()) == 2329
    for g in got[:4]:
        assert g == want and list(g) == list(want)
    assert len(got[4]) == 14 and got[4] == {k: v for k, v in want.items() if k in got[4]}


def test_open_from_bytes_and_ifcopenshell_file(fzk):
    path = CORPUS / "fzk-haus-ifc4.ifc"
    from_bytes = poinav.open(path.read_bytes(), name="fzk.ifc")
    assert from_bytes.file == "fzk.ifc"
    assert from_bytes.doors == fzk.doors
    f = ifcopenshell.open(str(path))
    from_ios = poinav.open(f)
    assert len(from_ios.doors) == 5 == from_ios.count(cls="IfcDoor")
    assert from_ios.count("IfcWall") == len(f.by_type("IfcWall"))
    assert sorted(d["guid"] for d in from_ios.doors) == sorted(d.GlobalId for d in f.by_type("IfcDoor"))


@pytest.mark.parametrize("name", BUILDINGS)
def test_meshes_are_numpy_arrays_of_every_element(name):
    model = poinav.open(CORPUS / name)
    meshes = model.meshes()
    failures = model.mesh_failures()
    f = ifcopenshell.open(str(CORPUS / name))
    guids = {e.GlobalId: e for e in f.by_type("IfcProduct")}
    assert meshes
    storeys = {s["id"]: s["name"] for s in model.storeys}
    for m in meshes:
        v, t = m["vertices"], m["triangles"]
        assert v.dtype == np.float64 and v.ndim == 2 and v.shape[1] == 3
        assert t.dtype == np.uint32 and t.ndim == 2 and t.shape[1] == 3
        assert len(t) > 0 and t.max() < len(v)
        assert np.isfinite(v).all()
        e = guids[m["global_id"]]
        assert e.is_a() == m["class"]
        if m["storey_id"] is not None:
            assert m["storey"] == storeys.get(m["storey_id"])
    # What the Rust library meshes, the wheel returns: the same triangles.
    assert sum(len(m["triangles"]) for m in meshes) == poinav._native.bench_meshes(str(CORPUS / name))
    assert all(isinstance(x["reason"], str) for x in failures)


def test_fzk_meshes_match_the_walls_and_doors(fzk):
    meshes = fzk.meshes()
    classes = [m["class"] for m in meshes]
    assert classes.count("IfcDoor") == 5
    assert classes.count("IfcWallStandardCase") + classes.count("IfcWall") == 13
    spaces = fzk.meshes(spaces=True)
    assert sum(1 for m in spaces if m["class"] == "IfcSpace") == 7
    # Heights in metres: the storeys are 2.7 m apart, nothing higher than the roof (~7.1 m).
    top = max(m["vertices"][:, 2].max() for m in meshes)
    assert 6.0 < top < 8.0


def test_bad_file_raises_ifc_error_with_line_and_id(tmp_path):
    bad = tmp_path / "bad.ifc"
    bad.write_text(
        "ISO-10303-21;\nHEADER;\nFILE_DESCRIPTION((''),'2;1');\nFILE_NAME('','',(''),(''),'','','');\n"
        "FILE_SCHEMA(('IFC4'));\nENDSEC;\nDATA;\n#1=IFCPERSON($,$,'x',$,$,$,$,$);\n"
        "#2=IFCDOOR('abc,$,$,$,$,$,$,$,$,$,$,$,$);\n"
    )
    with pytest.raises(poinav.IfcError) as e:
        poinav.open(bad)
    assert e.value.file == str(bad)
    assert e.value.line == 9
    assert e.value.entity_id == 2
    assert "never closed" in str(e.value)
    assert isinstance(e.value, poinav.PoinavError)


def test_missing_and_non_ifc_files_raise_ifc_error(tmp_path):
    with pytest.raises(poinav.IfcError) as e:
        poinav.open(tmp_path / "missing.ifc")
    assert e.value.line is None and e.value.entity_id is None
    with pytest.raises(poinav.IfcError, match="ISO-10303-21"):
        poinav.open(b"hello")
    with pytest.raises(poinav.IfcError) as e:
        poinav.open(b"")
    assert e.value.file == "<bytes>"
