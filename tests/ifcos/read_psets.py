"""Dump one named property set per element as IfcOpenShell reads it.

Usage: .venv/bin/python tests/ifcos/read_psets.py FILE PSET_NAME [--types]

Prints JSON {GlobalId: {property: value}} for every object (IfcObject; with
--types also IfcTypeObject) whose ifcopenshell.util.element.get_psets result
has a set named PSET_NAME. Occurrences inherit their type's sets, as get_psets
does by default. Values are as IfcOpenShell returns them (lists stay lists;
anything not JSON-native is written with str()). The "id" key is dropped.
Exits 1 if FILE cannot be opened.
"""

import json
import sys

import ifcopenshell
import ifcopenshell.util.element as uel


def main(argv):
    types = "--types" in argv
    args = [a for a in argv if a != "--types"]
    if len(args) != 2:
        print(__doc__.strip(), file=sys.stderr)
        return 2
    path, pset_name = args
    try:
        f = ifcopenshell.open(path)
    except Exception as exc:
        print(f"read_psets: cannot open {path}: {type(exc).__name__}: {exc}", file=sys.stderr)
        return 1
    classes = ["IfcObject"] + (["IfcTypeObject"] if types else [])
    out = {}
    for cls in classes:
        for element in f.by_type(cls):
            pset = uel.get_psets(element, psets_only=True).get(pset_name)
            if pset is not None:
                out[element.GlobalId] = {k: v for k, v in pset.items() if k != "id"}
    json.dump(out, sys.stdout, indent=1, sort_keys=True, default=str)
    sys.stdout.write("\n")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
