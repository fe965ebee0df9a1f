"""Write a heavy, furnished, multi-storey IFC2X3 building as Revit or ArchiCAD export it.

Usage: .venv/bin/python scripts/make-heavy-model.py OUT.ifc [--small] [--seed N]
                                                     [--storeys N] [--furnished-rooms N]

The corpus has no large furnished model, and those are what real BIM tools write: furniture as
faceted breps of thousands of triangles each, shared through mapped items, walls clipped by
half-spaces, a length unit in feet. This writes one, deterministically (the same arguments give
the same bytes: GlobalIds come from the seed, timestamps are fixed):

- length unit FOOT (IfcConversionBasedUnit, 0.3048 m), also square/cubic foot and degree;
- N occupied storeys (default 4, 12 ft apart) and a "Roof" storey holding only the roof slab;
  each occupied storey has 4 dining rooms (north), 4 lounges (south), a stair room and a
  corridor between them: 10 IfcSpace (aggregated into the storey, extruded bodies), each
  with IfcRelSpaceBoundary to its walls, doors and floor slab;
- 13 walls per storey (IfcWallStandardCase with a material layer set usage, Axis and Body;
  exterior and corridor walls extruded past the slab above and clipped back by an
  IfcHalfSpaceSolid in an IfcBooleanClippingResult, as Revit does);
- floor slabs with a stair-well void (IfcArbitraryProfileDefWithVoids), a roof slab;
- 3.5 ft (42") doors, 3.2 ft (0.975 m) clear between the linings: IfcOpeningElement voiding
  the wall (IfcRelVoidsElement), IfcDoor filling it
  (IfcRelFillsElement) with OverallWidth/OverallHeight, a lining and a leaf as body, and an
  IfcDoorStyle with IfcDoorLiningProperties; one entrance door on the ground floor;
- a straight stair (IfcStair aggregating an IfcStairFlight, 20 risers of 0.6 ft) from each
  occupied storey to the next;
- a lift car (IfcTransportElement ELEVATOR) at the corridor's east end of each occupied storey,
  so that wheeled robots can go between storeys;
- furnishings (IfcFurnishingElement) in every dining room and lounge: round tables with four
  chairs each, sofas, a counter, plants. Bodies are IfcFacetedBrep closed shells (one per
  part: tessellated boxes, cylinders, spheres), 1,000 to 10,000 triangles per element.
  Chairs, about 3/4 of the dining tables and half of the sofas and plants are shared through
  IfcRepresentationMap + IfcMappedItem (with an IfcFurnitureType); counters, coffee tables and
  the rest are unique breps.
  As in exported files, furniture vertices are not exactly where the procedure puts them:
  each moves by up to --noise feet (default 1e-6 ft = 0.3 um, what single-precision meshes
  carry at these coordinates; written with 9 decimals), so nominally vertical faces are not
  exactly vertical and project to needle-thin triangles instead of nothing (what makes floor
  plans of real models slow). --noise 0 writes the exact procedure (4 decimals).

--small keeps the building (same storeys, spaces, walls, doors, stairs) and furnishes only one
dining room and one lounge (~2 MB, for tests); --furnished-rooms N furnishes the first N rooms.
Prints one summary line (JSON) with counts. The output is written atomically.
"""

import argparse
import json
import math
import os
import random
import sys
import uuid
from pathlib import Path

import ifcopenshell
import ifcopenshell.guid

FT = 0.3048
STOREY_HEIGHT = 12.0
SLAB = 1.0
EXT_T = 1.0
INT_T = 0.5
# Footprint in feet (wall centre lines): x 0..132, y 0..60; corridor y 27..33.
WIDTH = 132.0
DEPTH = 60.0
CORR_S = 27.0
CORR_N = 33.0
DOOR_W = 3.5
DOOR_H = 7.0
RISERS = 20
RISER = STOREY_HEIGHT / RISERS
GOING = 0.9
STAIR_X0 = 124.0
STAIR_W = 4.0
STAIR_Y0 = 3.0
TIMESTAMP = 1767225600  # 2026-01-01T00:00:00Z
TIMESTAMP_ISO = "2026-01-01T00:00:00"


def r4(v):
    """Coordinates are written with 4 decimals (0.03 mm in feet): smaller files, same bytes."""
    v = round(v, 4)
    return 0.0 if v == 0 else v


# ---------------------------------------------------------------- procedural closed meshes


class Part:
    """One closed triangle shell: vertices deduplicated after rounding, outward-facing."""

    def __init__(self):
        self.verts = []
        self.index = {}
        self.tris = []

    def v(self, x, y, z):
        key = (r4(x), r4(y), r4(z))
        i = self.index.get(key)
        if i is None:
            i = len(self.verts)
            self.index[key] = i
            self.verts.append(key)
        return i

    def tri(self, a, b, c):
        if a == b or b == c or a == c:
            raise ValueError("degenerate triangle after rounding")
        self.tris.append((a, b, c))

    def quad(self, a, b, c, d):
        self.tri(a, b, c)
        self.tri(a, c, d)


