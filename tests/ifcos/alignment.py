"""IFC4X3 alignments from IfcOpenShell, for checking poinav-geom's linear placements and
sectioned solids against.

Usage: .venv/bin/python tests/ifcos/alignment.py RAILWAY.ifc OUT.ifc

1. Authors OUT.ifc with ifcopenshell.api.alignment: a horizontal layout of line, clothoid,
   circular arc, clothoid, line; a vertical layout of constant gradient, parabolic arc,
   circular arc, constant gradient; proxies placed along the gradient curve by IfcLinearPlacement at several
   distances and offsets (each a 2 x 1 x 0.5 m box off its origin, so orientation shows), and
   one IfcSectionedSolidHorizontal over the clothoid and arc; open surfaces (courses named
   `surface ...`): IfcSectionedSurface of IFC4X3 IfcOpenCrossProfileDef sections (widths along
   the slopes from an offset point, and horizontal widths) and of IfcArbitraryOpenProfileDef
   sections, and an open cross profile extruded; sectioned solids along two
   IfcOffsetCurveByDistances of the gradient curve (courses named `offset course ...`,
   constant and growing offsets), and a sectioned solid along a plain 3D IfcPolyline 0.2 m
   below the origin, level and then rising (`course on a 3D polyline`). The first four proxies are in railway part
   West, the other three in East, the courses in none (no storey, no building).
2. Meshes them, and a fixed sample of RAILWAY.ifc (IfcOpenShell needs about 1.6 s per track
   element there, so the whole file is out of reach): track elements spread over the track,
   two courses (sectioned solids) and a rail.

Prints one JSON object: {"authored": {GlobalId: shape}, "railway": {"#id": shape}} where a
shape is {class, name, matrix (4 x 4 row-major placement, m), min, max (world bounding box, m),
area (of the triangles, m2)}.
IfcOpenShell's own log output (it prints to stdout) is kept off the JSON.
"""

import json
import math
import os
import sys

import ifcopenshell
import ifcopenshell.api.aggregate
import ifcopenshell.api.alignment
import ifcopenshell.api.context
import ifcopenshell.api.geometry
import ifcopenshell.api.root
import ifcopenshell.api.spatial
import ifcopenshell.api.unit
import ifcopenshell.geom
import numpy as np

PLACED = [  # distance along, lateral, vertical, longitudinal offsets
    (20.0, 0.0, 0.0, 0.0),
    (130.0, 1.5, 0.2, 0.0),
    (200.0, -2.0, 0.0, 0.5),
    (290.0, 0.0, 1.0, 0.0),
    (350.0, 3.0, -0.5, 0.0),
    (420.0, -1.0, 0.0, -0.3),
    (500.0, 0.0, 0.0, 0.0),
]


def start_of(end):
    return (float(end[0][3]), float(end[1][3])), math.atan2(end[1][0], end[0][0])


