"""Faces for the speed benchmarks, built in code (deterministic, not the bundled
examples): smooth terrain-like bicubic B-spline patches with any pole count,
and trimmed doubly curved faces (a dome with an opening, a saddle trimmed by a
curve, a roof with a drum hole), and random bands closed on themselves
(closed_band). Import FreeCAD before this module."""

import math
import random

import FreeCAD
import Part

V = FreeCAD.Vector


def height(x, y, extent, detail=0.0):
    """A smooth terrain-like height field (mm) on [0, extent]^2: a few long
    waves, and hills `detail` times finer (about `detail` wavelengths across;
    0: none), deterministic."""
    s = x / extent, y / extent
    waves = [(0.08, 1.1, 0.7, 0.3), (0.04, 2.3, 1.9, 1.1), (0.02, 4.1, 3.7, 2.0),
             (0.01, 7.3, 6.1, 0.5)]
    if detail > 0:
        waves += [(0.004, 0.61 * detail, 0.53 * detail, 0.7), (0.002, detail, 0.87 * detail, 1.3)]
    z = 0.0
    for a, fx, fy, ph in waves:
        z += a * extent * math.sin(2 * math.pi * (fx * s[0] + ph)) * math.cos(
            2 * math.pi * (fy * s[1] - 0.5 * ph))
    return z


def _clamped_uniform(n, degree=3):
    """Knots and multiplicities of a clamped uniform B-spline with n poles."""
    spans = n - degree
    knots = [float(i) / spans for i in range(spans + 1)]
    mults = [degree + 1] + [1] * (spans - 1) + [degree + 1]
    return knots, mults


def terrain_face(nu, nv, extent=100000.0):
    """Untrimmed bicubic B-spline face with nu x nv poles over an extent x extent
    square: poles on a regular grid, heights from height() with hills about
    eight pole spacings wide (as fine as the poles can carry)."""
    detail = min(nu, nv) / 8.0
    poles = [[V(extent * i / (nu - 1), extent * j / (nv - 1),
                height(extent * i / (nu - 1), extent * j / (nv - 1), extent, detail))
              for j in range(nv)] for i in range(nu)]
    uk, um = _clamped_uniform(nu)
    vk, vm = _clamped_uniform(nv)
    s = Part.BSplineSurface()
    s.buildFromPolesMultsKnots(poles, um, vm, uk, vk, False, False, 3, 3)
    return s.toShape().Faces[0]


def refined_face(face, nu, nv):
    """The same surface as face's (a B-spline) with simple knots inserted
    until it has nu x nv poles: the same shape, many more poles and spans."""
    s = face.Surface.copy()
    for n_have, n_want, insert in ((s.NbUPoles, nu, s.insertUKnot), (s.NbVPoles, nv, s.insertVKnot)):
        extra = n_want - n_have
        for k in range(extra):
            insert((k + 0.5) / (extra + 1), 1, 1e-12)
    return s.toShape().Faces[0]


def _approx_surface(fn, nu, nv):
    """A bicubic B-spline through fn(s, t) sampled on an nu x nv grid, s, t in [0,1]."""
    pts = [[fn(i / (nu - 1), j / (nv - 1)) for j in range(nv)] for i in range(nu)]
    s = Part.BSplineSurface()
    s.interpolate(pts)
    return s


def _trimmed(surface, outer_uv, holes_uv=()):
    """Face of `surface` trimmed by closed uv loops (lists of (u,v)), each made a
    periodic 2D B-spline on the surface."""
    def wire(loop):
        pts = [FreeCAD.Base.Vector2d(u, v) for u, v in loop]
        c = Part.Geom2d.BSplineCurve2d()
        c.interpolate(pts, PeriodicFlag=True)
        return Part.Wire([c.toShape(surface)])

    face = Part.Face(surface, wire(outer_uv))
    if holes_uv:
        face.cutHoles([wire(h) for h in holes_uv])
    face.validate()
    if not face.isValid():
        raise RuntimeError("benchmark face is not valid")
    return face


