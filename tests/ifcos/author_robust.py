"""Elements that must be meshed even where part of their geometry is broken or odd, written and
meshed with IfcOpenShell, for poinav-geom's test `robust_vs_ifcopenshell.rs`.

Usage: .venv/bin/python tests/ifcos/author_robust.py OUT.ifc

IFC4, metres, radians. One element per case (its Name is the case), each placed 5 m further
along y, all in one storey:

- a profile drawn as a star in one stroke (the polygon {1001/2}: each of 1,001 points on the
  unit circle joined to the next but one, twice around), extruded 1 m: IfcOpenShell fills
  what it winds around (nearly the unit disc);
- walls (4 x 0.2 x 3 m) whose opening cannot be made: an opening with Depth 0, one without
  a representation, one whose profile encloses no area, and a wall with a good opening and a
  bad one; IfcOpenShell keeps the wall uncut (cut by the good opening only);
- boolean results whose second operand cannot be made (Depth 0): DIFFERENCE, UNION and
  INTERSECTION, and a clipping whose half-space plane has a zero normal; IfcOpenShell keeps
  the first operand;
- boolean results whose first operand cannot be made (Depth 0) or is a point: alone, nested
  in differences (IfcOpenShell reads a run of differences as one list, the first operand then
  the second operands from the outside in, and cuts the first of them it can make by the
  others), under a union, and under a clipping (the half-space then heads the list and
  IfcOpenShell keeps what the next solid has in the half-space's material);
- a face of a surface model drawn as a star in one stroke (401 points, {401/2}): filled;
- a face of a surface model bounded by an IfcEdgeLoop of two half circles (a disc);
- a face with two outer bounds (invalid): both meshed;
- an IfcMirroredProfileDef (an L mirrored about its y axis) and the same as an
  IfcDerivedProfileDef with a mirroring operator;
- an IfcCurveBoundedPlane (a 3 x 2 m rectangle with a 1 x 0.5 m hole, on a plane tilted
  about x by 30 degrees), an open surface.

Every element is meshed by ifcopenshell.geom (world coordinates, default settings). Prints one
JSON object mapping each case name to {min, max, volume, area} of IfcOpenShell's mesh (or
{error} when it gives none), plus `left_out`: the STEP ids of the openings or operands that
cannot be made, which poinav names in its warnings.
"""

import json
import math
import sys

import ifcopenshell
import ifcopenshell.geom
import numpy as np
from authoring import Authoring

f = ifcopenshell.file(schema="IFC4")


a = Authoring(f, "poinav-test-robust:")
gid, pt, d = a.gid, a.pt, a.d3


def ax(x=0.0, y=0.0, z=0.0, axis=None, ref=None):
    """A placement whose axis and reference direction default to IFC's (left out)."""
    return a.axis(x, y, z, axis, ref)


ctx = f.createIfcGeometricRepresentationContext(None, "Model", 3, 1.0e-5, ax(), None)
body = f.createIfcGeometricRepresentationSubContext("Body", "Model", None, None, None, None, ctx, None, "MODEL_VIEW", None)
units = f.createIfcUnitAssignment(
    [
        f.createIfcSIUnit(None, "LENGTHUNIT", None, "METRE"),
        f.createIfcSIUnit(None, "PLANEANGLEUNIT", None, "RADIAN"),
    ]
)
project = f.createIfcProject(gid("project"), None, "Robust", None, None, None, None, [ctx], units)
site_pl = f.createIfcLocalPlacement(None, ax())
site = f.createIfcSite(gid("site"), None, "Site", None, None, site_pl, None, None, "ELEMENT", None, None, None, None, None)
storey_pl = f.createIfcLocalPlacement(site_pl, ax())
storey = f.createIfcBuildingStorey(gid("storey"), None, "Storey", None, None, storey_pl, None, None, "ELEMENT", 0.0)
f.createIfcRelAggregates(gid("agg project"), None, None, None, project, [site])
f.createIfcRelAggregates(gid("agg site"), None, None, None, site, [storey])
elements = []
left_out = {}


def shape(items, kind="SweptSolid"):
    rep = f.createIfcShapeRepresentation(body, "Body", kind, items)
    return f.createIfcProductDefinitionShape(None, None, [rep])


def case(name, items, cls="IfcBuildingElementProxy", kind="SweptSolid", openings=()):
    """An element `name` 5 m further along y than the last, its body `items`, voided by
    `openings` (each a product definition shape or None)."""
    pl = f.createIfcLocalPlacement(storey_pl, ax(0.0, 5.0 * len(elements), 0.0))
    e = f.create_entity(cls, GlobalId=gid(name), Name=name, ObjectPlacement=pl, Representation=shape(items, kind))
    for k, o in enumerate(openings):
        op_pl = f.createIfcLocalPlacement(pl, ax())
        op = f.createIfcOpeningElement(gid(f"{name} opening {k}"), None, f"{name} opening {k}", None, None, op_pl, o, None, "OPENING")
        f.createIfcRelVoidsElement(gid(f"{name} voids {k}"), None, None, None, e, op)
    elements.append(e)
    return e


