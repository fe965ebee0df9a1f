"""Slope of every IfcRamp and IfcRampFlight from IfcOpenShell's world-coordinate mesh: the
steepest 0.25-degree bin of upward faces (at most 35 degrees) holding at least 10 % of their
area, as its area-weighted mean slope. Prints {GlobalId: degrees}."""
import json
import math
import sys

import ifcopenshell
import ifcopenshell.geom
import numpy as np

model = ifcopenshell.open(sys.argv[1])
settings = ifcopenshell.geom.settings()
settings.set("use-world-coords", True)
out = {}
for e in model.by_type("IfcRamp") + model.by_type("IfcRampFlight"):
    if e.Representation is None:
        continue
    shape = ifcopenshell.geom.create_shape(settings, e)
    v = np.array(shape.geometry.verts).reshape(-1, 3)
    f = np.array(shape.geometry.faces).reshape(-1, 3)
    n = np.cross(v[f[:, 1]] - v[f[:, 0]], v[f[:, 2]] - v[f[:, 0]])
    length = np.linalg.norm(n, axis=1)
    keep = length > 1e-12
    nz = n[keep, 2] / length[keep]
    area = length[keep] / 2
    up = nz >= math.cos(math.radians(35))
    slope = np.degrees(np.arccos(np.clip(nz[up], -1, 1)))
    bins = {}
    for s, a in zip(slope, area[up]):
        b = bins.setdefault(int(s // 0.25), [0.0, 0.0])
        b[0] += a
        b[1] += a * s
    total = sum(b[0] for b in bins.values())
    key = max(k for k, b in bins.items() if b[0] >= 0.1 * total)
    out[e.GlobalId] = 0.0 if key == 0 else bins[key][1] / bins[key][0]
print(json.dumps(out))
