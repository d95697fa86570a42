"""Writes the bundled example faces into examples/*.brep (units: mm).

Run with FreeCAD's Python (headless):

    PYTHONPATH=/usr/lib/freecad-python3/lib /usr/bin/python3 examples/make_examples.py

Each file holds exactly one face. The script checks every face (valid, number of
wires, area) and fails loudly if one is off, so the files stay trustworthy.
"""

import math
import os
import sys

import FreeCAD  # noqa: F401  (must come before Part, see DESIGN.md)
import Part
from FreeCAD import Base, Vector

HERE = os.path.dirname(os.path.abspath(__file__))

#: name -> (builder, expected wire count, (min area, max area) in mm^2, description)
EXAMPLES = {}


def example(name, wires, area_range, description):
    def register(builder):
        EXAMPLES[name] = (builder, wires, area_range, description)
        return builder

    return register


def _single_face(shape):
    faces = shape.Faces
    if len(faces) != 1:
        raise RuntimeError(f"expected one face, got {len(faces)}")
    return faces[0]


@example(
    "trimmed_bspline_holes",
    3,
    (1.7e8, 2.4e8),
    "doubly curved B-spline, ~20 m x 14 m, non-uniform knots, curved irregular "
    "outline, a circular and an elliptic hole",
)
def trimmed_bspline_holes():
    # 7 x 6 poles, degree 3 x 3, covering 22 m x 16 m (the outline trims it to ~20 x 14).
    # Interior knots are clustered so equal parameter steps give very unequal lengths.
    xs = [-1000.0, 1500.0, 3500.0, 9000.0, 15000.0, 19500.0, 21000.0]
    ys = [-1000.0, 2500.0, 5000.0, 9500.0, 13000.0, 15000.0]
    poles = []
    for i, x in enumerate(xs):
        row = []
        for j, y in enumerate(ys):
            # A saddle plus a bump: doubly curved, with both signs of Gauss curvature.
            sx = (x - 10000.0) / 11000.0
            sy = (y - 7000.0) / 8000.0
            z = 2500.0 * sx * sx - 1800.0 * sy * sy + 1200.0 * math.sin(2.1 * i + 0.7 * j)
            row.append(Vector(x, y, z))
        poles.append(row)
    # Knot range not [0, 1] either: an imported surface rarely has it.
    uknots = [0.0, 4.4, 7.4, 27.8, 37.0]  # 7 poles, degree 3 -> 3 interior knots
    umults = [4, 1, 1, 1, 4]
    vknots = [5.0, 6.4, 9.2, 19.0]  # 6 poles, degree 3 -> 2 interior knots
    vmults = [4, 1, 1, 4]
    surface = Part.BSplineSurface()
    surface.buildFromPolesMultsKnots(
        poles, umults, vmults, uknots, vknots, False, False, 3, 3
    )

    # The trims are drawn in plan (x, y) and mapped into the surface's (u, v): the
    # poles' x depends on i only and y on j only, so x(u, v) = X(u), y(u, v) = Y(v),
    # both increasing. The loops become 2D splines in (u, v) (the pcurves); their 3D
    # curves are built from them. The file stays small and the trims exact in uv.
    def plan_to_uv(x, y):
        return Base.Vector2d(_invert(lambda u: surface.value(u, 5.0).x, 0.0, 37.0, x),
                             _invert(lambda v: surface.value(0.0, v).y, 5.0, 19.0, y))

    def loop(plan_points, clockwise):
        uv = [plan_to_uv(x, y) for x, y in plan_points]
        if (_signed_area(uv) < 0.0) != clockwise:
            uv.reverse()
        curve = Part.Geom2d.BSplineCurve2d()
        curve.interpolate(Points=uv, PeriodicFlag=True)
        return Part.Wire([curve.toShape(surface)])

    # Irregular curved outline, ~20 m x 14 m in plan.
    n = 40
    outline = []
    for k in range(n):
        t = 2.0 * math.pi * k / n
        r = 1.0 + 0.06 * math.sin(3.0 * t) + 0.04 * math.cos(5.0 * t + 0.4)
        outline.append((10000.0 + 9800.0 * r * math.cos(t),
                        7000.0 + 7000.0 * r * math.sin(t) * (1.0 - 0.12 * math.cos(t))))
    # Holes: a circle (r 1.2 m) and an ellipse (2.0 m x 1.0 m, turned 30 degrees).
    circle = [(5200.0 + 1200.0 * math.cos(t), 6200.0 + 1200.0 * math.sin(t))
              for t in (2.0 * math.pi * k / 24 for k in range(24))]
    a = math.radians(30.0)
    ellipse = []
    for k in range(24):
        t = 2.0 * math.pi * k / 24
        ex, ey = 2000.0 * math.cos(t), 1000.0 * math.sin(t)
        ellipse.append((13800.0 + ex * math.cos(a) - ey * math.sin(a),
                        8200.0 + ex * math.sin(a) + ey * math.cos(a)))

    face = Part.Face(surface, loop(outline, clockwise=False))
    face.cutHoles([loop(circle, clockwise=True), loop(ellipse, clockwise=True)])
    face.fix(1e-7, 1e-7, 1e-3)  # orients the hole wires; geometry stays as built
    return face


