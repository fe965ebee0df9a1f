"""What the authoring scripts (author_*.py) share: GlobalIds fixed by a name, points,
directions and placements, each created on one ifcopenshell.file in the order its arguments
are written (so a script's entity numbers do not depend on this module).

    from authoring import Authoring
    f = ifcopenshell.file(schema="IFC4")
    a = Authoring(f, "poinav-test-house:")
    gid, pt, d3, axis, place = a.gid, a.pt, a.d3, a.axis, a.place
"""

import hashlib
import uuid

import ifcopenshell.guid


class Authoring:
    """Building blocks on the file `f`; GlobalIds are an MD5 of `prefix` + name."""

    def __init__(self, f, prefix):
        self.f = f
        self.prefix = prefix

    def gid(self, name):
        """A fixed GlobalId from a name (so tests can name elements)."""
        h = hashlib.md5((self.prefix + name).encode()).hexdigest()
        return ifcopenshell.guid.compress(uuid.UUID(h).hex)

    def pt(self, *c):
        return self.f.createIfcCartesianPoint([float(x) for x in c])

    def d3(self, *c):
        return self.f.createIfcDirection([float(x) for x in c])

    def axis(self, x=0.0, y=0.0, z=0.0, axis=(0, 0, 1), ref=(1, 0, 0)):
        """An IfcAxis2Placement3D at (x, y, z); `axis` or `ref` None leaves it out."""
        return self.f.createIfcAxis2Placement3D(
            self.pt(x, y, z), self.d3(*axis) if axis else None, self.d3(*ref) if ref else None
        )

    def place(self, rel=None, x=0.0, y=0.0, z=0.0):
        """An IfcLocalPlacement at (x, y, z) relative to `rel`."""
        return self.f.createIfcLocalPlacement(rel, self.axis(x, y, z))

    def spine(self, name, storey="Ground floor"):
        """A metre model's context and body subcontext, project, site, building and one
        storey at 0.00 m, aggregated; returns (body, storey, storey placement)."""
        f, gid, place = self.f, self.gid, self.place
        ctx = f.createIfcGeometricRepresentationContext(None, "Model", 3, 1.0e-5, self.axis(), None)
        body = f.createIfcGeometricRepresentationSubContext(
            "Body", "Model", None, None, None, None, ctx, None, "MODEL_VIEW", None
        )
        units = f.createIfcUnitAssignment([f.createIfcSIUnit(None, "LENGTHUNIT", None, "METRE")])
        project = f.createIfcProject(gid("project"), None, name, None, None, None, None, [ctx], units)
        site_pl = place()
        site = f.createIfcSite(
            gid("site"), None, "Site", None, None, site_pl, None, None, "ELEMENT", None, None, None, None, None
        )
        bldg_pl = place(site_pl)
        building = f.createIfcBuilding(
            gid("building"), None, name, None, None, bldg_pl, None, None, "ELEMENT", None, None, None
        )
        storey_pl = place(bldg_pl)
        st = f.createIfcBuildingStorey(
            gid("storey"), None, storey, None, None, storey_pl, None, None, "ELEMENT", 0.0
        )
        f.createIfcRelAggregates(gid("agg project"), None, None, None, project, [site])
        f.createIfcRelAggregates(gid("agg site"), None, None, None, site, [building])
        f.createIfcRelAggregates(gid("agg building"), None, None, None, building, [st])
        return body, st, storey_pl
