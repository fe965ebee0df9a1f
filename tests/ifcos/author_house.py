"""A two-storey test house written with IfcOpenShell, for poinav's navigation tests.

Usage: .venv/bin/python tests/ifcos/author_house.py OUT.ifc

IFC4, metres. The house is 10 x 8 m with 0.2 m walls; what it holds (GlobalIds are fixed so
that tests can name them; printed as JSON with the levels):

- storey "Ground floor" whose Elevation (and placement) is -0.60 m while its floor slab's top
  and its spaces' bottoms are at 0.00 m (the walking level is 0.00);
- on it the Hall (x 0.2-6.0 less the technical room), the Room (x 6.2-9.8) and a technical room (x 0.2-2.8,
  y 4.0-7.8) behind the stair's west wall; a front door in the south wall (one space
  boundary: the Hall; an entrance), a door Hall-Room and a door Hall-technical room;
- a U-shaped stair (two flights of 8 steps, 0.1875 m risers, 0.30 m treads, and a half
  landing) in the Hall: flight 1 at x 3.0-4.2 rises north from y 4.0, the landing at y
  6.4-7.6 is 1.50 m up, flight 2 at x 4.2-5.4 rises south back to y 4.0 at 3.00 m;
- storey "Upper floor" at 3.00 m (its slab's top too), whose floor slab has the stairwell
  as a hole (an IfcOpeningElement, x 3.0-5.4, y 4.0-7.6);
- on it the Landing hall (x 0.2-6.0), Bedroom 1 (x 6.2-9.8, y 0.2-3.9) and Bedroom 2
  (x 6.2-9.8, y 4.1-7.8), each door to a bedroom with a space boundary naming the bedroom
  only (one-sided, as some exporters write them), and a balcony door in the south wall with
  a boundary naming the Landing hall only (nothing behind it: no entrance on an upper
  floor).
"""

import json
import sys

import ifcopenshell
from authoring import Authoring

f = ifcopenshell.file(schema="IFC4")
_n = [0]


a = Authoring(f, "poinav-test-house:")
gid, pt, d3, axis, place = a.gid, a.pt, a.d3, a.axis, a.place


owner = None
origin = pt(0, 0, 0)
ctx = f.createIfcGeometricRepresentationContext(
    None, "Model", 3, 1.0e-5, f.createIfcAxis2Placement3D(origin, None, None), None
)
body_ctx = f.createIfcGeometricRepresentationSubContext(
    "Body", "Model", None, None, None, None, ctx, None, "MODEL_VIEW", None
)
units = f.createIfcUnitAssignment(
    [
        f.createIfcSIUnit(None, "LENGTHUNIT", None, "METRE"),
        f.createIfcSIUnit(None, "AREAUNIT", None, "SQUARE_METRE"),
        f.createIfcSIUnit(None, "VOLUMEUNIT", None, "CUBIC_METRE"),
        f.createIfcSIUnit(None, "PLANEANGLEUNIT", None, "RADIAN"),
    ]
)
project = f.createIfcProject(gid("project"), owner, "Test house", None, None, None, None, [ctx], units)


def rel_aggregates(whole, parts):
    f.createIfcRelAggregates(gid("agg-" + whole.GlobalId), owner, None, None, whole, parts)


site_pl = place()
site = f.createIfcSite(gid("site"), owner, "Site", None, None, site_pl, None, None, "ELEMENT", None, None, None, None, None)
bldg_pl = place(site_pl)
building = f.createIfcBuilding(gid("building"), owner, "House", None, None, bldg_pl, None, None, "ELEMENT", None, None, None)
rel_aggregates(project, [site])
rel_aggregates(site, [building])

storeys = {}
storey_pl = {}
for name, elev in [("Ground floor", -0.60), ("Upper floor", 3.00)]:
    pl = place(bldg_pl, z=elev)
    s = f.createIfcBuildingStorey(gid("storey " + name), owner, name, None, None, pl, None, None, "ELEMENT", elev)
    storeys[name] = s
    storey_pl[name] = (pl, elev)
rel_aggregates(building, list(storeys.values()))
contained = {name: [] for name in storeys}


def box_solid(x0, y0, z0, x1, y1, z1):
    """An extruded rectangle in the product's own coordinates (which are world - storey z)."""
    prof = f.createIfcRectangleProfileDef(
        "AREA", None, f.createIfcAxis2Placement2D(pt((x0 + x1) / 2, (y0 + y1) / 2), None), x1 - x0, y1 - y0
    )
    return f.createIfcExtrudedAreaSolid(prof, axis(0, 0, z0), d3(0, 0, 1), z1 - z0)


def shape(items):
    return f.createIfcProductDefinitionShape(
        None, None, [f.createIfcShapeRepresentation(body_ctx, "Body", "SweptSolid", items)]
    )


