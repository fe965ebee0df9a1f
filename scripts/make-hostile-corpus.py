#!/usr/bin/env python3
"""Writes the hostile-geometry corpus: small IFC4 files, each with one kind of damage.

Usage: python3 scripts/make-hostile-corpus.py OUT_DIR

Stdlib only; the outputs are not committed (crates/poinav/tests/hostile_geometry.rs runs this
script into a temporary folder). Every file is the same small, valid base model (one storey,
walls A, B and C, a door in an opening of wall B, a slab) with one change. The damaged element
is always wall A (#100) unless the file name says otherwise, so a test can check that exactly
that element is reported and every other one is still exported.

Files:
  base.ifc                    the undamaged model
  inf-placement.ifc           wall A's placement point has an x of 1.E400 (overflows to +inf)
  nan-placement.ifc           wall A's placement point has an x written as NaN (as C's printf does)
  inf-profile.ifc             wall A's rectangle profile XDim is 1.E400
  nan-profile.ifc             wall A's rectangle profile XDim is NaN
  zero-depth.ifc              wall A's extrusion Depth is 0.
  rect-xdim-zero.ifc          wall A's rectangle profile XDim is 0.
  polyline-2-points.ifc       wall A's profile is a closed-profile polyline with two points
  polyline-self-intersecting.ifc  wall A's profile is a bow tie (self-intersecting polyline)
  opening-bigger-than-wall.ifc    wall A has an opening larger than the wall in every direction
  opening-zero-depth.ifc      wall A has an opening (#700) whose extrusion Depth is 0.: the
                              wall is kept uncut, the opening named in a warning
  door-without-geometry.ifc   a second door (#600) with a placement but no representation
  truncated-NN-WHAT.ifc       the base file cut at one point (every section start and end,
                              and in the middle of an instance); NN orders them
"""

import os
import sys

HEADER = [
    "ISO-10303-21;",
    "HEADER;",
    "FILE_DESCRIPTION(('ViewDefinition [DesignTransferView]'),'2;1');",
    "FILE_NAME('hostile.ifc','2024-01-01T00:00:00',('poinav'),('poinav'),'poinav tests','poinav tests','');",
    "FILE_SCHEMA(('IFC4'));",
    "ENDSEC;",
]


def guid(n):
    """A fixed, valid-looking 22-character GlobalId per number."""
    chars = "0123456789ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz_$"
    s = ""
    for _ in range(4):
        s = chars[n % 64] + s
        n //= 64
    return ("0Hostile" + "x" * 10 + s)[:22]


def wall(base, name, x, y, length, profile_xdim=None, depth="3.", point=None, profile=None):
    """Instances of a wall at (x, y) along +x: placement, rectangle-profile extrusion."""
    xdim = profile_xdim if profile_xdim is not None else f"{length:.1f}"
    pt = point if point is not None else f"({x:.1f},{y:.1f},0.)"
    b = base
    prof = profile or [
        f"#{b + 7}=IFCRECTANGLEPROFILEDEF(.AREA.,$,#{b + 10},{xdim},0.2);",
        f"#{b + 10}=IFCAXIS2PLACEMENT2D(#{b + 11},$);",
        f"#{b + 11}=IFCCARTESIANPOINT(({length / 2:.2f},0.1));",
    ]
    return [
        f"#{b}=IFCWALL('{guid(b)}',$,'{name}',$,$,#{b + 1},#{b + 2},$,.STANDARD.);",
        f"#{b + 1}=IFCLOCALPLACEMENT(#12,#{b + 3});",
        f"#{b + 3}=IFCAXIS2PLACEMENT3D(#{b + 4},$,$);",
        f"#{b + 4}=IFCCARTESIANPOINT({pt});",
        f"#{b + 2}=IFCPRODUCTDEFINITIONSHAPE($,$,(#{b + 5}));",
        f"#{b + 5}=IFCSHAPEREPRESENTATION(#21,'Body','SweptSolid',(#{b + 6}));",
        f"#{b + 6}=IFCEXTRUDEDAREASOLID(#{b + 7},#11,#13,{depth});",
    ] + prof


