"""The bundled example faces (examples/*.brep): they load, are valid single faces,
panelize with every method, and the panels of the trimmed face keep out of its holes."""

import math
import os
import sys

import pytest

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
for _p in ("/usr/lib/freecad-python3/lib", REPO):
    if _p not in sys.path:
        sys.path.append(_p)

import FreeCAD  # noqa: E402,F401  (before Part)
import Part  # noqa: E402
import numpy as np  # noqa: E402

EXAMPLES = os.path.join(REPO, "examples")

#: name -> (surface type, wire count)
EXPECTED = {
    "trimmed_bspline_holes": ("Part::GeomBSplineSurface", 3),
    "bezier_patch": ("Part::GeomBezierSurface", 1),
    "cylinder_part": ("Part::GeomCylinder", 1),
    "plane": ("Part::GeomPlane", 2),
    "full_cylinder": ("Part::GeomCylinder", 1),
    "british_museum_roof": ("Part::GeomBSplineSurface", 2),  # examples/make_british_museum.py
}
METHODS = ("iso_grid", "equal_size_grid")
TARGET_PANELS = 60  # coarse: keeps the whole file well under the time budget


def load(name):
    shape = Part.Shape()
    shape.read(os.path.join(EXAMPLES, name + ".brep"))
    return shape


def coarse_size(face):
    return math.sqrt(face.Area / TARGET_PANELS)


_cache = {}


def panelized(name, method):
    if (name, method) not in _cache:
        import freecad_workbench as tessella

        face = load(name).Faces[0]
        _cache[name, method] = tessella.panelize(face, method=method, size=coarse_size(face))
    return _cache[name, method]


def test_every_brep_is_listed():
    found = {f[:-5] for f in os.listdir(EXAMPLES) if f.endswith(".brep")}
    assert found == set(EXPECTED)


@pytest.mark.parametrize("name", sorted(EXPECTED))
def test_example_is_a_valid_single_face(name):
    shape = load(name)
    assert not shape.isNull()
    assert len(shape.Faces) == 1
    face = shape.Faces[0]
    assert face.isValid()
    surface_type, wires = EXPECTED[name]
    assert face.Surface.TypeId == surface_type
    assert len(face.Wires) == wires
    assert face.Area > 1e7  # mm^2: every example is at least 10 m^2


def test_full_cylinder_has_a_seam():
    face = load("full_cylinder").Faces[0]
    assert face.Surface.isUPeriodic()
    u0, u1, _, _ = face.ParameterRange
    assert u1 - u0 == pytest.approx(2 * math.pi)


@pytest.mark.parametrize("method", METHODS)
@pytest.mark.parametrize("name", sorted(EXPECTED))
def test_example_panelizes(name, method):
    r = panelized(name, method)
    face = load(name).Faces[0]
    assert len(r.panels) > 10
    assert r.vertices.shape == (len(r.uv), 3)
    assert len(r.rods) == r.summary["rod_count"] > 0
    assert np.all(np.isfinite(r.vertices))
    assert np.all(np.isfinite(r.metrics["panel_deviation"]))
    # The panels cover the face: their area is the face's within a few per cent
    # (boundary panels are chords of the curved trims; grids are coarse here).
    total = float(np.sum(r.metrics["panel_area"]))
    assert total == pytest.approx(face.Area, rel=0.03)


def _inner_loops_uv(face):
    """For each hole: its trim loop sampled in uv, and a uv point well inside it."""
    outer = face.OuterWire
    loops = []
    for wire in face.Wires:
        if wire.isSame(outer):
            continue
        uv = []
        for edge in wire.Edges:
            for p in edge.discretize(48):
                uv.append(face.Surface.parameter(p))
        uv = np.array(uv)
        loops.append((uv, uv.mean(axis=0)))  # holes here are convex: the mean is inside
    return loops


def _inside_polygon(point, polygon):
    """Even-odd rule, polygon (n,2)."""
    x, y = point
    inside = False
    n = len(polygon)
    for k in range(n):
        (x0, y0), (x1, y1) = polygon[k], polygon[(k + 1) % n]
        if (y0 > y) != (y1 > y) and x < x0 + (y - y0) * (x1 - x0) / (y1 - y0):
            inside = not inside
    return inside


@pytest.mark.parametrize("method", METHODS)
def test_trimmed_face_panels_keep_out_of_the_holes(method):
    face = load("trimmed_bspline_holes").Faces[0]
    r = panelized("trimmed_bspline_holes", method)
    loops = _inner_loops_uv(face)
    assert len(loops) == 2
    tol = 1e-3 * max(face.BoundBox.DiagonalLength, 1.0)  # 1e-3 of the model: ~25 mm

    # 1. Every node is on the face (inside or on a trim), none in a hole.
    for k, p in enumerate(r.vertices):
        assert face.isInside(FreeCAD.Vector(*p), tol, True), f"node {k} at {p} is off the face"
    for uv_loop, _ in loops:
        for k, (u, v) in enumerate(r.uv):
            if _inside_polygon((u, v), uv_loop):
                # Only a node on the trim itself may be "inside" the sampled loop.
                p = face.Surface.value(u, v)
                assert face.isInside(p, tol, True), f"node {k} lies in a hole"

    # 2. The holes stay open: no panel covers a hole's middle.
    for _, middle in loops:
        p = face.Surface.value(*middle)
        assert not face.isInside(p, 1e-6, True)  # the test point is really in the hole
        for k, panel in enumerate(r.panels):
            assert not _inside_polygon(middle, r.uv[list(panel)]), f"panel {k} covers a hole"

    # 3. The panel area has the holes taken out.
    assert float(np.sum(r.metrics["panel_area"])) == pytest.approx(face.Area, rel=0.03)
