"""A one-storey row of rooms off a corridor, written with IfcOpenShell, for the simulator's
doorway tests: doors of many clear widths in thick walls, some of them close to a corner.

Usage: .venv/bin/python tests/ifcos/author_doorways.py OUT.ifc W1 [W2 ...]

IFC4, metres, storey "Ground floor" at 0.00 m. A corridor (y 0.25-2.25, 0.25 m outer walls)
runs along x; north of its 0.25 m wall (y 2.25-2.50) one room per width, each 4.0 m wide
(x from 0.25 + 4.25 i) and 4.0 m deep, side walls 0.25 m thick. Room i's door (OverallWidth =
the clear width: no lining) is in the corridor wall: centred in the room for even i, 0.10 m
from the room's west wall for odd i (the corner case of real houses). Each door has a leaf
(a 4 cm panel in the middle of the wall) and space boundaries naming both spaces.

Prints JSON: {"doors": [{"name", "width", "centre": [x, y], "room"}], "corridor": name}.
"""

import json
import sys

import ifcopenshell
from authoring import Authoring

out = sys.argv[1]
widths = [float(w) for w in sys.argv[2:]]
f = ifcopenshell.file(schema="IFC4")


a = Authoring(f, "poinav-doorways:")
gid, pt, d3, axis, place = a.gid, a.pt, a.d3, a.axis, a.place


body, storey, storey_pl = a.spine("Doorways")
contained = []


def box(x0, y0, z0, x1, y1, z1):
    prof = f.createIfcRectangleProfileDef(
        "AREA", None, f.createIfcAxis2Placement2D(pt((x0 + x1) / 2, (y0 + y1) / 2), None), x1 - x0, y1 - y0
    )
    return f.createIfcExtrudedAreaSolid(prof, axis(0, 0, z0), d3(0, 0, 1), z1 - z0)


def shape(items):
    return f.createIfcProductDefinitionShape(None, None, [f.createIfcShapeRepresentation(body, "Body", "SweptSolid", items)])


def product(cls, name, b, **attrs):
    e = f.create_entity(cls, GlobalId=gid(cls + " " + name), Name=name, ObjectPlacement=place(storey_pl),
                        Representation=shape([box(*b)]), **attrs)
    contained.append(e)
    return e


def space(name, x0, y0, x1, y1):
    return f.createIfcSpace(gid("space " + name), None, name, None, None, place(storey_pl),
                            shape([box(x0, y0, 0.0, x1, y1, 2.6)]), name, "ELEMENT", "INTERNAL", None)


n = len(widths)
length = 0.25 + 4.25 * n
corridor = space("Corridor", 0.25, 0.25, length, 2.25)
spaces = [corridor]
product("IfcWall", "South", (0.0, 0.0, 0.0, length + 0.25, 0.25, 2.8), PredefinedType="STANDARD")
product("IfcWall", "West", (0.0, 0.25, 0.0, 0.25, 6.5, 2.8), PredefinedType="STANDARD")
product("IfcWall", "North", (0.0, 6.5, 0.0, length + 0.25, 6.75, 2.8), PredefinedType="STANDARD")
product("IfcWall", "East", (length, 0.25, 0.0, length + 0.25, 6.5, 2.8), PredefinedType="STANDARD")
corridor_wall = product("IfcWall", "Corridor wall", (0.25, 2.25, 0.0, length, 2.5, 2.8), PredefinedType="STANDARD")
doors = []
for i, w in enumerate(widths):
    x0 = 0.25 + 4.25 * i
    room = space(f"Room {i + 1}", x0, 2.5, x0 + 4.0, 6.5)
    spaces.append(room)
    if i + 1 < n:
        product("IfcWall", f"Side {i + 1}", (x0 + 4.0, 2.5, 0.0, x0 + 4.25, 6.5, 2.8), PredefinedType="STANDARD")
    cx = x0 + 2.0 if i % 2 == 0 else x0 + 0.10 + w / 2
    name = f"Door {w:.2f}"
    o = f.createIfcOpeningElement(gid("opening " + name), None, "Opening " + name, None, None, place(storey_pl),
                                  shape([box(cx - w / 2, 2.25, 0.0, cx + w / 2, 2.5, 2.1)]), None, "OPENING")
    f.createIfcRelVoidsElement(gid("voids " + name), None, None, None, corridor_wall, o)
    d = product("IfcDoor", name, (cx - w / 2, 2.355, 0.0, cx + w / 2, 2.395, 2.1),
                OverallHeight=2.1, OverallWidth=w, PredefinedType="DOOR")
    f.createIfcRelFillsElement(gid("fills " + name), None, None, None, o, d)
    for sp in (corridor, room):
        f.createIfcRelSpaceBoundary(gid(f"boundary {name} {sp.Name}"), None, None, None, sp, d, None, "PHYSICAL", "INTERNAL")
    doors.append({"name": name, "width": w, "centre": [cx, 2.375], "room": room.Name})

f.createIfcRelAggregates(gid("agg storey"), None, None, None, storey, spaces)
f.createIfcRelContainedInSpatialStructure(gid("contained"), None, None, None, contained, storey)
f.write(out)
print(json.dumps({"doors": doors, "corridor": corridor.Name}))
