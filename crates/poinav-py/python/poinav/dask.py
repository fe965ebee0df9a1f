"""Many models or design variants at once on a Dask cluster, gathered into one table.

Each helper maps one poinav call per task over a ``dask.distributed`` client and returns a
pandas DataFrame, one row per (file or variant, profile). The same code runs on a
``LocalCluster`` and on any Dask cluster: only the client's address changes. Workers need
poinav installed; files are read by the workers (``ship_bytes=True`` reads them here and sends
the bytes instead, for workers that do not share the file system). poinav releases the GIL, so
threaded workers (``LocalCluster(processes=False)``) run tasks in parallel. Without a client
the tasks run here, one after the other.

A task that fails does not stop the others: its row has the error in ``error``.

>>> from distributed import Client, LocalCluster
>>> import poinav.dask
>>> client = Client(LocalCluster(n_workers=2, processes=False))
>>> table = poinav.dask.audit_files(client, ["a.ifc", "b.ifc"], profiles=["paper", "cart.toml"])
>>> sweep = poinav.dask.door_width_sweep(client, [0.7, 0.8, 0.9, 1.0], profiles=["paper"])
>>> poinav.dask.flip_widths(sweep)
{'paper-robot': 0.9}
"""

from __future__ import annotations

import os
from typing import Any, Callable, Dict, Iterable, List, Optional, Sequence, Union

import poinav

PathLike = Union[str, "os.PathLike[str]"]

#: The paper's doorway scenario (crates/poinav-sim/scenarios/doorway.toml) with the door of
#: Room 2 as wide as ``{width}`` and the robot and enrichment for ``{profile}``.
DOORWAY_SCENARIO = """name = "doorway-sweep"
description = "Robot2 enters Room 2 through a door {width} m wide; its sensors validate the width"
duration_s = 3.0

[building]
demo = {{ room2_door_width_m = {width} }}
profile = "{profile}"

[poi]
start = "clear"

[[robot]]
name = "Robot2"
profile = "{profile}"
start = {{ x = 6.2, y = 6.0, heading_deg = -90.0 }}
controller = {{ kind = "route", to = "Room 2" }}
"""

#: The door the doorway scenario validates.
DOORWAY_DOOR = "Door Room 2"


def _source(path: PathLike, ship_bytes: bool) -> Any:
    if ship_bytes:
        with open(path, "rb") as f:
            return (os.fspath(path), f.read())
    return os.fspath(path)


def _open(source: Any) -> "poinav.Model":
    if isinstance(source, tuple):
        name, data = source
        return poinav.open(data, name=name)
    return poinav.open(source)


def _profile_arg(p: Optional[PathLike]) -> str:
    return "paper" if p is None else os.fspath(p)


def _run(client: Any, fn: Callable[..., List[Dict[str, Any]]], items: Sequence[Any]) -> Any:
    """Runs ``fn(item)`` per item (on ``client`` when given) and concatenates the rows."""
    import pandas as pd

    if client is None:
        results = [fn(i) for i in items]
    else:
        futures = client.map(fn, list(items), pure=False)
        results = client.gather(futures)
    rows = [r for rs in results for r in rs]
    return pd.DataFrame(rows)


def _error_rows(file: str, profiles: Sequence[Optional[PathLike]], e: Exception) -> List[Dict[str, Any]]:
    return [
        {"file": file, "profile": _profile_arg(p), "error": f"{type(e).__name__}: {e}"}
        for p in profiles
    ]


def audit_task(source: Any, profiles: Sequence[Optional[PathLike]], resolution: float = 0.05) -> List[Dict[str, Any]]:
    """One file's accessibility audit (``poinav audit``) for every profile: one row each with
    the door passages' status counts and the spaces reachable and not."""
    file = source[0] if isinstance(source, tuple) else source
    try:
        model = _open(source)
        building = model.building(_profile_arg(profiles[0]) if profiles else None)
        report = building.audit(profiles=[_profile_arg(p) for p in profiles], resolution=resolution)
    except poinav.PoinavError as e:
        return _error_rows(file, profiles, e)
    rows = []
    for p in report["profiles"]:
        statuses = [d["status"] for d in p["doors"]]
        rows.append(
            {
                "file": file,
                "schema": model.schema,
                "profile": p["profile"],
                "required_width_m": p["required_width_m"],
                "door_passages": len(p["doors"]),
                "full": statuses.count("FULL_ACCESS"),
                "restricted": statuses.count("RESTRICTED"),
                "blocked": statuses.count("BLOCKED"),
                "pending": statuses.count("PENDING_VALIDATION"),
                "spaces_reachable": sum(1 for s in p["spaces"] if s["reachable"]),
                "spaces_unreachable": sum(1 for s in p["spaces"] if not s["reachable"]),
                "error": None,
            }
        )
    return rows


def audit_files(client: Any, paths: Iterable[PathLike], profiles: Sequence[Optional[PathLike]] = (None,),
                resolution: float = 0.05, ship_bytes: bool = False) -> Any:
    """Audits every file for every profile (``None`` or ``"paper"``: the paper's robot; else
    a profile file the workers can read): a DataFrame with one row per file and profile."""
    profiles = list(profiles) or [None]
    items = [_source(p, ship_bytes) for p in paths]
    return _run(client, lambda s: audit_task(s, profiles, resolution), items)


