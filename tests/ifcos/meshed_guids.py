"""The products IfcOpenShell 0.9's geometry iterator meshes, per file.

Usage: .venv/bin/python tests/ifcos/meshed_guids.py FILE...

Default settings (Body representations, openings subtracted) and world coordinates, one
thread, over every product with a representation but openings (`IfcFeatureElementSubtraction`);
a product counts as meshed when its shape has at least one vertex and one face.

Prints JSON: {FILE: {GlobalId: class}}.
"""

import json
import sys

import ifcopenshell
import ifcopenshell.geom


def meshed(path):
    f = ifcopenshell.open(path)
    settings = ifcopenshell.geom.settings()
    settings.set("use-world-coords", True)
    products = [p for p in f.by_type("IfcProduct")
                if p.Representation is not None and not p.is_a("IfcFeatureElementSubtraction")]
    out = {}
    if not products:
        return out
    it = ifcopenshell.geom.iterator(settings, f, 1, include=products)
    if it.initialize():
        while True:
            shape = it.get()
            g = shape.geometry
            if len(g.verts) and len(g.faces):
                p = f.by_id(shape.id)
                out[p.GlobalId] = p.is_a()
            if not it.next():
                break
    return out


print(json.dumps({path: meshed(path) for path in sys.argv[1:]}))
