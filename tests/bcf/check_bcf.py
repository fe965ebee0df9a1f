"""Reads a BCF file written by `poinav audit --bcf` with IfcOpenShell's bcf-client and prints
what it found as JSON: per topic its GUID, title, labels, the IfcGuids selected and coloured in
its viewpoint, the camera and the snapshot's PNG size. With --xsd DIR, every XML file of the
archive is also validated with xmlschema against the buildingSMART XSDs in DIR (markup.xsd,
visinfo.xsd, version.xsd, project.xsd, extensions.xsd for 3.0).

Usage: check_bcf.py FILE.bcf VERSION [--xsd DIR]   (VERSION: 3.0 or 2.1)
"""

import json
import os
import struct
import sys
import zipfile


def png_size(data):
    if not data or data[:8] != b"\x89PNG\r\n\x1a\n":
        return None
    w, h = struct.unpack(">II", data[16:24])
    return [w, h]


def xyz(p):
    return [p.x, p.y, p.z]


def validate(path, version, xsd_dir):
    import xmlschema

    schemas = {}

    def schema(name):
        if name not in schemas:
            schemas[name] = xmlschema.XMLSchema(os.path.join(xsd_dir, name))
        return schemas[name]

    checked = 0
    with zipfile.ZipFile(path) as z:
        for name in z.namelist():
            base = name.rsplit("/", 1)[-1]
            xsd = {
                "markup.bcf": "markup.xsd",
                "bcf.version": "version.xsd",
                "project.bcfp": "project.xsd",
                "extensions.xml": "extensions.xsd",
            }.get(base)
            if base.endswith(".bcfv"):
                xsd = "visinfo.xsd"
            if xsd is None:
                continue
            schema(xsd).validate(z.read(name).decode("utf-8"))
            checked += 1
    return checked


def main():
    args = sys.argv[1:]
    xsd_dir = None
    if "--xsd" in args:
        i = args.index("--xsd")
        xsd_dir = args[i + 1]
        del args[i : i + 2]
    path, version = args
    if version == "3.0":
        from bcf.v3.bcfxml import BcfXml
    elif version == "2.1":
        from bcf.v2.bcfxml import BcfXml
    else:
        raise SystemExit(f"unknown BCF version {version}")
    bcf = BcfXml.load(path)
    out = {"version": bcf.version.version_id, "topics": []}
    for guid, handler in sorted(bcf.topics.items()):
        t = handler.topic
        labels = t.labels.label if version == "3.0" and t.labels else list(t.labels or [])
        entry = {
            "guid": guid,
            "title": t.title,
            "description": t.description,
            "labels": list(labels),
            "priority": t.priority,
            "topic_type": t.topic_type,
            "topic_status": t.topic_status,
            "creation_date": str(t.creation_date),
            "viewpoints": [],
        }
        for vp_name, vp in sorted(handler.viewpoints.items()):
            info = vp.visualization_info
            comps = info.components
            coloured = []
            if comps and comps.coloring:
                for colour in comps.coloring.color:
                    items = colour.components.component if version == "3.0" else colour.component
                    coloured += [[colour.color, c.ifc_guid] for c in items]
            cam = info.perspective_camera
            entry["viewpoints"].append(
                {
                    "file": vp_name,
                    "guid": info.guid,
                    "selected": vp.get_selected_guids() or [],
                    "coloured": coloured,
                    "camera": None
                    if cam is None
                    else {
                        "position": xyz(cam.camera_view_point),
                        "direction": xyz(cam.camera_direction),
                        "up": xyz(cam.camera_up_vector),
                        "field_of_view": cam.field_of_view,
                    },
                    "snapshot": png_size(vp.snapshot),
                }
            )
        out["topics"].append(entry)
    out["xsd_checked"] = validate(path, version, xsd_dir) if xsd_dir else None
    print(json.dumps(out, indent=1))


if __name__ == "__main__":
    main()
