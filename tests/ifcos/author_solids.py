"""Solids poinav meshes beyond extrusions and faceted breps, written with IfcOpenShell and
meshed by it, for poinav-geom's test `solids_vs_ifcopenshell.rs`.

Usage: .venv/bin/python tests/ifcos/author_solids.py OUT.ifc

IFC4, metres, radians. One IfcBuildingElementProxy per case (its Name is the case; each
placed at its own spot, so placements count), all on one storey:

- revolved solids: a ring profile turned a full turn and a quarter turn, a profile touching
  the axis turned a full and a half turn, a tapered quarter turn (the ring shrinking);
- tapered extrusions: a rectangle into a smaller one, a hollow rectangle into a smaller one
  (a profile with a hole);
- CSG: IfcSphere, IfcRightCircularCone and IfcRectangularPyramid alone (with Position),
  IfcCsgSolid differences (block less sphere, cylinder less cone), unions (block and a
  pyramid above it; block and a sphere overlapping one corner) and an intersection (block
  and sphere);
- advanced breps: a quarter cylinder with an IfcCylindricalSurface face and IfcCircle edges
  (and the same with its arcs as IfcSurfaceCurves on the cylinder);
  the same with its curved face and arcs as rational B-splines (weights matter), and with
  its curved face on an IfcSurfaceOfLinearExtrusion of a rational B-spline arc or on an
  IfcSurfaceOfRevolution of a line; a box whose
  top is a B-spline surface with B-spline edges; a full cylinder whose side face is bounded
  through a seam edge; a cylinder without a seam whose circles are IfcIndexedPolyCurves of
  arcs (OpenBuildings' way: half-circle edges, one with SameSense false, and a closed edge
  whose vertex is not the curve's start); the same cylinder in B-splines only (its side a
  rational B-spline surface closed in u, bounded by two closed B-spline circles); a torus
  bounded by its two seams; a box with a box-shaped void (IfcAdvancedBrepWithVoids); a tube
  whose side is a B-spline surface closed along v (periodic knots), bounded through a seam
  edge and two closed B-spline curves, and one closed along u bounded by the two curves alone;
- an IfcPolygonalFaceSet with IfcIndexedPolygonalFaceWithVoids (a square tube);
- an extruded profile bounded by a closed rational B-spline circle.

Then every proxy is meshed by ifcopenshell.geom (world coordinates, default settings) and one
JSON object is printed mapping each case name to {guid, ifcopenshell: true, min, max,
volume, area} (see `volume`: null when IfcOpenShell's mesh is not closed), or {guid, error} when
IfcOpenShell gives no shape (IfcOpenShell 0.9 fails on IfcRightCircularCone,
IfcRightCircularCylinder and this IfcAdvancedBrepWithVoids), each with `expected`: the exact volume, the bounding box where
IfcOpenShell gives none or a wrong one, and `ifcos_wrong`, why IfcOpenShell's shape is not
to be trusted.
"""

import json
import math
import os
import sys

import ifcopenshell
import ifcopenshell.geom
import numpy as np
from authoring import Authoring

f = ifcopenshell.file(schema="IFC4")
W = math.sqrt(0.5)


a = Authoring(f, "poinav-test-solids:")
gid, pt, d3, ax3 = a.gid, a.pt, a.d3, a.axis


def ax2(x=0.0, y=0.0):
    return f.createIfcAxis2Placement2D(pt(x, y), None)


ctx = f.createIfcGeometricRepresentationContext(None, "Model", 3, 1.0e-5, ax3(), None)
body = f.createIfcGeometricRepresentationSubContext("Body", "Model", None, None, None, None, ctx, None, "MODEL_VIEW", None)
units = f.createIfcUnitAssignment(
    [
        f.createIfcSIUnit(None, "LENGTHUNIT", None, "METRE"),
        f.createIfcSIUnit(None, "PLANEANGLEUNIT", None, "RADIAN"),
    ]
)
project = f.createIfcProject(gid("project"), None, "Solids", None, None, None, None, [ctx], units)
site_pl = f.createIfcLocalPlacement(None, ax3())
site = f.createIfcSite(gid("site"), None, "Site", None, None, site_pl, None, None, "ELEMENT", None, None, None, None, None)
storey_pl = f.createIfcLocalPlacement(site_pl, ax3())
storey = f.createIfcBuildingStorey(gid("storey"), None, "Storey", None, None, storey_pl, None, None, "ELEMENT", 0.0)
f.createIfcRelAggregates(gid("agg project"), None, None, None, project, [site])
f.createIfcRelAggregates(gid("agg site"), None, None, None, site, [storey])
products = []
slot = [0]


expected = {}


