"""Write N copies of an IFC file as one file, for throughput benchmarks.

Usage: .venv/bin/python scripts/make-scaled-model.py OUT.ifc [--copies N] [--source FILE]

The source defaults to synthetic-merged-office-duplex-ifc2x3.ifc from the corpus (../shared/ifc,
or $POINAV_SHARED/ifc; 17.9 MB), and N to 8 (about 140 MB). It is made the way that file was
made from office-a and duplex: copy k's entity ids are offset by k x 10^d (d: the digits of the
source's largest id), one IfcProject is kept (references to a copy's IfcProject point to the
first one's), and every copy's GlobalIds are regenerated (deterministically, from the copy
number and the old GlobalId; only IfcRoot subtypes' first attribute). Copies are NOT moved
apart: their buildings overlap in space, so plans of the result are not meaningful floor plans.
One entity instance per line is expected (as the corpus files have); anything else is an error.
Strings are left untouched ('#12' in a name is not a reference). Written atomically; the same
arguments give the same bytes.
"""

import argparse
import hashlib
import os
import re
import sys
import uuid
from pathlib import Path

import ifcopenshell
import ifcopenshell.guid

REPO = Path(__file__).resolve().parent.parent
SHARED = Path(os.environ.get("POINAV_SHARED", REPO.parent / "shared"))
INSTANCE = re.compile(r"#(\d+)\s*=\s*([A-Za-z0-9_]+)\s*\(")
REF = re.compile(r"#(\d+)")
GUID_FIRST = re.compile(r"\('([0-9A-Za-z_$]{22})'")


def root_types(schema):
    """Upper-case names of IfcRoot and its subtypes in `schema`."""
    s = ifcopenshell.ifcopenshell_wrapper.schema_by_name(schema)
    root = s.declaration_by_name("IfcRoot")
    out = set()

    def walk(d):
        out.add(d.name().upper())
        for sub in d.subtypes():
            walk(sub)

    walk(root)
    return out


def split_pieces(line):
    """The line as alternating [text, ref, text, ref, ..., text]; refs only outside strings."""
    pieces = []
    text = []
    for i, seg in enumerate(line.split("'")):
        if i:
            text.append("'")
        if i % 2:
            text.append(seg)
            continue
        last = 0
        for m in REF.finditer(seg):
            text.append(seg[last:m.start()])
            pieces.append("".join(text))
            pieces.append(int(m.group(1)))
            text = []
            last = m.end()
        text.append(seg[last:])
    pieces.append("".join(text))
    return pieces


def new_guid(copy, old):
    digest = hashlib.md5(f"{copy}:{old}".encode()).hexdigest()
    return ifcopenshell.guid.compress(uuid.UUID(digest).hex)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("out", type=Path)
    ap.add_argument("--copies", type=int, default=8)
    ap.add_argument("--source", type=Path, default=SHARED / "ifc" / "synthetic-merged-office-duplex-ifc2x3.ifc")
    args = ap.parse_args()
    if args.copies < 1:
        ap.error("--copies must be at least 1")
    try:
        text = args.source.read_text(encoding="ascii")
    except (OSError, UnicodeDecodeError) as e:
        sys.exit(f"error: {args.source}: {e}")
    head, sep, rest = text.partition("DATA;\n")
    data, sep2, tail = rest.partition("ENDSEC;\n")
    if not sep or not sep2:
        sys.exit(f"error: {args.source}: no DATA section")
    m = re.search(r"FILE_SCHEMA\s*\(\s*\(\s*'([A-Za-z0-9_]+)'", head)
    if not m:
        sys.exit(f"error: {args.source}: no FILE_SCHEMA")
    roots = root_types(m.group(1).upper())

    lines = []  # (id, type, pieces)
    project = None
    max_id = 0
    for no, line in enumerate(data.splitlines(), start=head.count("\n") + 2):
        if not line.strip():
            continue
        mm = INSTANCE.match(line)
        if not mm or not line.rstrip().endswith(";"):
            sys.exit(f"error: {args.source}:{no}: not one entity instance per line")
        iid, ty = int(mm.group(1)), mm.group(2).upper()
        max_id = max(max_id, iid)
        if ty == "IFCPROJECT":
            if project is not None:
                sys.exit(f"error: {args.source}:{no}: a second IfcProject (#{iid})")
            project = iid
        lines.append((iid, ty, line))
    if project is None:
        sys.exit(f"error: {args.source}: no IfcProject")
    step = 10 ** len(str(max_id))

    parsed = []
    for iid, ty, line in lines:
        body = line[line.index("=") + 1:]
        g = GUID_FIRST.search(body) if ty in roots else None
        guid = g.group(1) if g and body[:g.start()].strip().upper() == ty else None
        parsed.append((iid, ty, split_pieces(body), guid))

    head = re.sub(r"FILE_NAME\s*\(\s*'(?:[^']|'')*'", f"FILE_NAME('{args.out.name}'", head, count=1)
    tmp = args.out.with_name(args.out.name + ".tmp")
    args.out.parent.mkdir(parents=True, exist_ok=True)
    with open(tmp, "w", encoding="ascii", newline="\n") as out:
        out.write(head + "DATA;\n")
        for k in range(args.copies):
            off = k * step
            chunk = []
            for iid, ty, pieces, guid in parsed:
                if k and ty == "IFCPROJECT":
                    continue
                parts = [f"#{iid + off}="]
                for i, p in enumerate(pieces):
                    if i % 2:
                        parts.append(f"#{project if (k and p == project) else p + off}")
                    else:
                        parts.append(p)
                s = "".join(parts)
                if k and guid:
                    s = s.replace(f"'{guid}'", f"'{new_guid(k, guid)}'", 1)
                chunk.append(s)
            out.write("\n".join(chunk))
            out.write("\n")
        out.write("ENDSEC;\n" + tail)
    os.replace(tmp, args.out)
    print(f"{args.out}: {args.copies} copies of {args.source.name}, {len(parsed) * args.copies - (args.copies - 1)} "
          f"instances, {args.out.stat().st_size} bytes")


if __name__ == "__main__":
    sys.exit(main())