def _circle(cx, cy, r, n=48, wobble=0.0):
    return [(cx + r * (1 + wobble * math.sin(3 * a)) * math.cos(a),
             cy + r * (1 + wobble * math.sin(3 * a)) * math.sin(a))
            for a in (2 * math.pi * k / n for k in range(n))]


def dome_with_opening(radius=20000.0):
    """A shallow dome (a paraboloid as a B-spline) trimmed by a wavy outline,
    with an oculus off the centre."""
    def fn(s, t):
        x, y = radius * (2 * s - 1), radius * (2 * t - 1)
        return V(x, y, 0.5 * radius * (1 - 0.35 * (x * x + y * y) / radius ** 2))
    surf = _approx_surface(fn, 9, 9)
    u0, u1, v0, v1 = surf.bounds()
    cu, cv, ru, rv = 0.5 * (u0 + u1), 0.5 * (v0 + v1), 0.5 * (u1 - u0), 0.5 * (v1 - v0)
    outer = [(cu + 0.95 * ru * p, cv + 0.95 * rv * q) for p, q in _circle(0, 0, 1, 64, 0.04)]
    hole = list(reversed([(cu + 0.2 * ru + 0.15 * ru * p, cv + 0.1 * rv + 0.15 * rv * q)
                          for p, q in _circle(0, 0, 1, 32)]))
    return _trimmed(surf, outer, [hole])


def saddle_trimmed(extent=30000.0):
    """A hyperbolic paraboloid trimmed by a smooth closed curve (no hole)."""
    def fn(s, t):
        x, y = extent * (s - 0.5), extent * (t - 0.5)
        return V(x, y, 0.6 * (x * x - y * y) / extent + 0.05 * extent * math.sin(3 * s))
    surf = _approx_surface(fn, 9, 9)
    u0, u1, v0, v1 = surf.bounds()
    cu, cv, ru, rv = 0.5 * (u0 + u1), 0.5 * (v0 + v1), 0.5 * (u1 - u0), 0.5 * (v1 - v0)
    outer = [(cu + 0.9 * ru * (math.cos(a) + 0.08 * math.cos(2 * a)),
              cv + 0.8 * rv * (math.sin(a) + 0.1 * math.sin(3 * a)))
             for a in (2 * math.pi * k / 72 for k in range(72))]
    return _trimmed(surf, outer)


def roof_with_drum(width=70000.0, depth=50000.0, drum=22000.0):
    """A British-Museum-like roof: a doubly curved canopy over a rectangle with a
    round drum hole in the middle, rising towards the drum."""
    def fn(s, t):
        x, y = width * (s - 0.5), depth * (t - 0.5)
        r = math.hypot(x / width, y / depth)
        return V(x, y, 6000.0 * (1 - 1.6 * r * r) + 900.0 * math.cos(3 * math.pi * s))
    surf = _approx_surface(fn, 11, 9)
    u0, u1, v0, v1 = surf.bounds()
    cu, cv, ru, rv = 0.5 * (u0 + u1), 0.5 * (v0 + v1), 0.5 * (u1 - u0), 0.5 * (v1 - v0)
    # Rounded rectangle outline (superellipse) and a circular drum in 3D terms.
    outer = []
    n = 96
    for k in range(n):
        a = 2 * math.pi * k / n
        c, s = math.cos(a), math.sin(a)
        outer.append((cu + 0.97 * ru * math.copysign(abs(c) ** 0.25, c),
                      cv + 0.97 * rv * math.copysign(abs(s) ** 0.25, s)))
    hu, hv = 0.5 * drum / width * 2 * ru, 0.5 * drum / depth * 2 * rv
    hole = list(reversed([(cu + hu * p, cv + hv * q) for p, q in _circle(0, 0, 1, 48)]))
    return _trimmed(surf, outer, [hole])


