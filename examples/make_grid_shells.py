"""Writes examples/sun_valley_funnel.brep and examples/chen_shan_dome.brep: the
two grid shells of seed 004's case studies besides the British Museum roof
(sections 5.2.1 and 6.2), each as one B-spline face (units: mm).

Run with FreeCAD's Python (headless):

    PYTHONPATH=/usr/lib/freecad-python3/lib /usr/bin/python3 examples/make_grid_shells.py

Sun Valley funnel (Shanghai Expo 2010; paper section 6.2.2): half of a shell
of revolution, top circle 90 m across, bottom circle 20 m, height 41.5 m. The
paper gives only these figures; the profile chosen here is the trumpet
r(z) = 10 + 35 (z / 41.5)^2 m, vertical at the foot. As a curve it is the
quadratic Bezier with poles (10, 0), (10, 20.75), (45, 41.5) m in (r, z), so
the profile is exact, and revolving it by 0..180 degrees about the z axis
(Part.SurfaceOfRevolution, then toNurbs()) gives a rational B-spline surface
of degree 2 x 2 that is the exact surface of revolution. The face is
non-periodic (half shell, y >= 0) with one wire of four edges: the bottom and
top semicircles and the two profile sides at theta = 0 (x > 0) and 180 deg.

Chen Shan conservatory (Shanghai Chen Shan Botanical Gardens; section 5.2.1):
a dome with a 'bean'-shaped plan. The paper gives no sizes; chosen here:
about 90 m long, 46 m wide, 20 m high. Construction: an ellipse with
semi-axes A = 50 m and B = 20 m in coordinates (X, Y) is bent along a circle
of radius RB = 45 m centred on the concave (inner, +y) side,

    x = (RB - Y) sin(X / RB),   y = RB - (RB - Y) cos(X / RB),

(X = arc length along the bent spine Y = 0, Y = offset towards the centre),
and the height is z = H (1 - (X/A)^2 - (Y/B)^2) with H = 20 m, zero on the
outline. (With A = 45, B = 22, RB = 70 m the inner side of the plan is not
concave: a bent ellipse shows a concave side only where the bending curvature
beats the ellipse's own curvature B / A^2 at its vertex, and the tips must
bend for the plan to read as a bean; A = 50, B = 20, RB = 45 m gives a plan
of 90.4 m x 46.0 m whose inner side is 6 m deep.) z is sampled through the
inverse mapping X = RB atan2(x, RB - y), Y = RB - hypot(x, RB - y) on a
~1.5 m grid over the outline's plan box plus 3 m (outside the bean z < 0),
a cubic B-spline surface interpolates the samples (its parameters are x and
y in mm), and the part inside the outline is kept: a closed B-spline through
256 outline points, extruded to a prism, face.common(prism). The result is
one trimmed face with one outer wire (one periodic edge).

Checks (the script fails loudly otherwise): each face valid, alone, with the
expected wires and edges; the funnel's circles at the right heights and
lengths and profile points on the face; the dome's outline at z ~ 0
(within 1 mm), its top at H, its plan at the analytic outline's extent
(within 50 mm); and face.Area within 0.5% of an independent numeric
estimate that does not go through OCCT: for the funnel pi * integral of r ds
(Simpson's rule on the profile), for the dome the integral of the analytic
surface's area element over the ellipse in (X, Y) (Gauss-Legendre radially,
trapezoids in the angle). The funnel's face.Area reads 0.14% high: OCCT's
area integration (GProp) on this rational surface, not the geometry (its
points are exact, and integrating |S_u x S_v| on a fine (u,v) grid gives the
estimate to 1e-6).
"""

import math
import os
import sys

import numpy as np

import FreeCAD  # noqa: F401  (must come before Part, see DESIGN.md)
import Part
from FreeCAD import Vector

HERE = os.path.dirname(os.path.abspath(__file__))
FUNNEL_OUT = os.path.join(HERE, "sun_valley_funnel.brep")
DOME_OUT = os.path.join(HERE, "chen_shan_dome.brep")

# Sun Valley funnel (metres).
R_BOTTOM = 10.0
R_TOP = 45.0
HEIGHT = 41.5

# Chen Shan dome (metres).
A = 50.0  # half length of the bent spine
B = 20.0  # half width
RB = 45.0  # bending radius of the spine
H = 20.0  # height
GRID_STEP = 1.5
GRID_MARGIN = 3.0
OUTLINE_POINTS = 256


def funnel_radius(z):
    """r(z) of the trumpet profile, metres."""
    return R_BOTTOM + (R_TOP - R_BOTTOM) * (z / HEIGHT) ** 2