def box(x0, y0, z0, dx, dy, dz, nx, ny, nz):
    """A box subdivided nx*ny*nz: 4*(nx*ny + ny*nz + nz*nx) triangles."""
    p = Part()
    n = (nx, ny, nz)
    size = (dx, dy, dz)
    org = (x0, y0, z0)

    def lat(idx):
        return p.v(*(org[a] + size[a] * idx[a] / n[a] for a in range(3)))

    # (fixed axis, at max?, u axis, v axis) with u x v = outward normal.
    faces = [(2, False, 1, 0), (2, True, 0, 1), (1, False, 0, 2), (1, True, 2, 0),
             (0, False, 2, 1), (0, True, 1, 2)]
    for fixed, top, ua, va in faces:
        for i in range(n[ua]):
            for j in range(n[va]):
                corners = []
                for du, dv in ((0, 0), (1, 0), (1, 1), (0, 1)):
                    idx = [0, 0, 0]
                    idx[fixed] = n[fixed] if top else 0
                    idx[ua] = i + du
                    idx[va] = j + dv
                    corners.append(lat(idx))
                if top:
                    p.quad(*corners)
                else:  # the other diagonal, as independent tessellations of faces have
                    p.quad(corners[1], corners[2], corners[3], corners[0])
    return p


def cylinder(cx, cy, z0, r, h, seg, rings=1):
    """A vertical cylinder, capped: 2*seg*rings + 2*seg triangles."""
    p = Part()
    # Each ring is turned by half a segment from the one below (an anti-prism), as CAD
    # tessellations are: the caps' fans do not line up in plan.
    ring = [[p.v(cx + r * math.cos(math.pi * (2 * i + k) / seg), cy + r * math.sin(math.pi * (2 * i + k) / seg),
                 z0 + h * k / rings) for i in range(seg)] for k in range(rings + 1)]
    for k in range(rings):
        for i in range(seg):
            j = (i + 1) % seg
            p.quad(ring[k][i], ring[k][j], ring[k + 1][j], ring[k + 1][i])
    top = p.v(cx, cy, z0 + h)
    bot = p.v(cx, cy, z0)
    for i in range(seg):
        j = (i + 1) % seg
        p.tri(top, ring[rings][i], ring[rings][j])
        p.tri(bot, ring[0][j], ring[0][i])
    return p


def ellipsoid(cx, cy, cz, rx, ry, rz, seg, stacks):
    """A UV ellipsoid: 2*seg*(stacks-1) triangles."""
    p = Part()
    north = p.v(cx, cy, cz + rz)
    south = p.v(cx, cy, cz - rz)
    rings = []
    for k in range(1, stacks):
        th = math.pi * k / stacks
        s, c = math.sin(th), math.cos(th)
        # Turned by half a segment per ring: upper and lower halves do not line up in plan.
        rings.append([p.v(cx + rx * s * math.cos(math.pi * (2 * i + k) / seg),
                          cy + ry * s * math.sin(math.pi * (2 * i + k) / seg), cz + rz * c)
                      for i in range(seg)])
    for i in range(seg):
        j = (i + 1) % seg
        p.tri(north, rings[0][i], rings[0][j])
        p.tri(south, rings[-1][j], rings[-1][i])
    for k in range(len(rings) - 1):
        for i in range(seg):
            j = (i + 1) % seg
            p.quad(rings[k][i], rings[k + 1][i], rings[k + 1][j], rings[k][j])
    return p


# Furniture in its own coordinates (feet, origin at the floor, centred; +y is the front).

def chair(variant):
    seg = (24, 32, 40)[variant]
    n = (8, 10, 12)[variant]
    parts = [box(-0.8, -0.8, 1.4, 1.6, 1.6, 0.25, n, n, 2),
             box(-0.8, -0.95, 1.65, 1.6, 0.15, 1.6, n, 2, n)]
    for sx in (-0.65, 0.65):
        for sy in (-0.65, 0.65):
            parts.append(cylinder(sx, sy, 0.0, 0.07, 1.4, seg, 4))
    return parts