def author(path):
    f = ifcopenshell.file(schema="IFC4X3_ADD2")
    project = ifcopenshell.api.root.create_entity(f, ifc_class="IfcProject", name="Alignment test")
    ifcopenshell.api.unit.assign_unit(
        f,
        units=[
            ifcopenshell.api.unit.add_si_unit(f, unit_type="LENGTHUNIT"),
            ifcopenshell.api.unit.add_si_unit(f, unit_type="PLANEANGLEUNIT"),
        ],
    )
    model = ifcopenshell.api.context.add_context(f, context_type="Model")
    body = ifcopenshell.api.context.add_context(
        f, context_type="Model", context_identifier="Body", target_view="MODEL_VIEW", parent=model
    )
    alignment = ifcopenshell.api.alignment.create(f, "A1", include_vertical=True)
    horizontal = ifcopenshell.api.alignment.get_horizontal_layout(alignment)
    vertical = ifcopenshell.api.alignment.get_vertical_layout(alignment)
    point, direction = (1000.0, 2000.0), 0.3
    for kind, r0, r1, length in [
        ("LINE", 0.0, 0.0, 100.0),
        ("CLOTHOID", 0.0, 300.0, 80.0),
        ("CIRCULARARC", 300.0, 300.0, 150.0),
        ("CLOTHOID", 300.0, 0.0, 80.0),
        ("LINE", 0.0, 0.0, 100.0),
    ]:
        seg = f.createIfcAlignmentHorizontalSegment(
            StartPoint=f.createIfcCartesianPoint(point),
            StartDirection=direction,
            StartRadiusOfCurvature=r0,
            EndRadiusOfCurvature=r1,
            SegmentLength=length,
            PredefinedType=kind,
        )
        point, direction = start_of(ifcopenshell.api.alignment.create_layout_segment(f, horizontal, seg))
    height = 50.0
    for kind, start, length, g0, g1 in [
        ("CONSTANTGRADIENT", 0.0, 150.0, 0.02, 0.02),
        ("PARABOLICARC", 150.0, 200.0, 0.02, -0.01),
        ("CIRCULARARC", 350.0, 100.0, -0.01, 0.015),
        ("CONSTANTGRADIENT", 450.0, 60.0, 0.015, 0.015),
    ]:
        seg = f.createIfcAlignmentVerticalSegment(
            StartDistAlong=start,
            HorizontalLength=length,
            StartHeight=height,
            StartGradient=g0,
            EndGradient=g1,
            PredefinedType=kind,
        )
        ifcopenshell.api.alignment.create_layout_segment(f, vertical, seg)
        height += length * (g0 + g1) / 2.0
    curve = ifcopenshell.api.alignment.get_curve(alignment)
    assert curve.is_a("IfcGradientCurve"), curve

    def linear(d, lateral, vertical_offset, longitudinal):
        return f.createIfcAxis2PlacementLinear(
            Location=f.createIfcPointByDistanceExpression(
                DistanceAlong=f.createIfcLengthMeasure(d),
                OffsetLateral=lateral or None,
                OffsetVertical=vertical_offset or None,
                OffsetLongitudinal=longitudinal or None,
                BasisCurve=curve,
            )
        )

    box = f.createIfcExtrudedAreaSolid(
        SweptArea=f.createIfcRectangleProfileDef(ProfileType="AREA", XDim=2.0, YDim=1.0),
        Position=f.createIfcAxis2Placement3D(Location=f.createIfcCartesianPoint((1.5, 0.5, 0.0))),
        ExtrudedDirection=f.createIfcDirection((0.0, 0.0, 1.0)),
        Depth=0.5,
    )
    shape = f.createIfcProductDefinitionShape(
        Representations=[f.createIfcShapeRepresentation(body, "Body", "SweptSolid", [box])]
    )
    site = ifcopenshell.api.root.create_entity(f, ifc_class="IfcSite", name="Site")
    railway = ifcopenshell.api.root.create_entity(f, ifc_class="IfcRailway", name="Line")
    parts = [ifcopenshell.api.root.create_entity(f, ifc_class="IfcRailwayPart", name=n) for n in ("West", "East")]
    ifcopenshell.api.aggregate.assign_object(f, products=[site], relating_object=project)
    ifcopenshell.api.aggregate.assign_object(f, products=[railway], relating_object=site)
    ifcopenshell.api.aggregate.assign_object(f, products=parts, relating_object=railway)
    for i, (d, lat, ver, lon) in enumerate(PLACED):
        p = ifcopenshell.api.root.create_entity(f, ifc_class="IfcBuildingElementProxy", name=f"at {d}")
        p.ObjectPlacement = f.createIfcLinearPlacement(RelativePlacement=linear(d, lat, ver, lon))
        p.Representation = shape
        ifcopenshell.api.spatial.assign_container(f, products=[p], relating_structure=parts[i // 4])
    profile = f.createIfcArbitraryClosedProfileDef(
        ProfileType="AREA",
        OuterCurve=f.createIfcPolyline(
            [f.createIfcCartesianPoint(c) for c in [(-3.0, -1.0), (3.0, -1.0), (2.0, 0.0), (-1.0, 0.5), (-3.0, -1.0)]]
        ),
    )
    solid = f.createIfcSectionedSolidHorizontal(
        Directrix=curve,
        CrossSections=[profile, profile],
        CrossSectionPositions=[linear(110.0, 0.5, 0.3, 0.0), linear(320.0, -0.5, 0.0, 0.0)],
    )
    course = ifcopenshell.api.root.create_entity(f, ifc_class="IfcCourse", name="embankment")
    course.ObjectPlacement = f.createIfcLocalPlacement(
        RelativePlacement=f.createIfcAxis2Placement3D(Location=f.createIfcCartesianPoint((0.0, 0.0, 0.0)))
    )
    course.Representation = f.createIfcProductDefinitionShape(
        Representations=[f.createIfcShapeRepresentation(body, "Body", "AdvancedSweptSolid", [solid])]
    )
    cross = f.createIfcOpenCrossProfileDef(
        ProfileType="CURVE",
        HorizontalWidths=False,
        Widths=[2.0, 3.0, 1.5],
        Slopes=[-0.3, 0.0, 0.5],
        OffsetPoint=f.createIfcCartesianPoint((-3.0, 0.2)),
    )
    level = f.createIfcOpenCrossProfileDef(
        ProfileType="CURVE", HorizontalWidths=True, Widths=[2.0, 3.0, 1.5], Slopes=[-0.3, 0.0, 0.5]
    )
    ditch = f.createIfcArbitraryOpenProfileDef(
        ProfileType="CURVE",
        Curve=f.createIfcPolyline(
            [f.createIfcCartesianPoint(c) for c in [(-4.0, 0.5), (-2.0, 0.0), (2.0, 0.0), (4.0, 0.5)]]
        ),
    )
    surfaces = {
        "surface cross slopes": f.createIfcSectionedSurface(
            Directrix=curve,
            CrossSections=[cross, cross],
            CrossSectionPositions=[linear(60.0, 0.5, 0.3, 0.0), linear(260.0, -0.5, 0.0, 0.0)],
        ),
        "surface cross horizontal": f.createIfcSectionedSurface(
            Directrix=curve, CrossSections=[level, level], CrossSectionPositions=[linear(60.0, 0, 0, 0), linear(260.0, 0, 0, 0)]
        ),
        "surface open profile": f.createIfcSectionedSurface(
            Directrix=curve, CrossSections=[ditch, ditch], CrossSectionPositions=[linear(300.0, 0, 0, 0), linear(480.0, 0, 0, 0)]
        ),
        "surface cross extruded": f.createIfcExtrudedAreaSolid(
            SweptArea=cross,
            Position=f.createIfcAxis2Placement3D(Location=f.createIfcCartesianPoint((0.0, 0.0, 0.0))),
            ExtrudedDirection=f.createIfcDirection((0.0, 0.0, 1.0)),
            Depth=2.0,
        ),
    }
    # Courses along offset curves (IfcOffsetCurveByDistances of the gradient curve): offsets
    # 3 m left and 0.5 m up throughout, and offsets growing from 2 m to 6 m left.
    def by_distance(d, lateral, vertical_offset):
        return f.createIfcPointByDistanceExpression(
            DistanceAlong=f.createIfcLengthMeasure(d),
            OffsetLateral=lateral or None,
            OffsetVertical=vertical_offset or None,
            BasisCurve=curve,
        )

    beam = f.createIfcRectangleProfileDef(ProfileType="AREA", XDim=1.0, YDim=0.5)
    for name, values in [
        ("offset course", [(0.0, 3.0, 0.5), (500.0, 3.0, 0.5)]),
        ("offset course widening", [(0.0, 2.0, 0.0), (500.0, 6.0, 0.0)]),
    ]:
        offset = f.createIfcOffsetCurveByDistances(
            BasisCurve=curve, OffsetValues=[by_distance(*v) for v in values]
        )
        positions = [
            f.createIfcAxis2PlacementLinear(
                Location=f.createIfcPointByDistanceExpression(
                    DistanceAlong=f.createIfcLengthMeasure(d), BasisCurve=offset
                )
            )
            for d in (100.0, 300.0)
        ]
        surfaces[name] = f.createIfcSectionedSolidHorizontal(
            Directrix=offset, CrossSections=[beam, beam], CrossSectionPositions=positions
        )
    # A course along a plain 3D polyline 0.2 m below the origin (as Allplan writes a girder's
    # directrix), level for 20 m, then rising 1.25 m over 25 m: IfcOpenShell keeps the
    # polyline's heights and measures distance along it in space.
    line3d = f.createIfcPolyline(
        [f.createIfcCartesianPoint(c) for c in [(0.0, -5.0, -0.2), (20.0, -5.0, -0.2), (45.0, -5.0, 1.05)]]
    )
    surfaces["course on a 3D polyline"] = f.createIfcSectionedSolidHorizontal(
        Directrix=line3d,
        CrossSections=[beam, beam],
        CrossSectionPositions=[
            f.createIfcAxis2PlacementLinear(
                Location=f.createIfcPointByDistanceExpression(DistanceAlong=f.createIfcLengthMeasure(d), BasisCurve=line3d)
            )
            for d in (5.0, 40.0)
        ],
    )
    for name, item in surfaces.items():
        c = ifcopenshell.api.root.create_entity(f, ifc_class="IfcCourse", name=name)
        c.ObjectPlacement = f.createIfcLocalPlacement(
            RelativePlacement=f.createIfcAxis2Placement3D(Location=f.createIfcCartesianPoint((0.0, 0.0, 0.0)))
        )
        c.Representation = f.createIfcProductDefinitionShape(
            Representations=[f.createIfcShapeRepresentation(body, "Body", "AdvancedSurface", [item])]
        )
    f.write(path)
    return f


def shapes(f, products, key):
    settings = ifcopenshell.geom.settings()
    out = {}
    null = os.open(os.devnull, os.O_WRONLY)
    saved = os.dup(1)
    os.dup2(null, 1)
    try:
        it = ifcopenshell.geom.iterator(settings, f, 1, include=products)
        if it.initialize():
            while True:
                s = it.get()
                m = np.array(s.transformation.matrix, dtype=float).reshape((4, 4), order="F")
                v = np.array(s.geometry.verts, dtype=float).reshape(-1, 3)
                w = v @ m[:3, :3].T + m[:3, 3]
                t = w[np.array(s.geometry.faces, dtype=int).reshape(-1, 3)]
                e = f.by_id(s.id)
                out[key(e)] = {
                    "class": e.is_a(),
                    "name": e.Name,
                    "area": float(np.linalg.norm(np.cross(t[:, 1] - t[:, 0], t[:, 2] - t[:, 0]), axis=1).sum() / 2.0),
                    "matrix": m.tolist(),
                    "min": w.min(axis=0).tolist(),
                    "max": w.max(axis=0).tolist(),
                }
                if not it.next():
                    break
    finally:
        sys.stdout.flush()
        os.dup2(saved, 1)
    return out


def main():
    railway_path, out_path = sys.argv[1], sys.argv[2]
    authored = author(out_path)
    result = {
        "authored": shapes(
            authored,
            authored.by_type("IfcBuildingElementProxy") + authored.by_type("IfcCourse"),
            lambda e: e.GlobalId,
        )
    }
    railway = ifcopenshell.open(railway_path)
    track = sorted(railway.by_type("IfcTrackElement"), key=lambda e: e.id())
    courses = sorted(railway.by_type("IfcCourse"), key=lambda e: e.id())
    rails = sorted(railway.by_type("IfcRail"), key=lambda e: e.id())
    sample = track[::1895] + [track[-1], courses[0], courses[229], rails[115]]
    result["railway"] = shapes(railway, sample, lambda e: f"#{e.id()}")
    result["railway_sample"] = [f"#{e.id()}" for e in sample]
    json.dump(result, sys.stdout)


if __name__ == "__main__":
    main()