def funnel_point(theta, z):
    """Point of the funnel at angle theta (rad) and height z (m), in mm."""
    r = funnel_radius(z)
    return Vector(r * math.cos(theta) * 1000.0, r * math.sin(theta) * 1000.0, z * 1000.0)


def build_funnel():
    profile = Part.BSplineCurve()
    poles = [Vector(R_BOTTOM, 0, 0), Vector(R_BOTTOM, 0, HEIGHT / 2), Vector(R_TOP, 0, HEIGHT)]
    profile.buildFromPolesMultsKnots([p * 1000.0 for p in poles], [3, 3], [0.0, 1.0], False, 2)
    revolution = Part.SurfaceOfRevolution(profile, Vector(0, 0, 0), Vector(0, 0, 1))
    faces = revolution.toShape(0.0, math.pi, 0.0, 1.0).toNurbs().Faces
    if len(faces) != 1:
        raise RuntimeError(f"expected one funnel face, got {len(faces)}")
    return faces[0]


def funnel_area_estimate(n=2000):
    """Half of 2 pi * integral of r ds over the profile (Simpson), m2."""
    h = HEIGHT / n
    total = 0.0
    for k in range(n + 1):
        z = k * h
        drdz = 2.0 * (R_TOP - R_BOTTOM) * z / HEIGHT ** 2
        f = funnel_radius(z) * math.sqrt(1.0 + drdz * drdz)
        total += f * (1 if k in (0, n) else 4 if k % 2 else 2)
    return math.pi * total * h / 3.0


def check_area(face, estimate, problems):
    """(area in m2, estimate, problems): the face's area within 0.5% of the
    independent estimate (m2)."""
    area_m2 = face.Area / 1e6
    if abs(area_m2 / estimate - 1.0) > 5e-3:
        problems.append(f"area {area_m2:.2f} m2, estimate {estimate:.2f} m2")
    return area_m2, estimate, problems


def check_funnel(face):
    problems = []
    if not face.isValid():
        problems.append("face is not valid")
    surface = face.Surface
    if not isinstance(surface, Part.BSplineSurface):
        problems.append(f"surface is a {type(surface).__name__}, not a BSplineSurface")
    elif surface.isUPeriodic() or surface.isVPeriodic():
        problems.append("surface is periodic")
    if len(face.Wires) != 1 or len(face.Edges) != 4:
        problems.append(f"expected 1 wire of 4 edges, got {len(face.Wires)} wires, {len(face.Edges)} edges")
    circles = sorted((e for e in face.Edges if e.BoundBox.ZLength < 1e-6), key=lambda e: e.BoundBox.ZMin)
    if len(circles) != 2:
        problems.append(f"expected 2 horizontal edges (semicircles), got {len(circles)}")
    else:
        for edge, r, z in zip(circles, (R_BOTTOM, R_TOP), (0.0, HEIGHT)):
            if abs(edge.Length - math.pi * r * 1000.0) > 1e-3 or abs(edge.BoundBox.ZMin - z * 1000.0) > 1e-3:
                problems.append(f"semicircle at z = {edge.BoundBox.ZMin:.3f} mm has length {edge.Length:.3f} mm, "
                                f"expected pi * {r * 1000:.0f} at z = {z * 1000:.0f}")
    for theta, z in ((0.3, 5.0), (1.6, 20.0), (2.9, 37.0)):
        p = funnel_point(theta, z)
        d = face.distToShape(Part.Vertex(p))[0]
        if d > 1e-3:
            problems.append(f"profile point (theta {theta}, z {z} m) is {d:.4f} mm off the face")
    return check_area(face, funnel_area_estimate(), problems)


def to_plan(X, Y):
    """Bean coordinates (X along the bent spine, Y across it) -> plan (x, y), metres."""
    return (RB - Y) * math.sin(X / RB), RB - (RB - Y) * math.cos(X / RB)


def to_bean(x, y):
    """Plan (x, y) -> bean coordinates (X, Y), metres (the inverse of to_plan)."""
    return RB * math.atan2(x, RB - y), RB - math.hypot(x, RB - y)


def dome_height(x, y):
    """z(x, y) in metres: the elliptic paraboloid in bean coordinates (< 0 outside)."""
    X, Y = to_bean(x, y)
    return H * (1.0 - (X / A) ** 2 - (Y / B) ** 2)


def dome_outline(n=OUTLINE_POINTS):
    """n plan points (m) of the bean outline z = 0, counter-clockwise."""
    return [to_plan(A * math.cos(2 * math.pi * k / n), B * math.sin(2 * math.pi * k / n)) for k in range(n)]


