"""What IfcOpenShell reads and meshes in a model from scripts/make-heavy-model.py.

Usage: .venv/bin/python tests/ifcos/heavy_model.py FILE [--validate]

Prints one JSON object:
  schema, length_unit_m, length_unit_name   the project's length unit (FOOT: 0.3048)
  counts        entity counts (subtypes included) of the classes the generator writes
  furnishings   {GlobalId: triangles} for every IfcFurnishingElement the geometry iterator
                meshed (default settings, 2 threads)
  mapped        how many furnishings' bodies are IfcMappedItems
  validate      (with --validate) the number of schema problems ifcopenshell.validate finds
                (attribute types and counts, inverses; not the EXPRESS where rules)
"""

import json
import sys

import ifcopenshell
import ifcopenshell.geom
import ifcopenshell.util.unit as uunit
import ifcopenshell.validate

CLASSES = ["IfcBuildingStorey", "IfcSpace", "IfcDoor", "IfcOpeningElement", "IfcRelVoidsElement",
           "IfcRelFillsElement", "IfcWall", "IfcSlab", "IfcStair", "IfcStairFlight",
           "IfcFurnishingElement", "IfcFacetedBrep", "IfcMappedItem", "IfcRepresentationMap",
           "IfcBooleanClippingResult", "IfcHalfSpaceSolid", "IfcRelSpaceBoundary",
           "IfcDoorLiningProperties"]


def main():
    path = sys.argv[1]
    f = ifcopenshell.open(path)
    unit = uunit.get_project_unit(f, "LENGTHUNIT")
    out = {
        "schema": f.schema,
        "length_unit_m": uunit.calculate_unit_scale(f),
        "length_unit_name": unit.Name if unit is not None else None,
        "counts": {c: len(f.by_type(c)) for c in CLASSES},
    }
    settings = ifcopenshell.geom.settings()
    furnishings = f.by_type("IfcFurnishingElement")
    meshed = {}
    it = ifcopenshell.geom.iterator(settings, f, 2, include=furnishings)
    if furnishings and it.initialize():
        while True:
            shape = it.get()
            meshed[shape.guid] = len(shape.geometry.faces) // 3
            if not it.next():
                break
    out["furnishings"] = meshed
    out["mapped"] = sum(
        1 for e in furnishings
        if any(i.is_a("IfcMappedItem") for r in e.Representation.Representations for i in r.Items))
    if "--validate" in sys.argv[2:]:
        logger = ifcopenshell.validate.json_logger()
        ifcopenshell.validate.validate(f, logger)
        out["validate"] = len(logger.statements)
        out["validate_first"] = [str(s) for s in logger.statements[:5]]
    print(json.dumps(out, sort_keys=True))


if __name__ == "__main__":
    main()