def product(cls, name, storey, boxes, key=None, turned=False, **attrs):
    """A product on `storey` from world boxes (x0, y0, z0, x1, y1, z1); `turned`: its local x
    axis is the world's y (a door in a wall running north-south)."""
    pl, elev = storey_pl[storey]
    if turned:
        # Local (u, v) is world (-v, u).
        items = [box_solid(b[1], -b[3], b[2] - elev, b[4], -b[0], b[5] - elev) for b in boxes]
        placement = f.createIfcLocalPlacement(pl, f.createIfcAxis2Placement3D(pt(0, 0, 0), d3(0, 0, 1), d3(0, 1, 0)))
    else:
        items = [box_solid(b[0], b[1], b[2] - elev, b[3], b[4], b[5] - elev) for b in boxes]
        placement = place(pl)
    e = f.create_entity(
        cls,
        GlobalId=gid(key or name),
        OwnerHistory=owner,
        Name=name,
        ObjectPlacement=placement,
        Representation=shape(items),
        **attrs,
    )
    contained[storey].append(e)
    return e


def space(name, storey, x0, y0, x1, y1, z0, z1, ring=None):
    """A space: a box, or the prism over `ring` (world XY) from z0 to z1."""
    pl, elev = storey_pl[storey]
    if ring:
        poly = f.createIfcPolyline([pt(x, y) for x, y in ring + ring[:1]])
        prof = f.createIfcArbitraryClosedProfileDef("AREA", None, poly)
        solid = f.createIfcExtrudedAreaSolid(prof, axis(0, 0, z0 - elev), d3(0, 0, 1), z1 - z0)
    else:
        solid = box_solid(x0, y0, z0 - elev, x1, y1, z1 - elev)
    e = f.createIfcSpace(
        gid("space " + storey + " " + name), owner, name, None, None, place(pl),
        shape([solid]), name, "ELEMENT", "INTERNAL", None,
    )
    return e


spaces = {name: [] for name in storeys}


def add_space(name, storey, x0, y0, x1, y1, z0, z1, ring=None):
    e = space(name, storey, x0, y0, x1, y1, z0, z1, ring)
    spaces[storey].append(e)
    return e


def wall(name, storey, x0, y0, x1, y1, z0, z1):
    return product("IfcWall", name, storey, [(x0, y0, z0, x1, y1, z1)], key="wall " + storey + " " + name, PredefinedType="STANDARD")


def door(name, storey, hostwall, x0, y0, x1, y1, z0, width, spaces_bounded):
    """A door filling an opening (x0..x1, y0..y1 across the wall, z0..z0+2.1) in `hostwall`."""
    pl, elev = storey_pl[storey]
    o = f.createIfcOpeningElement(
        gid("opening " + storey + " " + name), owner, "Opening " + name, None, None, place(pl),
        shape([box_solid(x0, y0, z0 - elev, x1, y1, z0 + 2.1 - elev)]), None, "OPENING",
    )
    f.createIfcRelVoidsElement(gid("voids " + storey + " " + name), owner, None, None, hostwall, o)
    # The leaf: a thin panel in the middle of the opening.
    if x1 - x0 > y1 - y0:
        leaf = (x0, (y0 + y1) / 2 - 0.02, z0, x1, (y0 + y1) / 2 + 0.02, z0 + 2.1)
    else:
        leaf = ((x0 + x1) / 2 - 0.02, y0, z0, (x0 + x1) / 2 + 0.02, y1, z0 + 2.1)
    d = product("IfcDoor", name, storey, [leaf], key="door " + storey + " " + name, turned=x1 - x0 < y1 - y0,
                OverallHeight=2.1, OverallWidth=width, PredefinedType="DOOR")
    f.createIfcRelFillsElement(gid("fills " + storey + " " + name), owner, None, None, o, d)
    for sp in spaces_bounded:
        f.createIfcRelSpaceBoundary(
            gid("boundary " + storey + " " + name + " " + sp.Name), owner, None, None, sp, d, None, "PHYSICAL", "INTERNAL"
        )
    return d


def slab(name, storey, x0, y0, x1, y1, top, hole=None):
    s = product("IfcSlab", name, storey, [(x0, y0, top - 0.2, x1, y1, top)], key="slab " + name, PredefinedType="FLOOR")
    if hole:
        pl, elev = storey_pl[storey]
        hx0, hy0, hx1, hy1 = hole
        o = f.createIfcOpeningElement(
            gid("stairwell " + name), owner, "Stairwell", None, None, place(pl),
            shape([box_solid(hx0, hy0, top - 0.3 - elev, hx1, hy1, top + 0.1 - elev)]), None, "OPENING",
        )
        f.createIfcRelVoidsElement(gid("voids stairwell " + name), owner, None, None, s, o)
    return s