def build_dome():
    outline = dome_outline()
    xs = [p[0] for p in outline]
    ys = [p[1] for p in outline]
    x0 = math.floor(min(xs)) - GRID_MARGIN
    x1 = math.ceil(max(xs)) + GRID_MARGIN
    y0 = math.floor(min(ys)) - GRID_MARGIN
    y1 = math.ceil(max(ys)) + GRID_MARGIN
    nx = round((x1 - x0) / GRID_STEP)
    ny = round((y1 - y0) / GRID_STEP)
    dx = (x1 - x0) / nx
    dy = (y1 - y0) / ny
    z = [[dome_height(x0 + i * dx, y0 + j * dy) * 1000.0 for j in range(ny + 1)] for i in range(nx + 1)]
    surface = Part.BSplineSurface()
    surface.interpolate(z, x0 * 1000.0, dx * 1000.0, y0 * 1000.0, dy * 1000.0)
    plan = Part.BSplineCurve()
    plan.interpolate([Vector(x * 1000.0, y * 1000.0, 0.0) for x, y in outline], PeriodicFlag=True)
    prism = Part.Face(Part.Wire(plan.toShape())).extrude(Vector(0, 0, 3 * H * 1000.0))
    prism.translate(Vector(0, 0, -H * 1000.0))
    faces = Part.Face(surface).common(prism).Faces
    if len(faces) != 1:
        raise RuntimeError(f"expected one face inside the bean outline, got {len(faces)}")
    return faces[0]


def dome_area_estimate(nr=64, nt=720):
    """Area of the analytic dome, m2: integral over the ellipse in (X, Y) of
    sqrt(1 + |grad z|^2) * (plan area element), with X = A rho cos t,
    Y = B rho sin t. The bending is a polar map about (0, RB) with scale
    (RB - Y) / RB along X and 1 along Y (orthogonal)."""
    g, w = np.polynomial.legendre.leggauss(nr)
    rho = 0.5 * (g + 1.0)
    w_rho = 0.5 * w
    t = np.linspace(0.0, 2 * np.pi, nt, endpoint=False)
    rho, t = np.meshgrid(rho, t, indexing="ij")
    X = A * rho * np.cos(t)
    Y = B * rho * np.sin(t)
    scale = (RB - Y) / RB
    zx = -2.0 * H * X / A ** 2 / scale
    zy = -2.0 * H * Y / B ** 2
    integrand = np.sqrt(1.0 + zx ** 2 + zy ** 2) * scale * A * B * rho
    return float((integrand * w_rho[:, None]).sum() * (2 * np.pi / nt))


def check_dome(face):
    problems = []
    if not face.isValid():
        problems.append("face is not valid")
    if not isinstance(face.Surface, Part.BSplineSurface):
        problems.append(f"surface is a {type(face.Surface).__name__}, not a BSplineSurface")
    if len(face.Wires) != 1:
        problems.append(f"expected 1 wire (the outline), got {len(face.Wires)}")
    z_outline = [p.z for p in face.OuterWire.discretize(1000)]
    if min(z_outline) < -1.0 or max(z_outline) > 1.0:
        problems.append(f"outline z in [{min(z_outline):.3f}, {max(z_outline):.3f}] mm, expected ~0")
    top = face.Surface.value(0.0, 0.0).z
    if abs(top - H * 1000.0) > 1.0:
        problems.append(f"top at {top:.3f} mm, expected {H * 1000:.0f}")
    outline = np.array(dome_outline(4096)) * 1000.0
    bb = face.optimalBoundingBox()
    for got, want, name in ((bb.XMin, outline[:, 0].min(), "XMin"), (bb.XMax, outline[:, 0].max(), "XMax"),
                            (bb.YMin, outline[:, 1].min(), "YMin"), (bb.YMax, outline[:, 1].max(), "YMax")):
        if abs(got - want) > 50.0:
            problems.append(f"plan {name} {got:.0f} mm, analytic outline {want:.0f} mm")
    return check_area(face, dome_area_estimate(), problems)


def report(name, face, area_m2, estimate, problems, path):
    bb = face.optimalBoundingBox()
    print(f"{name}: area {area_m2:,.2f} m2 (independent estimate {estimate:,.2f} m2, "
          f"{100 * (area_m2 / estimate - 1):+.3f}%), {bb.XLength / 1000:.2f} m x {bb.YLength / 1000:.2f} m "
          f"x {bb.ZLength / 1000:.2f} m, {len(face.Wires)} wire(s), {len(face.Edges)} edge(s)")
    if problems:
        print(f"{name} FAILED:", "; ".join(problems), file=sys.stderr)
        return 1
    with open(path, "w") as f:
        f.write(face.exportBrepToString())
    print(f"wrote {path}")
    return 0


def main():
    funnel = build_funnel()
    failed = report("Sun Valley funnel", funnel, *check_funnel(funnel), FUNNEL_OUT)
    dome = build_dome()
    failed += report("Chen Shan dome", dome, *check_dome(dome), DOME_OUT)
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
