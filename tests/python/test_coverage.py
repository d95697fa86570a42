"""Every tiling method checks its own coverage before it returns: no gap, no
overlap, nothing outside the trims beyond 0.1% of the face (the core's
summary gap_fraction / overlap_fraction), re-measured here independently with
FreeCAD's own trim test (Face.isPartOfDomain) and matplotlib's point-in-polygon on
random points of the face, weighted by the surface's area element. The
guide-line methods report their coverage (coverage_warning) instead;
relaxed_grid, which kept whole cells, now cuts them by the trims and tiles the
face too; walking_agent's max_deviation holds on the pipeline's own measure
(checked densely with FreeCAD's projection), and an unreachable bound raises."""

import math
import os

import FreeCAD  # noqa: F401  (before Part)
import Part
import numpy as np
import pytest

import freecad_workbench as tessella
from conftest import dense_quad_deviation, independent_coverage

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
TILING = ("iso_grid", "equal_size_grid", "walking_agent", "gradient_descent", "boundary_driven")
#: trimmed faces with openings and notches (vertex (u,v) = corner (u,v): no seam)
FACES = ("trimmed_bspline_holes", "notched_shell", "vault_openings", "british_museum_roof")
SAMPLES = 3000


def load(name):
    shape = Part.Shape()
    shape.read(os.path.join(REPO, "examples", name + ".brep"))
    return shape.Faces[0]


def params(method, face):
    if method in ("walking_agent", "gradient_descent"):
        return {"max_deviation": 0.002 * face.BoundBox.DiagonalLength}
    return {"size": math.sqrt(face.Area) / 12}


#: every tiling method on two of the faces (the independent re-measure costs
#: a few seconds a case)
CASES = [(name, method) for k, name in enumerate(FACES) for j, method in enumerate(TILING)
         if (j + k) % 2 == 0]


@pytest.mark.parametrize("name,method", CASES)
def test_tiling_methods_cover_the_face_once(name, method):
    face = load(name)
    try:
        r = tessella.panelize(face, method=method, **params(method, face))
    except (ValueError, RuntimeError) as exc:
        # A refusal is allowed, but only the coverage refusal with its figures.
        assert "uncovered" in str(exc) or "overlap" in str(exc), exc
        pytest.skip(f"refused: {exc}")
    s = r.summary
    assert s["gap_fraction"] <= 1e-3 and s["overlap_fraction"] <= 1e-3, s
    assert s["coverage_warning"] == ""
    gap, extra = independent_coverage(face, r)
    # 3000 samples: a share p is seen within ~3 sqrt(p / 3000); 0.1% reads as < 0.4%.
    assert gap < 4e-3 and extra < 4e-3, (gap, extra)
    # No panel without area: every panel model measures a real area.
    assert np.all(r.metrics["panel_area"] > 1e-9 * s["nominal_area"])


def sides_used_once(r):
    """Panel sides no other panel runs along the other way (the mesh boundary)."""
    sides = {(p[k], p[(k + 1) % len(p)]) for p in r.panels for k in range(len(p))}
    return [(a, b) for a, b in sides if (b, a) not in sides]


@pytest.mark.parametrize("name", ("trimmed_bspline_holes", "vault_openings"))
def test_relaxed_grid_cuts_its_cells_by_the_trims(name):
    """relaxed_grid kept the relaxed cells whose middle lies in the face: at 8 x 8
    cells 4.9% of trimmed_bspline_holes uncovered and 11% outside, 3.8% and 3.8% of
    vault_openings. Its cells are now cut by the trims: the pipeline enforces the
    coverage, confirmed independently here; the boundary runs along the trims
    only (no crack, no T-junction: every side is shared or on a trim), and the
    boundary nodes lie on the face's edges (OCCT's distance)."""
    face = load(name)
    r = tessella.panelize(face, method="relaxed_grid", u_count=8, v_count=8)
    s = r.summary
    assert s["gap_fraction"] <= 1e-3 and s["overlap_fraction"] <= 1e-3, s
    assert s["coverage_warning"] == ""
    gap, extra = independent_coverage(face, r)
    assert gap < 4e-3 and extra < 4e-3, (gap, extra)
    trim = Part.Compound(face.Edges)
    tol = 1e-6 * s["model_size"]
    nodes = set(int(n) for n in r.nodes)
    surface = face.Surface
    boundary = set(v for side in sides_used_once(r) for v in side)
    assert boundary
    for v in boundary:
        # outline points lie on the piece planes, their (u,v) on the trim
        x = r.vertices[v] if v in nodes else tuple(surface.value(*map(float, r.uv[v])))
        assert trim.distToShape(Part.Vertex(FreeCAD.Vector(*map(float, x))))[0] <= tol, v
    # Every side used once each way at most (no rod shared by three panels).
    sides = [(p[k], p[(k + 1) % len(p)]) for p in r.panels for k in range(len(p))]
    assert len(sides) == len(set(sides))