def enrich_task(source: Any, profiles: Sequence[Optional[PathLike]], rules: Optional[PathLike] = None) -> List[Dict[str, Any]]:
    """One file's enrichment (``poinav enrich``): one row per profile with the doors',
    transitions' and spaces' AccessibilityStatus counts."""
    file = source[0] if isinstance(source, tuple) else source
    try:
        e = _open(source).enrich(profiles=[_profile_arg(p) for p in profiles], rules=rules)
    except poinav.PoinavError as err:
        return _error_rows(file, profiles, err)
    summary = e.summary
    rows = []
    for p in summary["profiles"]:
        row: Dict[str, Any] = {"file": file, "schema": summary["schema"], "profile": p["name"],
                               "elements": summary["elements"]}
        for group in ("doors", "transitions", "spaces"):
            for status, n in p[group].items():
                row[f"{group}_{status.lower()}"] = n
        row["error"] = None
        rows.append(row)
    return rows


def enrich_files(client: Any, paths: Iterable[PathLike], profiles: Sequence[Optional[PathLike]] = (None,),
                 rules: Optional[PathLike] = None, ship_bytes: bool = False) -> Any:
    """Enriches every file for every profile (nothing is written): one row per file and
    profile with status counts."""
    profiles = list(profiles) or [None]
    items = [_source(p, ship_bytes) for p in paths]
    return _run(client, lambda s: enrich_task(s, profiles, rules), items)


def simulate_task(job: Dict[str, Any]) -> List[Dict[str, Any]]:
    """One simulation: ``job`` has ``scenario`` (a file or TOML text), optional ``variant``,
    ``base`` and ``labels`` (copied into the row). The row has the labels, ``pass``, each
    robot's travelled distance and end zone, and each door's final status (``status:NAME``)."""
    row: Dict[str, Any] = dict(job.get("labels", {}))
    try:
        s = poinav.simulate(job["scenario"], job.get("variant"), base=job.get("base"), trace=False)
    except poinav.PoinavError as e:
        row.update({"pass": False, "error": f"{type(e).__name__}: {e}"})
        return [row]
    row["pass"] = s["pass"]
    for r in s["summary"]["robots"]:
        row[f"travelled_m:{r['name']}"] = r["travelled_m"]
        row[f"end_zone:{r['name']}"] = r["end_zone"]
    for p in s["poi"]:
        if p["class"] == "IfcDoor" and p["name"]:
            row[f"status:{p['name']}"] = p["status"]
    row["error"] = None
    return [row]


def simulate_many(client: Any, jobs: Sequence[Dict[str, Any]]) -> Any:
    """Runs every job (see ``simulate_task``): one row per job."""
    return _run(client, simulate_task, list(jobs))


def door_width_sweep(client: Any, widths: Iterable[float], profiles: Sequence[Optional[PathLike]] = (None,),
                     scenario: str = DOORWAY_SCENARIO, door: str = DOORWAY_DOOR) -> Any:
    """The doorway scenario on the test building for every door width and profile: one row per
    pair with ``profile``, ``width_m``, ``status`` (the door's AccessibilityStatus after the
    robot's sensors measured it; ``NO_ROUTE`` when no route lets the robot reach the door),
    ``pass`` and ``error``. Profile files are resolved to absolute paths here."""
    jobs = []
    for p in list(profiles) or [None]:
        prof = _profile_arg(p)
        if prof != "paper":
            prof = os.path.abspath(prof)
        for w in widths:
            text = scenario.format(width=round(float(w), 4), profile=prof.replace("\\", "/"))
            jobs.append({"scenario": text, "labels": {"profile": prof, "width_m": round(float(w), 4)}})
    df = simulate_many(client, jobs)
    col = f"status:{door}"
    if col not in df.columns:
        df[col] = None
    no_route = df["error"].fillna("").str.contains("no route")
    df["status"] = df[col].where(~no_route, "NO_ROUTE")
    df["profile"] = df["profile"].map(_profile_name)
    return df[["profile", "width_m", "status", "pass", "error"]].sort_values(["profile", "width_m"]).reset_index(drop=True)


def _profile_name(p: str) -> str:
    if p == "paper":
        return "paper-robot"
    try:
        import tomllib  # Python 3.11+
    except ImportError:  # pragma: no cover
        return os.path.splitext(os.path.basename(p))[0]
    with open(p, "rb") as f:
        return str(tomllib.load(f).get("name", os.path.basename(p)))


def flip_widths(sweep: Any) -> Dict[str, Optional[float]]:
    """Per profile, the smallest width from which every wider door in the sweep is
    FULL_ACCESS (None when the widest is not)."""
    out: Dict[str, Optional[float]] = {}
    for profile, rows in sweep.sort_values("width_m").groupby("profile", sort=True):
        flip = None
        for w, s in zip(reversed(list(rows["width_m"])), reversed(list(rows["status"]))):
            if s != "FULL_ACCESS":
                break
            flip = float(w)
        out[str(profile)] = flip
    return out
