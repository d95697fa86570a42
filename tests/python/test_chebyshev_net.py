"""chebyshev_net (equal rods, the layout made for repetition): on the bundled
doubly curved examples every rod between two nodes inside the face is `size`
long, measured from the result's vertices (checked on the surface by
FreeCAD); the panels cover the face (independent sampling); on the Chen Shan
dome, 2 mm families are at least 50% fewer than exactly congruent ones
(issue 17), every panel within 2 mm of its template by a Kabsch fit written
in the families tests; determinism and clear errors."""

import os
import sys
from collections import Counter

import pytest

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
HERE = os.path.dirname(os.path.abspath(__file__))
for _p in ("/usr/lib/freecad-python3/lib", REPO, HERE):
    if _p not in sys.path:
        sys.path.append(_p)

import FreeCAD  # noqa: E402  (before Part, or Part segfaults)
import Part  # noqa: E402
import numpy as np  # noqa: E402

import freecad_workbench as tessella  # noqa: E402
from conftest import independent_coverage, reopened  # noqa: E402
from freecad_workbench import families  # noqa: E402
from test_families import check_tolerance  # noqa: E402

EXAMPLES = os.path.join(REPO, "examples")


def example_face(name):
    return Part.read(os.path.join(EXAMPLES, name + ".brep")).Faces[0]


def rim_vertices(r):
    """The vertices on the face's boundary: of a panel side only one panel has
    (a boundary panel's outline points lie on its flat pieces, not on the
    surface: mesh/boundary_pieces)."""
    sides = Counter()
    for p in r.panels:
        for a, b in zip(p, list(p[1:]) + [p[0]]):
            sides[(min(a, b), max(a, b))] += 1
    return {v for side, n in sides.items() if n == 1 for v in side}


def interior_rod_lengths(r):
    """Lengths of the rods with no end on the face's boundary, from the
    vertices alone."""
    xyz = np.asarray(r.vertices, dtype=float).reshape(-1, 3)
    rim = rim_vertices(r)
    rods = [(a, b) for a, b in np.asarray(r.rods) if a not in rim and b not in rim]
    return np.array([np.linalg.norm(xyz[a] - xyz[b]) for a, b in rods])


@pytest.fixture(scope="module")
def dome():
    face = example_face("chen_shan_dome")
    return face, tessella.panelize(face, method="chebyshev_net", size=1500.0)


@pytest.mark.parametrize("name, share", [("chen_shan_dome", 1.0), ("british_museum_roof", 0.97),
                                         ("trimmed_bspline_holes", 1.0)])
