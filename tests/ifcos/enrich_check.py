"""Check an enriched IFC against its original with IfcOpenShell.

Usage: .venv/bin/python tests/ifcos/enrich_check.py ORIGINAL ENRICHED PREFIX [--no-validate]

Prints one JSON object:
  "psets":      {GlobalId: {set name: {property: value}}} for the three POI sets
                (PREFIX + POI_Classification / RobotAccessibility / RobotCoordination) as
                ifcopenshell.util.element.get_psets reads them (the "id" key dropped);
  "storeys":    {GlobalId: storey label} for enriched elements that IfcOpenShell places in a
                storey (ifcopenshell.util.element.get_container, walking up aggregates),
                labelled by its Name, else its GlobalId;
  "new_errors": ifcopenshell.validate errors of ENRICHED that ORIGINAL does not have
                (compared as multisets of the messages validate.py prints, with the
                FILE_NAME entry quoted in header errors left out, as its time stamp changes).
                Only the instances enrichment can have changed are validated (see `touched`):
                the same verdict as validating both whole files, in a fraction of the time.
Exit 1 if a file cannot be opened.
"""

import collections
import json
import os
import re
import sys

import ifcopenshell
import ifcopenshell.util.element as uel
import ifcopenshell.validate

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from validate import describe  # noqa: E402


def normalise(message):
    """Header errors quote the whole FILE_NAME, whose time stamp enrichment sets: compare
    them without the quoted entry and the caret line under it."""
    message = re.sub(r"FILE_NAME\(.*\)", "FILE_NAME(...)", message)
    return "\n".join(line for line in message.split("\n") if not re.fullmatch(r"\s*\^+\s*", line))


def errors(f, ids):
    """validate.py's errors for the header and the instances `ids` of `f`.

    validate() checks each instance by its own attribute values and its inverse attributes'
    cardinalities, plus GlobalId uniqueness among the instances it visits; it visits what
    iterating the file yields, so `f` is given a class whose iteration yields `ids` only."""

    class Only(type(f)):
        def __iter__(self):
            return iter(self.by_id(i) for i in ids)

    original = f.__class__
    f.__class__ = Only
    try:
        logger = ifcopenshell.validate.json_logger()
        ifcopenshell.validate.validate(f, logger)
    finally:
        f.__class__ = original
    return collections.Counter(normalise(describe(s)) for s in logger.statements if s.get("level") == "error")


def referenced(f, ids):
    """The ids of the instances that the instances `ids` of `f` refer to directly."""
    out = set()
    for i in ids:
        for value in f.by_id(i):
            stack = [value]
            while stack:
                v = stack.pop()
                if isinstance(v, ifcopenshell.entity_instance):
                    if v.id():
                        out.add(v.id())
                elif isinstance(v, (tuple, list)):
                    stack.extend(v)
    return out


def touched(before, after):
    """The instances whose validation can differ between BEFORE and AFTER, given that every
    instance of BEFORE is in AFTER unchanged or removed (the Rust side asserts it byte for
    byte): the added ones, and those an added or removed instance refers to (their inverse
    attributes change). Everything else has the same attributes and the same inverses.
    Returns the ids to validate in AFTER and in BEFORE, and the added ids."""
    old = {e.id() for e in before}
    new = {e.id() for e in after}
    added, removed = new - old, old - new
    changed = referenced(after, added) | referenced(before, removed)
    return sorted(added | (changed & new)), sorted(changed & old & new), added


def duplicate_guids(after, added):
    """GlobalIds an added instance shares with any other instance of AFTER (validate checks
    uniqueness only among the instances it visits)."""
    roots = after.by_type("IfcRoot")
    seen = collections.Counter(e.GlobalId for e in roots)
    return sorted(
        f"GlobalId {e.GlobalId} of #{e.id()} is not unique"
        for e in roots
        if e.id() in added and seen[e.GlobalId] > 1
    )


def storey_of(element):
    """The storey IfcOpenShell places `element` in (its container, or its whole's, upwards)."""
    if element.is_a("IfcSpatialStructureElement") or element.is_a("IfcSpatialElement"):
        return None
    return uel.get_container(element, ifc_class="IfcBuildingStorey")


def main(argv):
    validate = "--no-validate" not in argv
    args = [a for a in argv if a != "--no-validate"]
    if len(args) != 3:
        print(__doc__.strip(), file=sys.stderr)
        return 2
    original, enriched, prefix = args
    try:
        before = ifcopenshell.open(original)
        after = ifcopenshell.open(enriched)
    except Exception as exc:
        print(f"enrich_check: cannot open: {type(exc).__name__}: {exc}", file=sys.stderr)
        return 1
    names = [prefix + n for n in ("POI_Classification", "RobotAccessibility", "RobotCoordination")]
    psets = {}
    storeys = {}
    for element in after.by_type("IfcObject"):
        sets = uel.get_psets(element, psets_only=True)
        found = {n: {k: v for k, v in sets[n].items() if k != "id"} for n in names if n in sets}
        if found:
            psets[element.GlobalId] = found
            storey = storey_of(element)
            if storey is not None:
                storeys[element.GlobalId] = storey.Name if (storey.Name or "").strip() else storey.GlobalId
    new_errors = []
    if validate:
        in_after, in_before, added = touched(before, after)
        new_errors = sorted((errors(after, in_after) - errors(before, in_before)).elements())
        new_errors += duplicate_guids(after, added)
    json.dump({"psets": psets, "storeys": storeys, "new_errors": new_errors}, sys.stdout, indent=1, sort_keys=True, default=str)
    sys.stdout.write("\n")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
