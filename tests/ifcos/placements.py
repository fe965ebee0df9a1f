"""World placements from IfcOpenShell, for checking poinav-geom's PlacementCache against.

Usage: .venv/bin/python tests/ifcos/placements.py FILE

Prints one JSON object mapping the GlobalId of every IfcSpace, IfcDoor and IfcWall
(subtypes included) to its world matrix: 16 floats, row-major 4x4, from
ifcopenshell.util.placement.get_local_placement(e.ObjectPlacement), with the translation
column multiplied by ifcopenshell.util.unit.calculate_unit_scale (so in metres). An element
whose placement IfcOpenShell cannot evaluate (e.g. an IfcGridPlacement) maps to null.
"""

import json
import sys

import ifcopenshell
import ifcopenshell.util.placement as uplacement
import ifcopenshell.util.unit as uunit


def main(path):
    f = ifcopenshell.open(path)
    scale = uunit.calculate_unit_scale(f)
    out = {}
    for cls in ("IfcSpace", "IfcDoor", "IfcWall"):
        for e in f.by_type(cls):
            try:
                m = uplacement.get_local_placement(e.ObjectPlacement)
            except Exception:  # noqa: BLE001 - any failure is "IfcOpenShell cannot"
                out[e.GlobalId] = None
                continue
            m = m.copy()
            m[0:3, 3] *= scale
            out[e.GlobalId] = [float(x) for x in m.reshape(16)]
    json.dump(out, sys.stdout)


if __name__ == "__main__":
    main(sys.argv[1])