def case(name, items, kind="SweptSolid", volume=None, box=None, ifcos_wrong=None):
    """A proxy named `name` at the next slot of a 5 m grid, its body `items`; its exact
    `volume`, its bounding `box` ((min, max) in its own coordinates) where IfcOpenShell
    cannot mesh it, and why IfcOpenShell's shape is wrong when it is."""
    i = slot[0]
    slot[0] += 1
    origin = (5.0 * (i % 6), 5.0 * (i // 6), 0.5)
    expected[name] = {"volume": volume, "ifcos_wrong": ifcos_wrong}
    if box is not None:
        expected[name]["min"] = [o + x for o, x in zip(origin, box[0])]
        expected[name]["max"] = [o + x for o, x in zip(origin, box[1])]
    pl = f.createIfcLocalPlacement(storey_pl, ax3(*origin))
    rep = f.createIfcShapeRepresentation(body, "Body", kind, items)
    shape = f.createIfcProductDefinitionShape(None, None, [rep])
    p = f.createIfcBuildingElementProxy(gid(name), None, name, None, None, pl, shape, None, None)
    products.append(p)


def rect(x, y, dx, dy):
    return f.createIfcRectangleProfileDef("AREA", None, ax2(x, y), dx, dy)


# --- Revolved solids. The profile lies in the solid's xz plane (Position turns z to -y),
# the axis is the profile's y axis, i.e. the world z axis.
standing = dict(axis=(0, -1, 0), ref=(1, 0, 0))
y_axis = f.createIfcAxis1Placement(pt(0, 0, 0), d3(0, 1, 0))
ring = rect(1.5, 1.0, 1.0, 2.0)  # x 1..2, y 0..2
touching = rect(0.5, 1.0, 1.0, 2.0)  # x 0..1: touches the axis
case("revolved full", [f.createIfcRevolvedAreaSolid(ring, ax3(**standing), y_axis, 2 * math.pi)], volume=6 * math.pi)
case("revolved quarter", [f.createIfcRevolvedAreaSolid(ring, ax3(**standing), y_axis, math.pi / 2)], volume=1.5 * math.pi)
case("revolved touching axis", [f.createIfcRevolvedAreaSolid(touching, ax3(**standing), y_axis, 2 * math.pi)], volume=2 * math.pi)
case("revolved touching half", [f.createIfcRevolvedAreaSolid(touching, ax3(**standing), y_axis, math.pi)], volume=math.pi)
case(
    "revolved tapered",
    [
        f.createIfcRevolvedAreaSolidTapered(
            ring, ax3(**standing), y_axis, math.pi / 2, rect(1.5, 1.0, 0.5, 1.0)
        )
    ],
    # Pappus per section: the centroid stays at radius 1.5, the area goes from 2 to 0.5.
    volume=1.5 * math.pi / 2 * 7 / 6,
    # The outer radius goes from 2 to 1.75 as the profile turns from +x to +y.
    box=((0, 0, 0), (2, max((2 - 0.25 * t) * math.sin(math.pi / 2 * t) for t in np.linspace(0, 1, 100001)), 2)),
    ifcos_wrong="IfcOpenShell 0.9 ignores EndSweptArea of a tapered revolution",
)

# --- Tapered extrusions.
case(
    "tapered rectangle",
    [f.createIfcExtrudedAreaSolidTapered(rect(0, 0, 2.0, 1.0), ax3(), d3(0, 0, 1), 3.0, rect(0, 0, 1.0, 0.5))],
    volume=3.5,
)
hollow = f.createIfcRectangleHollowProfileDef("AREA", None, ax2(), 2.0, 2.0, 0.4, None, None)
hollow_end = f.createIfcRectangleHollowProfileDef("AREA", None, ax2(), 1.2, 1.2, 0.2, None, None)
case("tapered hollow", [f.createIfcExtrudedAreaSolidTapered(hollow, ax3(), d3(0, 0, 1), 2.0, hollow_end)], volume=3.2)

# --- CSG primitives and CSG trees.
case("sphere", [f.createIfcSphere(ax3(0.2, 0.3, 1.0), 0.8)], "CSG", volume=4 / 3 * math.pi * 0.8**3)
case("cone", [f.createIfcRightCircularCone(ax3(0, 0, 0, axis=(1, 0, 0), ref=(0, 1, 0)), 1.5, 0.5)], "CSG",
     volume=math.pi * 0.25 * 1.5 / 3, box=((0, -0.5, -0.5), (1.5, 0.5, 0.5)))
case("pyramid", [f.createIfcRectangularPyramid(ax3(-0.5, -1.0, 0), 1.0, 2.0, 1.5)], "CSG", volume=1.0)
block = f.createIfcBlock(ax3(), 2.0, 2.0, 2.0)
corner_ball = f.createIfcSphere(ax3(2.0, 2.0, 2.0), 0.8)
case("csg block less sphere", [f.createIfcCsgSolid(f.createIfcBooleanResult("DIFFERENCE", block, corner_ball))], "CSG",
     volume=8 - 4 / 3 * math.pi * 0.8**3 / 8)
cylinder = f.createIfcRightCircularCylinder(ax3(), 1.0, 0.6)
case(
    "csg cylinder less cone",
    [f.createIfcCsgSolid(f.createIfcBooleanResult("DIFFERENCE", cylinder, f.createIfcRightCircularCone(ax3(0, 0, 0.2), 1.0, 0.4)))],
    "CSG",
    # The cone's tip above the cylinder (height 0.2, base radius 0.08) stays outside.
    volume=math.pi * 0.36 - (math.pi * 0.16 / 3 - math.pi * 0.08**2 * 0.2 / 3),
    box=((-0.6, -0.6, 0), (0.6, 0.6, 1)),
)
case(
    "csg block and pyramid",
    [f.createIfcCsgSolid(f.createIfcBooleanResult("UNION", block, f.createIfcRectangularPyramid(ax3(0.4, 0.4, 2.1), 1.2, 1.2, 0.9)))],
    "CSG",
    volume=8 + 1.2 * 1.2 * 0.9 / 3,
)
case(
    "csg block and overlapping sphere",
    [f.createIfcCsgSolid(f.createIfcBooleanResult("UNION", block, corner_ball))],
    "CSG",
    # The ball's eighth inside the block counts once.
    volume=8 + 4 / 3 * math.pi * 0.8**3 * 7 / 8,
)
case(
    "csg block and sphere",
    [f.createIfcCsgSolid(f.createIfcBooleanResult("INTERSECTION", block, f.createIfcSphere(ax3(1.0, 1.0, 1.0), 1.3)))],
    "CSG",
    # The sphere less six caps 0.3 high.
    volume=4 / 3 * math.pi * 1.3**3 - 6 * math.pi * 0.09 * (3.9 - 0.3) / 3,
)


# --- Advanced breps.
class Brep:
    """Vertices, edges and faces of one closed shell."""

    def __init__(self):
        self.v = {}
        self.e = {}

    def vertex(self, name, *c):
        self.v[name] = f.createIfcVertexPoint(pt(*c))

    def edge(self, name, a, b, curve=None, sense=True):
        if curve is None:
            p = self.v[a].VertexGeometry.Coordinates
            q = self.v[b].VertexGeometry.Coordinates
            curve = f.createIfcPolyline([pt(*p), pt(*q)])
        self.e[name] = f.createIfcEdgeCurve(self.v[a], self.v[b], curve, sense)

    def face(self, surface, *loops, same_sense=True):
        bounds = []
        for i, lp in enumerate(loops):
            edges = [f.createIfcOrientedEdge(None, None, self.e[n.lstrip("-")], not n.startswith("-")) for n in lp]
            loop = f.createIfcEdgeLoop(edges)
            bounds.append((f.createIfcFaceOuterBound if i == 0 else f.createIfcFaceBound)(loop, True))
        return f.createIfcAdvancedFace(bounds, surface, same_sense)


def plane(x, y, z, normal, ref):
    return f.createIfcPlane(ax3(x, y, z, axis=normal, ref=ref))


def circle(z, r=1.0):
    return f.createIfcCircle(ax3(0, 0, z), r)


def bspline_curve(points, weights=None):
    n = len(points)
    deg = min(2, n - 1)
    mult = [deg + 1, deg + 1]
    cps = [pt(*p) for p in points]
    if weights is None:
        return f.createIfcBSplineCurveWithKnots(deg, cps, "UNSPECIFIED", False, False, mult, [0.0, 1.0], "UNSPECIFIED")
    return f.createIfcRationalBSplineCurveWithKnots(
        deg, cps, "UNSPECIFIED", False, False, mult, [0.0, 1.0], "UNSPECIFIED", weights
    )


def quarter_cylinder(rational, extrusion=False, revolution=False, surface_curves=False):
    """r = 1, h = 2 about z, in x >= 0, y >= 0; the curved face on a cylinder, a rational
    B-spline surface, a surface of linear extrusion of a rational B-spline quarter circle
    (`extrusion`), or a surface of revolution of a line about z (`revolution`); with
    `surface_curves` the arcs are IfcSurfaceCurves on the cylinder (their Curve3D a circle)."""
    b = Brep()
    cylinder = f.createIfcCylindricalSurface(ax3(), 1.0)
    for z, s in [(0, "0"), (2, "1")]:
        b.vertex("O" + s, 0, 0, z)
        b.vertex("A" + s, 1, 0, z)
        b.vertex("B" + s, 0, 1, z)
    for s, z in [("0", 0), ("1", 2)]:
        arc = (
            bspline_curve([(1, 0, z), (1, 1, z), (0, 1, z)], [1.0, W, 1.0])
            if rational
            else circle(z)
        )
        if surface_curves:
            arc = f.createIfcSurfaceCurve(arc, [cylinder], "CURVE3D")
        b.edge("oa" + s, "O" + s, "A" + s)
        b.edge("ab" + s, "A" + s, "B" + s, arc)
        b.edge("bo" + s, "B" + s, "O" + s)
    for n in "OAB":
        b.edge(n + "up", n + "0", n + "1")
    if rational:
        rows = [[pt(1, 0, 0), pt(1, 0, 2)], [pt(1, 1, 0), pt(1, 1, 2)], [pt(0, 1, 0), pt(0, 1, 2)]]
        curved = f.createIfcRationalBSplineSurfaceWithKnots(
            2, 1, rows, "UNSPECIFIED", False, False, False, [3, 3], [2, 2], [0.0, 1.0], [0.0, 1.0],
            "UNSPECIFIED", [[1.0, 1.0], [W, W], [1.0, 1.0]],
        )
    elif revolution:
        line = f.createIfcArbitraryOpenProfileDef("CURVE", None, f.createIfcPolyline([pt(1, 0), pt(1, 2)]))
        curved = f.createIfcSurfaceOfRevolution(
            line, ax3(axis=(0, -1, 0), ref=(1, 0, 0)), f.createIfcAxis1Placement(pt(0, 0, 0), d3(0, 1, 0))
        )
    elif extrusion:
        arc = f.createIfcRationalBSplineCurveWithKnots(
            2, [pt(1, 0), pt(1, 1), pt(0, 1)], "CIRCULAR_ARC", False, False, [3, 3], [0.0, 1.0],
            "UNSPECIFIED", [1.0, W, 1.0],
        )
        swept = f.createIfcArbitraryOpenProfileDef("CURVE", None, arc)
        curved = f.createIfcSurfaceOfLinearExtrusion(swept, ax3(), d3(0, 0, 1), 2.0)
    else:
        curved = cylinder
    faces = [
        b.face(plane(0, 0, 0, (0, 0, -1), (1, 0, 0)), ["-bo0", "-ab0", "-oa0"]),
        b.face(plane(0, 0, 2, (0, 0, 1), (1, 0, 0)), ["oa1", "ab1", "bo1"]),
        b.face(plane(0, 0, 0, (0, -1, 0), (1, 0, 0)), ["oa0", "Aup", "-oa1", "-Oup"]),
        b.face(plane(0, 0, 0, (-1, 0, 0), (0, 1, 0)), ["Oup", "-bo1", "-Bup", "bo0"]),
        b.face(curved, ["ab0", "Bup", "-ab1", "-Aup"]),
    ]
    return f.createIfcAdvancedBrep(f.createIfcClosedShell(faces))


case("advanced quarter cylinder", [quarter_cylinder(False)], "AdvancedBrep", volume=math.pi / 2)
case("advanced rational quarter cylinder", [quarter_cylinder(True)], "AdvancedBrep", volume=math.pi / 2)
case(
    "advanced quarter cylinder, surface curves",
    [quarter_cylinder(False, surface_curves=True)],
    "AdvancedBrep",
    volume=math.pi / 2,
)
case(
    "advanced revolution quarter cylinder",
    [quarter_cylinder(False, revolution=True)],
    "AdvancedBrep",
    volume=math.pi / 2,
)
case(
    "advanced extrusion quarter cylinder",
    [quarter_cylinder(False, extrusion=True)],
    "AdvancedBrep",
    volume=math.pi / 2,
)


def bspline_top_box():
    """2 x 2 base, walls 1 high, the top a biquadratic B-spline bulging up (centre 1.25)."""
    b = Brep()
    for x, y in [(0, 0), (2, 0), (2, 2), (0, 2)]:
        b.vertex("P%d%d" % (x, y), x, y, 0)
        b.vertex("T%d%d" % (x, y), x, y, 1)
    height = lambda i, j: 1.0 + 0.5 * ((i == 1) + (j == 1))
    grid = [[(i, j, height(i, j)) for j in range(3)] for i in range(3)]
    b.edge("cy0", "T00", "T20", bspline_curve([grid[i][0] for i in range(3)]))
    b.edge("cx2", "T20", "T22", bspline_curve([grid[2][j] for j in range(3)]))
    b.edge("cy2", "T02", "T22", bspline_curve([grid[i][2] for i in range(3)]))
    b.edge("cx0", "T00", "T02", bspline_curve([grid[0][j] for j in range(3)]))
    b.edge("by0", "P00", "P20")
    b.edge("bx2", "P20", "P22")
    b.edge("by2", "P02", "P22")
    b.edge("bx0", "P00", "P02")
    for c in ["00", "20", "22", "02"]:
        b.edge("v" + c, "P" + c, "T" + c)
    top = f.createIfcBSplineSurfaceWithKnots(
        2, 2, [[pt(*p) for p in row] for row in grid], "UNSPECIFIED", False, False, False,
        [3, 3], [3, 3], [0.0, 1.0], [0.0, 1.0], "UNSPECIFIED",
    )
    faces = [
        b.face(top, ["cy0", "cx2", "-cy2", "-cx0"]),
        b.face(plane(0, 0, 0, (0, 0, -1), (1, 0, 0)), ["bx0", "by2", "-bx2", "-by0"]),
        b.face(plane(0, 0, 0, (0, -1, 0), (1, 0, 0)), ["by0", "v20", "-cy0", "-v00"]),
        b.face(plane(2, 0, 0, (1, 0, 0), (0, 1, 0)), ["bx2", "v22", "-cx2", "-v20"]),
        b.face(plane(0, 2, 0, (0, 1, 0), (1, 0, 0)), ["-by2", "v02", "cy2", "-v22"]),
        b.face(plane(0, 0, 0, (-1, 0, 0), (0, 1, 0)), ["-bx0", "v00", "cx0", "-v02"]),
    ]
    return f.createIfcAdvancedBrep(f.createIfcClosedShell(faces))


# The bulge above z = 1 averages a third of the control heights' (0.5 at mid-edges, 1 at the centre).
case("advanced bspline top", [bspline_top_box()], "AdvancedBrep", volume=4 + 4 / 3)


def seam_cylinder():
    """r = 0.5, h = 1.2: the side face bounded by both circles and a seam used both ways."""
    b = Brep()
    b.vertex("S0", 0.5, 0, 0)
    b.vertex("S1", 0.5, 0, 1.2)
    b.edge("c0", "S0", "S0", circle(0, 0.5))
    b.edge("c1", "S1", "S1", circle(1.2, 0.5))
    b.edge("seam", "S0", "S1")
    faces = [
        b.face(f.createIfcCylindricalSurface(ax3(), 0.5), ["c0", "seam", "-c1", "-seam"]),
        b.face(plane(0, 0, 0, (0, 0, -1), (1, 0, 0)), ["-c0"]),
        b.face(plane(0, 0, 1.2, (0, 0, 1), (1, 0, 0)), ["c1"]),
    ]
    return f.createIfcAdvancedBrep(f.createIfcClosedShell(faces))


case("advanced seam cylinder", [seam_cylinder()], "AdvancedBrep", volume=math.pi * 0.25 * 1.2)


def polycurve_cylinder():
    """r = 0.5, h = 1.2 with no seam, as OpenBuildings writes cylinders: edges along
    IfcIndexedPolyCurves of arcs through 3D points. The bottom circle is two half-circle edges,
    one along its curve and one against it (SameSense false); the top one is one closed edge
    whose vertex is the curve's second point, not its first, inside an IfcIntersectionCurve.
    The side face is bounded by the two circles only."""
    b = Brep()
    r, h = 0.5, 1.2

    def arcs(z, *segments):
        points = f.createIfcCartesianPointList3D([(r, 0.0, z), (0.0, r, z), (-r, 0.0, z), (0.0, -r, z)])
        return f.createIfcIndexedPolyCurve(points, [f.createIfcArcIndex(s) for s in segments], False)

    b.vertex("E0", r, 0, 0)
    b.vertex("W0", -r, 0, 0)
    b.vertex("N1", 0, r, h)
    b.edge("north0", "E0", "W0", arcs(0.0, (1, 2, 3)))
    b.edge("south0", "W0", "E0", arcs(0.0, (1, 4, 3)), sense=False)
    top = arcs(h, (1, 2, 3), (3, 4, 1))
    b.edge("c1", "N1", "N1", f.createIfcIntersectionCurve(top, [plane(0, 0, h, (0, 0, 1), (1, 0, 0))], "CURVE3D"))
    cylinder = f.createIfcCylindricalSurface(ax3(), r)
    side = f.createIfcAdvancedFace(
        [
            f.createIfcFaceBound(f.createIfcEdgeLoop([f.createIfcOrientedEdge(None, None, b.e[n], True) for n in ["north0", "south0"]]), True),
            f.createIfcFaceBound(f.createIfcEdgeLoop([f.createIfcOrientedEdge(None, None, b.e["c1"], False)]), True),
        ],
        cylinder,
        True,
    )
    faces = [
        side,
        b.face(plane(0, 0, 0, (0, 0, -1), (1, 0, 0)), ["-south0", "-north0"]),
        b.face(plane(0, 0, h, (0, 0, 1), (1, 0, 0)), ["c1"]),
    ]
    return f.createIfcAdvancedBrep(f.createIfcClosedShell(faces))


case("advanced polycurve cylinder", [polycurve_cylinder()], "AdvancedBrep", volume=math.pi * 0.25 * 1.2)


def closed_bspline_cylinder():
    """r = 0.5, h = 1.2 with no seam, as OpenBuildings writes cylinders in B-splines only: the
    side face a rational B-spline surface closed in u (two cubic half circles, weights 1, 1/3,
    1/3, 1, its first and last rows of control points the same), bounded by two closed
    rational B-spline circles that start at the surface's closing line."""
    b = Brep()
    r, h = 0.5, 1.2
    half = [(r, 0), (r, 2 * r), (-r, 2 * r), (-r, 0), (-r, -2 * r), (r, -2 * r), (r, 0)]
    w = [1.0, 1 / 3, 1 / 3, 1.0, 1 / 3, 1 / 3, 1.0]
    side = f.createIfcRationalBSplineSurfaceWithKnots(
        3, 1, [[pt(x, y, 0.0), pt(x, y, h)] for x, y in half], "CYLINDRICAL_SURF", True, False, False,
        [4, 3, 4], [2, 2], [0.0, 0.5, 1.0], [0.0, 1.0], "UNSPECIFIED", [[x, x] for x in w],
    )
    quarter = [(r, 0), (r, r), (0, r), (-r, r), (-r, 0), (-r, -r), (0, -r), (r, -r), (r, 0)]

    def circle_at(z):
        return f.createIfcRationalBSplineCurveWithKnots(
            2, [pt(x, y, z) for x, y in quarter], "CIRCULAR_ARC", True, False, [3, 2, 2, 2, 3],
            [0.0, 0.25, 0.5, 0.75, 1.0], "UNSPECIFIED", [1.0, W, 1.0, W, 1.0, W, 1.0, W, 1.0],
        )

    b.vertex("S0", r, 0, 0)
    b.vertex("S1", r, 0, h)
    b.edge("c0", "S0", "S0", circle_at(0.0))
    b.edge("c1", "S1", "S1", circle_at(h))
    loop = lambda n, fwd: f.createIfcFaceBound(f.createIfcEdgeLoop([f.createIfcOrientedEdge(None, None, b.e[n], fwd)]), True)
    faces = [
        f.createIfcAdvancedFace([loop("c0", True), loop("c1", False)], side, True),
        b.face(plane(0, 0, 0, (0, 0, -1), (1, 0, 0)), ["-c0"]),
        b.face(plane(0, 0, h, (0, 0, 1), (1, 0, 0)), ["c1"]),
    ]
    return f.createIfcAdvancedBrep(f.createIfcClosedShell(faces))


case("advanced closed bspline cylinder", [closed_bspline_cylinder()], "AdvancedBrep", volume=math.pi * 0.25 * 1.2)


def periodic_tube(around_u=False):
    """h = 1.2: the side face a B-spline surface closed along v (a uniform cubic around the
    diamond (0.6, 0), (0, 0.6), (-0.6, 0), (0, -0.6), its first three control points repeated,
    as Geometry Gym writes a basin's bowl), bounded by a seam used both ways and two such
    closed B-spline curves; flat caps. With `around_u` the surface is closed along u instead
    and bounded by the two closed curves alone (no seam edge). Returns the brep, its
    section's area and its box."""
    ring = [(0.6, 0.0), (0.0, 0.6), (-0.6, 0.0), (0.0, -0.6)]
    ring += ring[:3]
    knots = [float(k) for k in range(-7, 4)]

    def ring_curve(z):
        cps = [pt(x, y, z) for x, y in ring]
        return f.createIfcBSplineCurveWithKnots(3, cps, "UNSPECIFIED", True, False, [1] * 11, knots, "UNSPECIFIED")

    # The curve at the domain's start (t = -4): (Q0 + 4 Q1 + Q2) / 6.
    x0, y0 = [(a + 4 * b + c) / 6 for a, b, c in zip(ring[0], ring[1], ring[2])]
    b = Brep()
    b.vertex("S0", x0, y0, 0)
    b.vertex("S1", x0, y0, 1.2)
    b.edge("c0", "S0", "S0", ring_curve(0.0))
    b.edge("c1", "S1", "S1", ring_curve(1.2))
    b.edge("seam", "S0", "S1")
    if around_u:
        # Around along u, up along v: the normal (u x v) points out.
        cols = [[pt(x, y, z) for z in (0.0, 1.2)] for x, y in ring]
        side = f.createIfcBSplineSurfaceWithKnots(3, 1, cols, "UNSPECIFIED", True, False, False, [1] * 11, [2, 2], knots, [0.0, 1.0], "UNSPECIFIED")
        side_face = b.face(side, ["c0"], ["-c1"])
    else:
        rows = [[pt(x, y, z) for x, y in ring] for z in (0.0, 1.2)]
        side = f.createIfcBSplineSurfaceWithKnots(1, 3, rows, "UNSPECIFIED", False, True, False, [2, 2], [1] * 11, [0.0, 1.0], knots, "UNSPECIFIED")
        # The surface's normal (along u x v: up x around) points in: SameSense false.
        side_face = b.face(side, ["c0", "seam", "-c1", "-seam"], same_sense=False)
    faces = [
        side_face,
        b.face(plane(0, 0, 0, (0, 0, -1), (1, 0, 0)), ["-c0"]),
        b.face(plane(0, 0, 1.2, (0, 0, 1), (1, 0, 0)), ["c1"]),
    ]
    # The section, sampled finely: four uniform cubic segments.
    t = np.linspace(0.0, 1.0, 4001)[:-1]
    basis = np.stack([(1 - t) ** 3, 3 * t**3 - 6 * t**2 + 4, -3 * t**3 + 3 * t**2 + 3 * t + 1, t**3]) / 6
    q = np.array(ring)
    section = np.concatenate([basis.T @ q[i:i + 4] for i in range(4)])
    area = 0.5 * abs(np.dot(section[:, 0], np.roll(section[:, 1], -1)) - np.dot(section[:, 1], np.roll(section[:, 0], -1)))
    lo, hi = section.min(axis=0), section.max(axis=0)
    box = ((lo[0], lo[1], 0.0), (hi[0], hi[1], 1.2))
    return f.createIfcAdvancedBrep(f.createIfcClosedShell(faces)), area, box


tube, tube_area, tube_box = periodic_tube()
case("advanced periodic bspline tube", [tube], "AdvancedBrep", volume=tube_area * 1.2, box=tube_box)
tube, tube_area, tube_box = periodic_tube(around_u=True)
case(
    "advanced periodic bspline tube, no seam",
    [tube],
    "AdvancedBrep",
    volume=tube_area * 1.2,
    box=tube_box,
    ifcos_wrong="IfcOpenShell 0.9 turns its side in: no consistent closed solid",
)


def torus():
    """R = 1, r = 0.3: one toroidal face bounded by its two seam circles, each run both ways."""
    b = Brep()
    b.vertex("V", 1.3, 0, 0)
    b.edge("outer", "V", "V", circle(0, 1.3))
    tube = f.createIfcCircle(ax3(1.0, 0, 0, axis=(0, -1, 0), ref=(1, 0, 0)), 0.3)
    b.edge("tube", "V", "V", tube)
    surface = f.createIfcToroidalSurface(ax3(), 1.0, 0.3)
    return f.createIfcAdvancedBrep(f.createIfcClosedShell([b.face(surface, ["outer", "tube", "-outer", "-tube"])]))


case("advanced torus", [torus()], "AdvancedBrep", volume=2 * math.pi**2 * 1.0 * 0.3**2)


def box_shell(x0, y0, z0, x1, y1, z1, inward=False):
    """The six planar advanced faces of a box, normals out (in when `inward`)."""
    b = Brep()
    c = {}
    for i, x in enumerate([x0, x1]):
        for j, y in enumerate([y0, y1]):
            for k, z in enumerate([z0, z1]):
                c[(i, j, k)] = "V%d%d%d" % (i, j, k)
                b.vertex(c[(i, j, k)], x, y, z)
    quads = [  # corner index triples, counter-clockwise seen from outside, and the normal
        ([(0, 0, 0), (0, 1, 0), (1, 1, 0), (1, 0, 0)], (0, 0, -1)),
        ([(0, 0, 1), (1, 0, 1), (1, 1, 1), (0, 1, 1)], (0, 0, 1)),
        ([(0, 0, 0), (1, 0, 0), (1, 0, 1), (0, 0, 1)], (0, -1, 0)),
        ([(1, 1, 0), (0, 1, 0), (0, 1, 1), (1, 1, 1)], (0, 1, 0)),
        ([(0, 1, 0), (0, 0, 0), (0, 0, 1), (0, 1, 1)], (-1, 0, 0)),
        ([(1, 0, 0), (1, 1, 0), (1, 1, 1), (1, 0, 1)], (1, 0, 0)),
    ]
    faces = []
    for quad, normal in quads:
        names = []
        for a, z in zip(quad, quad[1:] + quad[:1]):
            key = tuple(sorted([c[a], c[z]]))
            name = key[0] + key[1]
            if name not in b.e:
                b.edge(name, key[0], key[1])
            names.append(name if key[0] == c[a] else "-" + name)
        p = b.v[c[quad[0]]].VertexGeometry.Coordinates
        ref = (1, 0, 0) if abs(normal[0]) < 0.5 else (0, 1, 0)
        if inward:
            names = ["-" + n if not n.startswith("-") else n[1:] for n in reversed(names)]
            normal = tuple(-x for x in normal)
        faces.append(b.face(plane(*p, normal, ref), names))
    return f.createIfcClosedShell(faces)


case(
    "advanced box with void",
    [f.createIfcAdvancedBrepWithVoids(box_shell(0, 0, 0, 2, 2, 2), [box_shell(0.5, 0.5, 0.5, 1.5, 1.5, 1.5, inward=True)])],
    "AdvancedBrep",
    volume=7.0,
    box=((0, 0, 0), (2, 2, 2)),
)

# --- A polygonal face set with voids: a 2 x 2 x 1 square tube around a 1 x 1 hole.
outer = [(0, 0), (2, 0), (2, 2), (0, 2)]
inner = [(0.5, 0.5), (1.5, 0.5), (1.5, 1.5), (0.5, 1.5)]
coords = [(x, y, z) for z in (0, 1) for x, y in outer] + [(x, y, z) for z in (0, 1) for x, y in inner]
# 1-based: outer bottom 1-4, outer top 5-8, inner bottom 9-12, inner top 13-16.
pfaces = [
    f.createIfcIndexedPolygonalFaceWithVoids([1, 4, 3, 2], [[9, 10, 11, 12]]),
    f.createIfcIndexedPolygonalFaceWithVoids([5, 6, 7, 8], [[16, 15, 14, 13]]),
]
for i in range(4):
    a, b = i + 1, (i + 1) % 4 + 1
    pfaces.append(f.createIfcIndexedPolygonalFace([a, b, b + 4, a + 4]))
    pfaces.append(f.createIfcIndexedPolygonalFace([b + 8, a + 8, a + 12, b + 12]))
case(
    "polygonal face set with voids",
    [f.createIfcPolygonalFaceSet(f.createIfcCartesianPointList3D(coords), True, pfaces, None)],
    "Tessellation",
    volume=3.0,
)

# --- A profile bounded by a closed rational B-spline circle (r = 1, nine control points),
# extruded 1 m.
cps = [(1, 0), (1, 1), (0, 1), (-1, 1), (-1, 0), (-1, -1), (0, -1), (1, -1), (1, 0)]
circle_curve = f.createIfcRationalBSplineCurveWithKnots(
    2, [pt(*c) for c in cps], "CIRCULAR_ARC", True, False, [3, 2, 2, 2, 3], [0.0, 0.25, 0.5, 0.75, 1.0],
    "UNSPECIFIED", [1.0, W, 1.0, W, 1.0, W, 1.0, W, 1.0],
)
disc = f.createIfcArbitraryClosedProfileDef("AREA", None, circle_curve)
case("bspline profile", [f.createIfcExtrudedAreaSolid(disc, ax3(), d3(0, 0, 1), 1.0)], volume=math.pi)

f.createIfcRelContainedInSpatialStructure(gid("contains"), None, None, None, products, storey)
f.write(sys.argv[1])

# --- IfcOpenShell's meshes.


def volume(verts, faces):
    """The enclosed volume and the surface area of a triangle mesh, made robust against what
    IfcOpenShell 0.9 gives for some solids (a pyramid with its sides facing in, a tapered
    extrusion with its caps written twice): vertices welded, repeated triangles dropped, every
    connected part oriented consistently across shared edges, each part counted positive.
    (None, None) when the mesh is not closed (an edge not shared by exactly two triangles)."""
    keys = {}
    index = [keys.setdefault(tuple(np.round(v, 7)), len(keys)) for v in verts]
    pts = np.array(list(keys.keys()), dtype=float)
    seen = set()
    tris = []
    for t in faces:
        t = [index[i] for i in t]
        if len(set(t)) == 3 and frozenset(t) not in seen:
            seen.add(frozenset(t))
            tris.append(t)
    by_edge = {}
    for n, t in enumerate(tris):
        for k in range(3):
            by_edge.setdefault(frozenset((t[k], t[(k + 1) % 3])), []).append(n)
    if any(len(v) != 2 for v in by_edge.values()):
        return None, None
    done = [False] * len(tris)
    total = 0.0
    for first in range(len(tris)):
        if done[first]:
            continue
        done[first] = True
        stack, part = [first], []
        while stack:
            n = stack.pop()
            part.append(n)
            t = tris[n]
            for k in range(3):
                a, b = t[k], t[(k + 1) % 3]
                for m in by_edge[frozenset((a, b))]:
                    if done[m]:
                        continue
                    u = tris[m]
                    # Consistent: the neighbour runs the shared edge the other way.
                    if any(u[j] == a and u[(j + 1) % 3] == b for j in range(3)):
                        tris[m] = [u[0], u[2], u[1]]
                    done[m] = True
                    stack.append(m)
        tri = pts[np.array([tris[n] for n in part])]
        total += abs(np.einsum("ij,ij->i", tri[:, 0], np.cross(tri[:, 1], tri[:, 2])).sum() / 6.0)
    tri = pts[np.array(tris)]
    area = 0.5 * np.linalg.norm(np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0]), axis=1).sum()
    return float(total), float(area)