def test_a_partial_guide_line_grid_reports_its_gap():
    """GSM from a middle guide on the plate with an opening stops short of the
    plate's sides (measured 24% uncovered): reported, and confirmed here."""
    face = load("plane")
    u0, u1, v0, v1 = face.ParameterRange
    guide = Part.Edge(face.Surface.uIso(0.5 * (u0 + u1)), v0, v1)
    r = tessella.panelize(face, method="guide_line_scaling", guides=[guide],
                          rod_length=math.sqrt(face.Area) / 12)
    s = r.summary
    assert "uncovered" in s["coverage_warning"], s["coverage_warning"]
    gap, _ = independent_coverage(face, r)
    assert gap > 0.1
    assert abs(s["gap_fraction"] - gap) < 0.03, (s["gap_fraction"], gap)


@pytest.mark.parametrize("name", ("british_museum_roof", "trimmed_bspline_holes"))
def test_walking_agent_bound_holds_on_the_pipeline_measure(name):
    """On these two faces the agent's own estimate let panels through 2% and
    22% over the bound; now every panel is within it as the pipeline measures,
    and the largest quads stay within it by FreeCAD's own dense re-measure."""
    face = load(name)
    bound = 0.002 * face.BoundBox.DiagonalLength
    r = tessella.panelize(face, method="walking_agent", max_deviation=bound)
    dev = r.metrics["panel_deviation"]
    assert dev.max() <= bound, (dev.max(), bound)
    quads = sorted((k for k, p in enumerate(r.panels) if len(p) == 4), key=lambda k: -dev[k])
    for k in quads[:5]:
        dense = dense_quad_deviation(face.Surface, r.vertices[list(r.panels[k])], 30)
        assert dense <= bound * (1 + 1e-9), (k, dense, bound)
        assert dense <= dev[k] * (1 + 1e-6) + 1e-9, (k, dense, dev[k])


def test_walking_agent_unreachable_bound_raises():
    face = load("chen_shan_dome")
    with pytest.raises((ValueError, RuntimeError), match="max_deviation"):
        tessella.panelize(face, method="walking_agent",
                          max_deviation=2e-3 * face.BoundBox.DiagonalLength, max_refinements=0,
                          edge_share=1.0)


def test_an_opening_inside_one_grid_cell_does_not_overlap():
    """vault_openings at 0.005 x the diagonal: gradient_descent's grid holds a
    whole opening in one cell, split through the opening. The split line's ends
    on the cell's grid lines were taken for trim crossings and snapped onto the
    nearest trim (the face's edge u = 0), so panels wrapped around their
    neighbour: 0.13% overlap, refused. Now the result tiles the face."""
    face = load("vault_openings")
    r = tessella.panelize(face, method="gradient_descent",
                          max_deviation=0.005 * face.BoundBox.DiagonalLength)
    s = r.summary
    assert s["gap_fraction"] <= 1e-6 and s["overlap_fraction"] <= 1e-6, s
    gap, extra = independent_coverage(face, r)
    assert gap < 4e-3 and extra < 4e-3, (gap, extra)


def test_a_square_opening_in_the_middle_cell_of_a_plate():
    """A 3 x 3 iso grid on a 1000 mm plate whose opening [400, 600]^2 lies in
    the middle cell: each half of the split cell (its short rods to the
    opening merged) is split again into quads dented at a node, whose bilinear
    patches folded over themselves (3D area 1.0136 x the face, refused).
    Checked by FreeCAD's own figures: the panels' areas add up to Face.Area,
    and random points are covered once."""
    def square(x0, x1, clockwise):
        pts = [FreeCAD.Vector(x0, x0, 0), FreeCAD.Vector(x1, x0, 0),
               FreeCAD.Vector(x1, x1, 0), FreeCAD.Vector(x0, x1, 0)]
        if clockwise:
            pts.reverse()
        return Part.makePolygon(pts + [pts[0]])

    face = Part.Face([square(0, 1000, False), square(400, 600, True)])
    assert abs(face.Area - 960000) < 1e-6
    r = tessella.panelize(face, method="iso_grid", u_count=3, v_count=3)
    s = r.summary
    assert s["gap_fraction"] <= 1e-9 and s["overlap_fraction"] <= 1e-9, s
    assert abs(r.metrics["panel_area"].sum() - face.Area) < 1e-6 * face.Area
    gap, extra = independent_coverage(face, r, samples=6000)
    assert gap < 1e-3 and extra < 1e-3, (gap, extra)