def test_every_rod_inside_the_face_has_the_size(name, share):
    size = 1500.0 if name != "trimmed_bspline_holes" else 400.0
    face = example_face(name)
    r = tessella.panelize(face, method="chebyshev_net", size=size)
    lengths = interior_rod_lengths(r)
    assert len(lengths) > 500
    equal = np.abs(lengths - size) <= 1e-6 * size
    # The roof's net crosses its drum opening on the surface beneath it and
    # shears there: a few rows beyond it are guesses (about 1%).
    assert equal.mean() >= share, f"{equal.mean():.4f} of {len(lengths)} rods are {size} mm"
    # The nodes inside are on the surface (FreeCAD's own distance to the face).
    xyz = np.asarray(r.vertices, dtype=float).reshape(-1, 3)
    inside = sorted(set(range(len(xyz))) - rim_vertices(r))
    for k in inside[:: max(1, len(inside) // 200)]:
        assert face.distToShape(Part.Vertex(FreeCAD.Vector(*xyz[k])))[0] < 1e-6 * size
    gap, extra = independent_coverage(face, r)
    assert gap < 0.003 and extra < 0.003


def test_the_dome_has_half_the_families_of_exact_congruence(dome):
    face, r = dome
    exact = tessella.panel_families(r, family_tolerance=1e-3)
    fam = tessella.panel_families(r, family_tolerance=2.0)
    # Issue 17: at least 50% fewer at 2 mm than at 1e-3 mm (iso_grid 41%,
    # equal_size_grid 43%; no grouping of theirs can reach 50%).
    assert fam.count <= 0.5 * exact.count, (fam.count, exact.count)
    check_tolerance(families.panel_corners(r), fam, 2.0)


def test_deterministic():
    face = example_face("notched_shell")
    a = tessella.panelize(face, method="chebyshev_net", size=900.0, seed_u=0.4)
    b = tessella.panelize(face, method="chebyshev_net", size=900.0, seed_u=0.4)
    assert np.asarray(a.vertices).tobytes() == np.asarray(b.vertices).tobytes()
    assert [list(p) for p in a.panels] == [list(p) for p in b.panels]
    c = tessella.panelize(face, method="chebyshev_net", size=900.0)
    assert np.asarray(a.vertices).tobytes() != np.asarray(c.vertices).tobytes()  # the seed moved


@pytest.mark.parametrize("params, words", [
    ({}, "size"),
    ({"size": 0.0}, "size"),
    ({"size": -100.0}, "size"),
    ({"size": 500.0, "seed_u": 1.5}, "seed_u"),
    ({"size": 500.0, "seed_v": -0.1}, "seed_v"),
    ({"size": 1.0}, "max_panels"),
    ({"size": 500.0, "max_panels": 10}, "max_panels"),
])
def test_bad_parameters_are_clear_errors(params, words):
    with pytest.raises((ValueError, RuntimeError)) as e:
        tessella.panelize(example_face("bezier_patch"), method="chebyshev_net", **params)
    assert words in str(e.value)


def test_a_whole_sphere_is_panelized_without_a_turned_panel():
    # No Chebyshev net covers a sphere (its total curvature is over 2 pi);
    # beyond the net the lattice is laid out again so that no cell turns over.
    radius = 5000.0
    r = tessella.panelize(Part.makeSphere(radius).Faces[0], method="chebyshev_net", size=800.0)
    xyz = np.asarray(r.vertices, dtype=float).reshape(-1, 3)
    areas, sides = [], []
    for p in r.panels:
        c = xyz[list(p)]
        n = sum(np.cross(c[k] - c[0], c[k + 1] - c[0]) for k in range(1, len(c) - 1)) / 2
        areas.append(np.linalg.norm(n))
        sides.append(np.sign(np.dot(n, c.mean(axis=0))))  # outwards or inwards
    assert len(set(sides)) == 1 and sides[0] != 0  # no panel turned over
    # Flat panels on the sphere: their area a little under the sphere's.
    assert 0.97 * 4 * np.pi * radius**2 < sum(areas) <= 4 * np.pi * radius**2
    lengths = interior_rod_lengths(r)
    assert (np.abs(lengths - 800.0) <= 1e-6 * 800.0).sum() > 50  # the net's middle


def test_the_net_runs_on_across_faces_of_one_surface():
    """A face set whose faces lie on one surface (not a bundled example: the
    face-set tests' wavy surface with a hole, cut along its plan's
    diagonals) cuts one net made on their union: the one face's nodes away
    from the cuts are the set's, the rows carry on across the cuts, and the
    faces conform."""
    from test_face_sets import (assert_same_result, check_conforming, rows_carried,
                                wavy_face_with_a_hole_split_along_diagonals)

    face, pieces = wavy_face_with_a_hole_split_along_diagonals()
    size = 800.0
    one = tessella.panelize(face, method="chebyshev_net", size=size)
    r = tessella.panelize_faces(pieces, method="chebyshev_net", size=size, threads=2)
    assert_same_result(r, tessella.panelize_faces(pieces, method="chebyshev_net", size=size,
                                                  threads=1))
    assert check_conforming(pieces, r) > 20
    assert abs(r.metrics["panel_area"].sum() / pieces.Area - 1) < 5e-3
    share, count = rows_carried(pieces, r)
    assert count >= 20 and share >= 0.5, (share, count)
    # The one face's nodes inside, away from the cuts, are nodes of the set.
    cuts = [e for e in pieces.Edges
            if sum(any(e.isSame(g) for g in f.Edges) for f in pieces.Faces) == 2]
    rim = rim_vertices(one)
    xyz = np.asarray(one.vertices, dtype=float).reshape(-1, 3)
    theirs = np.asarray(r.vertices, dtype=float).reshape(-1, 3)
    checked = 0
    for k in range(0, len(xyz), 3):
        if k in rim:
            continue
        p = Part.Vertex(FreeCAD.Vector(*xyz[k]))
        if min(e.distToShape(p)[0] for e in cuts) < 1.5 * size:
            continue
        assert np.min(np.linalg.norm(theirs - xyz[k], axis=1)) < 1e-6 * size, k
        checked += 1
    assert checked > 30


def test_a_face_smaller_than_the_size_is_one_or_two_panels():
    # No rod of the net fits: its lattice steps one rod by the surface's
    # speed (a step of 1/64 of the face made a 1,912-panel sliver of a
    # random shape's split).
    surf = Part.BSplineSurface()
    surf.interpolate([[FreeCAD.Vector(150.0 * i, 100.0 * j, 20.0 * i * j) for j in range(3)]
                      for i in range(3)])
    face = surf.toShape()
    r = tessella.panelize(face, method="chebyshev_net", size=1000.0)
    assert 1 <= len(r.panels) <= 4
    assert abs(r.metrics["panel_area"].sum() / face.Area - 1) < 5e-3


def test_a_cylinder_thinner_than_the_size_keeps_three_panels_round():
    # A rod longer than the diameter fits nowhere round the cylinder: the net
    # steps a third of the turn (two cells made the two halves one flat
    # panel twice, and broke the join of random shape 529's fused cylinder).
    import math

    from conftest import widest_turn_round_z

    face = Part.makeCylinder(700.0, 5000.0).Faces[0]
    r = tessella.panelize(face, method="chebyshev_net", size=2400.0)
    corner_sets = [frozenset(int(v) for v in p) for p in r.panels]
    assert len(set(corner_sets)) == len(corner_sets)  # no panel twice
    assert widest_turn_round_z(r) < math.pi - 1e-6
    assert min(r.metrics["panel_area"]) > 0


def _roof_diagonals(roof):
    """The British Museum roof's plan diagonals as edges on its surface (its
    (u, v) is the plan's (x, y)): interpolated through 401 surface points."""
    s = roof.Surface
    u0, u1, v0, v1 = roof.ParameterRange
    out = []
    for flip in (False, True):
        pts = [s.value(u0 + t * (u1 - u0), (v1 - t * (v1 - v0)) if flip else (v0 + t * (v1 - v0)))
               for t in np.linspace(0.0, 1.0, 401)]
        c = Part.BSplineCurve()
        c.interpolate(pts)
        out.append(c.toShape())
    return out


def test_guides_are_the_generators():
    """Two crossing edges as the generators: the net's rows run along them,
    their nodes a rod apart on each (here the roof's plan diagonals)."""
    roof = example_face("british_museum_roof")
    guides = _roof_diagonals(roof)
    size = 1500.0
    r = tessella.panelize(roof, method="chebyshev_net", size=size, guides=guides)
    xyz = np.asarray(r.vertices, dtype=float).reshape(-1, 3)
    nodes = xyz[np.asarray(r.nodes)]
    bb = roof.BoundBox
    for a, b in (((bb.XMin, bb.YMin), (bb.XMax, bb.YMax)), ((bb.XMin, bb.YMax), (bb.XMax, bb.YMin))):
        a, b = np.array(a), np.array(b)
        d = (b - a) / np.linalg.norm(b - a)
        off = np.abs((nodes[:, 0] - a[0]) * d[1] - (nodes[:, 1] - a[1]) * d[0])
        on = nodes[off < 1.0]  # the guide is the diagonal within its interpolation
        on = on[np.argsort((on[:, :2] - a) @ d)]
        steps = np.linalg.norm(np.diff(on, axis=0), axis=1)
        assert (np.abs(steps - size) < 1e-6 * size).sum() >= 20, steps
    gap, extra = independent_coverage(roof, r)
    assert gap < 0.003 and extra < 0.003


@pytest.mark.parametrize("which, words", [
    ("one", "guides"),
    ("apart", "do not cross"),
])
def test_bad_guides_are_clear_errors(which, words):
    roof = example_face("british_museum_roof")
    a, b = _roof_diagonals(roof)
    if which == "one":
        guides = [a]
    else:  # one diagonal's first half, the other's last 40%: they miss each other
        guides = [Part.Edge(a.Curve, a.FirstParameter, 0.5 * (a.FirstParameter + a.LastParameter)),
                  Part.Edge(b.Curve, 0.6 * b.LastParameter + 0.4 * b.FirstParameter,
                            b.LastParameter)]
    with pytest.raises((ValueError, RuntimeError)) as e:
        tessella.panelize(roof, method="chebyshev_net", size=1500.0, guides=guides)
    assert words in str(e.value)


def _plan_diagonal_sections(face):
    """The curves a split along the face's plan diagonals cuts it along,
    through any opening (bench/face_sets.py, which wrote the roof's split)."""
    sys.path.append(os.path.join(os.path.dirname(__file__), "..", "..", "bench"))
    from face_sets import plan_diagonal_guides

    return plan_diagonal_guides(face)


def _rod_statistics(r):
    lengths = np.asarray(r.metrics["rod_length"], dtype=float)
    return len(r.panels), lengths.mean(), lengths.var()


def test_guides_along_a_roof_s_cuts_give_the_one_face_s_net():
    """Issue 14's target on seed 004's split: the roof cut along its plan's
    diagonals, the net's generators along the same diagonals (the tests'
    own interpolated curves, which run up to a few millimetres off the cuts).
    The cuts are rows of the net: the set has the one face's panels, rod
    mean and rod variance (within 1%; the issue asks 5%), and conforms."""
    from test_face_sets import check_conforming

    roof = example_face("british_museum_roof")
    pieces = Part.read(os.path.join(EXAMPLES, "face_sets", "british_museum_roof_diagonals.brep"))
    guides = _roof_diagonals(roof)
    size = 1500.0
    one = tessella.panelize(roof, method="chebyshev_net", size=size, guides=guides)
    r = tessella.panelize_faces(pieces, method="chebyshev_net", size=size, guides=guides)
    assert check_conforming(pieces, r) > 80
    (n1, m1, v1), (n2, m2, v2) = _rod_statistics(one), _rod_statistics(r)
    assert abs(n2 / n1 - 1) < 0.01 and abs(m2 / m1 - 1) < 0.01 and abs(v2 / v1 - 1) < 0.01, (
        n1, n2, m1, m2, v1, v2)
    # The rods along the cuts are the net's: a rod long but at the cuts' ends.
    cuts = [e for e in pieces.Edges
            if sum(any(e.isSame(g) for g in f.Edges) for f in pieces.Faces) == 2]
    xyz = np.asarray(r.vertices, dtype=float).reshape(-1, 3)
    along = []
    for a, b in np.asarray(r.rods):
        mid = Part.Vertex(FreeCAD.Vector(*(0.5 * (xyz[a] + xyz[b]))))  # off by the sagitta
        ends = [Part.Vertex(FreeCAD.Vector(*xyz[k])) for k in (a, b)]
        if (all(min(e.distToShape(v)[0] for e in cuts) < 1e-3 for v in ends)
                and min(e.distToShape(mid)[0] for e in cuts) < 0.02 * size):
            along.append(np.linalg.norm(xyz[b] - xyz[a]))
    along = np.array(along)
    assert len(along) > 80
    assert (np.abs(along - size) < 2.0).mean() > 0.9, np.sort(along)[:10]


def test_guides_along_the_cuts_of_a_face_that_is_not_an_example():
    """The same on the face-set tests' wavy surface with a round hole, cut
    along its plan's diagonals, the guides the planes' sections of its
    surface: conforming, the one face's panel count and rod mean within 1%
    and rod variance within the issue's 5% (the corner cells, split by the
    cuts, are merged otherwise: -0.3% here, -2.0% to -1.8% at 700-1000 mm),
    the same on one and two threads."""
    from test_face_sets import (assert_same_result, check_conforming,
                                wavy_face_with_a_hole_split_along_diagonals)

    face, pieces = wavy_face_with_a_hole_split_along_diagonals()
    guides = _plan_diagonal_sections(face)
    size = 600.0
    one = tessella.panelize(face, method="chebyshev_net", size=size, guides=guides)
    r = tessella.panelize_faces(pieces, method="chebyshev_net", size=size, guides=guides,
                                threads=2)
    assert_same_result(r, tessella.panelize_faces(pieces, method="chebyshev_net", size=size,
                                                  guides=guides, threads=1))
    assert check_conforming(pieces, r) > 20
    (n1, m1, v1), (n2, m2, v2) = _rod_statistics(one), _rod_statistics(r)
    assert abs(n2 / n1 - 1) < 0.01 and abs(m2 / m1 - 1) < 0.01 and abs(v2 / v1 - 1) < 0.05, (
        n1, n2, m1, m2, v1, v2)
    assert abs(r.metrics["panel_area"].sum() / pieces.Area - 1) < 5e-3


def test_a_document_net_on_a_face_set_with_guides(tmp_path):
    """The Panelization of the split roof with the diagonals (document edges)
    as Guides: the console's panels, a Size change recomputes, and the
    document saves and reopens with the same panels."""
    from test_face_sets import check_conforming

    roof = example_face("british_museum_roof")
    pieces = Part.read(os.path.join(EXAMPLES, "face_sets", "british_museum_roof_diagonals.brep"))
    doc = FreeCAD.newDocument("NetWithGuides")
    try:
        obj = doc.addObject("Part::Feature", "Roof")
        obj.Shape = pieces
        lines = []
        for k, edge in enumerate(_roof_diagonals(roof)):
            line = doc.addObject("Part::Feature", f"Diagonal{k}")
            line.Shape = edge
            lines.append((line, "Edge1"))
        doc.recompute()
        p = tessella.make_panelization(obj, method="chebyshev_net", size=1500.0, guides=lines)
        console = tessella.panelize_faces(pieces, method="chebyshev_net", size=1500.0,
                                          guides=_roof_diagonals(roof))
        assert p.PanelCount == len(console.panels)
        p.Size = 2000.0
        doc.recompute()
        r = p.Proxy.result(p).result
        assert p.isValid() and r.face_count == 4 and p.PanelCount < len(console.panels)
        assert check_conforming(pieces, r) > 50
        count = p.PanelCount
        doc, p = reopened(doc, str(tmp_path / "net.FCStd"), p.Name)
        assert p.isValid() and p.PanelCount == count
    finally:
        FreeCAD.closeDocument(doc.Name)


def test_guides_on_faces_of_several_surfaces_are_a_clear_error():
    # One net serves faces of one surface; the roof's four sub-surfaces
    # (each its own B-spline surface) have no common (u, v).
    import sys
    sys.path.append(os.path.join(os.path.dirname(__file__), "..", "..", "bench"))
    from face_sets import sub_surfaces

    roof = example_face("british_museum_roof")
    pieces = Part.read(os.path.join(EXAMPLES, "face_sets", "british_museum_roof_diagonals.brep"))
    with pytest.raises(ValueError) as e:
        tessella.panelize_faces(sub_surfaces(pieces), method="chebyshev_net", size=1500.0,
                                guides=_roof_diagonals(roof))
    assert "guides" in str(e.value) and "one surface" in str(e.value)


@pytest.mark.parametrize("turn", [(2.5, 4.0), (5.5, 7.0)])  # the second crosses the seam
def test_two_helices_on_a_cylinder_are_the_generators(turn):
    """Guides on a closed face: two helices crossing at 74 deg on the
    surface, nearly parallel in (u, v) (u an angle, v a height in mm: the
    crossing angle is taken on the surface), one pair across the seam (the
    second guide found a period over). Rods along the helices are a rod long."""
    import math

    radius, size = 3000.0, 900.0
    face = Part.makeCylinder(radius, 8000.0).Faces[0]

    def helix(t0, t1):
        pts = [FreeCAD.Vector(radius * math.cos(t), radius * math.sin(t), z)
               for t, z in zip(np.linspace(t0, t1, 200), np.linspace(1000.0, 7000.0, 200))]
        c = Part.BSplineCurve()
        c.interpolate(pts)
        return c.toShape()

    a, b = turn
    r = tessella.panelize(face, method="chebyshev_net", size=size,
                          guides=[helix(a, b), helix(b, a)])
    assert r.summary["gap_fraction"] < 1e-3 and r.summary["overlap_fraction"] < 1e-3
    lengths = interior_rod_lengths(r)
    # A cylinder is developable: the net holds everywhere but at the seam's
    # cut (one rod in 170 crosses it).
    assert (np.abs(lengths - size) <= 1e-6 * size).mean() > 0.98
