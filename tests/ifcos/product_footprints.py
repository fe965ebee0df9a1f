"""Product footprints from IfcOpenShell's geometry, for checking poinav-geom's footprints against.

Usage: .venv/bin/python tests/ifcos/product_footprints.py FILE [CLASS...]

Each product of the CLASSes (subtypes included; default IfcSpace) is triangulated by ifcopenshell.geom (world coordinates, metres, default
settings otherwise, so boolean clippings are applied). Prints one JSON object mapping each
product's GlobalId to

  z_min, z_max   the z-range of all mesh vertices (m)
  hull_area      area of the convex hull of the vertices projected on XY (m2)
  outline_area   area enclosed by the outer boundaries of the union of the mesh triangles
                 projected on XY, holes filled (m2): the exact footprint outline

or to {"error": "..."} when IfcOpenShell produces no shape. poinav's footprint is compared
with outline_area when it is an exact outline and with hull_area when it is a convex hull.
"""

import json
import sys

import ifcopenshell
import ifcopenshell.geom
import numpy as np
import shapely
from shapely.geometry import Polygon


def footprint(shape):
    verts = np.array(shape.geometry.verts, dtype=float).reshape(-1, 3)
    faces = np.array(shape.geometry.faces, dtype=int).reshape(-1, 3)
    tri = verts[faces][:, :, :2]  # (n, 3, 2) projected triangles
    a, b, c = tri[:, 0], tri[:, 1], tri[:, 2]
    doubled = np.abs((b[:, 0] - a[:, 0]) * (c[:, 1] - a[:, 1]) - (b[:, 1] - a[:, 1]) * (c[:, 0] - a[:, 0]))
    tri = tri[doubled > 2e-10]  # vertical faces project to nothing
    union = shapely.union_all(shapely.polygons(tri))
    polys = list(union.geoms) if hasattr(union, "geoms") else [union]
    outline = sum(Polygon(p.exterior).area for p in polys if not p.is_empty)
    return {
        "z_min": float(verts[:, 2].min()),
        "z_max": float(verts[:, 2].max()),
        "hull_area": float(shapely.multipoints(verts[:, :2]).convex_hull.area),
        "outline_area": float(outline),
    }


def main(path, classes):
    f = ifcopenshell.open(path)
    settings = ifcopenshell.geom.settings()
    settings.set("use-world-coords", True)
    products = [p for cls in classes for p in f.by_type(cls) if p.Representation is not None]
    out = {p.GlobalId: {"error": "IfcOpenShell produced no shape"} for p in products}
    if products:
        # The iterator shares work between products with the same (mapped) representation.
        it = ifcopenshell.geom.iterator(settings, f, 1, include=products)
        if it.initialize():
            while True:
                shape = it.get()
                out[shape.guid] = footprint(shape)
                if not it.next():
                    break
    json.dump(out, sys.stdout)


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2:] or ["IfcSpace"])
