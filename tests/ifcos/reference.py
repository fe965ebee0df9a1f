"""Reference facts from IfcOpenShell, for checking poinav against.

Usage: .venv/bin/python tests/ifcos/reference.py FILE [FILE...]

Prints one JSON object mapping each FILE (as given) to what IfcOpenShell reads:
schema, length unit scale (m), entity counts (incl. subtypes), doors (name,
overall width/height in m, storey), storeys sorted by elevation, spaces and the
number of property sets per door. A file that cannot be read maps to
{"error": "..."} and the exit code is 1; otherwise 0.
"""

import json
import sys

import ifcopenshell
import ifcopenshell.util.element as uel
import ifcopenshell.util.unit as uunit

COUNT_CLASSES = [
    "IfcWall", "IfcDoor", "IfcWindow", "IfcSpace", "IfcSlab", "IfcStair", "IfcRamp",
    "IfcColumn", "IfcFurnishingElement", "IfcOpeningElement", "IfcBuildingStorey",
    "IfcProduct", "IfcPropertySet", "IfcRelDefinesByProperties",
]


def by_type(f, cls):
    """f.by_type(cls), or None if the schema has no such class."""
    try:
        return f.by_type(cls)
    except RuntimeError:
        return None


def storey_of(element):
    """Name of the IfcBuildingStorey above element in the spatial tree, or None.

    Walks ifcopenshell.util.element.get_parent (containment, aggregation,
    nesting, filling, voiding) upward, the same path get_container takes.
    """
    seen = set()
    node = uel.get_parent(element)
    while node is not None and node.id() not in seen:
        if node.is_a("IfcBuildingStorey"):
            return node.Name
        seen.add(node.id())
        node = uel.get_parent(node)
    return None


def scaled(value, scale):
    return None if value is None else value * scale


def describe(path):
    f = ifcopenshell.open(path)
    scale = uunit.calculate_unit_scale(f)
    counts = {}
    for cls in COUNT_CLASSES:
        items = by_type(f, cls)
        if items is not None:
            counts[cls] = len(items)
    doors = {
        d.GlobalId: {
            "name": d.Name,
            "overall_width_m": scaled(d.OverallWidth, scale),
            "overall_height_m": scaled(d.OverallHeight, scale),
            "storey": storey_of(d),
        }
        for d in f.by_type("IfcDoor")
    }
    storeys = [
        {"guid": s.GlobalId, "name": s.Name, "elevation_m": scaled(s.Elevation, scale)}
        for s in f.by_type("IfcBuildingStorey")
    ]
    # elevation then name (missing ones first), then guid so ties are stable
    storeys.sort(key=lambda s: (
        s["elevation_m"] is not None, s["elevation_m"] or 0.0,
        s["name"] is not None, s["name"] or "", s["guid"],
    ))
    spaces = {
        s.GlobalId: {"name": s.Name, "long_name": s.LongName, "storey": storey_of(s)}
        for s in f.by_type("IfcSpace")
    }
    psets_per_door = {
        d.GlobalId: len(uel.get_psets(d, psets_only=True)) for d in f.by_type("IfcDoor")
    }
    return {
        "schema": f.schema,  # e.g. "IFC4X3"
        "schema_identifier": f.schema_identifier,  # as in the header, e.g. "IFC4X3_ADD2"
        "length_unit_m": scale,
        "counts": counts,
        "doors": doors,
        "storeys": storeys,
        "spaces": spaces,
        "psets_per_door": psets_per_door,
    }


def main(argv):
    if not argv:
        print(__doc__.strip(), file=sys.stderr)
        return 2
    result, failed = {}, False
    for path in argv:
        try:
            result[path] = describe(path)
        except Exception as exc:  # keep going: one bad file must not hide the rest
            result[path] = {"error": f"{type(exc).__name__}: {exc}"}
            failed = True
    json.dump(result, sys.stdout, indent=1, sort_keys=True)
    sys.stdout.write("\n")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
