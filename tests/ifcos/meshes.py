"""Element meshes from IfcOpenShell, for checking poinav-geom's meshes against.

Usage: .venv/bin/python tests/ifcos/meshes.py FILE [CLASS...]

Every product of the CLASSes (subtypes included; default IfcWall IfcDoor IfcSlab IfcColumn
IfcWindow) that has a representation is triangulated by ifcopenshell.geom's iterator in
world coordinates (metres), default settings otherwise, so openings are subtracted from
their hosts and boolean clippings applied. Prints one JSON object mapping each GlobalId that
IfcOpenShell meshed to

  class          the IFC class
  min, max       the axis-aligned bounding box of the mesh vertices, [x, y, z] in m
  area           the mesh's surface area (sum of triangle areas), m2
  triangles      the number of triangles
  colours        RGBA of each surface style the mesh uses (alpha = 1 - transparency), in
                 IfcOpenShell's order; styles IfcOpenShell makes up itself (no IFC instance)
                 are left out

Products IfcOpenShell produces no shape for are left out.
"""

import json
import sys

import ifcopenshell
import ifcopenshell.geom
import numpy as np

DEFAULT = ["IfcWall", "IfcDoor", "IfcSlab", "IfcColumn", "IfcWindow"]


def summary(shape, cls):
    verts = np.array(shape.geometry.verts, dtype=float).reshape(-1, 3)
    faces = np.array(shape.geometry.faces, dtype=int).reshape(-1, 3)
    tri = verts[faces]
    area = 0.5 * np.linalg.norm(np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0]), axis=1).sum()
    return {
        "class": cls,
        "min": verts.min(axis=0).tolist(),
        "max": verts.max(axis=0).tolist(),
        "area": float(area),
        "triangles": int(len(faces)),
        "colours": [colour(m) for m in shape.geometry.materials if m.instance_id() != 0],
    }


def colour(style):
    t = style.transparency
    alpha = 1.0 if t != t else 1.0 - float(t)  # NaN: not given
    return [float(c) for c in style.diffuse.components] + [alpha]


def main(path, classes):
    f = ifcopenshell.open(path)
    settings = ifcopenshell.geom.settings()
    settings.set("use-world-coords", True)
    products = [p for cls in classes for p in f.by_type(cls) if p.Representation is not None]
    out = {}
    if products:
        it = ifcopenshell.geom.iterator(settings, f, 1, include=products)
        if it.initialize():
            while True:
                shape = it.get()
                if len(shape.geometry.faces):
                    out[shape.guid] = summary(shape, f.by_guid(shape.guid).is_a())
                if not it.next():
                    break
    json.dump(out, sys.stdout)


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2:] or DEFAULT)
