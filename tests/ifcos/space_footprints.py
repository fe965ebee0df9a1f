"""Space footprints from IfcOpenShell's geometry, for checking poinav-geom's footprints against.

Usage: .venv/bin/python tests/ifcos/space_footprints.py FILE

Each IfcSpace is triangulated by ifcopenshell.geom (world coordinates, metres, default
settings otherwise, so boolean clippings are applied). Prints one JSON object mapping each
space's GlobalId to

  z_min, z_max   the z-range of all mesh vertices (m)
  hull_area      area of the convex hull of the vertices projected on XY (m2)
  outline_area   area enclosed by the outer boundaries of the union of the mesh triangles
                 projected on XY, holes filled (m2): the exact footprint outline

or to {"error": "..."} when IfcOpenShell produces no shape. poinav's footprint is compared
with outline_area when it is an exact outline and with hull_area when it is a convex hull.
The work is done by product_footprints.py beside this file.
"""

import sys

import product_footprints

if __name__ == "__main__":
    product_footprints.main(sys.argv[1], ["IfcSpace"])
