"""Swept solids and open profiles written and meshed with IfcOpenShell, for poinav-geom's
swept_vs_ifcopenshell test.

Usage: .venv/bin/python tests/ifcos/author_swept.py OUTDIR

Writes OUTDIR/swept-ifc4.ifc and OUTDIR/swept-ifc4x3.ifc (metres, radians) and
OUTDIR/swept-ifc2x3.ifc (millimetres, degrees), one storey each, one element per case, named
after its case; meshes every element with ifcopenshell.geom (world coordinates, default
settings) and prints one JSON object mapping each case name to

  file           the file name the element is in
  class          its IFC class
  min, max       the bounding box of IfcOpenShell's mesh, [x, y, z] in m (absent when
                 IfcOpenShell gives no shape)
  volume         the mesh's signed volume (divergence theorem), m3
  reference      for cases IfcOpenShell 0.9 does not mesh as the schema says (it ignores
                 StartParam/EndParam and the Thickness of centre line profiles, fails on
                 FilletRadius, takes the parameters of a trimmed polyline as lengths
                 instead of segment index plus fraction, and draws a Bezier curve as its
                 chord), the case whose element has the
                 geometry the schema defines, written out explicitly

The cases: swept disks along a 3D polyline with posts (a railing; again along an
IfcSurfaceCurve whose Curve3D is that polyline), a tube (InnerRadius) along
a non-planar polyline, a composite curve of a line, a trimmed circle arc and a reversed
(SameSense .F.) polyline, an indexed poly curve with an arc, a whole circle (a ring), a circle
trimmed by points; IfcSweptDiskSolidPolygonal with FilletRadius; StartParam/EndParam trims;
IfcSurfaceCurveSweptAreaSolid (on a plane, a cylinder and a surface of linear extrusion),
IfcFixedReferenceSweptAreaSolid (with a Position) and the
IFC4X3 IfcDirectrixDerivedReferenceSweptAreaSolid; an IfcArbitraryOpenProfileDef on a
trimmed polyline and an IfcCenterLineProfileDef, both extruded; rolled I, L and U profiles
with root fillets and edge radii and a cold-formed C with rounded bends, extruded; trapezia
whose top line reaches past the bottom one (their bounding box is centred); in IFC2X3, a bent bar as
Revit writes reinforcement, a crane rail (IfcCraneRailAShapeProfileDef) extruded and a
profile bounded by an IfcBezierCurve (IfcOpenShell 0.9 draws its chord: compared with a
reference).
"""

import json
import math
import os
import sys

import ifcopenshell
import ifcopenshell.geom
import ifcopenshell.guid
import numpy as np


