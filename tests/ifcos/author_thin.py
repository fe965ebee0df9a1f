"""Thin and open obstacles, written with IfcOpenShell and meshed by it, for the floor-plan test
of surfaces and thin panels (`crates/poinav-bridge/tests/thin_obstacles.rs`).

Usage: .venv/bin/python tests/ifcos/author_thin.py OUT.ifc

IFC4, metres, one storey "Ground floor" at 0.00 m; four rooms (IfcSpace, 3.8 m x 4.8 m, 0 to
2.5 m) side by side, room i over x 4i + 0.1 .. 4i + 3.9 and y 0.1 .. 4.9, in 0.2 m walls on
the lines x = 4i and y = 0, 5. Across them, each reaching into the walls:
- room 0, "Fence": an IfcRailing, an L-shaped IfcArbitraryOpenProfileDef (0, 2) - (2.5, 2) -
  (2.5, 5) extruded 1.2 m up as an IfcExtrudedAreaSolid: a surface;
- room 1, "Surface wall": an IfcWall whose body is an IfcShellBasedSurfaceModel, one vertical
  face from (4.6, 0) to (7.4, 5), 0 to 2.5 m;
- room 2, "Glass": an IfcPlate, a closed 5 mm panel over x 8 .. 12, y 2.5 .. 2.505, 0 to 2 m;
- room 3, "Kick plate": an IfcRailing like the fence along (12, 1.5) - (14, 1.5) - (16, 1.6),
  0 to 0.04 m (below the plan's band; IfcOpenShell 0.9 meshes no open profile of a single
  segment), and "Transom": an IfcPlate 5 mm panel over x 12 .. 16, y 3.5 .. 3.505, from 1.2
  to 2.5 m (above it).
Between rooms 2 and 3, in the wall on x = 12: "Door", 1.0 m wide over y 1.0 .. 2.0 (an
opening of that width filled by an IfcDoor whose body is a 4 cm leaf in the middle of the
wall, 2.1 m high, with space boundaries naming both rooms), and beside it "Sidelight", a
full-height glazed IfcWindow over y 2.0 .. 2.6 in an opening of its own: a closed 5 mm pane in
the middle of the wall (x 11.9975 .. 12.0025), 0 to 2.1 m.

Prints JSON: {"elements": {name: {"class", "vertices": [[x, y, z], ...]}}} with each thin
element's mesh vertices in world coordinates as IfcOpenShell's geometry iterator makes them.
"""

import json
import sys

import ifcopenshell
import ifcopenshell.geom
from authoring import Authoring

out = sys.argv[1]
f = ifcopenshell.file(schema="IFC4")
a = Authoring(f, "poinav-thin:")
gid, pt, d3, axis, place = a.gid, a.pt, a.d3, a.axis, a.place

body, storey, storey_pl = a.spine("Thin")
contained = []
spaces = []


def box(x0, y0, z0, x1, y1, z1):
    prof = f.createIfcRectangleProfileDef(
        "AREA", None, f.createIfcAxis2Placement2D(f.createIfcCartesianPoint([(x0 + x1) / 2, (y0 + y1) / 2]), None),
        x1 - x0, y1 - y0,
    )
    return f.createIfcExtrudedAreaSolid(prof, axis(0, 0, z0), d3(0, 0, 1), z1 - z0)


def open_extrusion(points, z0, z1):
    line = f.createIfcPolyline([f.createIfcCartesianPoint([float(x), float(y)]) for x, y in points])
    prof = f.createIfcArbitraryOpenProfileDef("CURVE", None, line)
    return f.createIfcExtrudedAreaSolid(prof, axis(0, 0, z0), d3(0, 0, 1), z1 - z0)


def vertical_face(a, b, z0, z1):
    loop = f.createIfcPolyLoop([pt(a[0], a[1], z0), pt(b[0], b[1], z0), pt(b[0], b[1], z1), pt(a[0], a[1], z1)])
    face = f.createIfcFace([f.createIfcFaceOuterBound(loop, True)])
    return f.createIfcShellBasedSurfaceModel([f.createIfcOpenShell([face])])


