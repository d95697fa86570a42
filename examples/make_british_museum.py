"""Writes examples/british_museum_roof.brep: the British Museum Great Court roof
as one trimmed B-spline face (units: mm), built from Chris Williams' analytic
definition (2001) as given in shared/reference/british_museum_roof.md.

Run with FreeCAD's Python (headless):

    PYTHONPATH=/usr/lib/freecad-python3/lib /usr/bin/python3 examples/make_british_museum.py

Construction: z(x, y) is sampled on a ~1 m grid over the court rectangle
(x in [-b, b], y in [-d, c]; origin at the Reading Room centre, y north), a
cubic B-spline surface interpolates the samples, and the Reading Room drum
(the cylinder r = a) is cut out of it, leaving a face with one hole. The
analytic formula is only valid for r >= a; inside the drum (which becomes the
hole) it is continued radially (r clamped to 0.8 a) so the interpolant has no
kink near the drum edge.

The script checks the face (one face, two wires, z = h_edg on the rectangle,
z = h_cen on the drum) and prints its area next to the published ~6,100 m2
of glazing; it fails loudly if the area leaves [6,000, 6,200] m2.
"""

import math
import os
import sys

import FreeCAD  # noqa: F401  (must come before Part, see DESIGN.md)
import Part
from FreeCAD import Vector

HERE = os.path.dirname(os.path.abspath(__file__))
OUT = os.path.join(HERE, "british_museum_roof.brep")

# Williams' constants (metres).
A = 22.245  # drum radius
B = 36.625  # half width, x in [-B, B]
C = 46.025  # north edge, y <= C
D = 51.125  # south edge, y >= -D
LAMBDA = 0.5
MU = 14.0
H_CEN = 20.955
H_EDG = 19.71

PUBLISHED_GLAZING_M2 = 6100.0


def _q(s, t):
    return math.sqrt(s * s + t * t) / (s * t)


def roof_height(x, y):
    """z(x, y) in metres for r >= A inside the rectangle (Williams 2001)."""
    r = math.hypot(x, y)
    theta = math.asin(max(-1.0, min(1.0, y / r)))
    s = math.sin(theta)
    c2 = math.cos(2.0 * theta)
    psi = (1 - x / B) * (1 + x / B) * (1 - y / C) * (1 + y / D)
    k = A / r
    eta = psi / ((1 - k * x / B) * (1 + k * x / B) * (1 - k * y / C) * (1 + k * y / D))
    alpha = (r / A - 1) * psi
    qsum = _q(B - x, C - y) + _q(B - x, D + y) + _q(B + x, C - y) + _q(B + x, D + y)
    beta = (1 - A / r) / qsum
    z1 = (H_CEN - H_EDG) * eta + H_EDG
    p = (1 - c2) / 2 + s
    m = (1 - c2) / 2 - s
    z2 = alpha * (
        (1 - LAMBDA) * ((35 + 10 * psi) * (1 + c2) / 2 + 12 * p + (7.5 + 12 * psi) * m - 1.6)
        - (5 * (1 + c2) + 10 * (p / 2) ** 2 * (1 - 3 * alpha))
        + 2.5 * (m / 2) ** 2 * (r / A - 1) ** 2
    )
    ex = math.exp(-MU * (1 - x / B)) + math.exp(-MU * (1 + x / B))
    ey = math.exp(-MU * (1 - y / C)) + math.exp(-MU * (1 + y / D))
    z3 = beta * (LAMBDA * (1.75 * (1 + c2) + 1.5 * (1 - c2) + 0.3 * s) + 1.05 * ex * ey)
    return z1 + z2 + z3


def sample_height(x, y):
    """z on the whole rectangle: on its edges the formula's limit, inside the
    drum the formula continued from r = 0.8 A along the radius."""
    eps = 1e-9
    x = max(-B + eps, min(B - eps, x))
    y = max(-D + eps, min(C - eps, y))
    r = math.hypot(x, y)
    r_min = 0.8 * A
    if r < r_min:
        if r < 1e-9:
            x, y = r_min, 0.0
        else:
            x, y = x * r_min / r, y * r_min / r
    return roof_height(x, y)


def build_face(nx=74, ny=98, drum_radius=A):
    """The roof interpolated on (nx + 1) x (ny + 1) samples of the formula, the
    drum (radius in m) cut out. Other samplings and drum radii give the
    independent builds the guide-line tests and benchmarks run on."""
    dx = 2 * B / nx
    dy = (C + D) / ny
    z = [[sample_height(-B + i * dx, -D + j * dy) * 1000.0 for j in range(ny + 1)] for i in range(nx + 1)]
    surface = Part.BSplineSurface()
    surface.interpolate(z, -B * 1000.0, dx * 1000.0, -D * 1000.0, dy * 1000.0)
    roof = Part.Face(surface)
    drum = Part.makeCylinder(drum_radius * 1000.0, 100000.0, Vector(0, 0, -20000.0))
    faces = roof.cut(drum).Faces
    if len(faces) != 1:
        raise RuntimeError(f"expected one face after cutting the drum, got {len(faces)}")
    return faces[0]


def court_edges(face):
    """The four straight court edges by compass side ("west", "east", "south",
    "north"), as indices into face.Edges (they stay valid after the face is
    moved or turned)."""
    bb = face.BoundBox
    sides = {}
    for i, e in enumerate(face.Edges):
        eb = e.BoundBox
        if eb.XLength < 1:
            sides["west" if abs(eb.XMin - bb.XMin) < 1 else "east"] = i
        elif eb.YLength < 1:
            sides["south" if abs(eb.YMin - bb.YMin) < 1 else "north"] = i
    return sides


def check(face):
    problems = []
    if not face.isValid():
        problems.append("face is not valid")
    if len(face.Wires) != 2:
        problems.append(f"expected 2 wires (outline + drum), got {len(face.Wires)}")
    bb = face.BoundBox
    if abs(bb.XLength - 2 * B * 1000) > 1 or abs(bb.YLength - (C + D) * 1000) > 1:
        problems.append(f"plan extent {bb.XLength:.0f} x {bb.YLength:.0f} mm")
    # z = h_edg on the rectangle, h_cen on the drum (within 1 mm).
    for x, y, want in ((0.0, C, H_EDG), (B, 0.0, H_EDG), (-B, -20.0, H_EDG), (A, 0.0, H_CEN), (0.0, -A, H_CEN)):
        got = roof_height(x * (1 - 1e-9), y * (1 - 1e-9)) if (x, y) != (0, 0) else None
        if got is not None and abs(got - want) > 1e-3:
            problems.append(f"analytic z({x}, {y}) = {got:.4f} m, expected {want}")
    area_m2 = face.Area / 1e6
    if not 6000.0 <= area_m2 <= 6200.0:
        problems.append(f"area {area_m2:.1f} m2 outside [6000, 6200]")
    return area_m2, problems


def main():
    face = build_face()
    area_m2, problems = check(face)
    print(f"British Museum roof: area {area_m2:,.1f} m2 (published glazing ~{PUBLISHED_GLAZING_M2:,.0f} m2, "
          f"{100 * (area_m2 / PUBLISHED_GLAZING_M2 - 1):+.2f}%), plan {face.BoundBox.XLength / 1000:.2f} m x "
          f"{face.BoundBox.YLength / 1000:.2f} m, height {face.BoundBox.ZMin / 1000:.3f}-{face.BoundBox.ZMax / 1000:.3f} m")
    if problems:
        print("FAILED:", "; ".join(problems), file=sys.stderr)
        return 1
    with open(OUT, "w") as f:
        f.write(face.exportBrepToString())
    print(f"wrote {OUT}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
