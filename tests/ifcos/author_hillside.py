"""A two-storey hillside house written with IfcOpenShell, for poinav's terrain-entrance tests.

Usage: .venv/bin/python tests/ifcos/author_hillside.py OUT_DIR

Writes four IFC4 files (metres) into OUT_DIR that differ in how the terrain is modelled (and
one in a roof behind the house), and prints JSON with their names, IfcOpenShell's mesh of each one's terrain (class, triangles,
z range, area), the doors' and spaces' GlobalIds and the terrain's heights:

- hillside-geographic.ifc: an IfcGeographicElement of PredefinedType TERRAIN contained in the
  site;
- hillside-site.ifc: the IfcSite's own body;
- hillside-proxy.ifc: an IfcBuildingElementProxy named "Gelände" (as IFC2X3 exporters write
  terrain) contained in the site;
- hillside-covered.ifc: as hillside-geographic.ifc, plus the ground floor's roof slab (ROOF,
  top at 3.00) over a strip behind the house (x 0-10, y 8-10): the hillside door opens onto
  a roof of the building, not onto the terrain.

The house is 10 x 8 m (x 0-10, y 0-8) with 0.2 m walls and no stair:

- storey "Ground floor" at 0.00: the Hall (one space), a front door in the south wall (one
  space boundary: the Hall; an entrance at ground level);
- storey "Upper floor" at 3.00 (its slab's top too): the Upper hall (x 0.2-6.0) and the Upper
  room (x 6.2-9.8), joined by the Upper room door; a hillside door in the north wall (x 2-3)
  and a balcony door in the south wall (x 2-3), each with a boundary naming the Upper hall
  only. Nothing else leads up: the upper rooms are reachable only through the hillside door.

The terrain is an open triangulated surface around the house's footprint (nothing under the
house): flat at 0.00 south of the house (y <= 0), rising along the house's sides to 3.00 at
its north wall (y = 8) and on to 3.40 at y = 20 behind it. So the hillside door opens onto
terrain at 3.02 m, 0.6 m beyond its outer face; the balcony door is 3 m above the terrain.
"""

import json
import os
import sys

import ifcopenshell
from authoring import Authoring

# Terrain heights by y (piecewise linear between these rows), and the rows' x extents.
TERRAIN_ROWS = [(-10.0, 0.0), (0.0, 0.0), (8.0, 3.0), (20.0, 3.4)]
TERRAIN_COLS = [-10.0, 0.0, 10.0, 20.0]


