"""poinav for Python: read IFC building models, enrich them with robot POI semantics, mesh
them into numpy arrays, navigate and audit them for robot profiles, and simulate scenarios.

>>> import poinav
>>> model = poinav.open("building.ifc")          # or bytes, or an ifcopenshell.file
>>> model.schema, len(model.doors)
>>> e = model.enrich(profiles=["paper"]); e.summary["profiles"][0]["doors"]
>>> e.write("building.poi.ifc", csv="poi.csv")
>>> b = model.building(); g = b.grid(0); g.cells.shape
>>> poinav.simulate("doorway.toml", variant="door-0.80")["pass"]

Long calls release the GIL, so threads (and Dask's threaded workers) run them in parallel.
Every failure raises `PoinavError`; a file that cannot be read raises `IfcError` with
`file`, `line` and `entity_id`; no route raises `NoRouteError`.
"""

from __future__ import annotations

import os
from typing import Any, Dict, Optional, Union

from . import _native
from ._native import Building, Enrichment, Grid, IfcError, Model, NoRouteError, PoinavError

__version__: str = _native.__version__

__all__ = [
    "open",
    "simulate",
    "read_trace",
    "Model",
    "Enrichment",
    "Building",
    "Grid",
    "PoinavError",
    "IfcError",
    "NoRouteError",
]

PathLike = Union[str, "os.PathLike[str]"]


def open(source: Union[PathLike, bytes, bytearray, memoryview, Any], name: Optional[str] = None) -> Model:
    """Read an IFC model.

    ``source`` is a path, the file's bytes, STEP text (a ``str`` starting with
    ``ISO-10303-21``), or an ``ifcopenshell.file`` (read through its ``to_string()``).
    ``name`` is what errors call a model given as bytes. Raises ``IfcError`` when the file
    cannot be read (``file``, ``line``, ``entity_id`` say where).
    """
    if hasattr(source, "to_string") and hasattr(source, "by_type"):
        source = source.to_string()
    if isinstance(source, str) and source.lstrip().startswith("ISO-10303-21"):
        source = source.encode("utf-8")
    if isinstance(source, (bytes, bytearray, memoryview)):
        return _native.open_bytes(bytes(source), name or "<bytes>")
    return _native.open_path(os.fspath(source))


def simulate(scenario: Union[PathLike, str], variant: Optional[str] = None, *,
             output: Optional[PathLike] = None, trace: bool = True,
             base: Optional[PathLike] = None, stream: bool = False) -> Dict[str, Any]:
    """Run one variant of a scenario (``poinav simulate``).

    ``scenario`` is a scenario file, or its TOML text (relative paths then resolve from
    ``base``, default the current folder). A scenario with variants needs ``variant``.
    Returns a dict: ``summary`` (as summary.json), ``pass``, ``poi`` (each POI record at the
    end: roles, ``status``, ``method``), ``trace`` (numpy columns ``step``, ``t``, ``robot``
    (index into ``robots``), ``xy`` (n, 2), ``heading_deg``, ``speed``, ``omega_deg_s``,
    ``ray_m`` (n, 5)) unless ``trace=False``, and ``outputs`` (files written into ``output``).
    With ``stream=True`` (and ``output``) the trace is written to ``output/trace.jsonl`` as the
    steps are taken instead of kept in memory (long runs); ``trace_path`` names it.
    """
    text = isinstance(scenario, str) and "\n" in scenario
    return _native.simulate(
        scenario if text else os.fspath(scenario),
        variant,
        text,
        None if base is None else os.fspath(base),
        None if output is None else os.fspath(output),
        trace,
        stream,
    )


def read_trace(path: PathLike) -> Dict[str, Any]:
    """Read a trace ``poinav simulate`` wrote: ``trace.jsonl``, or the compact ``trace.bin``
    (``--trace-format bin``, about a quarter of the bytes), into the numpy columns
    ``simulate`` returns as ``trace``. Raises ``PoinavError`` naming the file when it is
    missing or damaged.
    """
    return _native.read_trace(os.fspath(path))