def box(x, y, z, dx, dy, dz):
    """An extruded rectangle from (x, y, z) spanning (dx, dy, dz); dz = 0 cannot be made."""
    prof = f.createIfcRectangleProfileDef("AREA", None, f.createIfcAxis2Placement2D(pt(x + dx / 2, y + dy / 2), None), dx, dy)
    return f.createIfcExtrudedAreaSolid(prof, ax(0.0, 0.0, z), d(0, 0, 1), dz)


def wall():
    return box(0, 0, 0, 4, 0.2, 3)


# --- A star in one stroke.
n = 1001
star = [pt(math.cos(2 * math.pi * (2 * i % n) / n), math.sin(2 * math.pi * (2 * i % n) / n)) for i in range(n)]
star_profile = f.createIfcArbitraryClosedProfileDef("AREA", None, f.createIfcPolyline(star + [star[0]]))
case("star_1001", [f.createIfcExtrudedAreaSolid(star_profile, ax(), d(0, 0, 1), 1.0)])

# --- Walls whose openings cannot be made.
flat_opening = box(1, -0.5, 0, 1, 1.2, 0.0)
w = case("opening_depth_zero", [wall()], "IfcWall", openings=[shape([flat_opening])])
left_out["opening_depth_zero"] = [w.HasOpenings[0].RelatedOpeningElement.id()]
w = case("opening_without_body", [wall()], "IfcWall", openings=[None])
left_out["opening_without_body"] = [w.HasOpenings[0].RelatedOpeningElement.id()]
line = f.createIfcPolyline([pt(0, 0), pt(1, 0), pt(2, 0), pt(0, 0)])
no_area = f.createIfcExtrudedAreaSolid(f.createIfcArbitraryClosedProfileDef("AREA", None, line), ax(), d(0, 0, 1), 2.0)
w = case("opening_without_area", [wall()], "IfcWall", openings=[shape([no_area])])
left_out["opening_without_area"] = [w.HasOpenings[0].RelatedOpeningElement.id()]
w = case("good_and_bad_openings", [wall()], "IfcWall",
         openings=[shape([box(1, -0.5, 0, 1, 1.2, 2)]), shape([box(2.5, -0.5, 0, 1, 1.2, 0.0)])])
left_out["good_and_bad_openings"] = [w.HasOpenings[1].RelatedOpeningElement.id()]

# --- Boolean results whose second operand cannot be made.
for op in ["DIFFERENCE", "UNION", "INTERSECTION"]:
    bad = box(1, -0.5, 0, 1, 1.2, 0.0)
    case(f"boolean_{op.lower()}_bad_operand", [f.createIfcBooleanResult(op, wall(), bad)])
    left_out[f"boolean_{op.lower()}_bad_operand"] = [bad.id()]
no_normal = f.createIfcHalfSpaceSolid(f.createIfcPlane(f.createIfcAxis2Placement3D(pt(0, 0, 2), d(0, 0, 0), None)), False)
case("clipping_bad_plane", [f.createIfcBooleanClippingResult("DIFFERENCE", wall(), no_normal)])
left_out["clipping_bad_plane"] = [no_normal.id()]

# --- Boolean results whose first operand cannot be made (Depth 0) or holds no solid: left
# out, the operands after it in IfcOpenShell's list take its place.
bad = box(1, -0.5, 0, 1, 1.2, 0.0)
case("first_operand_bad", [f.createIfcBooleanResult("DIFFERENCE", bad, box(0, 0, 0, 2, 1, 1))])
left_out["first_operand_bad"] = [bad.id()]
bad = box(1, -0.5, 0, 1, 1.2, 0.0)
inner = f.createIfcBooleanResult("DIFFERENCE", bad, box(0, 0, 0, 2, 1, 1))
case("first_operand_bad_nested", [f.createIfcBooleanResult("DIFFERENCE", inner, box(1, 0, 0, 2, 1, 1))])
left_out["first_operand_bad_nested"] = [bad.id()]
bad = box(1, -0.5, 0, 1, 1.2, 0.0)
inner = f.createIfcBooleanResult("UNION", bad, box(0, 0, 0, 2, 1, 1))
case("first_operand_bad_union_cut", [f.createIfcBooleanResult("DIFFERENCE", inner, box(0, 0, 0.5, 5, 1, 1))])
left_out["first_operand_bad_union_cut"] = [bad.id()]
bad = box(1, -0.5, 0, 1, 1.2, 0.0)
inner = f.createIfcBooleanResult("DIFFERENCE", bad, box(0, 0, 0, 2, 1, 1))
above = f.createIfcHalfSpaceSolid(f.createIfcPlane(ax(0.0, 0.0, 0.5)), False)
case("first_operand_bad_clipped", [f.createIfcBooleanClippingResult("DIFFERENCE", inner, above)])
left_out["first_operand_bad_clipped"] = [bad.id()]
point = pt(0, 0, 0)
case("first_operand_point", [f.createIfcBooleanResult("DIFFERENCE", point, box(0, 0, 0, 2, 1, 1))])
left_out["first_operand_point"] = [point.id()]