class Writer:
    def __init__(self, schema, mm_degrees=False):
        self.f = f = ifcopenshell.file(schema=schema)
        self.n = 0
        self.origin = self.axis(0, 0, 0)
        self.ctx = f.createIfcGeometricRepresentationContext(None, "Model", 3, 1.0e-5, self.origin, None)
        self.body = f.createIfcGeometricRepresentationSubContext(
            "Body", "Model", None, None, None, None, self.ctx, None, "MODEL_VIEW", None
        )
        length = f.createIfcSIUnit(None, "LENGTHUNIT", "MILLI" if mm_degrees else None, "METRE")
        radian = f.createIfcSIUnit(None, "PLANEANGLEUNIT", None, "RADIAN")
        if mm_degrees:
            exponents = f.createIfcDimensionalExponents(0, 0, 0, 0, 0, 0, 0)
            per_degree = f.createIfcMeasureWithUnit(f.createIfcPlaneAngleMeasure(math.pi / 180), radian)
            angle = f.createIfcConversionBasedUnit(exponents, "PLANEANGLEUNIT", "DEGREE", per_degree)
        else:
            angle = radian
        units = f.createIfcUnitAssignment([length, angle])
        project = f.createIfcProject(self.gid(), None, "Swept solids", None, None, None, None, [self.ctx], units)
        site = f.createIfcSite(self.gid(), None, "Site", None, None, self.place(), None, None, "ELEMENT",
                               None, None, None, None, None)
        building = f.createIfcBuilding(self.gid(), None, "Building", None, None, self.place(), None, None,
                                       "ELEMENT", None, None, None)
        self.storey = f.createIfcBuildingStorey(self.gid(), None, "Ground floor", None, None, self.place(), None,
                                                None, "ELEMENT", 0.0)
        f.createIfcRelAggregates(self.gid(), None, None, None, project, [site])
        f.createIfcRelAggregates(self.gid(), None, None, None, site, [building])
        f.createIfcRelAggregates(self.gid(), None, None, None, building, [self.storey])
        self.elements = []

    def gid(self):
        self.n += 1
        return ifcopenshell.guid.compress("%032x" % (0x5EE7 * 2**100 + self.n))

    def pt(self, *c):
        return self.f.createIfcCartesianPoint([float(x) for x in c])

    def d(self, *c):
        return self.f.createIfcDirection([float(x) for x in c])

    def axis(self, x, y, z):
        return self.f.createIfcAxis2Placement3D(self.pt(x, y, z), None, None)

    def place(self):
        return self.f.createIfcLocalPlacement(None, self.axis(0, 0, 0))

    def polyline(self, *pts):
        return self.f.createIfcPolyline([self.pt(*p) for p in pts])

    def element(self, cls, name, item, rep_type="AdvancedSweptSolid"):
        f = self.f
        rep = f.createIfcShapeRepresentation(self.body, "Body", rep_type, [item])
        shape = f.createIfcProductDefinitionShape(None, None, [rep])
        e = f.create_entity(cls, GlobalId=self.gid(), Name=name, ObjectPlacement=self.place(), Representation=shape)
        self.elements.append(e)
        return e

    def save(self, path):
        self.f.createIfcRelContainedInSpatialStructure(self.gid(), None, None, None, self.elements, self.storey)
        self.f.write(path)


