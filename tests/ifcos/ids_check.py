"""Check IFC files against IDS files with IfcOpenShell's ifctester.

Usage: .venv/bin/python tests/ifcos/ids_check.py IDS IFC [IDS IFC ...]

For each (IDS, IFC) pair: opens the IDS with ifctester.ids.open(path,
validate=True), which validates the XML against ifctester's bundled IDS 1.0
XSD (ids.xsd, offline) and then parses it; opens the IFC with IfcOpenShell;
runs Ids.validate. Prints one JSON list, one object per pair:

  {"ids": path, "ifc": path, "schema": "IFC4", "seconds": 1.2,
   "specifications": [{"name", "identifier", "ifc_versions", "status",
       "is_ifc_version", "applicable", "passed", "failed",
       "applicable_ids": [STEP ids, sorted],
       "failures": [{"facet", "id", "class", "guid", "reason"}] (first 20)}]}

"status" is ifctester's: true passed, false failed. Exits 1 (message on
stderr) if an IDS is invalid or a file cannot be opened.
"""

import json
import sys
import time

import ifcopenshell
from ifctester import ids


def check(ids_path, ifc_path):
    start = time.perf_counter()
    try:
        spec = ids.open(ids_path, validate=True)
    except Exception as exc:
        detail = getattr(exc, "xml_error", None)
        detail = f" ({getattr(detail, 'reason', None) or detail} at {getattr(detail, 'path', '?')})" if detail else ""
        raise SystemExit(f"ids_check: {ids_path} is not a valid IDS 1.0 file: {type(exc).__name__}: {exc}{detail}")
    try:
        model = ifcopenshell.open(ifc_path)
    except Exception as exc:
        raise SystemExit(f"ids_check: cannot open {ifc_path}: {type(exc).__name__}: {exc}")
    spec.validate(model)
    specs = []
    for s in spec.specifications:
        failures = []
        for facet in s.requirements:
            for failure in facet.failures:
                element = failure["element"]
                failures.append(
                    {
                        "facet": f"{type(facet).__name__} {getattr(facet, 'propertySet', '')}.{getattr(facet, 'baseName', '')}",
                        "id": element.id(),
                        "class": element.is_a(),
                        "guid": getattr(element, "GlobalId", None),
                        "reason": failure["reason"],
                    }
                )
        specs.append(
            {
                "name": s.name,
                "identifier": s.identifier,
                "ifc_versions": s.ifcVersion,
                "status": s.status,
                "is_ifc_version": s.is_ifc_version,
                "applicable": len(s.applicable_entities),
                "passed": len(s.passed_entities - s.failed_entities),
                "failed": len(s.failed_entities),
                "applicable_ids": sorted(e.id() for e in s.applicable_entities),
                "failures": failures[:20],
            }
        )
    return {
        "ids": ids_path,
        "ifc": ifc_path,
        "schema": model.schema_identifier,
        "seconds": round(time.perf_counter() - start, 3),
        "specifications": specs,
    }


def main(argv):
    if not argv or len(argv) % 2:
        print(__doc__.strip(), file=sys.stderr)
        return 2
    results = [check(argv[i], argv[i + 1]) for i in range(0, len(argv), 2)]
    json.dump(results, sys.stdout)
    print()
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