def _normal_line_coverage(face, r, reach, samples=1200, seed=3):
    """(gap, overlap): shares of area-weighted random points of the face whose
    normal line meets no panel / more than one within `reach` (panels
    fan-triangulated in 3D); independent of the core's (u,v) scan."""
    rng = np.random.default_rng(seed)
    u0, u1, v0, v1 = face.ParameterRange
    surf = face.Surface
    pts, nrm, w = [], [], []
    while len(pts) < samples:
        u, v = rng.uniform(u0, u1), rng.uniform(v0, v1)
        if not face.isPartOfDomain(u, v):
            continue
        n = np.cross(np.array(surf.getDN(u, v, 1, 0)), np.array(surf.getDN(u, v, 0, 1)))
        if np.linalg.norm(n) == 0:
            continue
        pts.append(np.array(surf.value(u, v)))
        nrm.append(n / np.linalg.norm(n))
        w.append(np.linalg.norm(n))
    x, nrm, w = np.array(pts), np.array(nrm), np.array(w)
    v = np.asarray(r.vertices)
    tris = [(p[0], p[k], p[k + 1]) for p in r.panels for k in range(1, len(p) - 1)]
    owner = np.repeat(np.arange(len(r.panels)), [len(p) - 2 for p in r.panels])
    a, b, c = (v[[t[i] for t in tris]] for i in range(3))
    e1, e2 = b - a, c - a
    count = np.zeros(len(x), int)
    for k in range(len(x)):  # Moller-Trumbore along the normal
        pvec = np.cross(nrm[k], e2)
        det = np.einsum("ij,ij->i", e1, pvec)
        ok = np.abs(det) > 1e-12
        inv = 1.0 / np.where(ok, det, 1.0)
        tvec = x[k] - a
        b1 = np.einsum("ij,ij->i", tvec, pvec) * inv
        qvec = np.cross(tvec, e1)
        b2 = (qvec @ nrm[k]) * inv
        t = np.einsum("ij,ij->i", e2, qvec) * inv
        hit = ok & (b1 >= -1e-9) & (b2 >= -1e-9) & (b1 + b2 <= 1 + 1e-9) & (np.abs(t) <= reach)
        count[k] = len(set(owner[hit]))
    return (w * (count == 0)).sum() / w.sum(), (w * (count > 1)).sum() / w.sum()


@pytest.mark.parametrize("method", ["iso_grid", "equal_size_grid"])
@pytest.mark.parametrize("size", [700.0, 1500.0, 3000.0])
def test_grids_tile_a_hemisphere_up_to_its_apex(method, size):
    """A hemisphere (a pole on its seam): iso_grid at 1500 mm was refused with
    "the panels leave 0.11% of the face uncovered (the widest hole, 3043.8 mm
    across ...)" - the pole row's short rods were merged, a fan panel then had
    corners on both sides of the seam and the coverage scan read it the long
    way round. Outlines are now unwrapped across the seam before they are
    scanned. Checked independently in 3D: normal lines of random surface points
    meet the panels once."""
    face = Part.makeSphere(10000.0, FreeCAD.Vector(), FreeCAD.Vector(0, 0, 1), 0, 90, 360).Faces[0]
    r = tessella.panelize(face, method=method, size=size)
    gap, overlap = _normal_line_coverage(face, r, reach=0.2 * size)
    assert gap < 2e-3 and overlap < 2e-3
    assert 0.95 < r.metrics["panel_area"].sum() / face.Area <= 1.0