settings = ifcopenshell.geom.settings()
settings.set("use-world-coords", True)
g = ifcopenshell.open(sys.argv[1])
out = {}
# IfcOpenShell's tessellator prints debugging text on stdout for some solids: keep the JSON
# apart by sending file descriptor 1 to stderr while it works.
sys.stdout.flush()
saved = os.dup(1)
os.dup2(2, 1)
try:
    for p in g.by_type("IfcBuildingElementProxy"):
        try:
            shape = ifcopenshell.geom.create_shape(settings, p)
        except Exception as e:  # noqa: BLE001 - reported, the test decides
            out[p.Name] = {"guid": p.GlobalId, "error": str(e).split(", representation")[0]}
            continue
        verts = np.array(shape.geometry.verts, dtype=float).reshape(-1, 3)
        faces = np.array(shape.geometry.faces, dtype=int).reshape(-1, 3)
        v, a = volume(verts, faces)
        out[p.Name] = {
            "guid": p.GlobalId,
            "ifcopenshell": True,
            "min": verts.min(axis=0).tolist(),
            "max": verts.max(axis=0).tolist(),
            "volume": v,
            "area": a,
        }
finally:
    os.dup2(saved, 1)
    os.close(saved)
for name, e in expected.items():
    out[name]["expected"] = e
json.dump(out, sys.stdout, indent=1, sort_keys=True)