def box(base, cls, name, x, y, z, dx, dy, dz, extra, placement_rel="#12"):
    """A product with a rectangle extrusion dx x dy x dz whose corner is at (x, y, z)."""
    b = base
    return [
        f"#{b}={cls}('{guid(b)}',$,'{name}',$,$,#{b + 1},#{b + 2},${extra});",
        f"#{b + 1}=IFCLOCALPLACEMENT({placement_rel},#{b + 3});",
        f"#{b + 3}=IFCAXIS2PLACEMENT3D(#{b + 4},$,$);",
        f"#{b + 4}=IFCCARTESIANPOINT(({x:.2f},{y:.2f},{z:.2f}));",
        f"#{b + 2}=IFCPRODUCTDEFINITIONSHAPE($,$,(#{b + 5}));",
        f"#{b + 5}=IFCSHAPEREPRESENTATION(#21,'Body','SweptSolid',(#{b + 6}));",
        f"#{b + 6}=IFCEXTRUDEDAREASOLID(#{b + 7},#11,#13,{dz:.2f});",
        f"#{b + 7}=IFCRECTANGLEPROFILEDEF(.AREA.,$,#{b + 10},{dx:.2f},{dy:.2f});",
        f"#{b + 10}=IFCAXIS2PLACEMENT2D(#{b + 11},$);",
        f"#{b + 11}=IFCCARTESIANPOINT(({dx / 2:.2f},{dy / 2:.2f}));",
    ]


def model(wall_a=None, extra=None, contained_extra=""):
    """The base model's DATA lines; `wall_a` replaces wall A's instances."""
    data = [
        "#1=IFCPROJECT('0HostileProject00000001',$,'Project',$,$,$,$,(#20),#2);",
        "#2=IFCUNITASSIGNMENT((#3));",
        "#3=IFCSIUNIT(*,.LENGTHUNIT.,$,.METRE.);",
        f"#4=IFCBUILDINGSTOREY('{guid(4)}',$,'Ground Floor',$,$,#12,$,$,.ELEMENT.,0.);",
        f"#5=IFCRELAGGREGATES('{guid(5)}',$,$,$,#1,(#4));",
        f"#6=IFCRELCONTAINEDINSPATIALSTRUCTURE('{guid(6)}',$,$,$,(#100,#200,#300,#400,#500{contained_extra}),#4);",
        f"#7=IFCRELVOIDSELEMENT('{guid(7)}',$,$,$,#200,#450);",
        f"#8=IFCRELFILLSELEMENT('{guid(8)}',$,$,$,#450,#400);",
        "#10=IFCCARTESIANPOINT((0.,0.,0.));",
        "#11=IFCAXIS2PLACEMENT3D(#10,$,$);",
        "#12=IFCLOCALPLACEMENT($,#11);",
        "#13=IFCDIRECTION((0.,0.,1.));",
        "#20=IFCGEOMETRICREPRESENTATIONCONTEXT($,'Model',3,1.E-05,#11,$);",
        "#21=IFCGEOMETRICREPRESENTATIONSUBCONTEXT('Body','Model',*,*,*,*,#20,$,.MODEL_VIEW.,$);",
    ]
    data += wall_a if wall_a is not None else wall(100, "Wall A", 0.0, 0.0, 5.0)
    data += wall(200, "Wall B", 0.0, 4.0, 5.0)
    data += wall(300, "Wall C", 5.0, 0.0, 4.0)
    # The opening in wall B and its door, both placed relative to wall B.
    data += box(450, "IFCOPENINGELEMENT", "Opening B", 1.0, -0.1, 0.0, 1.0, 0.4, 2.1, ",.OPENING.", "#201")
    data += box(400, "IFCDOOR", "Door 1", 1.0, 0.0, 0.0, 1.0, 0.2, 2.1, ",2.1,1.,.DOOR.,.SINGLE_SWING_LEFT.,$", "#451")
    data += box(500, "IFCSLAB", "Slab", 0.0, 0.0, -0.2, 5.0, 4.2, 0.2, ",.FLOOR.")
    data += extra or []
    return data


def text(data):
    return "\n".join(HEADER + ["DATA;"] + data + ["ENDSEC;", "END-ISO-10303-21;"]) + "\n"