def author_ifc4(w):
    f = w.f
    disk = f.createIfcSweptDiskSolid
    # A railing: posts up from the floor and a handrail 1 m up, 3 m long.
    w.element("IfcRailing", "disk_polyline",
              disk(w.polyline((0, 0, 0), (0, 0, 1), (3, 0, 1), (3, 0, 0)), 0.025, None, None, None))
    # A tube along a non-planar polyline.
    w.element("IfcPipeSegment", "disk_tube",
              disk(w.polyline((5, 0, 0.5), (8, 0, 0.5), (8, 3, 2)), 0.05, 0.04, None, None))
    # Composite: a line up to (10, 0), a quarter circle about (9, 0) to (9, 1), then a polyline
    # written from (7, 1) to (9, 1) and used against its sense. Tangent-continuous joints.
    circle = f.createIfcCircle(w.axis(9, 0, 0.5), 1.0)
    arc = f.createIfcTrimmedCurve(circle, [f.createIfcParameterValue(0.0)],
                                  [f.createIfcParameterValue(math.pi / 2)], True, "PARAMETER")
    segs = [
        f.createIfcCompositeCurveSegment("CONTINUOUS", True, w.polyline((10, -2, 0.5), (10, 0, 0.5))),
        f.createIfcCompositeCurveSegment("CONTINUOUS", True, arc),
        f.createIfcCompositeCurveSegment("CONTINUOUS", False, w.polyline((7, 1, 0.5), (9, 1, 0.5))),
    ]
    w.element("IfcPipeSegment", "disk_composite", disk(f.createIfcCompositeCurve(segs, False), 0.05, None, None, None))
    # The same railing's handrail along an IfcSurfaceCurve (its Curve3D a polyline, on the
    # plane y = 20): the curve in space is swept.
    wall_plane = f.createIfcPlane(f.createIfcAxis2Placement3D(w.pt(0, 20, 0), f.createIfcDirection((0., 1., 0.)), None))
    on_plane = f.createIfcSurfaceCurve(w.polyline((0, 20, 0), (0, 20, 1), (3, 20, 1), (3, 20, 0)), [wall_plane], "CURVE3D")
    w.element("IfcRailing", "disk_surface_curve", disk(on_plane, 0.025, None, None, None))
    # Indexed poly curve: a line, a tangent quarter arc about (2, 6), a line.
    h = math.sqrt(0.5)
    pts = f.createIfcCartesianPointList3D(
        [[0., 5., .2], [2., 5., .2], [2. + h, 6. - h, .2], [3., 6., .2], [3., 8., .2]])
    ipc = f.createIfcIndexedPolyCurve(pts, [f.createIfcLineIndex([1, 2]), f.createIfcArcIndex([2, 3, 4]),
                                            f.createIfcLineIndex([4, 5])], False)
    w.element("IfcReinforcingBar", "disk_indexed", disk(ipc, 0.02, None, None, None))
    # Polygonal with fillet 0.3 at the corner of an L; its reference is the same bar written
    # as lines and the tangent arc about (2.7, 10.3).
    poly = w.polyline((0, 10, 0.2), (3, 10, 0.2), (3, 13, 0.2))
    w.element("IfcReinforcingBar", "disk_polygonal",
              f.createIfcSweptDiskSolidPolygonal(poly, 0.02, None, None, None, 0.3))
    c = (2.7 + 0.3 * h, 10.3 - 0.3 * h)
    pts = f.createIfcCartesianPointList3D(
        [[0., 10., .2], [2.7, 10., .2], [c[0], c[1], .2], [3., 10.3, .2], [3., 13., .2]])
    ipc = f.createIfcIndexedPolyCurve(pts, [f.createIfcLineIndex([1, 2]), f.createIfcArcIndex([2, 3, 4]),
                                            f.createIfcLineIndex([4, 5])], False)
    w.element("IfcReinforcingBar", "disk_polygonal_reference", disk(ipc, 0.02, None, None, None))
    # StartParam 0.5 / EndParam 1.5 on an L polyline: from the middle of the first leg to the
    # middle of the second; its reference is that path written out.
    w.element("IfcPipeSegment", "disk_trimmed",
              disk(w.polyline((0, 15, 0.5), (4, 15, 0.5), (4, 19, 0.5)), 0.05, None, 0.5, 1.5))
    w.element("IfcPipeSegment", "disk_trimmed_reference",
              disk(w.polyline((2, 15, 0.5), (4, 15, 0.5), (4, 17, 0.5)), 0.05, None, None, None))
    # A ring: a whole circle of radius 1 at 1 m.
    w.element("IfcRailing", "disk_circle", disk(f.createIfcCircle(w.axis(10, 10, 1), 1.0), 0.03, None, None, None))
    # A circle trimmed by points (three quarters, clockwise from (17, 0) to (15, 2)).
    circle = f.createIfcCircle(w.axis(15, 0, 0.3), 2.0)
    arc = f.createIfcTrimmedCurve(circle, [w.pt(17, 0, 0.3)], [w.pt(15, 2, 0.3)], False, "CARTESIAN")
    w.element("IfcPipeSegment", "disk_trimmed_circle", disk(arc, 0.04, 0.03, None, None))
    # Profiles swept along a directrix: a 0.3 x 0.1 rectangle off-centre, an I shape.
    rect = f.createIfcRectangleProfileDef("AREA", None, f.createIfcAxis2Placement2D(w.pt(0.15, 0.05), None), 0.3, 0.1)
    plane = f.createIfcPlane(w.axis(0, 0, 0))
    arc = f.createIfcTrimmedCurve(f.createIfcCircle(w.axis(20, 2, 0), 2.0), [f.createIfcParameterValue(-math.pi / 2)],
                                  [f.createIfcParameterValue(0.0)], True, "PARAMETER")
    segs = [
        f.createIfcCompositeCurveSegment("CONTINUOUS", True, w.polyline((16, 0, 0), (20, 0, 0))),
        f.createIfcCompositeCurveSegment("CONTINUOUS", True, arc),
    ]
    w.element("IfcMember", "surface_swept",
              f.createIfcSurfaceCurveSweptAreaSolid(rect, None, f.createIfcCompositeCurve(segs, False), None, None,
                                                    plane))
    # The same rectangle on a cylinder (x axis radial, outwards) and on a curved wall: an arc
    # extruded up (x axis the arc's direction cross the extrusion's: outwards here too).
    cylinder = f.createIfcCylindricalSurface(w.axis(25, 0, 0), 2.0)
    arc = f.createIfcTrimmedCurve(f.createIfcCircle(w.axis(25, 0, 0.5), 2.0), [f.createIfcParameterValue(0.0)],
                                  [f.createIfcParameterValue(math.pi / 2)], True, "PARAMETER")
    w.element("IfcMember", "surface_cylinder",
              f.createIfcSurfaceCurveSweptAreaSolid(rect, None, arc, None, None, cylinder))
    base = f.createIfcTrimmedCurve(f.createIfcCircle(f.createIfcAxis2Placement2D(w.pt(27, 5), None), 2.0),
                                   [f.createIfcParameterValue(0.0)], [f.createIfcParameterValue(math.pi / 2)], True,
                                   "PARAMETER")
    wall = f.createIfcArbitraryOpenProfileDef("CURVE", None, base)
    extrusion = f.createIfcSurfaceOfLinearExtrusion(wall, w.axis(0, 0, 0), w.d(0, 0, 1), 3.0)
    arc = f.createIfcTrimmedCurve(f.createIfcCircle(w.axis(27, 5, 1), 2.0), [f.createIfcParameterValue(0.0)],
                                  [f.createIfcParameterValue(math.pi / 2)], True, "PARAMETER")
    w.element("IfcMember", "surface_extrusion",
              f.createIfcSurfaceCurveSweptAreaSolid(rect, None, arc, None, None, extrusion))
    ishape = f.createIfcIShapeProfileDef("AREA", None, None, 0.2, 0.3, 0.01, 0.015, None, None, None)
    pts = f.createIfcCartesianPointList3D([[0., 0., 0.], [3., 0., 0.], [4., 1., 0.], [3., 2., 0.]])
    ipc = f.createIfcIndexedPolyCurve(pts, [f.createIfcLineIndex([1, 2]), f.createIfcArcIndex([2, 3, 4])], False)
    w.element("IfcBeam", "fixed_swept",
              f.createIfcFixedReferenceSweptAreaSolid(ishape, f.createIfcAxis2Placement3D(w.pt(0, 25, 1), None, None),
                                                      ipc, None, None, w.d(0, 0, 1)))
    # Open profile on a trimmed polyline (parameters 0.5 to 2.25: from the middle of the
    # first segment to a quarter into the third), extruded 2 m: a surface.
    basis = w.polyline((0, 30), (2, 30), (2, 32), (4, 32))
    trimmed = f.createIfcTrimmedCurve(basis, [f.createIfcParameterValue(0.5)], [f.createIfcParameterValue(2.25)],
                                      True, "PARAMETER")
    open_profile = f.createIfcArbitraryOpenProfileDef("CURVE", None, trimmed)
    w.element("IfcBuildingElementProxy", "open_profile",
              f.createIfcExtrudedAreaSolid(open_profile, w.axis(0, 0, 0), w.d(0, 0, 1), 2.0), "SweptSolid")
    explicit = f.createIfcArbitraryOpenProfileDef("CURVE", None, w.polyline((1, 30), (2, 30), (2, 32), (2.5, 32)))
    w.element("IfcBuildingElementProxy", "open_profile_reference",
              f.createIfcExtrudedAreaSolid(explicit, w.axis(0, 0, 0), w.d(0, 0, 1), 2.0), "SweptSolid")
    # Centre line profile: an L of centre lines, 0.2 thick, extruded 3 m.
    centre = f.createIfcCenterLineProfileDef("AREA", None, w.polyline((6, 30), (10, 30), (10, 33)), 0.2)
    w.element("IfcWall", "centre_line",
              f.createIfcExtrudedAreaSolid(centre, w.axis(0, 0, 0), w.d(0, 0, 1), 3.0), "SweptSolid")
    outline = w.polyline((6, 29.9), (10.1, 29.9), (10.1, 33), (9.9, 33), (9.9, 30.1), (6, 30.1), (6, 29.9))
    explicit = f.createIfcArbitraryClosedProfileDef("AREA", None, outline)
    w.element("IfcWall", "centre_line_reference",
              f.createIfcExtrudedAreaSolid(explicit, w.axis(0, 0, 0), w.d(0, 0, 1), 3.0), "SweptSolid")
    # Rolled steel profiles with root fillets and edge radii, extruded 2 m: an IPE 200 (its
    # fillets are 4 % of its area), an angle and a channel; and a cold-formed C with rounded
    # bends.
    rolled = [
        ("IfcBeam", "rolled_ipe", f.createIfcIShapeProfileDef("AREA", None, None, 0.1, 0.2, 0.0056, 0.0085, 0.012,
                                                               None, None)),
        ("IfcMember", "rolled_angle", f.createIfcLShapeProfileDef("AREA", None, None, 0.15, 0.1, 0.01, 0.01, 0.005,
                                                                   None)),
        ("IfcMember", "rolled_channel", f.createIfcUShapeProfileDef("AREA", None, None, 0.3, 0.1, 0.01, 0.02, 0.008,
                                                                     0.004, None)),
        ("IfcMember", "cold_formed_c", f.createIfcCShapeProfileDef("AREA", None, None, 0.2, 0.1, 0.005, 0.02, 0.002)),
    ]
    for k, (cls, name, profile) in enumerate(rolled):
        w.element(cls, name, f.createIfcExtrudedAreaSolid(profile, w.axis(2 * k, 40, 0), w.d(0, 0, 1), 2.0),
                  "SweptSolid")
    # Trapezia whose top line reaches past the bottom one, to the left (negative TopXOffset)
    # and to the right: the schema centres the bounding box, not the bottom line, on the
    # position (0.1 m apart here).
    trapezia = [("trapezium_left", 0.5, 0.6, -0.2), ("trapezium_right", 0.4, 0.3, 0.3)]
    for k, (name, bottom, top, offset) in enumerate(trapezia):
        profile = f.createIfcTrapeziumProfileDef("AREA", None, None, bottom, top, 0.25, offset)
        w.element("IfcColumn", name, f.createIfcExtrudedAreaSolid(profile, w.axis(2 * k, 44, 0), w.d(0, 0, 1), 1.0),
                  "SweptSolid")