@pytest.mark.parametrize("method", ["iso_grid", "equal_size_grid", "walking_agent", "boundary_driven"])
def test_a_face_whose_first_wire_is_its_hole(method):
    # A STEP part's thin annulus listed its hole's wire first; the grids
    # snapped their crossings with the outer circle onto the hole (the trim
    # loop index counted the B-rep's wires, not outer-first) and left 0.4-1.8%
    # of the face uncovered. Built here with the hole first and with the
    # outer wire first: the same panels, and their areas (flat, on a plane)
    # sum to the annulus's within the trim polylines' deflection.
    V = FreeCAD.Vector
    big, small = 625.0, 517.0
    halves = [Part.ArcOfCircle(Part.Circle(V(), V(0, 0, 1), big), a, a + math.pi).toShape()
              for a in (0.0, math.pi)]
    outer = Part.Wire(halves)
    hole = Part.Wire(Part.Circle(V(), V(0, 0, 1), small).toShape())
    hole.reverse()
    hole_first = Part.Face(Part.Plane(), [hole, outer])
    outer_first = Part.Face(Part.Plane(), [outer, hole])
    assert hole_first.isValid() and outer_first.isValid()
    assert hole_first.Wires[0].Length < hole_first.Wires[1].Length  # the hole comes first
    annulus = math.pi * (big ** 2 - small ** 2)
    assert abs(hole_first.Area - annulus) < 1e-6 * annulus
    kw = {"size": 146.0} if method != "walking_agent" else {"max_size": 146.0, "max_deviation": 1.0}
    a = tessella.panelize(hole_first, method=method, **kw)
    b = tessella.panelize(outer_first, method=method, **kw)
    for r in (a, b):
        assert r.summary["gap_fraction"] < 1e-4 and r.summary["overlap_fraction"] < 1e-4
        xy = r.vertices[:, :2]
        radius = np.hypot(xy[:, 0], xy[:, 1])
        assert radius.min() > small - 1e-6 and radius.max() < big + 1e-6
        # Every panel lies on the plane z = 0: its area is its polygon's.
        area = sum(0.5 * abs(np.dot(xy[list(p), 0], np.roll(xy[list(p), 1], -1))
                             - np.dot(xy[list(p), 1], np.roll(xy[list(p), 0], -1)))
                   for p in r.panels)
        assert abs(area - annulus) < 1e-4 * annulus, (method, area, annulus)
    assert len(a.panels) == len(b.panels)


@pytest.mark.parametrize("method", ["iso_grid", "equal_size_grid"])
def test_a_size_coarser_than_a_closed_face(method):
    # A full cylinder at a size beyond its circumference got one cell around
    # (its corners coincide: no panel, "100% uncovered"), at a size beyond
    # half of it two cells (two flat panels through the axis, the same in
    # space); a full sphere at a size beyond its meridian got one cell from
    # pole to pole ("157% uncovered"). The grids take at least three cells
    # around a closed direction and two between two poles.
    def area(x):
        return 0.5 * sum(np.linalg.norm(np.cross(x[k] - x[0], x[k + 1] - x[0]))
                         for k in range(1, len(x) - 1))

    radius, height = 1000.0, 10000.0
    cylinder = next(f for f in Part.makeCylinder(radius, height).Faces
                    if f.Surface.__class__.__name__ == "Cylinder")
    for size in (8000.0, 4000.0):
        r = tessella.panelize(cylinder, method=method, size=size)
        assert r.summary["gap_fraction"] < 1e-6 and r.summary["overlap_fraction"] < 1e-6
        # Flat rectangles of an inscribed prism of n >= 3 sides: their areas
        # sum to n chords x the height, and no two lie on the same side.
        angles = {round(math.atan2(*r.vertices[list(p)].mean(axis=0)[:2][::-1]), 6)
                  for p in r.panels}
        n = len(angles)
        assert n >= 3
        total = sum(area(r.vertices[list(p)]) for p in r.panels)
        assert abs(total - n * 2 * radius * math.sin(math.pi / n) * height) < 1e-6 * total
    sphere = Part.makeSphere(2000.0).Faces[0]
    r = tessella.panelize(sphere, method=method, size=20000.0)
    assert len(r.panels) == 6 and r.summary["gap_fraction"] < 1e-6
    for p in r.panels:  # triangles from a pole to the equator, none without area
        x = np.unique(np.round(r.vertices[list(p)], 6), axis=0)
        assert len(x) == 3 and area(x) > 1e6
    with pytest.raises(ValueError, match="u_count must be at least 3"):
        tessella.panelize(cylinder, method="iso_grid", u_count=2, v_count=3)