# --- A face of 401 points drawn as a star in one stroke ({401/2}), alone in a surface model:
# IfcOpenShell fills it (nearly the unit disc).
n = 401
star_face = [pt(math.cos(2 * math.pi * (2 * i % n) / n), math.sin(2 * math.pi * (2 * i % n) / n), 0.0) for i in range(n)]
loop = f.createIfcPolyLoop(star_face)
face = f.createIfcFace([f.createIfcFaceOuterBound(loop, True)])
case("star_face_401", [f.createIfcShellBasedSurfaceModel([f.createIfcOpenShell([face])])], kind="SurfaceModel")

# --- A face of a surface model bounded by an IfcEdgeLoop: two IfcEdgeCurves, each half of
# one IfcCircle of radius 1 (as IfcOpenShell's test/input/faces.ifc writes a disc).
circle = f.createIfcCircle(ax(), 1.0)
east, west = f.createIfcVertexPoint(pt(1, 0, 0)), f.createIfcVertexPoint(pt(-1, 0, 0))
halves = [f.createIfcEdgeCurve(east, west, circle, True), f.createIfcEdgeCurve(west, east, circle, True)]
edge_loop = f.createIfcEdgeLoop([f.createIfcOrientedEdge(None, None, h, True) for h in halves])
disc = f.createIfcFace([f.createIfcFaceOuterBound(edge_loop, True)])
case("edge_loop_disc_face", [f.createIfcFaceBasedSurfaceModel([f.createIfcConnectedFaceSet([disc])])], kind="SurfaceModel")

# --- A face with two outer bounds (invalid, as IfcOpenShell's test/input/faces.ifc writes
# one): two 0.3 x 0.8 m rectangles side by side, the second bound reversed; IfcOpenShell
# meshes both (it gives no shape when one of them has a hole).
def square_loop(x0, y0, x1, y1):
    return f.createIfcPolyLoop([pt(x0, y0, 0.0), pt(x1, y0, 0.0), pt(x1, y1, 0.0), pt(x0, y1, 0.0)])


two_outer = f.createIfcFace([
    f.createIfcFaceOuterBound(square_loop(-0.4, -0.4, -0.1, 0.4), True),
    f.createIfcFaceOuterBound(square_loop(0.1, -0.4, 0.4, 0.4), False),
])
case("two_outer_bounds_face", [f.createIfcFaceBasedSurfaceModel([f.createIfcConnectedFaceSet([two_outer])])], kind="SurfaceModel")

# --- Mirrored profiles.
ell = f.createIfcArbitraryClosedProfileDef(
    "AREA", None, f.createIfcPolyline([pt(0, 0), pt(2, 0), pt(2, 1), pt(1, 1), pt(1, 3), pt(0, 3), pt(0, 0)])
)
case("mirrored_profile", [f.createIfcExtrudedAreaSolid(f.createIfcMirroredProfileDef("AREA", None, ell, None, None), ax(), d(0, 0, 1), 1.0)])
mirror = f.createIfcCartesianTransformationOperator2D(d(-1, 0), d(0, 1), pt(0, 0), 1.0)
derived = f.createIfcDerivedProfileDef("AREA", None, ell, mirror, None)
case("derived_mirror_profile", [f.createIfcExtrudedAreaSolid(derived, ax(), d(0, 0, 1), 1.0)])

# --- A curve bounded plane with a hole, tilted 30 degrees about x.
c, s = math.cos(math.radians(30)), math.sin(math.radians(30))
plane = f.createIfcPlane(ax(1.0, 0.0, 0.5, axis=(0, -s, c), ref=(1, 0, 0)))
outer = f.createIfcPolyline([pt(0, 0), pt(3, 0), pt(3, 2), pt(0, 2), pt(0, 0)])
hole = f.createIfcPolyline([pt(1, 0.5), pt(1, 1), pt(2, 1), pt(2, 0.5), pt(1, 0.5)])
case("curve_bounded_plane", [f.createIfcCurveBoundedPlane(plane, outer, [hole])], kind="Surface")

f.createIfcRelContainedInSpatialStructure(gid("contained"), None, None, None, elements, storey)
f.write(sys.argv[1])

settings = ifcopenshell.geom.settings()
settings.set("use-world-coords", True)
out = {}
for e in elements:
    try:
        geometry = ifcopenshell.geom.create_shape(settings, e).geometry
    except Exception as ex:  # noqa: BLE001 - reported, the test decides
        out[e.Name] = {"error": str(ex).split(", representation")[0]}
        continue
    v = np.array(geometry.verts, dtype=float).reshape(-1, 3)
    tri = v[np.array(geometry.faces, dtype=int).reshape(-1, 3)]
    cross = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
    out[e.Name] = {
        "min": v.min(axis=0).tolist(),
        "max": v.max(axis=0).tolist(),
        "volume": float(np.einsum("ij,ij->i", tri[:, 0], np.cross(tri[:, 1], tri[:, 2])).sum() / 6.0),
        "area": float(np.linalg.norm(cross, axis=1).sum() / 2.0),
    }
    if e.Name in left_out:
        out[e.Name]["left_out"] = left_out[e.Name]
json.dump(out, sys.stdout, indent=1, sort_keys=True)
