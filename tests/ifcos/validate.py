"""Validate an IFC file with IfcOpenShell and list the errors.

Usage: .venv/bin/python tests/ifcos/validate.py FILE

Runs ifcopenshell.validate.validate (schema checks: attribute types,
optionality, inverse cardinalities, unique rules, header; not the EXPRESS
WHERE rules, which would need pytest) and prints a sorted JSON list of error
strings, each "#id IfcClass.Attribute: message" with whatever context is known.
Exit 0 whatever was found; 1 if FILE cannot be opened.
"""

import json
import sys

import ifcopenshell
import ifcopenshell.validate


def describe(statement):
    where = []
    inst = statement.get("instance")
    if isinstance(inst, ifcopenshell.entity_instance):
        where.append(f"#{inst.id()}" if inst.id() else inst.is_a())
    elif inst is not None:
        where.append(str(inst).split("=", 1)[0])
    if statement.get("attribute"):
        where.append(statement["attribute"])
    elif isinstance(inst, ifcopenshell.entity_instance) and inst.id():
        where.append(inst.is_a())
    prefix = " ".join(where)
    return f"{prefix}: {statement['message']}" if prefix else statement["message"]


def main(argv):
    if len(argv) != 1:
        print(__doc__.strip(), file=sys.stderr)
        return 2
    try:
        f = ifcopenshell.open(argv[0])
    except Exception as exc:
        print(f"validate: cannot open {argv[0]}: {type(exc).__name__}: {exc}", file=sys.stderr)
        return 1
    logger = ifcopenshell.validate.json_logger()
    ifcopenshell.validate.validate(f, logger)
    errors = sorted(describe(s) for s in logger.statements if s.get("level") == "error")
    json.dump(errors, sys.stdout, indent=1)
    sys.stdout.write("\n")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
