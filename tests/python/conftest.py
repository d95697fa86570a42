"""Shared fixtures: FreeCAD must be imported before Part (else segfault)."""
import math

import FreeCAD  # noqa: F401  (first, always)
import Part  # noqa: F401
import pytest


@pytest.fixture(scope="session")
def freeform_face():
    """A doubly curved B-spline face, NOT one of the bundled examples: irregular
    curved outline (common with an ellipse-and-notch prism) and two holes."""
    return make_freeform_face()


def make_freeform_face():
    import math

    nu, nv = 6, 5
    surf = Part.BSplineSurface()
    poles = []
    for i in range(nu):
        row = []
        for j in range(nv):
            x, y = 3000.0 * i, 2500.0 * j
            z = 1800.0 * math.sin(0.9 * i) * math.cos(0.7 * j) + 150.0 * i * j
            row.append(FreeCAD.Vector(x, y, z))
        poles.append(row)
    # Uneven knots: the parameterization is not proportional to length.
    surf.buildFromPolesMultsKnots(
        poles, [4, 1, 1, 4], [4, 1, 4], [0.0, 0.15, 0.3, 1.0], [0.0, 0.7, 1.0], False, False, 3, 3
    )
    base = surf.toShape()
    # Irregular outline: an ellipse with a bite taken out, extruded through the surface.
    ell = Part.Ellipse(FreeCAD.Vector(7600, 5000, -5000), 7000, 4600)
    outline = Part.Face(Part.Wire(ell.toShape())).extrude(FreeCAD.Vector(0, 0, 12000))
    bite = Part.makeCylinder(1500, 12000, FreeCAD.Vector(14000, 5200, -5000))
    hole1 = Part.makeCylinder(1100, 12000, FreeCAD.Vector(5000, 4000, -5000))
    hole2 = Part.makeBox(1800, 1200, 12000, FreeCAD.Vector(9000, 6000, -5000))
    hole2 = hole2.rotate(FreeCAD.Vector(9900, 6600, 0), FreeCAD.Vector(0, 0, 1), 30)
    face = base.common(outline).cut(bite).cut(hole1).cut(hole2)
    faces = face.Faces
    assert len(faces) == 1, len(faces)
    f = faces[0]
    assert f.isValid() and len(f.Wires) == 3
    return f


def make_round_trimmed_face():
    """A doubly curved B-spline patch trimmed by a circle, with a circular hole
    (not a bundled example): the fabrication tests' face."""
    import math

    surf = Part.BSplineSurface()
    poles = [[FreeCAD.Vector(2000.0 * i, 1800.0 * j,
                             900 * math.sin(0.8 * i + 0.3) * math.cos(0.9 * j) + 60 * i * j)
              for j in range(5)] for i in range(5)]
    surf.buildFromPolesMultsKnots(poles, [4, 1, 4], [4, 1, 4], [0, 0.4, 1], [0, 0.6, 1],
                                  False, False, 3, 3)
    trim = Part.makeCylinder(3800, 20000, FreeCAD.Vector(4000, 3600, -10000))
    hole = Part.makeCylinder(1300, 20000, FreeCAD.Vector(4200, 3900, -10000))
    faces = surf.toShape().common(trim).cut(hole).Faces
    assert len(faces) == 1 and len(faces[0].Wires) == 2
    return faces[0]


def dense_quad_deviation(surface, p, n=40):
    """Largest distance of the bilinear patch of the quad p (4 x 3 corners) to
    the surface, by FreeCAD's own projection (Surface.parameter + value) of
    (n + 1)^2 points: an independent dense re-measure of panel_deviation."""
    import math

    import numpy as np

    s = np.linspace(0.0, 1.0, n + 1)
    S, T = np.meshgrid(s, s)
    S, T = S.ravel()[:, None], T.ravel()[:, None]
    pts = (1 - S) * (1 - T) * p[0] + S * (1 - T) * p[1] + S * T * p[2] + (1 - S) * T * p[3]
    worst = 0.0
    for x in pts:
        u, v = surface.parameter(FreeCAD.Vector(*x))
        q = surface.value(u, v)
        worst = max(worst, math.dist((q.x, q.y, q.z), x))
    return worst


def independent_coverage(face, r, samples=3000):
    """(gap, overlap + outside) as shares of the face's surface area, by random
    points of the face's parameter range weighted by |Su x Sv|."""
    import numpy as np
    from matplotlib.path import Path

    rng = np.random.default_rng(5)
    u0, u1, v0, v1 = face.ParameterRange
    pts = np.column_stack([rng.uniform(u0, u1, samples), rng.uniform(v0, v1, samples)])
    surf = face.Surface
    inside = np.array([face.isPartOfDomain(u, v) for u, v in pts])
    weight = np.array([
        np.linalg.norm(np.cross(np.array(surf.getDN(u, v, 1, 0)), np.array(surf.getDN(u, v, 0, 1))))
        for u, v in pts])
    count = np.zeros(samples, int)
    uv = np.asarray(r.uv)
    for p in r.panels:
        count += Path(uv[list(p)]).contains_points(pts)
    total = (weight * inside).sum()
    gap = (weight * (inside & (count == 0))).sum() / total
    extra = (weight * (np.maximum(count - 1, 0) + ((~inside) & (count > 0)))).sum() / total
    return gap, extra


def widest_turn_round_z(r):
    """The largest angle round the z axis one panel's corners span (those off
    the axis): per panel 2 pi less the largest gap between their sorted
    angles. A panel at pi or more is half way round a closed face."""
    import numpy as np

    out = []
    for p in r.panels:
        x = r.vertices[list(p)]
        x = x[np.hypot(x[:, 0], x[:, 1]) > 1e-6]
        a = np.sort(np.mod(np.arctan2(x[:, 1], x[:, 0]), 2 * math.pi))
        gaps = np.diff(np.append(a, a[0] + 2 * math.pi))
        out.append(2 * math.pi - gaps.max())
    return max(out)


def diagonal_distance(p):
    """Distance between a quad's diagonals (as skew lines): its warp, computed
    here independently of the core."""
    import numpy as np

    d1, d2 = p[2] - p[0], p[3] - p[1]
    n = np.cross(d1, d2)
    return abs(np.dot(p[1] - p[0], n)) / np.linalg.norm(n)


def close_node_pairs(nodes, tol):
    """Index pairs of points closer than tol (a grid of tol-sized cells)."""
    import numpy as np

    cells = {}
    for k, key in enumerate(map(tuple, np.floor(nodes / tol).astype(np.int64))):
        cells.setdefault(key, []).append(k)
    pairs = []
    for (x, y, z), members in cells.items():
        for dx in (-1, 0, 1):
            for dy in (-1, 0, 1):
                for dz in (-1, 0, 1):
                    for j in cells.get((x + dx, y + dy, z + dz), ()):
                        pairs += [(i, j) for i in members
                                  if i < j and np.linalg.norm(nodes[i] - nodes[j]) <= tol]
    return pairs


def reopened(doc, path, name):
    """Save `doc` to `path`, close it, open it again and recompute the object
    `name` from scratch (touched): (the reopened document, that object)."""
    import FreeCAD

    doc.saveAs(path)
    FreeCAD.closeDocument(doc.Name)
    doc = FreeCAD.openDocument(path)
    obj = doc.getObject(name)
    obj.touch()
    doc.recompute()
    return doc, obj