def shape(item, kind):
    return f.createIfcProductDefinitionShape(None, None, [f.createIfcShapeRepresentation(body, "Body", kind, [item])])


def product(cls, name, item, kind, **attrs):
    e = f.create_entity(cls, GlobalId=gid(cls + " " + name), Name=name, ObjectPlacement=place(storey_pl),
                        Representation=shape(item, kind), **attrs)
    contained.append(e)
    return e


# Walls on the grid lines, 0.2 m thick, 3 m high.
product("IfcWall", "South", box(-0.1, -0.1, 0.0, 16.1, 0.1, 3.0), "SweptSolid")
product("IfcWall", "North", box(-0.1, 4.9, 0.0, 16.1, 5.1, 3.0), "SweptSolid")
cross = [product("IfcWall", "Cross %d" % i, box(4.0 * i - 0.1, 0.1, 0.0, 4.0 * i + 0.1, 4.9, 3.0), "SweptSolid")
         for i in range(5)]
for i in range(4):
    x = 4.0 * i
    s = product("IfcSpace", "Room %d" % i, box(x + 0.1, 0.1, 0.0, x + 3.9, 4.9, 2.5), "SweptSolid",
                CompositionType="ELEMENT")
    contained.remove(s)
    spaces.append(s)
f.createIfcRelAggregates(gid("agg storey"), None, None, None, storey, spaces)


def filling(cls, name, y0, y1, body, **attrs):
    """An opening over y0 .. y1 in the wall on x = 12 and `cls` filling it."""
    o = f.createIfcOpeningElement(gid("opening " + name), None, "Opening " + name, None, None, place(storey_pl),
                                  shape(box(11.9, y0, 0.0, 12.1, y1, 2.1), "SweptSolid"), None, "OPENING")
    f.createIfcRelVoidsElement(gid("voids " + name), None, None, None, cross[3], o)
    e = product(cls, name, body, "SweptSolid", OverallHeight=2.1, OverallWidth=y1 - y0, **attrs)
    f.createIfcRelFillsElement(gid("fills " + name), None, None, None, o, e)
    return e


door = filling("IfcDoor", "Door", 1.0, 2.0, box(11.98, 1.0, 0.0, 12.02, 2.0, 2.1), PredefinedType="DOOR")
for room in spaces[2:4]:
    f.createIfcRelSpaceBoundary(gid("boundary Door " + room.Name), None, None, None, room, door, None, "PHYSICAL",
                                "INTERNAL")

thin = {
    "Fence": product("IfcRailing", "Fence", open_extrusion([(0, 2), (2.5, 2), (2.5, 5)], 0.0, 1.2), "SweptSolid"),
    "Surface wall": product("IfcWall", "Surface wall", vertical_face((4.6, 0.0), (7.4, 5.0), 0.0, 2.5), "SurfaceModel"),
    "Glass": product("IfcPlate", "Glass", box(8.0, 2.5, 0.0, 12.0, 2.505, 2.0), "SweptSolid"),
    "Kick plate": product("IfcRailing", "Kick plate", open_extrusion([(12, 1.5), (14, 1.5), (16, 1.6)], 0.0, 0.04), "SweptSolid"),
    "Transom": product("IfcPlate", "Transom", box(12.0, 3.5, 1.2, 16.0, 3.505, 2.5), "SweptSolid"),
    "Sidelight": filling("IfcWindow", "Sidelight", 2.0, 2.6, box(11.9975, 2.0, 0.0, 12.0025, 2.6, 2.1),
                         PredefinedType="WINDOW"),
}
f.createIfcRelContainedInSpatialStructure(gid("contained"), None, None, None, contained, storey)
f.write(out)

settings = ifcopenshell.geom.settings()
settings.set("use-world-coords", True)
elements = {}
for name, e in thin.items():
    verts = ifcopenshell.geom.create_shape(settings, f.by_guid(e.GlobalId)).geometry.verts
    elements[name] = {
        "class": e.is_a(),
        "vertices": [[round(verts[i + k], 9) for k in range(3)] for i in range(0, len(verts), 3)],
    }
print(json.dumps({"elements": elements}))