G, U = "Ground floor", "Upper floor"
levels = {G: 0.0, U: 3.0}
for st in (G, U):
    z0, z1 = levels[st], levels[st] + 2.8
    walls = {
        "south": wall("South", st, 0.0, 0.0, 10.0, 0.2, z0, z1),
        "north": wall("North", st, 0.0, 7.8, 10.0, 8.0, z0, z1),
        "west": wall("West", st, 0.0, 0.2, 0.2, 7.8, z0, z1),
        "east": wall("East", st, 9.8, 0.2, 10.0, 7.8, z0, z1),
        "middle": wall("Middle", st, 6.0, 0.2, 6.2, 7.8, z0, z1),
    }
    if st == G:
        walls["closet south"] = wall("Closet south", st, 0.2, 3.8, 2.8, 4.0, z0, z1)
        walls["stair west"] = wall("Stair west", st, 2.8, 3.8, 3.0, 7.8, z0, z1)
        hall = add_space("Hall", st, 0, 0, 0, 0, z0, z1,
                         ring=[(0.2, 0.2), (6.0, 0.2), (6.0, 7.8), (3.0, 7.8), (3.0, 3.8), (0.2, 3.8)])
        room = add_space("Room", st, 6.2, 0.2, 9.8, 7.8, z0, z1)
        tech = add_space("Technical room", st, 0.2, 4.0, 2.8, 7.8, z0, z1)
        door("Front door", st, walls["south"], 2.0, 0.0, 3.0, 0.2, z0, 1.0, [hall])
        door("Room door", st, walls["middle"], 6.0, 1.0, 6.2, 2.0, z0, 1.0, [hall, room])
        door("Technical door", st, walls["closet south"], 1.0, 3.8, 2.0, 4.0, z0, 1.0, [hall, tech])
        slab("Ground slab", st, 0.0, 0.0, 10.0, 8.0, 0.0)
    else:
        walls["bedrooms"] = wall("Bedrooms", st, 6.2, 3.9, 9.8, 4.1, z0, z1)
        landing = add_space("Landing hall", st, 0.2, 0.2, 6.0, 7.8, z0, z1)
        bed1 = add_space("Bedroom 1", st, 6.2, 0.2, 9.8, 3.9, z0, z1)
        bed2 = add_space("Bedroom 2", st, 6.2, 4.1, 9.8, 7.8, z0, z1)
        door("Bedroom 1 door", st, walls["middle"], 6.0, 1.0, 6.2, 2.0, z0, 1.0, [bed1])
        door("Bedroom 2 door", st, walls["middle"], 6.0, 5.5, 6.2, 6.5, z0, 1.0, [bed2])
        door("Balcony door", st, walls["south"], 2.0, 0.0, 3.0, 0.2, z0, 1.0, [landing])
        slab("Upper slab", st, 0.0, 0.0, 10.0, 8.0, 3.0, hole=(3.0, 4.0, 5.4, 7.6))

# The U-shaped stair on the ground floor.
rise, tread = 0.1875, 0.30
f1 = [(3.0, 4.0 + tread * (k - 1), 0.0, 4.2, 4.0 + tread * k, rise * k) for k in range(1, 9)]
f2 = [(4.2, 6.4 - tread * k, 1.3, 5.4, 6.4 - tread * (k - 1), 1.5 + rise * k) for k in range(1, 9)]
flight1 = product("IfcStairFlight", "Flight 1", G, f1, key="flight 1", PredefinedType="STRAIGHT")
half = product("IfcSlab", "Half landing", G, [(3.0, 6.4, 1.3, 5.4, 7.6, 1.5)], key="half landing", PredefinedType="LANDING")
flight2 = product("IfcStairFlight", "Flight 2", G, f2, key="flight 2", PredefinedType="STRAIGHT")
for p in (flight1, half, flight2):
    contained[G].remove(p)
stair = f.createIfcStair(gid("stair"), owner, "U stair", None, None, place(storey_pl[G][0]), None, None, "HALF_TURN_STAIR")
rel_aggregates(stair, [flight1, half, flight2])
contained[G].append(stair)

for name, s in storeys.items():
    f.createIfcRelContainedInSpatialStructure(gid("contains " + name), owner, None, None, contained[name], s)
    if spaces[name]:
        rel_aggregates(s, spaces[name])

f.write(sys.argv[1])
print(json.dumps({
    "storeys": {n: s.GlobalId for n, s in storeys.items()},
    "stair": stair.GlobalId,
    "doors": {e.Name: e.GlobalId for e in f.by_type("IfcDoor")},
    "spaces": {e.Name: e.GlobalId for e in f.by_type("IfcSpace")},
}))