def author_ifc4x3(w):
    # A level turn, then a rise: corners about axes along or across the fixed reference,
    # where the section's frame is the same on both sides.
    f = w.f
    rect = f.createIfcRectangleProfileDef("AREA", None, f.createIfcAxis2Placement2D(w.pt(0.1, 0.0), None), 0.2, 0.4)
    w.element("IfcMember", "derived_swept",
              f.createIfcDirectrixDerivedReferenceSweptAreaSolid(
                  rect, None, w.polyline((0, 0, 0), (4, 0, 0), (4, 3, 0), (4, 6, 1)), None, None, w.d(0, 0, 1)))


def author_ifc2x3(w):
    # A bent bar as Revit writes reinforcement in IFC2X3 (millimetres, degrees): a composite
    # curve of a polyline, a quarter circle trimmed by parameters in degrees and a polyline,
    # with StartParam 0 and EndParam its length.
    f = w.f
    circle = f.createIfcCircle(w.axis(2000, 40300, 200), 300.0)
    arc = f.createIfcTrimmedCurve(circle, [f.createIfcParameterValue(-90.0)], [f.createIfcParameterValue(0.0)],
                                  True, "PARAMETER")
    segs = [
        f.createIfcCompositeCurveSegment("CONTINUOUS", True, w.polyline((0, 40000, 200), (2000, 40000, 200))),
        f.createIfcCompositeCurveSegment("CONTINUOUS", True, arc),
        f.createIfcCompositeCurveSegment("CONTINUOUS", True, w.polyline((2300, 40300, 200), (2300, 42000, 200))),
    ]
    length = 2000 + 300 * math.pi / 2 + 1700
    w.element("IfcReinforcingBar", "disk_ifc2x3_mm_degrees",
              f.createIfcSweptDiskSolid(f.createIfcCompositeCurve(segs, False), 16.0, None, 0.0, length))
    # A crane rail (IfcCraneRailAShapeProfileDef, 100 mm high, base 150 mm) 6 m long (upright).
    rail = f.createIfcCraneRailAShapeProfileDef(
        "AREA", None, f.createIfcAxis2Placement2D(w.pt(0, 45000), None),
        100.0, 150.0, None, 60.0, 20.0, 30.0, 20.0, 100.0, 15.0, 30.0, 40.0, None)
    # A slab edge drawn with an IfcBezierCurve of two quadratic pieces (IFC2X3 only), closed
    # by a polyline; IfcOpenShell 0.9 draws its chord instead, so the reference is the same
    # curve written out as a polyline of 200 points per piece.
    arc_pts = [(2000, 50000), (2000, 51000), (1500, 51500), (1000, 52000), (0, 52000)]

    def bezier_point(a, b, c, t):
        return tuple((1 - t) ** 2 * a[i] + 2 * t * (1 - t) * b[i] + t * t * c[i] for i in range(2))

    sampled = [bezier_point(*arc_pts[2 * k:2 * k + 3], i / 200) for k in range(2) for i in range(200)]
    for name, arc in [
        ("bezier_profile_ifc2x3",
         f.createIfcBezierCurve(2, [w.pt(*q) for q in arc_pts], "UNSPECIFIED", False, False)),
        ("bezier_profile_ifc2x3_reference", w.polyline(*sampled, arc_pts[-1])),
    ]:
        closing = w.polyline((0, 52000), (0, 50000), (2000, 50000))
        outline = f.createIfcCompositeCurve([f.createIfcCompositeCurveSegment("CONTINUOUS", True, arc),
                                             f.createIfcCompositeCurveSegment("CONTINUOUS", True, closing)], False)
        w.element("IfcSlab", name,
                  f.createIfcExtrudedAreaSolid(f.createIfcArbitraryClosedProfileDef("AREA", None, outline),
                                               w.axis(0, 0, 0), f.createIfcDirection((0., 0., 1.)), 200.0),
                  "SweptSolid")
    w.element("IfcBeam", "crane_rail_ifc2x3",
              f.createIfcExtrudedAreaSolid(rail, w.axis(0, 0, 0), f.createIfcDirection((0., 0., 1.)), 6000.0),
              "SweptSolid")