def closed_band(seed):
    """(face, size) for a random band round the z axis closed on itself: a
    B-spline interpolated through an elliptic section turned by a random
    phase, its first point repeated last (not periodic, as a STEP file's
    surfaces come; its sides meet at a slight crease), its radii shrinking
    upwards, to an apex for about half the seeds, closed along v for about a
    third; size gives about 20, 80 or 300 panels."""
    rng = random.Random(seed)
    around, up = rng.choice([6, 8, 12]), rng.choice([3, 4, 5])
    apex = rng.random() < 0.5
    radii = [1000 * (1 - 0.7 * j / (up - 1)) * (1 + 0.1 * rng.uniform(-1, 1)) for j in range(up)]
    if apex:
        radii[-1] = 0.0
    heights = [j * rng.uniform(300, 700) for j in range(up)]
    phase = rng.uniform(0, 1)
    rows = []
    for k in range(around + 1):
        a = 2 * math.pi * (k % around) / around
        wobble = 1 + 0.15 * math.sin(2 * a + phase)
        rows.append([V(r * wobble * math.cos(a), r * wobble * math.sin(a), z)
                     for r, z in zip(radii, heights)])
    if rng.random() < 0.3:  # closed along v instead
        rows = [list(column) for column in zip(*rows)]
    surface = Part.BSplineSurface()
    surface.interpolate(rows)
    face = Part.Face(surface)
    return face, math.sqrt(face.Area / rng.choice([20, 80, 300]))


def _random_bspline_surface(rng, extent):
    """A bicubic B-spline over [0, extent]^2 with 5-7 x 5-7 poles (clamped,
    uniform knots), its poles' heights random up to a quarter of extent."""
    nu, nv = rng.randint(5, 7), rng.randint(5, 7)
    amp = rng.uniform(0.05, 0.25) * extent
    poles = [[V(extent * i / (nu - 1), extent * j / (nv - 1), amp * rng.uniform(-1, 1))
              for j in range(nv)] for i in range(nu)]
    uknots, umults = _clamped_uniform(nu)
    vknots, vmults = _clamped_uniform(nv)
    surface = Part.BSplineSurface()
    surface.buildFromPolesMultsKnots(poles, umults, vmults, uknots, vknots, False, False, 3, 3)
    return surface


def _slice(shape, planes):
    """The shape cut by planes (BOPTools' Split: the pieces share the cuts'
    edges)."""
    import BOPTools.SplitAPI as split_api

    big = 4 * shape.BoundBox.DiagonalLength
    tools = [Part.Plane(p, n).toShape(-big, big, -big, big) for p, n in planes]
    return split_api.slice(shape, tools, "Split")


