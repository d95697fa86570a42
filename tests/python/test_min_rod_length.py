"""min_rod_length (issue 12, part 2): no rod shorter than the limit, for every
method at three sizes, on a trimmed doubly curved face that is NOT a bundled
example (a B-spline surface with a circular hole and a skew straight trim).
Everything is measured independently of the core: rod lengths from the result
vertices, trim distances with OCCT (distToShape), areas against Part's face area."""

import math
from collections import Counter

import FreeCAD  # noqa: F401  (before Part)
import numpy as np
import Part
import pytest

import freecad_workbench as tessella

SIZES = (400.0, 800.0, 1200.0)
METHODS = ("iso_grid", "equal_size_grid", "boundary_driven", "walking_agent",
           "gradient_descent", "relaxed_grid", "guide_line_scaling", "guide_line_diamond",
           "two_guide_lines")
# Methods whose panels do not cover the face to 0.5% before any merge (their own
# coverage, not this stage's): for them the stage must keep the area it got.
COVERAGE_OF_THE_METHOD = {"boundary_driven", "guide_line_scaling", "guide_line_diamond",
                          "two_guide_lines"}
# Methods whose own boundary nodes are not all on the trim (guide_line_scaling
# stops short of it): for them the stage must keep the positions it got.
TRIM_OF_THE_METHOD = {"guide_line_scaling"}


def make_face():
    nu = nv = 5
    poles = []
    for i in range(nu):
        row = []
        for j in range(nv):
            z = 1200.0 * math.cos(0.8 * i - 1.5) * math.sin(0.9 * j + 0.3) + 90.0 * i * j
            row.append(FreeCAD.Vector(2500.0 * i, 2000.0 * j, z))
        poles.append(row)
    surf = Part.BSplineSurface()
    surf.buildFromPolesMultsKnots(poles, [4, 1, 4], [4, 1, 4], [0.0, 0.4, 1.0], [0.0, 0.55, 1.0],
                                  False, False, 3, 3)
    hole = Part.makeCylinder(1300, 20000, FreeCAD.Vector(4700, 4300, -8000))
    # Skew straight trim: everything beyond the plan line (-1000, 5000)-(11000, 7500) goes.
    beyond = Part.makePolygon([FreeCAD.Vector(-1000, 5000, -8000), FreeCAD.Vector(11000, 7500, -8000),
                               FreeCAD.Vector(11000, 9000, -8000), FreeCAD.Vector(-1000, 9000, -8000),
                               FreeCAD.Vector(-1000, 5000, -8000)])
    beyond = Part.Face(beyond).extrude(FreeCAD.Vector(0, 0, 20000))
    faces = surf.toShape().cut(hole).cut(beyond).Faces
    assert len(faces) == 1
    face = faces[0]
    assert face.isValid() and len(face.Wires) == 2
    return face


@pytest.fixture(scope="module")
def face():
    return make_face()


def _plan_guide(face, x=None, y=None):
    bb = face.BoundBox
    z = bb.ZMax + 1000
    if x is not None:
        a, b = FreeCAD.Vector(x, bb.YMin - 10, z), FreeCAD.Vector(x, bb.YMax + 10, z)
    else:
        a, b = FreeCAD.Vector(bb.XMin - 10, y, z), FreeCAD.Vector(bb.XMax + 10, y, z)
    edges = face.makeParallelProjection(Part.LineSegment(a, b).toShape(),
                                        FreeCAD.Vector(0, 0, -1)).Edges
    return max(edges, key=lambda e: e.Length)


def method_params(face, method, size):
    bb = face.BoundBox
    g1 = _plan_guide(face, x=bb.XMin + 0.3 * bb.XLength)
    g2 = _plan_guide(face, y=bb.YMin + 0.4 * bb.YLength)
    return {
        "iso_grid": dict(size=size),
        "equal_size_grid": dict(size=size),
        "boundary_driven": dict(size=size),
        "walking_agent": dict(max_deviation=size / 40),
        "gradient_descent": dict(max_deviation=size / 40),
        "relaxed_grid": dict(u_count=max(3, int(bb.XLength / size)),
                             v_count=max(3, int(bb.YLength / size))),
        "guide_line_scaling": dict(guides=[g1], rod_length=size),
        "guide_line_diamond": dict(guides=[g1, g2], rod_length=size),
        "two_guide_lines": dict(guides=[g1, g2], rod_length=size),
    }[method]


def rod_lengths(r):
    v = np.asarray(r.vertices)
    return np.linalg.norm(v[r.rods[:, 0]] - v[r.rods[:, 1]], axis=1)


def boundary_nodes(r):
    """Nodes on an edge only one panel uses (the mesh boundary: the trim)."""
    return sorted(set(boundary_vertices(r)) & set(int(n) for n in r.nodes))


def boundary_vertices(r):
    used = Counter()
    for p in r.panels:
        for k in range(len(p)):
            used[(p[k], p[(k + 1) % len(p)])] += 1
    out = set()
    for a, b in used:
        if (b, a) not in used:
            out.update((a, b))
    return sorted(out)