def _invert(f, lo, hi, target, iterations=80):
    """The parameter t in [lo, hi] with f(t) = target, f increasing (bisection)."""
    for _ in range(iterations):
        mid = 0.5 * (lo + hi)
        if f(mid) < target:
            lo = mid
        else:
            hi = mid
    return 0.5 * (lo + hi)


def _signed_area(points):
    return 0.5 * sum(p.x * q.y - q.x * p.y for p, q in zip(points, points[1:] + points[:1]))


@example("bezier_patch", 1, (0.9e8, 1.4e8), "Bezier surface, degree 3 x 3, ~10 m x 10 m")
def bezier_patch():
    surface = Part.BezierSurface()
    surface.increase(3, 3)
    heights = [
        [0.0, 600.0, 900.0, 200.0],
        [700.0, 2200.0, 1800.0, 900.0],
        [500.0, 1600.0, 2600.0, 1200.0],
        [0.0, 800.0, 1100.0, 300.0],
    ]
    for i in range(4):
        for j in range(4):
            surface.setPole(i + 1, j + 1, Vector(i * 10000.0 / 3.0, j * 10000.0 / 3.0, heights[i][j]))
    return _single_face(surface.toShape())


@example("cylinder_part", 1, (0.8e8, 0.88e8), "partial cylinder, R 5 m, 120 degrees, height 8 m")
def cylinder_part():
    cylinder = Part.Cylinder()
    cylinder.Radius = 5000.0
    return _single_face(cylinder.toShape(0.0, 2.0 * math.pi / 3.0, 0.0, 8000.0))


@example("plane", 2, (2.2e7, 2.2e7), "plane 6 m x 4 m with a 2 m x 1 m rectangular hole")
def plane():
    sheet = Part.makePlane(6000.0, 4000.0)
    hole = Part.makeBox(2000.0, 1000.0, 200.0, Vector(2500.0, 1200.0, -100.0))
    return _single_face(sheet.cut(hole))


@example("full_cylinder", 1, (1.1e8, 1.15e8), "full periodic cylinder with seam, R 3 m, height 6 m")
def full_cylinder():
    solid = Part.makeCylinder(3000.0, 6000.0)
    lateral = [f for f in solid.Faces if f.Surface.TypeId == "Part::GeomCylinder"]
    return _single_face(Part.Compound(lateral))


def _prism_tool(profile_2d, origin, x_axis, z_axis, depth):
    """A solid: the closed 2D profile [(x, z), ...] (or a Part.Wire builder) drawn in
    the plane through `origin` spanned by x_axis and z_axis, extruded both ways
    along their normal by `depth` (mm). Used to cut openings and notches."""
    normal = x_axis.cross(z_axis)
    normal.normalize()

    def to3d(x, z):
        return origin + x_axis * x + z_axis * z

    if callable(profile_2d):
        wire = profile_2d(to3d)
    else:
        pts = [to3d(x, z) for x, z in profile_2d]
        wire = Part.makePolygon(pts + pts[:1])
    face = Part.Face(wire)
    face.translate(normal * -depth)
    return face.extrude(normal * (2 * depth))


def _circle_wire(cx, cz, r):
    def build(to3d):
        pts = [to3d(cx + r * math.cos(2 * math.pi * k / 64), cz + r * math.sin(2 * math.pi * k / 64))
               for k in range(64)]
        spline = Part.BSplineCurve()
        spline.interpolate(pts, PeriodicFlag=True)
        return Part.Wire([spline.toShape()])

    return build


def _ellipse_wire(cx, cz, a, b, turn):
    def build(to3d):
        pts = []
        for k in range(64):
            t = 2 * math.pi * k / 64
            x, z = a * math.cos(t), b * math.sin(t)
            c, s = math.cos(turn), math.sin(turn)
            pts.append(to3d(cx + c * x - s * z, cz + s * x + c * z))
        spline = Part.BSplineCurve()
        spline.interpolate(pts, PeriodicFlag=True)
        return Part.Wire([spline.toShape()])

    return build


