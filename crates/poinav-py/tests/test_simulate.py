"""poinav.simulate: the doorway scenario's variants against `poinav simulate`, the trace as
numpy columns, errors."""

import json

import numpy as np
import poinav
import pytest
from conftest import CLI, SCENARIOS

DOORWAY = SCENARIOS / "doorway.toml"


@pytest.mark.parametrize("variant,status", [("door-0.80", "RESTRICTED"), ("door-1.20", "FULL_ACCESS")])
def test_doorway_variants(variant, status, tmp_path):
    run = poinav.simulate(DOORWAY, variant, output=tmp_path / "py")
    assert run["pass"] is True
    door = [p for p in run["poi"] if p["name"] == "Door Room 2"]
    assert len(door) == 1
    assert door[0]["status"] == status
    assert door[0]["method"] == "SENSOR_BASED"
    assert ("B-2" in door[0]["conditional_roles"]) == (status == "RESTRICTED")

    trace = run["trace"]
    n = run["summary"]["records"]
    assert trace["robots"] == ["Robot2"]
    assert trace["xy"].shape == (n, 2) and trace["xy"].dtype == np.float64
    assert trace["ray_m"].shape == (n, 5)
    assert trace["step"].dtype == np.uint64 and trace["robot"].dtype == np.uint32
    assert (np.diff(trace["t"]) > 0).all()
    assert trace["t"][1] - trace["t"][0] == pytest.approx(1 / 60, abs=1e-6)
    # The robot drives into Room 2: from y = 6.0 downwards.
    assert trace["xy"][0, 1] == pytest.approx(6.0)
    assert trace["xy"][-1, 1] < 5.0
    end = run["summary"]["robots"][0]
    assert end["end_zone"] == "Room 2"
    assert np.isclose(np.hypot(*np.diff(trace["xy"], axis=0).T).sum(), end["travelled_m"], atol=1e-3)

    # The CLI's summary and trace are the same.
    import subprocess

    subprocess.run([str(CLI), "--quiet", "simulate", str(DOORWAY), "-o", str(tmp_path / "cli"),
                    "--variant", variant], check=True)
    out = tmp_path / "cli" / variant
    cli_summary = json.loads((out / "summary.json").read_text())
    assert run["summary"] == cli_summary
    assert (tmp_path / "py" / "trace.jsonl").read_bytes() == (out / "trace.jsonl").read_bytes()
    lines = (out / "trace.jsonl").read_text().splitlines()
    assert len(lines) == n
    last = json.loads(lines[-1])
    assert trace["xy"][-1, 0] == last["x"] and trace["speed"][-1] == last["speed"]
    assert sorted(run["outputs"]) == sorted(str(tmp_path / "py" / f) for f in
                                            ["trace.jsonl", "summary.json", "trajectories.svg", "speed.svg", "distance.svg"])


def test_scenario_text_and_no_trace(tmp_path):
    text = DOORWAY.read_text()
    run = poinav.simulate(text, "door-1.20", trace=False)
    assert "trace" not in run and run["pass"] is True
    assert run["summary"]["variant"] == "door-1.20"


def test_simulate_errors(tmp_path):
    with pytest.raises(poinav.PoinavError, match="door-0.80, door-1.20"):
        poinav.simulate(DOORWAY)
    with pytest.raises(poinav.PoinavError, match="door-9"):
        poinav.simulate(DOORWAY, "door-9")
    with pytest.raises(poinav.PoinavError, match="missing.toml"):
        poinav.simulate(tmp_path / "missing.toml")
    with pytest.raises(poinav.PoinavError, match="<scenario>:2"):
        poinav.simulate('name = "x"\nduration_s = "long"\n')


def test_stream_trace_to_file(tmp_path):
    kept = poinav.simulate(DOORWAY, "door-0.80", output=tmp_path / "kept")
    streamed = poinav.simulate(DOORWAY, "door-0.80", output=tmp_path / "streamed", stream=True)
    path = tmp_path / "streamed" / "trace.jsonl"
    assert "trace" not in streamed and streamed["trace_path"] == str(path)
    # The same lines as the trace kept in memory and written at the end.
    assert path.read_bytes() == (tmp_path / "kept" / "trace.jsonl").read_bytes()
    assert len(path.read_bytes().splitlines()) == len(kept["trace"]["t"]) == kept["summary"]["records"]
    assert streamed["summary"] == kept["summary"] and streamed["pass"] is True
    assert sorted(streamed["outputs"]) == sorted(p.replace("kept", "streamed") for p in kept["outputs"])
    with pytest.raises(poinav.PoinavError, match="output="):
        poinav.simulate(DOORWAY, "door-0.80", stream=True)


def test_read_trace_of_either_format(tmp_path):
    import subprocess

    kept = poinav.simulate(DOORWAY, "door-0.80")["trace"]
    out = {}
    for fmt in ["jsonl", "bin"]:
        subprocess.run([str(CLI), "--quiet", "simulate", str(DOORWAY), "--variant", "door-0.80",
                        "-o", str(tmp_path / fmt), "--trace-format", fmt], check=True)
        out[fmt] = poinav.read_trace(tmp_path / fmt / "door-0.80" / f"trace.{fmt}")
    bin_path = tmp_path / "bin" / "door-0.80" / "trace.bin"
    assert bin_path.stat().st_size * 2 < (tmp_path / "jsonl" / "door-0.80" / "trace.jsonl").stat().st_size
    for cols in out.values():
        assert cols["robots"] == kept["robots"] == ["Robot2"]
        assert set(cols) == set(kept)
        for k in kept:
            if k != "robots":
                assert cols[k].dtype == kept[k].dtype and cols[k].shape == kept[k].shape, k
                assert np.array_equal(cols[k], kept[k]), k
    assert len(kept["t"]) > 100
    # A damaged compact trace and a missing file raise PoinavError naming the file.
    cut = tmp_path / "cut.bin"
    cut.write_bytes(bin_path.read_bytes()[:-9])
    with pytest.raises(poinav.PoinavError, match="cut.bin"):
        poinav.read_trace(cut)
    with pytest.raises(poinav.PoinavError, match="missing.bin"):
        poinav.read_trace(tmp_path / "missing.bin")