def summary(shape):
    verts = np.array(shape.geometry.verts, dtype=float).reshape(-1, 3)
    faces = np.array(shape.geometry.faces, dtype=int).reshape(-1, 3)
    tri = verts[faces]
    volume = np.einsum("ij,ij->i", tri[:, 0], np.cross(tri[:, 1], tri[:, 2])).sum() / 6.0
    return {"min": verts.min(axis=0).tolist(), "max": verts.max(axis=0).tolist(), "volume": float(volume)}


def main(out):
    settings = ifcopenshell.geom.settings()
    settings.set("use-world-coords", True)
    result = {}
    files = [
        ("IFC4", "swept-ifc4.ifc", author_ifc4),
        ("IFC4X3_ADD2", "swept-ifc4x3.ifc", author_ifc4x3),
        ("IFC2X3", "swept-ifc2x3.ifc", author_ifc2x3),
    ]
    for schema, name, author in files:
        w = Writer(schema, mm_degrees=schema == "IFC2X3")
        author(w)
        path = os.path.join(out, name)
        w.save(path)
        for e in w.elements:
            r = {"file": name, "class": e.is_a()}
            try:
                r.update(summary(ifcopenshell.geom.create_shape(settings, e)))
            except RuntimeError:
                pass
            if e.Name + "_reference" in [x.Name for x in w.elements]:
                r["reference"] = e.Name + "_reference"
            result[e.Name] = r
    json.dump(result, sys.stdout, indent=1)


if __name__ == "__main__":
    main(sys.argv[1])