@example(
    "cone_facade",
    3,
    (1.2e8, 1.9e8),
    "partial cone (R 14 m to 9 m, 100 degrees, 10 m high) trimmed by six curves like the "
    "west facade of seed 001 section 4.1: a curved sloping top, a round bite and a door "
    "notch in the outline, an elliptic and a round opening",
)
def cone_facade():
    r1, r2, h, sweep = 14000.0, 9000.0, 10000.0, 100.0
    cone = Part.makeCone(r1, r2, h, Vector(0, 0, 0), Vector(0, 0, 1), sweep)
    face = [f for f in cone.Faces if f.Surface.TypeId == "Part::GeomCone"][0]
    mid = math.radians(sweep / 2)
    view = Vector(math.cos(mid), math.sin(mid), 0)  # facade normal at its middle
    x_axis = Vector(-math.sin(mid), math.cos(mid), 0)
    z_axis = Vector(0, 0, 1)
    origin = view * 11500.0
    depth = 20000.0
    tools = []

    # 1. curved sloping top: everything above a spline from (left, 9.2 m) to (right, 6.5 m)
    def top(to3d):
        xs = [-13000.0 + 2600.0 * k for k in range(11)]
        curve_pts = [to3d(x, 7900.0 - 1350.0 * math.sin(x / 9000.0) + 500.0 * math.cos(x / 3000.0))
                     for x in xs]
        spline = Part.BSplineCurve()
        spline.interpolate(curve_pts)
        a, b = curve_pts[0], curve_pts[-1]
        up_b, up_a = to3d(13000.0, 20000.0), to3d(-13000.0, 20000.0)
        return Part.Wire([spline.toShape(), Part.makeLine(b, up_b), Part.makeLine(up_b, up_a),
                          Part.makeLine(up_a, a)])

    tools.append(_prism_tool(top, origin, x_axis, z_axis, depth))
    # 2. a round bite out of the lower right corner (notch in the outline)
    tools.append(_prism_tool(_circle_wire(10500.0, 700.0, 2600.0), origin, x_axis, z_axis, depth))
    # 3. a door notch in the bottom edge, with a round arch
    def door(to3d):
        w, hh = 1400.0, 2600.0
        left = [to3d(-3000.0 - w, -1000.0), to3d(-3000.0 - w, hh)]
        right = [to3d(-3000.0 + w, hh), to3d(-3000.0 + w, -1000.0)]
        arch = Part.Arc(left[1], to3d(-3000.0, hh + w), right[0]).toShape()
        return Part.Wire([Part.makeLine(left[0], left[1]), arch, Part.makeLine(right[0], right[1]),
                          Part.makeLine(right[1], left[0])])

    tools.append(_prism_tool(door, origin, x_axis, z_axis, depth))
    # 4.-5. an elliptic and a round opening
    tools.append(_prism_tool(_ellipse_wire(3500.0, 4300.0, 2300.0, 1200.0, 0.35), origin, x_axis,
                             z_axis, depth))
    tools.append(_prism_tool(_circle_wire(-7500.0, 5200.0, 1100.0), origin, x_axis, z_axis, depth))
    shape = face
    for t in tools:
        shape = shape.cut(t)
    return _single_face(shape)


@example(
    "notched_shell",
    3,
    (1.3e8, 2.0e8),
    "doubly curved B-spline shell ~18 m x 12 m with three notches in its outline (corner, "
    "edge, V) and two openings (rotated rectangle, circle)",
)
def notched_shell():
    nu, nv = 6, 5
    poles = []
    for i in range(nu):
        row = []
        for j in range(nv):
            x, y = -500.0 + 3800.0 * i, -500.0 + 3200.0 * j
            z = 1500.0 * math.cos(0.8 * i - 1.5) * math.sin(0.6 * j + 0.4) + 90.0 * i * j
            row.append(Vector(x, y, z))
        poles.append(row)
    surface = Part.BSplineSurface()
    surface.buildFromPolesMultsKnots(poles, [4, 1, 1, 4], [4, 1, 4], [0.0, 0.3, 0.55, 1.0],
                                     [0.0, 0.4, 1.0], False, False, 3, 3)
    base = surface.toShape()
    down, up = Vector(0, 0, -8000), Vector(0, 0, 16000)

    def prism(points):
        pts = [Vector(x, y, 0) + down for x, y in points]
        return Part.Face(Part.makePolygon(pts + pts[:1])).extrude(up)

    outline = prism([(0, 0), (18000, 0), (18000, 12000), (0, 12000)])
    shape = base.common(outline)
    shape = shape.cut(prism([(-100, 8500), (3500, 8500), (3500, 12100), (-100, 12100)]))  # corner
    shape = shape.cut(prism([(8000, -100), (10500, -100), (10500, 2600), (8000, 2600)]))  # edge
    shape = shape.cut(prism([(18100, 4500), (15200, 6500), (18100, 8500)]))  # V notch
    c, s = math.cos(0.5), math.sin(0.5)
    rect = [(-1500, -900), (1500, -900), (1500, 900), (-1500, 900)]
    shape = shape.cut(prism([(5500 + c * x - s * y, 5000 + s * x + c * y) for x, y in rect]))
    shape = shape.cut(Part.makeCylinder(1300, 24000, Vector(12500, 7200, -8000)))
    return _single_face(shape)