def random_face_set(seed):
    """(kind, shape, size) for a random multi-face shape, not a bundled
    example: a B-spline face split by one to three random vertical planes
    ("split"), a box with some edges filleted, open at the bottom
    ("fillet"), a revolved B-spline profile closed by a planar top
    ("revolve"), an extruded closed B-spline curve with its caps
    ("extrude"), or a box fused with a cylinder through it ("fuse"); from
    seed 1000 on: a sphere's face cut by one or two planes ("sphere": poles
    and seams beside the cuts), a torus's face cut by a plane through its
    axis ("torus": periodic both ways), or a B-spline face with one or two holes split by
    a plane ("holed"); size gives about 60, 200 or 600 panels over the
    whole shape."""
    import sys

    sys.path.append("/usr/share/freecad/Mod/Part")  # BOPTools
    rng = random.Random(seed)
    if seed >= 1000:
        kind = ("sphere", "torus", "holed")[seed % 3]
    else:
        kind = ("split", "fillet", "revolve", "extrude", "fuse")[seed % 5]
    extent = 10000.0
    if kind == "sphere":
        radius = rng.uniform(0.2, 0.5) * extent
        sphere = Part.makeSphere(radius)
        planes = []
        for _ in range(rng.randint(1, 2)):
            a, b = rng.uniform(0, 2 * math.pi), rng.uniform(-1, 1)
            normal = V(math.cos(a) * math.sqrt(1 - b * b), math.sin(a) * math.sqrt(1 - b * b), b)
            planes.append((normal * (rng.uniform(-0.6, 0.6) * radius), normal))
        shape = _slice(sphere.Faces[0], planes)
    elif kind == "torus":
        major = rng.uniform(0.2, 0.4) * extent
        torus = Part.makeTorus(major, rng.uniform(0.15, 0.6) * major)
        a = rng.uniform(0, math.pi)
        shape = _slice(torus.Faces[0], [(V(0, 0, 0), V(math.cos(a), math.sin(a), 0))])
    elif kind == "holed":
        face = _random_bspline_surface(rng, extent).toShape()
        for _ in range(rng.randint(1, 2)):
            radius = rng.uniform(0.05, 0.15) * extent
            centre = V(rng.uniform(0.25, 0.75) * extent, rng.uniform(0.25, 0.75) * extent,
                       -extent)
            face = face.cut(Part.makeCylinder(radius, 2 * extent, centre))
        a = rng.uniform(0, math.pi)
        plane = (V(rng.uniform(0.3, 0.7) * extent, rng.uniform(0.3, 0.7) * extent, 0),
                 V(math.cos(a), math.sin(a), 0))
        shape = _slice(face, [plane])
    elif kind == "split":
        face = _random_bspline_surface(rng, extent).toShape()
        planes = []
        for _ in range(rng.randint(1, 3)):
            a = rng.uniform(0, math.pi)
            planes.append((V(rng.uniform(0.3, 0.7) * extent, rng.uniform(0.3, 0.7) * extent, 0),
                           V(math.cos(a), math.sin(a), 0)))
        shape = _slice(face, planes)
    elif kind == "fillet":
        dims = [rng.uniform(0.3, 1.0) * extent for _ in range(3)]
        box = Part.makeBox(*dims)
        edges = [e for e in box.Edges if rng.random() < 0.6] or box.Edges[:1]
        radius = rng.uniform(0.03, 0.2) * min(dims)
        solid = box.makeFillet(radius, edges)
        faces = [f for f in solid.Faces if f.CenterOfMass.z > 1e-6 * extent]
        shape = Part.Shell(faces)
    elif kind == "revolve":
        n = rng.randint(4, 7)
        height_ = rng.uniform(0.3, 1.0) * extent
        points = [V(0.3 * extent * (1 + 0.5 * rng.uniform(-1, 1)), 0, height_ * k / (n - 1))
                  for k in range(n)]
        curve = Part.BSplineCurve()
        curve.interpolate(points)
        side = curve.toShape().revolve(V(0, 0, 0), V(0, 0, 1), 360)
        top = Part.Face(Part.Wire(Part.makeCircle(points[-1].x, V(0, 0, height_))))
        shape = Part.Shell([side.Faces[0], top])
        shape.sewShape()
    elif kind == "extrude":
        n = rng.randint(5, 9)
        points = []
        for k in range(n):
            a = 2 * math.pi * k / n
            r = 0.3 * extent * (1 + 0.3 * rng.uniform(-1, 1))
            points.append(V(r * math.cos(a), r * math.sin(a), 0))
        curve = Part.BSplineCurve()
        curve.interpolate(points, PeriodicFlag=True)
        base = Part.Face(Part.Wire(curve.toShape()))
        solid = base.extrude(V(0, rng.uniform(-0.2, 0.2) * extent, rng.uniform(0.3, 1.0) * extent))
        shape = solid
    else:
        dims = [rng.uniform(0.4, 1.0) * extent for _ in range(3)]
        box = Part.makeBox(*dims)
        radius = rng.uniform(0.1, 0.3) * min(dims[0], dims[1])
        cyl = Part.makeCylinder(radius, 2 * dims[2],
                                V(rng.uniform(0.3, 0.7) * dims[0], rng.uniform(0.3, 0.7) * dims[1],
                                  -0.5 * dims[2]))
        shape = box.fuse(cyl).removeSplitter()
    area = sum(f.Area for f in shape.Faces)
    return kind, shape, math.sqrt(area / rng.choice([60, 200, 600]))


TRIMMED = {
    "dome_with_opening": dome_with_opening,
    "saddle_trimmed": saddle_trimmed,
    "roof_with_drum": roof_with_drum,
}