def build(variant):
    f = ifcopenshell.file(schema="IFC4")

    a = Authoring(f, "poinav-test-hillside:")
    gid, pt, d3, axis, place = a.gid, a.pt, a.d3, a.axis, a.place

    ctx = f.createIfcGeometricRepresentationContext(
        None, "Model", 3, 1.0e-5, f.createIfcAxis2Placement3D(pt(0, 0, 0), None, None), None
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
    project = f.createIfcProject(gid("project"), None, "Hillside house", None, None, None, None, [ctx], units)

    def rel_aggregates(whole, parts):
        f.createIfcRelAggregates(gid("agg-" + whole.GlobalId), None, None, None, whole, parts)

    def shape(items, kind="SweptSolid"):
        return f.createIfcProductDefinitionShape(
            None, None, [f.createIfcShapeRepresentation(body_ctx, "Body", kind, items)]
        )

    def terrain_surface():
        """The terrain as a triangulated face set (world = site coordinates), facing up."""
        coords, index = [], {}
        for j, (y, z) in enumerate(TERRAIN_ROWS):
            for i, x in enumerate(TERRAIN_COLS):
                index[(i, j)] = len(coords) + 1
                coords.append((x, y, z))
        tris = []
        for j in range(len(TERRAIN_ROWS) - 1):
            for i in range(len(TERRAIN_COLS) - 1):
                if (i, j) == (1, 1):
                    continue  # the house's footprint: no terrain under it
                a, b = index[(i, j)], index[(i + 1, j)]
                c, d = index[(i + 1, j + 1)], index[(i, j + 1)]
                tris += [(a, b, c), (a, c, d)]
        pts = f.createIfcCartesianPointList3D([[float(v) for v in p] for p in coords])
        return f.createIfcTriangulatedFaceSet(pts, None, False, tris, None)

    site_pl = place()
    site_shape = shape([terrain_surface()], "Tessellation") if variant == "site" else None
    site = f.createIfcSite(gid("site"), None, "Site", None, None, site_pl, site_shape, None, "ELEMENT", None, None, None, None, None)
    bldg_pl = place(site_pl)
    building = f.createIfcBuilding(gid("building"), None, "House", None, None, bldg_pl, None, None, "ELEMENT", None, None, None)
    rel_aggregates(project, [site])
    rel_aggregates(site, [building])

    if variant in ("geographic", "covered"):
        terrain = f.createIfcGeographicElement(
            gid("terrain"), None, "Hill", None, None, place(site_pl),
            shape([terrain_surface()], "Tessellation"), None, "TERRAIN",
        )
    elif variant == "proxy":
        terrain = f.createIfcBuildingElementProxy(
            gid("terrain"), None, "Gelände", None, None, place(site_pl),
            shape([terrain_surface()], "Tessellation"), None, "NOTDEFINED",
        )
    else:
        terrain = None
    if terrain is not None:
        f.createIfcRelContainedInSpatialStructure(gid("contains site"), None, None, None, [terrain], site)

    storeys, storey_pl = {}, {}
    for name, elev in [("Ground floor", 0.0), ("Upper floor", 3.0)]:
        pl = place(bldg_pl, z=elev)
        storeys[name] = f.createIfcBuildingStorey(gid("storey " + name), None, name, None, None, pl, None, None, "ELEMENT", elev)
        storey_pl[name] = (pl, elev)
    rel_aggregates(building, list(storeys.values()))
    contained = {name: [] for name in storeys}
    spaces = {name: [] for name in storeys}

    def box_solid(x0, y0, z0, x1, y1, z1):
        prof = f.createIfcRectangleProfileDef(
            "AREA", None, f.createIfcAxis2Placement2D(pt((x0 + x1) / 2, (y0 + y1) / 2), None), x1 - x0, y1 - y0
        )
        return f.createIfcExtrudedAreaSolid(prof, axis(0, 0, z0), d3(0, 0, 1), z1 - z0)

    def product(cls, name, storey, box, key, turned=False, **attrs):
        """A product on `storey` from a world box; `turned`: local x is the world's y."""
        pl, elev = storey_pl[storey]
        x0, y0, z0, x1, y1, z1 = box
        if turned:
            item = box_solid(y0, -x1, z0 - elev, y1, -x0, z1 - elev)
            placement = f.createIfcLocalPlacement(pl, f.createIfcAxis2Placement3D(pt(0, 0, 0), d3(0, 0, 1), d3(0, 1, 0)))
        else:
            item = box_solid(x0, y0, z0 - elev, x1, y1, z1 - elev)
            placement = place(pl)
        e = f.create_entity(cls, GlobalId=gid(key), Name=name, ObjectPlacement=placement, Representation=shape([item]), **attrs)
        contained[storey].append(e)
        return e

    def add_space(name, storey, x0, y0, x1, y1, z0, z1):
        pl, elev = storey_pl[storey]
        e = f.createIfcSpace(
            gid("space " + name), None, name, None, None, place(pl),
            shape([box_solid(x0, y0, z0 - elev, x1, y1, z1 - elev)]), name, "ELEMENT", "INTERNAL", None,
        )
        spaces[storey].append(e)
        return e

    def wall(name, storey, x0, y0, x1, y1, z0, z1):
        return product("IfcWall", name, storey, (x0, y0, z0, x1, y1, z1), "wall " + storey + " " + name, PredefinedType="STANDARD")

    def door(name, storey, host, x0, y0, x1, y1, z0, bounded):
        pl, elev = storey_pl[storey]
        o = f.createIfcOpeningElement(
            gid("opening " + name), None, "Opening " + name, None, None, place(pl),
            shape([box_solid(x0, y0, z0 - elev, x1, y1, z0 + 2.1 - elev)]), None, "OPENING",
        )
        f.createIfcRelVoidsElement(gid("voids " + name), None, None, None, host, o)
        if x1 - x0 > y1 - y0:
            leaf = (x0, (y0 + y1) / 2 - 0.02, z0, x1, (y0 + y1) / 2 + 0.02, z0 + 2.1)
        else:
            leaf = ((x0 + x1) / 2 - 0.02, y0, z0, (x0 + x1) / 2 + 0.02, y1, z0 + 2.1)
        d = product("IfcDoor", name, storey, leaf, "door " + name, turned=x1 - x0 < y1 - y0,
                    OverallHeight=2.1, OverallWidth=1.0, PredefinedType="DOOR")
        f.createIfcRelFillsElement(gid("fills " + name), None, None, None, o, d)
        for sp in bounded:
            f.createIfcRelSpaceBoundary(gid("boundary " + name + " " + sp.Name), None, None, None, sp, d, None, "PHYSICAL", "INTERNAL")
        return d

    def slab(name, storey, top):
        return product("IfcSlab", name, storey, (0.0, 0.0, top - 0.2, 10.0, 8.0, top), "slab " + name, PredefinedType="FLOOR")

    G, U = "Ground floor", "Upper floor"
    for st, z0 in ((G, 0.0), (U, 3.0)):
        z1 = z0 + 2.8
        walls = {
            "south": wall("South", st, 0.0, 0.0, 10.0, 0.2, z0, z1),
            "north": wall("North", st, 0.0, 7.8, 10.0, 8.0, z0, z1),
            "west": wall("West", st, 0.0, 0.2, 0.2, 7.8, z0, z1),
            "east": wall("East", st, 9.8, 0.2, 10.0, 7.8, z0, z1),
        }
        if st == G:
            hall = add_space("Hall", st, 0.2, 0.2, 9.8, 7.8, z0, z1)
            door("Front door", st, walls["south"], 2.0, 0.0, 3.0, 0.2, z0, [hall])
            slab("Ground slab", st, 0.0)
            if variant == "covered":
                product("IfcSlab", "Rear roof", st, (0.0, 8.0, 2.8, 10.0, 10.0, 3.0), "slab rear roof", PredefinedType="ROOF")
        else:
            walls["middle"] = wall("Middle", st, 6.0, 0.2, 6.2, 7.8, z0, z1)
            upper_hall = add_space("Upper hall", st, 0.2, 0.2, 6.0, 7.8, z0, z1)
            upper_room = add_space("Upper room", st, 6.2, 0.2, 9.8, 7.8, z0, z1)
            door("Hillside door", st, walls["north"], 2.0, 7.8, 3.0, 8.0, z0, [upper_hall])
            door("Balcony door", st, walls["south"], 2.0, 0.0, 3.0, 0.2, z0, [upper_hall])
            door("Upper room door", st, walls["middle"], 6.0, 3.0, 6.2, 4.0, z0, [upper_hall, upper_room])
            slab("Upper slab", st, 3.0)

    for name, s in storeys.items():
        f.createIfcRelContainedInSpatialStructure(gid("contains " + name), None, None, None, contained[name], s)
        rel_aggregates(s, spaces[name])
    return f


def terrain_mesh(model):
    """IfcOpenShell's world mesh of the terrain product: triangles, z range and area."""
    import ifcopenshell.geom
    import numpy as np

    settings = ifcopenshell.geom.settings()
    settings.set("use-world-coords", True)
    for e in model.by_type("IfcSite") + model.by_type("IfcGeographicElement") + model.by_type("IfcBuildingElementProxy"):
        if e.Representation is None:
            continue
        g = ifcopenshell.geom.create_shape(settings, e).geometry
        v = np.array(g.verts, dtype=float).reshape(-1, 3)
        t = np.array(g.faces, dtype=int).reshape(-1, 3)
        area = 0.5 * np.linalg.norm(np.cross(v[t[:, 1]] - v[t[:, 0]], v[t[:, 2]] - v[t[:, 0]]), axis=1).sum()
        return {"class": e.is_a(), "triangles": len(t), "zmin": v[:, 2].min(), "zmax": v[:, 2].max(), "area": area}
    return None


out_dir = sys.argv[1]
files, meshes = {}, {}
for variant in ("geographic", "site", "proxy", "covered"):
    model = build(variant)
    name = "hillside-%s.ifc" % variant
    model.write(os.path.join(out_dir, name))
    files[variant] = name
    meshes[variant] = terrain_mesh(model)
print(json.dumps({
    "files": files,
    "terrain": meshes,
    "doors": {e.Name: e.GlobalId for e in model.by_type("IfcDoor")},
    "spaces": {e.Name: e.GlobalId for e in model.by_type("IfcSpace")},
    "terrain_rows": TERRAIN_ROWS,
}))