def main():
    if len(sys.argv) != 2:
        sys.exit("usage: make-hostile-corpus.py OUT_DIR")
    out = sys.argv[1]
    os.makedirs(out, exist_ok=True)
    files = {}
    files["base.ifc"] = text(model())
    files["inf-placement.ifc"] = text(model(wall(100, "Wall A", 0, 0, 5.0, point="(1.E400,0.,0.)")))
    files["nan-placement.ifc"] = text(model(wall(100, "Wall A", 0, 0, 5.0, point="(NaN,0.,0.)")))
    files["inf-profile.ifc"] = text(model(wall(100, "Wall A", 0, 0, 5.0, profile_xdim="1.E400")))
    files["nan-profile.ifc"] = text(model(wall(100, "Wall A", 0, 0, 5.0, profile_xdim="NaN")))
    files["zero-depth.ifc"] = text(model(wall(100, "Wall A", 0, 0, 5.0, depth="0.")))
    files["rect-xdim-zero.ifc"] = text(model(wall(100, "Wall A", 0, 0, 5.0, profile_xdim="0.")))
    files["polyline-2-points.ifc"] = text(
        model(
            wall(
                100,
                "Wall A",
                0,
                0,
                5.0,
                profile=[
                    "#107=IFCARBITRARYCLOSEDPROFILEDEF(.AREA.,$,#110);",
                    "#110=IFCPOLYLINE((#111,#112));",
                    "#111=IFCCARTESIANPOINT((0.,0.));",
                    "#112=IFCCARTESIANPOINT((5.,0.2));",
                ],
            )
        )
    )
    files["polyline-self-intersecting.ifc"] = text(
        model(
            wall(
                100,
                "Wall A",
                0,
                0,
                5.0,
                profile=[
                    "#107=IFCARBITRARYCLOSEDPROFILEDEF(.AREA.,$,#110);",
                    "#110=IFCPOLYLINE((#111,#112,#113,#114,#111));",
                    "#111=IFCCARTESIANPOINT((0.,0.));",
                    "#112=IFCCARTESIANPOINT((5.,0.2));",
                    "#113=IFCCARTESIANPOINT((5.,0.));",
                    "#114=IFCCARTESIANPOINT((0.,0.2));",
                ],
            )
        )
    )
    files["opening-zero-depth.ifc"] = text(
        model(
            extra=box(700, "IFCOPENINGELEMENT", "Flat opening", 1.0, -0.1, 0.0, 1.0, 0.4, 0.0, ",.OPENING.", "#101")
            + [f"#9=IFCRELVOIDSELEMENT('{guid(9)}',$,$,$,#100,#700);"]
        )
    )
    files["opening-bigger-than-wall.ifc"] = text(
        model(
            extra=box(700, "IFCOPENINGELEMENT", "Huge opening", -1.0, -1.0, -1.0, 7.0, 2.2, 5.0, ",.OPENING.", "#101")
            + [f"#9=IFCRELVOIDSELEMENT('{guid(9)}',$,$,$,#100,#700);"]
        )
    )
    files["door-without-geometry.ifc"] = text(
        model(
            extra=[
                f"#600=IFCDOOR('{guid(600)}',$,'Door 2',$,$,#601,$,$,2.1,0.9,.DOOR.,.SINGLE_SWING_LEFT.,$);",
                "#601=IFCLOCALPLACEMENT(#12,#11);",
            ],
            contained_extra=",#600",
        )
    )
    # Truncations of the base file: at each section keyword (before it and after it) and
    # in the middle of an instance line.
    base = files["base.ifc"]
    lines = base.splitlines(keepends=True)
    cuts = []

    def offset_of_line(i):
        return sum(len(x) for x in lines[:i])

    for i, line in enumerate(lines):
        s = line.strip()
        name = s.rstrip(";").split("(")[0].lower().replace("-", "")
        if s in ("ISO-10303-21;", "HEADER;", "ENDSEC;", "DATA;", "END-ISO-10303-21;") or s.startswith("FILE_"):
            kind = "data-endsec" if s == "ENDSEC;" and i > 8 else name
            cuts.append((f"before-{kind}", offset_of_line(i)))
            cuts.append((f"after-{kind}", offset_of_line(i) + len(line.rstrip("\n"))))
    mid = next(i for i, l in enumerate(lines) if l.startswith("#200="))
    cuts.append(("mid-instance-200", offset_of_line(mid) + len(lines[mid]) // 2))
    cuts.append(("mid-string-200", offset_of_line(mid) + lines[mid].index("'") + 5))
    seen = set()
    n = 0
    for what, at in sorted(cuts, key=lambda c: c[1]):
        if at in seen or at >= len(base.rstrip("\n")):
            continue
        seen.add(at)
        files[f"truncated-{n:02d}-{what}.ifc"] = base[:at]
        n += 1
    for name, body in files.items():
        with open(os.path.join(out, name), "w", newline="\n") as f:
            f.write(body)
    print(f"wrote {len(files)} files to {out}")


if __name__ == "__main__":
    main()