@example(
    "vault_openings",
    4,
    (1.6e8, 2.2e8),
    "partial cylinder vault (R 7 m, 140 degrees, 12 m long) with an arched door notch in "
    "one long edge and three round windows",
)
def vault_openings():
    cyl = Part.makeCylinder(7000.0, 12000.0, Vector(0, 0, 0), Vector(1, 0, 0), 140.0)
    face = [f for f in cyl.Faces if f.Surface.TypeId == "Part::GeomCylinder"][0]
    shape = face
    surf = face.Surface
    u_end = face.ParameterRange[1]
    # windows: radial prisms through the vault at three positions
    for k, (u, x) in enumerate(((0.55, 2500.0), (1.2, 6000.0), (1.85, 9500.0))):
        radial = surf.value(u, 0.0)
        radial.normalize()
        x_axis = Vector(1, 0, 0)
        z_axis = radial.cross(x_axis)
        tool = _prism_tool(_circle_wire(0.0, 0.0, 900.0 + 150.0 * k), Vector(x, 0, 0) + radial * 7000.0,
                           x_axis, z_axis, 3000.0)
        shape = shape.cut(tool)
    # an arched door notch in the long edge at u = u_end, drawn in the tangent plane there
    edge_point = surf.value(u_end, 0.0)
    inward = surf.tangent(u_end, 0.0)[0] * -1.0  # toward smaller u, into the face

    def door(to3d):
        w, hh = 1300.0, 2200.0
        a, b = to3d(6000.0 - w, -1000.0), to3d(6000.0 - w, hh)
        c, d = to3d(6000.0 + w, hh), to3d(6000.0 + w, -1000.0)
        arch = Part.Arc(b, to3d(6000.0, hh + w), c).toShape()
        return Part.Wire([Part.makeLine(a, b), arch, Part.makeLine(c, d), Part.makeLine(d, a)])

    shape = shape.cut(_prism_tool(door, edge_point, Vector(1, 0, 0), inward, 3000.0))
    return _single_face(shape)


def check(name, face, wires, area_range):
    problems = []
    if face.ShapeType != "Face":
        problems.append(f"not a face ({face.ShapeType})")
    if not face.isValid():
        problems.append("face.isValid() is False")
    if len(face.Wires) != wires:
        problems.append(f"{len(face.Wires)} wires, expected {wires}")
    lo, hi = area_range
    if not lo <= face.Area <= hi:
        problems.append(f"area {face.Area:.4g} outside [{lo:.4g}, {hi:.4g}]")
    if problems:
        raise RuntimeError(f"{name}: " + "; ".join(problems))


def main(out_dir=HERE):
    for name, (builder, wires, area_range, description) in EXAMPLES.items():
        face = builder()
        check(name, face, wires, area_range)
        path = os.path.join(out_dir, name + ".brep")
        face.exportBrep(path)
        # Read back: what the demo and the tests will see.
        back = Part.Shape()
        back.read(path)
        check(name, _single_face(back), wires, area_range)
        bb = face.optimalBoundingBox()
        print(
            f"{name:24s} {face.Surface.TypeId:22s} wires={len(face.Wires)} "
            f"area={face.Area / 1e6:8.2f} m2  box={bb.XLength / 1000:.1f} x "
            f"{bb.YLength / 1000:.1f} x {bb.ZLength / 1000:.1f} m  "
            f"{os.path.getsize(path) / 1024:.0f} KiB"
        )
    return 0


if __name__ == "__main__":
    sys.exit(main())