@pytest.mark.parametrize("size", SIZES)
@pytest.mark.parametrize("method", METHODS)
def test_no_rod_shorter_than_min_rod_length(face, method, size):
    kw = method_params(face, method, size)
    r = tessella.panelize(face, method=method, **kw)
    s = r.summary
    limit = s["min_rod_length"]
    # The automatic limit: a quarter of the nominal panel edge.
    assert limit == pytest.approx(0.25 * math.sqrt(s["nominal_area"]), rel=1e-12)
    lengths = rod_lengths(r)
    assert lengths.min() >= limit, (method, size, lengths.min(), limit)
    assert s["shortest_rod"] == pytest.approx(lengths.min(), rel=1e-12)
    assert s["short_rods"] == 0
    # Every node on the boundary lies on the face's trim edges (OCCT's distance)
    # at a position the method gave a boundary vertex (kept exactly).
    unmerged = tessella.panelize(face, method=method, min_rod_length=1e-6, **kw)
    assert unmerged.summary["merged_rods"] == 0
    trim = Part.Compound(face.Edges)
    tol = 1e-6 * s["model_size"]
    # (the surface points of its (u,v): an outline point of a flat boundary piece
    # sits on the piece's plane, a trim point made a node is back on the trim)
    surface = face.Surface
    before = np.array([tuple(surface.value(*unmerged.uv[v])) for v in boundary_vertices(unmerged)])
    for n in boundary_nodes(r):
        x = np.asarray(r.vertices[n])
        assert np.min(np.linalg.norm(before - x, axis=1)) <= 1e-9 * s["model_size"]
        d = trim.distToShape(Part.Vertex(FreeCAD.Vector(*map(float, x))))[0]
        if method not in TRIM_OF_THE_METHOD:
            assert d <= tol, (method, size, n, d)
    # Every node lies on the face (none was moved off it).
    on_face = r.nodes if method not in TRIM_OF_THE_METHOD else []
    for x in r.vertices[on_face][:: max(1, len(on_face) // 60)]:
        assert face.distToShape(Part.Vertex(FreeCAD.Vector(*map(float, x))))[0] <= tol
    # The panels keep covering the face: within 0.5% of its area, or (for a
    # method that does not cover it that well itself) the area it had unmerged.
    area = r.metrics["panel_area"].sum()
    area0 = unmerged.metrics["panel_area"].sum()
    assert abs(area - area0) <= 1e-3 * face.Area, (method, size, area, area0)
    if method not in COVERAGE_OF_THE_METHOD:
        assert abs(area / face.Area - 1) <= 0.005, (method, size, area / face.Area)
    # Fewer nodes after merging, never more; no panel with fewer than 3 nodes.
    # (not counting the trim nodes the boundary-piece stage adds after the merge)
    added, added0 = s["boundary_nodes_added"], unmerged.summary["boundary_nodes_added"]
    assert s["node_count"] - added <= unmerged.summary["node_count"] - added0 - s["merged_rods"]
    node_set = set(int(n) for n in r.nodes)
    for p in r.panels:
        assert len(p) >= 3 and len(set(p)) == len(p)
        assert sum(1 for v in p if v in node_set) >= 3
    if method == "walking_agent":
        # The hard bound still holds on every panel.
        assert r.metrics["panel_deviation"].max() <= kw["max_deviation"]


def test_the_grids_had_short_rods_before(face):
    # The stage has work to do on this face: unmerged, the grids have rods far
    # under a quarter of the panel size.
    r = tessella.panelize(face, method="equal_size_grid", size=800.0, min_rod_length=1e-6)
    assert rod_lengths(r).min() < 0.1 * 800.0


def test_an_explicit_min_rod_length(face):
    r = tessella.panelize(face, method="iso_grid", size=800.0, min_rod_length=300.0)
    assert r.summary["min_rod_length"] == 300.0
    assert rod_lengths(r).min() >= 300.0
    assert r.summary["merged_rods"] > 0


def test_a_negative_min_rod_length_is_refused(face):
    with pytest.raises(ValueError, match="min_rod_length"):
        tessella.panelize(face, method="iso_grid", size=800.0, min_rod_length=-1.0)


def test_the_folds_and_the_fold_angles_stay_consistent(face):
    r = tessella.panelize(face, method="walking_agent", max_deviation=10.0)
    tris = [tuple(sorted(p)) for p in r.panels if len(p) == 3]
    for (a, b), angle in zip(r.folds, r.metrics["fold_angle"]):
        # A fold is the diagonal two triangles share.
        assert sum(1 for t in tris if a in t and b in t) == 2
        assert np.isfinite(angle)


@pytest.mark.parametrize("method", ["iso_grid", "equal_size_grid", "walking_agent"])
def test_no_merge_makes_a_panel_go_half_way_round(method):
    # A cone at 1.5 m: its top rim (628 mm round) had three rods of 173 mm,
    # under min_rod_length; collapsing one left two round it and a panel
    # turning 240 degrees (iso_grid, equal_size_grid; walking_agent 211): no
    # sheet to bend. Such a collapse is refused; the short rods stay.
    from conftest import widest_turn_round_z

    face = Part.makeCone(400, 100, 2000).Faces[0]
    kw = ({"max_size": 1500.0, "max_deviation": 300.0} if method == "walking_agent"
          else {"size": 1500.0})
    r = tessella.panelize(face, method=method, **kw)
    assert widest_turn_round_z(r) < 0.99 * math.pi
    assert r.summary["gap_fraction"] < 1e-3 and r.summary["overlap_fraction"] < 1e-3