def round_table(radius, seg):
    return [cylinder(0, 0, 2.35, radius, 0.12, seg, 2),
            cylinder(0, 0, 0.1, 0.18, 2.25, seg // 2, 8),
            cylinder(0, 0, 0.0, radius * 0.45, 0.1, seg // 2, 1),
            ellipsoid(0, 0, 2.35, 0.3, 0.3, 0.12, seg // 2, 12)]


def sofa(length, n):
    d = 2.8
    m = max(4, int(n * length / 6))
    parts = [box(-length / 2, -d / 2, 0.3, length, d, 1.0, m, n, 3),
             box(-length / 2, -d / 2, 1.3, length, 0.6, 1.6, m, 3, n),
             box(-length / 2 - 0.5, -d / 2, 0.3, 0.5, d, 1.7, 2, n, n),
             box(length / 2, -d / 2, 0.3, 0.5, d, 1.7, 2, n, n)]
    cushions = max(2, int(length // 2.5))
    w = length / cushions
    for c in range(cushions):
        parts.append(ellipsoid(-length / 2 + w * (c + 0.5), 0.1, 1.45, w * 0.45, 1.1, 0.2, 24, 10))
    for sx in (-length / 2, length / 2):
        for sy in (-d / 2 + 0.2, d / 2 - 0.2):
            parts.append(cylinder(sx, sy, 0.0, 0.12, 0.3, 16, 1))
    return parts


def counter(length, n):
    m = max(6, int(n * length / 4))
    parts = [box(-length / 2, -1.25, 0.0, length, 2.5, 3.0, m, n, n),
             box(-length / 2 - 0.1, -1.4, 3.0, length + 0.2, 2.8, 0.15, m, n, 2)]
    stools = max(2, int(length // 3))
    for s in range(stools):
        x = -length / 2 + length * (s + 0.5) / stools
        parts.append(cylinder(x, 2.2, 0.0, 0.1, 2.4, 16, 4))
        parts.append(cylinder(x, 2.2, 2.4, 0.6, 0.15, 32, 1))
    return parts


def plant(radius, seg):
    return [cylinder(0, 0, 0.0, 0.7, 1.4, seg, 4),
            ellipsoid(0, 0, 1.4 + radius, radius, radius, radius * 1.2, seg, seg // 2)]


def triangles(parts):
    return sum(len(p.tris) for p in parts)


# ---------------------------------------------------------------- the IFC writer


class Writer:
    def __init__(self, seed, noise=0.0):
        self.rng = random.Random(seed)
        self.noise = noise
        self.noise_rng = random.Random(seed * 104729 + 3)
        self.guid_rng = random.Random(seed * 7919 + 1)
        self.f = ifcopenshell.file(schema="IFC2X3")
        self.counts = {}

    def c(self, ty, *args, **kw):
        return self.f.create_entity(ty, *args, **kw)

    def guid(self):
        return ifcopenshell.guid.compress(uuid.UUID(int=self.guid_rng.getrandbits(128)).hex)

    def pt(self, *xyz):
        return self.c("IfcCartesianPoint", tuple(r4(v) for v in xyz))

    def dir(self, *xyz):
        return self.c("IfcDirection", tuple(float(v) for v in xyz))

    def ax3(self, loc=(0.0, 0.0, 0.0), z=None, x=None):
        return self.c("IfcAxis2Placement3D", self.pt(*loc), self.dir(*z) if z else None,
                      self.dir(*x) if x else None)

    def ax2(self, loc=(0.0, 0.0)):
        return self.c("IfcAxis2Placement2D", self.pt(*loc), None)

    def place(self, rel, loc=(0.0, 0.0, 0.0), x=None):
        return self.c("IfcLocalPlacement", rel, self.ax3(loc, (0, 0, 1) if x else None, x))

    def rect(self, cx, cy, dx, dy):
        return self.c("IfcRectangleProfileDef", "AREA", None, self.ax2((cx, cy)), dx, dy)

    def extrude(self, profile, depth, loc=(0.0, 0.0, 0.0), z=None, x=None):
        return self.c("IfcExtrudedAreaSolid", profile, self.ax3(loc, z, x), self.dir(0, 0, 1), depth)

    def body(self, kind, items):
        return self.c("IfcShapeRepresentation", self.body_ctx, "Body", kind, items)

    def pds(self, *reps):
        return self.c("IfcProductDefinitionShape", None, None, list(reps))

    def count(self, key, n=1):
        self.counts[key] = self.counts.get(key, 0) + n

    def setup(self, name):
        f = self.f
        person = self.c("IfcPerson", None, "Doe", "Jane", None, None, None, None, None)
        org = self.c("IfcOrganization", None, "poinav", None, None, None)
        pao = self.c("IfcPersonAndOrganization", person, org, None)
        app = self.c("IfcApplication", org, "1.0", "poinav make-heavy-model.py", "poinav-heavy")
        self.oh = self.c("IfcOwnerHistory", pao, app, None, "NOCHANGE", None, None, None, TIMESTAMP)
        dims = self.c("IfcDimensionalExponents", 1, 0, 0, 0, 0, 0, 0)
        metre = self.c("IfcSIUnit", None, "LENGTHUNIT", None, "METRE")
        foot = self.c("IfcConversionBasedUnit", dims, "LENGTHUNIT", "FOOT",
                      self.c("IfcMeasureWithUnit", f.create_entity("IfcLengthMeasure", FT), metre))
        sqm = self.c("IfcSIUnit", None, "AREAUNIT", None, "SQUARE_METRE")
        sqft = self.c("IfcConversionBasedUnit", self.c("IfcDimensionalExponents", 2, 0, 0, 0, 0, 0, 0),
                      "AREAUNIT", "SQUARE_FOOT",
                      self.c("IfcMeasureWithUnit", f.create_entity("IfcAreaMeasure", 0.09290304), sqm))
        m3 = self.c("IfcSIUnit", None, "VOLUMEUNIT", None, "CUBIC_METRE")
        cuft = self.c("IfcConversionBasedUnit", self.c("IfcDimensionalExponents", 3, 0, 0, 0, 0, 0, 0),
                      "VOLUMEUNIT", "CUBIC_FOOT",
                      self.c("IfcMeasureWithUnit", f.create_entity("IfcVolumeMeasure", 0.028316846592), m3))
        rad = self.c("IfcSIUnit", None, "PLANEANGLEUNIT", None, "RADIAN")
        deg = self.c("IfcConversionBasedUnit", self.c("IfcDimensionalExponents", 0, 0, 0, 0, 0, 0, 0),
                     "PLANEANGLEUNIT", "DEGREE",
                     self.c("IfcMeasureWithUnit", f.create_entity("IfcPlaneAngleMeasure", 0.017453292519943295), rad))
        units = self.c("IfcUnitAssignment", [foot, sqft, cuft, deg])
        self.ctx = self.c("IfcGeometricRepresentationContext", None, "Model", 3, 1.0e-5, self.ax3(),
                          self.c("IfcDirection", (0.0, 1.0)))
        self.body_ctx = self.c("IfcGeometricRepresentationSubContext", "Body", "Model", None, None, None,
                               None, self.ctx, None, "MODEL_VIEW", None)
        self.axis_ctx = self.c("IfcGeometricRepresentationSubContext", "Axis", "Model", None, None, None,
                               None, self.ctx, None, "GRAPH_VIEW", None)
        self.project = self.c("IfcProject", self.guid(), self.oh, name, None, None, None, None,
                              [self.ctx], units)
        self.site_place = self.place(None)
        self.site = self.c("IfcSite", self.guid(), self.oh, "Default", None, None, self.site_place, None,
                           None, "ELEMENT", (51, 30, 0), (0, -7, 0), 0.0, None, None)
        self.bldg_place = self.place(self.site_place)
        self.building = self.c("IfcBuilding", self.guid(), self.oh, name, None, None, self.bldg_place,
                               None, None, "ELEMENT", None, None, None)
        self.rel("IfcRelAggregates", self.project, [self.site])
        self.rel("IfcRelAggregates", self.site, [self.building])
        mat = self.c("IfcMaterial", "Furniture - Oak")
        colour = self.c("IfcColourRgb", None, 0.55, 0.4, 0.25)
        shading = self.c("IfcSurfaceStyleShading", colour)
        style = self.c("IfcSurfaceStyle", "Furniture - Oak", "BOTH", [shading])
        self.furn_style = self.c("IfcPresentationStyleAssignment", [style])
        self.furn_material = mat
        self.wall_materials = {}

    def rel(self, ty, relating, related):
        return self.c(ty, self.guid(), self.oh, None, None, relating, related)

    def layer_usage(self, thickness):
        if thickness not in self.wall_materials:
            m = self.c("IfcMaterial", "Gypsum Wall Board" if thickness < 1 else "Concrete Masonry Units")
            layer = self.c("IfcMaterialLayer", m, thickness, None)
            lset = self.c("IfcMaterialLayerSet", [layer], f"Basic Wall:Generic - {thickness * 12:.0f}\"")
            self.wall_materials[thickness] = lset
        return self.c("IfcMaterialLayerSetUsage", self.wall_materials[thickness], "AXIS2", "POSITIVE",
                      -thickness / 2)

    # ----------------------------------------------------------- building elements

    def wall(self, storey, name, a, b, t, height, clipped, external):
        (x0, y0), (x1, y1) = a, b
        length = math.hypot(x1 - x0, y1 - y0)
        ux, uy = (x1 - x0) / length, (y1 - y0) / length
        placement = self.place(storey["place"], (x0, y0, 0.0), (ux, uy, 0.0))
        axis = self.c("IfcShapeRepresentation", self.axis_ctx, "Axis", "Curve2D",
                      [self.c("IfcPolyline", [self.pt(0.0, 0.0), self.pt(length, 0.0)])])
        if clipped:
            solid = self.extrude(self.rect(length / 2, 0.0, length, t), height + SLAB + 0.5)
            plane = self.c("IfcPlane", self.ax3((0.0, 0.0, height), (0, 0, 1), (1, 0, 0)))
            half = self.c("IfcHalfSpaceSolid", plane, False)
            item = self.c("IfcBooleanClippingResult", "DIFFERENCE", solid, half)
            rep = self.body("Clipping", [item])
            self.count("clipping booleans")
        else:
            rep = self.body("SweptSolid", [self.extrude(self.rect(length / 2, 0.0, length, t), height)])
        w = self.c("IfcWallStandardCase", self.guid(), self.oh, name, None,
                   f"Basic Wall:Generic - {t * 12:.0f}\"", placement, self.pds(axis, rep), None)
        self.c("IfcRelAssociatesMaterial", self.guid(), self.oh, None, None, [w], self.layer_usage(t))
        props = [self.c("IfcPropertySingleValue", "IsExternal", None,
                        self.f.create_entity("IfcBoolean", external), None),
                 self.c("IfcPropertySingleValue", "LoadBearing", None,
                        self.f.create_entity("IfcBoolean", external), None)]
        pset = self.c("IfcPropertySet", self.guid(), self.oh, "Pset_WallCommon", None, props)
        self.c("IfcRelDefinesByProperties", self.guid(), self.oh, None, None, [w], pset)
        storey["elements"].append(w)
        self.count("walls")
        return {"entity": w, "place": placement, "a": a, "b": b, "t": t, "external": external,
                "length": length, "u": (ux, uy)}

    def door(self, storey, wall, s, name):
        """A door centred at distance s along the wall from its start."""
        t = wall["t"]
        op_place = self.place(wall["place"], (s - DOOR_W / 2, 0.0, 0.0))
        op_body = self.body("SweptSolid", [self.extrude(self.rect(DOOR_W / 2, 0.0, DOOR_W, t + 0.2), DOOR_H)])
        opening = self.c("IfcOpeningElement", self.guid(), self.oh, f"{name} opening", None, "Opening",
                         op_place, self.pds(op_body), None)
        self.c("IfcRelVoidsElement", self.guid(), self.oh, None, None, wall["entity"], opening)
        d_place = self.place(op_place)
        lining = 0.15
        items = [self.extrude(self.rect(lining / 2, 0.0, lining, t), DOOR_H),
                 self.extrude(self.rect(DOOR_W - lining / 2, 0.0, lining, t), DOOR_H),
                 self.extrude(self.rect(DOOR_W / 2, 0.0, DOOR_W, t), lining, (0.0, 0.0, DOOR_H - lining)),
                 self.extrude(self.rect(DOOR_W / 2, 0.0, DOOR_W - 2 * lining, 0.15), DOOR_H - lining - 0.05,
                              (0.0, 0.0, 0.03))]
        d = self.c("IfcDoor", self.guid(), self.oh, name, None, "Single-Flush:42\" x 84\"", d_place,
                   self.pds(self.body("SweptSolid", items)), None, DOOR_H, DOOR_W)
        self.c("IfcRelFillsElement", self.guid(), self.oh, None, None, opening, d)
        self.doors.append(d)
        storey["elements"].append(d)
        self.count("doors")
        self.count("openings")
        return d

    def make_door_style(self):
        self.doors = []
        lp = self.c("IfcDoorLiningProperties", self.guid(), self.oh, "Lining", None,
                    LiningDepth=EXT_T, LiningThickness=0.15)
        self.door_style = self.c("IfcDoorStyle", self.guid(), self.oh, "Single-Flush:42\" x 84\"", None, None,
                                 [lp], None, None, "SINGLE_SWING_LEFT", "NOTDEFINED", False, False)

    def slab(self, storey, name, kind, z, holes):
        outer = [(-EXT_T / 2, -EXT_T / 2), (WIDTH + EXT_T / 2, -EXT_T / 2),
                 (WIDTH + EXT_T / 2, DEPTH + EXT_T / 2), (-EXT_T / 2, DEPTH + EXT_T / 2)]

        def poly(pts):
            return self.c("IfcPolyline", [self.pt(*p) for p in pts + [pts[0]]])

        if holes:
            prof = self.c("IfcArbitraryProfileDefWithVoids", "AREA", None, poly(outer),
                          [poly(h) for h in holes])
        else:
            prof = self.c("IfcArbitraryClosedProfileDef", "AREA", None, poly(outer))
        placement = self.place(storey["place"], (0.0, 0.0, z))
        s = self.c("IfcSlab", self.guid(), self.oh, name, None, "Floor:Generic 12\"", placement,
                   self.pds(self.body("SweptSolid", [self.extrude(prof, SLAB)])), None, kind)
        storey["elements"].append(s)
        self.count("slabs")
        return s

    def stair(self, storey, name):
        pts = [(0.0, 0.0)]
        for i in range(RISERS):
            pts.append((i * GOING, (i + 1) * RISER))
            pts.append(((i + 1) * GOING, (i + 1) * RISER))
        run = RISERS * GOING
        pts.append((run, RISERS * RISER - 1.0))
        pts.append((GOING / RISER * 1.0, 0.0))  # the soffit runs parallel to the pitch, 1 ft below
        prof = self.c("IfcArbitraryClosedProfileDef", "AREA", None,
                      self.c("IfcPolyline", [self.pt(*p) for p in pts + [pts[0]]]))
        solid = self.c("IfcExtrudedAreaSolid", prof,
                       self.ax3((STAIR_X0, STAIR_Y0, 0.0), (1, 0, 0), (0, 1, 0)), self.dir(0, 0, 1), STAIR_W)
        st_place = self.place(storey["place"])
        stair = self.c("IfcStair", self.guid(), self.oh, name, None, "Stair:Monolithic", st_place, None, None,
                       "STRAIGHT_RUN_STAIR")
        fl_place = self.place(st_place)
        flight = self.c("IfcStairFlight", self.guid(), self.oh, f"{name} run", None, None, fl_place,
                        self.pds(self.body("SweptSolid", [solid])), None, RISERS, RISERS - 1, RISER, GOING)
        self.rel("IfcRelAggregates", stair, [flight])
        storey["elements"].append(stair)
        self.count("stairs")

    def lift(self, storey, name):
        """A lift car at the corridor's east end (IfcTransportElement ELEVATOR), one per storey."""
        x0, y0 = WIDTH - INT_T / 2 - 3.5, CORR_S + INT_T / 2 + 0.25
        placement = self.place(storey["place"], (x0, y0, 0.0))
        body = self.body("SweptSolid", [self.extrude(self.rect(1.75, 2.5, 3.5, 5.0), STOREY_HEIGHT - SLAB)])
        e = self.c("IfcTransportElement", self.guid(), self.oh, name, None, "Elevator:Car 3.5 x 5 ft", placement,
                   self.pds(body), None, "ELEVATOR", None, None)
        storey["elements"].append(e)
        self.count("lifts")

    def space(self, storey, name, long_name, rect, ext_sides):
        x0, y0, x1, y1 = rect
        inset = [EXT_T / 2 if s else INT_T / 2 for s in ext_sides]  # west, south, east, north
        ix0, iy0, ix1, iy1 = x0 + inset[0], y0 + inset[1], x1 - inset[2], y1 - inset[3]
        placement = self.place(storey["place"], (ix0, iy0, 0.0))
        rep = self.body("SweptSolid", [self.extrude(self.rect((ix1 - ix0) / 2, (iy1 - iy0) / 2, ix1 - ix0,
                                                              iy1 - iy0), STOREY_HEIGHT - SLAB)])
        sp = self.c("IfcSpace", self.guid(), self.oh, name, None, None, placement, self.pds(rep), long_name,
                    "ELEMENT", "INTERNAL", 0.0)
        storey["spaces"].append(sp)
        self.count("spaces")
        return sp

    def boundary(self, space, element, external):
        self.c("IfcRelSpaceBoundary", self.guid(), self.oh, "1stLevel", None, space, element, None,
               "PHYSICAL", "EXTERNAL" if external else "INTERNAL")
        self.count("space boundaries")

    # ----------------------------------------------------------- furniture

    def brep_items(self, parts):
        items = []
        for p in parts:
            if self.noise > 0:
                # Exporters write tessellated bodies through transforms and per-face
                # tessellation: a nominally vertical edge's two ends are not bit-identical.
                # Each (shared) vertex moves by up to `noise` feet, so shells stay closed.
                n, r = self.noise, self.noise_rng
                verts = [tuple(round(c + r.uniform(-n, n), 9) for c in v) for v in p.verts]
            else:
                verts = p.verts
            pts = [self.c("IfcCartesianPoint", v) for v in verts]
            faces = [self.c("IfcFace", [self.c("IfcFaceOuterBound",
                                               self.c("IfcPolyLoop", [pts[a], pts[b], pts[c]]), True)])
                     for a, b, c in p.tris]
            brep = self.c("IfcFacetedBrep", self.c("IfcClosedShell", faces))
            self.c("IfcStyledItem", brep, [self.furn_style], None)
            items.append(brep)
        self.count("brep triangles written", triangles(parts))
        return items

    def type_map(self, key, label, parts):
        """A shared furniture body: IfcRepresentationMap + IfcFurnitureType."""
        rep = self.body("Brep", self.brep_items(parts))
        rmap = self.c("IfcRepresentationMap", self.ax3(), rep)
        ftype = self.c("IfcFurnitureType", self.guid(), self.oh, label, None, None, None, [rmap], None,
                       label.split("-")[0], "NOTDEFINED")
        return {"map": rmap, "type": ftype, "tris": triangles(parts), "instances": []}

    def furnishing(self, storey, label, x, y, angle, parts=None, shared=None):
        ca, sa = math.cos(angle), math.sin(angle)
        placement = self.place(storey["place"], (x, y, 0.0), (r4(ca), r4(sa), 0.0))
        if shared is not None:
            op = self.c("IfcCartesianTransformationOperator3D", None, None, self.pt(0.0, 0.0, 0.0), None, None)
            rep = self.body("MappedRepresentation", [self.c("IfcMappedItem", shared["map"], op)])
            tris = shared["tris"]
            self.count("mapped items")
        else:
            rep = self.body("Brep", self.brep_items(parts))
            tris = triangles(parts)
        if not 1000 <= tris <= 10000:
            raise ValueError(f"{label}: {tris} triangles, outside 1000..10000")
        e = self.c("IfcFurnishingElement", self.guid(), self.oh, f"{label}:{len(storey['elements'])}", None,
                   label, placement, self.pds(rep), None)
        if shared is not None:
            shared["instances"].append(e)
        storey["elements"].append(e)
        self.c("IfcRelAssociatesMaterial", self.guid(), self.oh, None, None, [e], self.furn_material)
        self.count("furnishings")
        self.count("furnishing triangles", tris)
        return e


def dining_room(w, storey, rect, shared, small=False):
    """Round tables with four chairs each (2 x 2 tables; one row of 2 when small)."""
    x0, y0, x1, y1 = rect
    rng = w.rng
    rows = (0.5,) if small else (0.3, 0.72)
    for fy in rows:
        for fx in (0.25, 0.75):
            cx, cy = x0 + (x1 - x0) * fx, y0 + (y1 - y0) * fy
            radius = round(rng.uniform(1.4, 2.0), 2)
            custom = fx == 0.75 if small else rng.random() < 0.25
            if custom:
                w.furnishing(storey, "Table-Round:Custom", cx, cy, rng.uniform(0, math.pi),
                             parts=round_table(radius, 64 if small else rng.choice((96, 128, 160))))
            else:
                w.furnishing(storey, "Table-Round:Pedestal", cx, cy, 0.0, shared=rng.choice(shared["tables"]))
            chairs = rng.choice(shared["chairs"])
            for k in range(4):
                a = math.pi / 2 * k + math.pi / 4
                d = 3.1
                # The chair's front (+y) faces the table: rotate its local +y towards the centre.
                w.furnishing(storey, "Chair-Dining", cx + d * math.cos(a), cy + d * math.sin(a),
                             a + math.pi / 2, shared=chairs)


def lounge(w, storey, rect, shared, small=False):
    """A counter with stools, two sofas, a coffee table, two plants (one plant when small)."""
    x0, y0, x1, y1 = rect
    rng = w.rng
    cx = (x0 + x1) / 2
    if small:
        w.furnishing(storey, "Plant-Ball", x0 + 2.5, y1 - 3.0, 0.0, parts=plant(1.0, 32))
        return
    length = round((x1 - x0) - 10 - rng.uniform(0, 4), 1)
    w.furnishing(storey, "Counter-Bar", cx, y0 + 2.0, 0.0, parts=counter(length, rng.choice((4, 6))))
    for side in (-1, 1):
        if rng.random() < 0.5:
            w.furnishing(storey, "Sofa-Lounge:Standard", cx + side * 7.0, y0 + 12.0, 0.0,
                         shared=rng.choice(shared["sofas"]))
        else:
            w.furnishing(storey, "Sofa-Lounge:Custom", cx + side * 7.0, y0 + 12.0, 0.0,
                         parts=sofa(round(rng.uniform(5.0, 7.5), 1), rng.choice((6, 8, 10))))
    w.furnishing(storey, "Table-Coffee", cx, y0 + 16.0, 0.0,
                 parts=round_table(round(rng.uniform(1.2, 1.8), 2), rng.choice((64, 96))))
    for px in (x0 + 2.5, x1 - 2.5):
        if rng.random() < 0.5:
            w.furnishing(storey, "Plant-Ball:Standard", px, y1 - 3.0, 0.0, shared=rng.choice(shared["plants"]))
        else:
            w.furnishing(storey, "Plant-Ball:Custom", px, y1 - 3.0, 0.0,
                         parts=plant(round(rng.uniform(0.8, 1.4), 2), rng.choice((32, 40, 48))))


def build(args):
    w = Writer(args.seed, args.noise)
    name = "Heavy furnished building (ft)"
    w.setup(name)
    w.make_door_style()
    shared = {
        "chairs": [w.type_map(("chair", v), f"Chair-Dining:Type {'ABC'[v]}", chair(v))
                   for v in range(1 if args.small else 3)],
        "tables": [w.type_map(("table", v), f"Table-Round:Pedestal {v}", round_table(1.6 + 0.2 * v, 128))
                   for v in range(1 if args.small else 2)],
        "sofas": [] if args.small else [w.type_map(("sofa", v), f"Sofa-Lounge:Standard {v}", sofa(6.0 + v, 8))
                                        for v in range(2)],
        "plants": [] if args.small else [w.type_map(("plant", v), f"Plant-Ball:Standard {v}", plant(1.0 + 0.2 * v, 40))
                                         for v in range(2)],
    }
    storeys = []
    furnished = 0
    limit = args.furnished_rooms
    kinds_done = set()
    for level in range(args.storeys + 1):
        roof = level == args.storeys
        z = level * STOREY_HEIGHT
        sname = "Roof" if roof else f"Level {level + 1}"
        place = w.place(w.bldg_place, (0.0, 0.0, z))
        ent = w.c("IfcBuildingStorey", w.guid(), w.oh, sname, None, None, place, None, None, "ELEMENT", z)
        storey = {"entity": ent, "place": place, "elements": [], "spaces": []}
        storeys.append(storey)
        w.count("storeys")
        hole = [(STAIR_X0 - 0.5, STAIR_Y0 - 0.5), (STAIR_X0 + STAIR_W + 0.5, STAIR_Y0 - 0.5),
                (STAIR_X0 + STAIR_W + 0.5, STAIR_Y0 + RISERS * GOING),
                (STAIR_X0 - 0.5, STAIR_Y0 + RISERS * GOING)]
        if roof:
            w.slab(storey, "Roof slab", "ROOF", 0.0, [])
            continue
        floor = w.slab(storey, f"{sname} floor", "FLOOR", -SLAB, [hole] if level > 0 else [])
        h = STOREY_HEIGHT - SLAB
        walls = []

        def wall(nm, a, b, t, clipped, external):
            walls.append(w.wall(storey, nm, a, b, t, h, clipped, external))
            return walls[-1]

        e = EXT_T / 2
        wall("Exterior S", (-e, 0.0), (WIDTH + e, 0.0), EXT_T, True, True)
        wall("Exterior E", (WIDTH, 0.0), (WIDTH, DEPTH), EXT_T, True, True)
        wall("Exterior N", (WIDTH + e, DEPTH), (-e, DEPTH), EXT_T, True, True)
        west = wall("Exterior W", (0.0, DEPTH), (0.0, 0.0), EXT_T, True, True)
        corr_s = wall("Corridor S", (0.0, CORR_S), (WIDTH, CORR_S), INT_T, True, False)
        corr_n = wall("Corridor N", (0.0, CORR_N), (WIDTH, CORR_N), INT_T, level % 2 == 0, False)
        north_x = [0.0, 33.0, 66.0, 99.0, WIDTH]
        south_x = [0.0, 30.0, 60.0, 90.0, 120.0, WIDTH]
        for x in north_x[1:-1]:
            wall(f"Partition N {x:.0f}", (x, CORR_N), (x, DEPTH), INT_T, False, False)
        for x in south_x[1:-1]:
            wall(f"Partition S {x:.0f}", (x, 0.0), (x, CORR_S), INT_T, False, False)

        rooms = []  # (space, rect, door)
        num = (level + 1) * 100
        for i in range(4):
            rect = (north_x[i], CORR_N, north_x[i + 1], DEPTH)
            sp = w.space(storey, f"{num + 1 + i}", "Dining", rect, (i == 0, False, i == 3, True))
            d = w.door(storey, corr_n, (rect[0] + rect[2]) / 2, f"Door {num + 1 + i}")
            rooms.append((sp, rect, d, "dining"))
        for i in range(5):
            rect = (south_x[i], 0.0, south_x[i + 1], CORR_S)
            stair_room = i == 4
            sp = w.space(storey, f"{num + 5 + i}", "Stair" if stair_room else "Lounge", rect,
                         (i == 0, True, i == 4, False))
            d = w.door(storey, corr_s, (rect[0] + rect[2]) / 2, f"Door {num + 5 + i}")
            rooms.append((sp, rect, d, "stair" if stair_room else "lounge"))
        corridor = w.space(storey, f"{num}", "Corridor", (0.0, CORR_S, WIDTH, CORR_N), (True, False, True, False))
        entrance = None
        if level == 0:
            entrance = w.door(storey, west, DEPTH - (CORR_S + CORR_N) / 2, "Entrance")
        if level < args.storeys - 1:
            w.stair(storey, f"Stair {sname}")
        w.lift(storey, f"Lift {sname}")

        # Space boundaries: walls on the room's edges, its door(s), its floor.
        def bounds(rect):
            x0, y0, x1, y1 = rect
            for wl in walls:
                (ax, ay), (bx, by) = wl["a"], wl["b"]
                if ay == by and ay in (y0, y1) and min(max(ax, bx), x1) - max(min(ax, bx), x0) > 0.01:
                    yield wl
                elif ax == bx and ax in (x0, x1) and min(max(ay, by), y1) - max(min(ay, by), y0) > 0.01:
                    yield wl

        for sp, rect, d, kind in rooms:
            for wl in bounds(rect):
                w.boundary(sp, wl["entity"], wl["external"])
            w.boundary(sp, d, False)
            w.boundary(corridor, d, False)
            w.boundary(sp, floor, False)
        for wl in bounds((0.0, CORR_S, WIDTH, CORR_N)):
            w.boundary(corridor, wl["entity"], wl["external"])
        w.boundary(corridor, floor, False)
        if entrance is not None:
            w.boundary(corridor, entrance, True)

        for sp, rect, d, kind in rooms:
            if kind == "stair" or (limit is not None and furnished >= limit):
                continue
            if args.small and kind in kinds_done:
                continue
            kinds_done.add(kind)
            furnished += 1
            inner = (rect[0] + 0.5, rect[1] + 0.5, rect[2] - 0.5, rect[3] - 0.5)
            if kind == "dining":
                dining_room(w, storey, inner, shared, args.small)
            else:
                lounge(w, storey, inner, shared, args.small)
        w.rel("IfcRelAggregates", ent, storey["spaces"])

    w.rel("IfcRelAggregates", w.building, [s["entity"] for s in storeys])
    for s in storeys:
        if s["elements"]:
            w.c("IfcRelContainedInSpatialStructure", w.guid(), w.oh, None, None, s["elements"], s["entity"])
    w.c("IfcRelDefinesByType", w.guid(), w.oh, None, None, w.doors, w.door_style)
    for group in shared.values():
        for t in group:
            if t["instances"]:
                w.c("IfcRelDefinesByType", w.guid(), w.oh, None, None, t["instances"], t["type"])
    return w


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("out", type=Path)
    ap.add_argument("--seed", type=int, default=15)
    ap.add_argument("--storeys", type=int, default=4, help="occupied storeys (a Roof storey is added)")
    ap.add_argument("--furnished-rooms", type=int, default=None,
                    help="furnish only the first N dining rooms/lounges (default: all)")
    ap.add_argument("--noise", type=float, default=1e-6, metavar="FT",
                    help="largest offset of a furniture vertex from its exact place, feet (default 1e-6; 0: exact)")
    ap.add_argument("--small", action="store_true", help="furnish one dining room and one lounge (~2 MB)")
    args = ap.parse_args()
    if args.storeys < 1:
        ap.error("--storeys must be at least 1")
    w = build(args)
    f = w.f
    # Fixed header name (not the output path), so the same arguments give the same bytes anywhere.
    f.header.file_name.name = "heavy-furnished-ft-small.ifc" if args.small else "heavy-furnished-ft.ifc"
    f.header.file_name.time_stamp = TIMESTAMP_ISO
    f.header.file_name.author = ("poinav",)
    f.header.file_name.organization = ("poinav",)
    f.header.file_name.preprocessor_version = "IfcOpenShell " + ifcopenshell.version
    f.header.file_name.originating_system = "poinav scripts/make-heavy-model.py"
    f.header.file_description.description = ("ViewDefinition [CoordinationView_V2.0]",)
    args.out.parent.mkdir(parents=True, exist_ok=True)
    tmp = args.out.with_name(args.out.name + ".tmp")
    f.write(str(tmp))
    os.replace(tmp, args.out)
    summary = dict(w.counts)
    summary["bytes"] = args.out.stat().st_size
    summary["file"] = str(args.out)
    print(json.dumps(summary, sort_keys=True))


if __name__ == "__main__":
    sys.exit(main())
