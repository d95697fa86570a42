"""The console API on real OCCT faces, checked by independent means: FreeCAD's
own distance and projection (OCCT Extrema), numpy sampling, closed forms."""
import math

import FreeCAD
import numpy as np
import Part
import pytest

import freecad_workbench as tessella


def surface_distance(face, p):
    """Distance from p to the underlying surface, by FreeCAD's projection."""
    u, v = face.Surface.parameter(FreeCAD.Vector(*p))
    return (face.Surface.value(u, v) - FreeCAD.Vector(*p)).Length


def trimmed_distance(face, p):
    """Distance from p to the trimmed face (outside or over a hole is far)."""
    return Part.Vertex(FreeCAD.Vector(*p)).distToShape(face)[0]


@pytest.fixture(scope="module", params=["iso_grid", "equal_size_grid"])
def result(request, freeform_face):
    return tessella.panelize(freeform_face, method=request.param, size=1500.0)


def test_result_has_the_contract_shapes(result):
    n = len(result.vertices)
    assert result.vertices.shape == (n, 3) and result.vertices.dtype == np.float64
    assert result.uv.shape == (n, 2)
    assert result.normals.shape == (n, 3)
    np.testing.assert_allclose(np.linalg.norm(result.normals, axis=1), 1.0, atol=1e-12)
    assert result.rods.ndim == 2 and result.rods.shape[1] == 2
    assert np.all(result.rods[:, 0] < result.rods[:, 1])
    assert len({tuple(r) for r in result.rods}) == len(result.rods)
    p = len(result.panels)
    for name in ("panel_deviation", "panel_planarity", "panel_area", "panel_min_angle",
                 "panel_max_angle"):
        assert result.metrics[name].shape == (p,)
    assert result.metrics["rod_length"].shape == (len(result.rods),)
    assert result.panel_ids[0] == "P-0001" and len(set(result.panel_ids)) == p
    # Rods join consecutive nodes along each panel's outline (outline points
    # between them only shape the boundary panels).
    node_set = set(int(v) for v in result.nodes)
    edges = set()
    for q in result.panels:
        ring = [v for v in q if v in node_set]
        for k in range(len(ring)):
            a, b = ring[k], ring[(k + 1) % len(ring)]
            if a != b:
                edges.add((min(a, b), max(a, b)))
    assert edges == {tuple(r) for r in result.rods}
    assert set(result.rods.ravel()) <= node_set
    assert len(result.node_ids) == len(result.nodes) == result.summary["node_count"]
    assert result.metrics["node_valence"].shape == (len(result.nodes),)
    assert result.metrics["node_valence"].min() >= 2
    # Every other vertex is an outline point of exactly one (boundary) panel.
    uses = np.zeros(n, dtype=int)
    for q in result.panels:
        uses[list(q)] += 1
    outline = np.setdiff1d(np.arange(n), result.nodes)
    assert np.all(uses[outline] == 1)
    assert result.summary["panel_count"] == p
    assert result.summary["irregular_count"] == int(result.irregular.sum())


def test_every_vertex_lies_on_the_surface_and_within_the_trim(result, freeform_face):
    size = result.summary["model_size"]
    # Nodes are surface points; an outline point of a flat boundary piece lies on
    # the piece's plane, within that panel's deviation of the surface.
    nodes = set(int(v) for v in result.nodes)
    allowed = np.zeros(len(result.vertices))
    for k, q in enumerate(result.panels):
        allowed[list(q)] = np.maximum(allowed[list(q)], result.metrics["panel_deviation"][k])
    for v, p in enumerate(result.vertices):
        limit = 1e-6 * size if v in nodes else allowed[v] * (1 + 1e-9) + 1e-6 * size
        assert surface_distance(freeform_face, p) <= limit
    # Nodes are on the true trim: grid/trim crossings are snapped onto it; outline
    # points (the (u,v) of samples of the trim curves) map onto it.
    rng = np.random.default_rng(3)
    for k in rng.choice(len(result.vertices), size=min(150, len(result.vertices)), replace=False):
        p = result.vertices[k] if k in nodes else freeform_face.Surface.value(*result.uv[k])
        assert trimmed_distance(freeform_face, np.asarray(p)) <= 1e-6 * size
    uses = np.zeros(len(result.vertices), dtype=int)
    for q in result.panels:
        uses[list(q)] += 1
    boundary_nodes = [v for v in result.nodes if uses[v] <= 2][:120]
    for v in boundary_nodes:
        assert trimmed_distance(freeform_face, result.vertices[v]) <= 1e-6 * size


def test_no_panel_reaches_outside_the_face_or_into_a_hole(result, freeform_face):
    # Edge midpoints and corner means of panels, measured against the trimmed
    # face: a point over a hole or beyond the outline would be far (the holes
    # and the bite are >1 m across); a point of a panel is within the panel's
    # deviation of the face. Boundary panels (not quads) all, quads a sample.
    dev = result.metrics["panel_deviation"]
    rng = np.random.default_rng(5)
    quads = [k for k, q in enumerate(result.panels) if len(q) == 4]
    chosen = [k for k, q in enumerate(result.panels) if len(q) != 4]
    chosen += list(rng.choice(quads, size=min(20, len(quads)), replace=False))
    for k in chosen:
        pts = result.vertices[list(result.panels[k])]
        probes = list(0.5 * (pts + np.roll(pts, -1, axis=0)))[::max(1, len(pts) // 12)]
        if len(pts) == 4:  # the mean of a non-convex outline may lie outside it
            probes.append(pts.mean(axis=0))
        for q in probes:
            assert trimmed_distance(freeform_face, q) <= dev[k] + 1.0, (k, q)


def test_no_gap_along_the_boundary(result, freeform_face):
    # Boundary rods (used by one panel) sum to the face's boundary length
    # within the chord shortening of the trim curves.
    uses = {}
    for q in result.panels:
        for k in range(len(q)):
            e = tuple(sorted((q[k], q[(k + 1) % len(q)])))
            uses[e] = uses.get(e, 0) + 1
    assert max(uses.values()) <= 2
    boundary = sum(np.linalg.norm(result.vertices[a] - result.vertices[b])
                   for (a, b), n in uses.items() if n == 1)
    perimeter = sum(w.Length for w in freeform_face.Wires)
    assert boundary == pytest.approx(perimeter, rel=2e-3)


def test_area_matches_the_face_and_converges(freeform_face, result):
    area = result.metrics["panel_area"].sum()
    assert area == pytest.approx(freeform_face.Area, rel=0.01)
    finer = tessella.panelize(freeform_face, method=result.method, size=500.0)
    assert abs(finer.metrics["panel_area"].sum() - freeform_face.Area) < abs(area - freeform_face.Area)


def test_reported_deviation_agrees_with_independent_sampling(result, freeform_face):
    rng = np.random.default_rng(7)
    quads = [k for k, q in enumerate(result.panels) if len(q) == 4]
    for k in rng.choice(quads, size=min(12, len(quads)), replace=False):
        p0, p1, p2, p3 = result.vertices[list(result.panels[k])]
        worst = 0.0
        for s in np.linspace(0, 1, 13):
            for t in np.linspace(0, 1, 13):
                x = (1 - s) * (1 - t) * p0 + s * (1 - t) * p1 + s * t * p2 + (1 - s) * t * p3
                worst = max(worst, surface_distance(freeform_face, x))
        reported = result.metrics["panel_deviation"][k]
        assert reported == pytest.approx(worst, rel=0.05, abs=1e-3), k


def test_panels_are_counter_clockwise_about_the_face_normal(result):
    for q in result.panels:
        pts = result.vertices[list(q)]
        newell = np.sum(np.cross(pts, np.roll(pts, -1, axis=0)), axis=0)
        assert np.dot(newell, result.normals[list(q)].mean(axis=0)) > 0


def test_results_are_bitwise_deterministic(freeform_face):
    a = tessella.panelize(freeform_face, method="equal_size_grid", size=2000.0)
    b = tessella.panelize(freeform_face, method="equal_size_grid", size=2000.0)
    assert np.array_equal(a.vertices, b.vertices) and a.panels == b.panels
    assert np.array_equal(a.metrics["panel_deviation"], b.metrics["panel_deviation"])


def test_full_cylinder_is_welded_at_the_seam():
    face = Part.makeCylinder(5000, 8000).Faces[0]
    r = tessella.panelize(face, method="iso_grid", size=1000.0)
    assert all(len(q) == 4 for q in r.panels)
    d = np.linalg.norm(r.vertices[:, None, :] - r.vertices[None, :, :], axis=2)
    np.fill_diagonal(d, np.inf)
    assert d.min() > 100.0  # no duplicate node along the seam
    n = 31  # round(2 pi 5000 / 1000)
    assert r.metrics["panel_deviation"].max() == pytest.approx(5000 * (1 - math.cos(math.pi / n)), rel=1e-6)


def test_bezier_patch_and_plane_and_counts():
    bez = Part.BezierSurface()
    bez.increase(3, 3)
    for i in range(4):
        for j in range(4):
            bez.setPole(i + 1, j + 1, FreeCAD.Vector(1000 * i, 1000 * j, 400 * ((i - 1.5) ** 2 - (j - 1.5) ** 2)))
    r = tessella.panelize(bez.toShape(), method="iso_grid", u_count=6, v_count=4)
    assert len(r.panels) == 24 and all(len(q) == 4 for q in r.panels)
    plane = Part.makePlane(6000, 4000)
    r = tessella.panelize(plane, size=1000.0)
    assert len(r.panels) == 24
    assert r.metrics["panel_deviation"].max() < 1e-9
    np.testing.assert_allclose(r.metrics["panel_area"], 1e6, rtol=1e-12)


def test_selection_tuple_is_accepted():
    doc = FreeCAD.newDocument("ApiSel")
    try:
        obj = doc.addObject("Part::Feature", "Box")
        obj.Shape = Part.makeBox(3000, 2000, 1000)
        r = tessella.panelize((obj, "Face6"), size=500.0)  # top face, 3 m x 2 m
        assert len(r.panels) == 24
        with pytest.raises(ValueError, match="not a face"):
            tessella.panelize((obj, "Edge1"), size=500.0)
        with pytest.raises(ValueError, match="Face99"):
            tessella.panelize((obj, "Face99"), size=500.0)
    finally:
        FreeCAD.closeDocument(doc.Name)


@pytest.mark.parametrize(
    "kwargs, match",
    [
        (dict(size=0.0), "size"),
        (dict(size=-5.0), "size"),
        (dict(size="abc"), "size"),
        (dict(size=float("nan")), "size"),
        (dict(), "size"),
        (dict(size=100.0, u_count=3, v_count=3), "either size"),
        (dict(u_count=-1, v_count=3), "u_count"),
        (dict(size=1500.0, colour="red"), "unknown parameter"),
        (dict(size=1.0), "max_panels|too small"),
        (dict(size=100.0, max_panels=10), "max_panels"),
        (dict(size=1500.0, sliver_fraction=2.0), "sliver_fraction"),
        (dict(size=1500.0, samples=0), "samples"),
        (dict(size=1500.0, min_angle=-3), "min_angle"),
    ],
)
def test_bad_parameters_raise_value_error_naming_them(freeform_face, kwargs, match):
    with pytest.raises(ValueError, match=match):
        tessella.panelize(freeform_face, method="iso_grid", **kwargs)


def test_bad_shapes_raise_value_error():
    with pytest.raises(ValueError, match="method"):
        tessella.panelize(Part.makePlane(10, 10), method="voronoi", size=1.0)
    with pytest.raises(ValueError, match="6 faces"):
        tessella.panelize(Part.makeBox(10, 10, 10), size=1.0)
    with pytest.raises(ValueError, match="0 faces"):
        tessella.panelize(Part.makeLine((0, 0, 0), (1, 0, 0)), size=1.0)
    with pytest.raises(TypeError):
        tessella.panelize("Face1", size=1.0)
    # A B-spline patch collapsed onto a line has no area.
    flat = Part.BSplineSurface()
    flat.buildFromPolesMultsKnots(
        [[FreeCAD.Vector(i, 0, 0), FreeCAD.Vector(i, 0, 0)] for i in range(2)],
        [2, 2], [2, 2], [0, 1], [0, 1], False, False, 1, 1,
    )
    with pytest.raises(ValueError, match="degenerate"):
        tessella.panelize(flat.toShape(), size=1.0)


def test_shapes_round_trip_through_brep(result):
    panels = Part.Shape()
    panels.importBrepFromString(result.panels_brep())
    assert len(panels.childShapes()) == len(result.panels)
    # Every panel is a valid shape through its corners, facing the surface normal.
    pieces = panels.childShapes()
    for k, (piece, q) in enumerate(zip(pieces, result.panels)):
        assert piece.isValid(), k
        # Its vertices are the panel's corners (same points, nothing else).
        mine = np.array([v.Point for v in piece.Vertexes])
        corners = result.vertices[list(q)]
        d = np.linalg.norm(mine[:, None, :] - corners[None, :, :], axis=2)
        assert d.min(axis=1).max() < 1e-6 and d.min(axis=0).max() < 1e-6, k
        normal = result.normals[list(q)].mean(axis=0)
        for f in piece.Faces:
            u0, u1, v0, v1 = f.ParameterRange
            n = f.normalAt(0.5 * (u0 + u1), 0.5 * (v0 + v1))
            assert np.dot([n.x, n.y, n.z], normal) > 0, k
    rods = Part.Shape()
    rods.importBrepFromString(result.rods_brep())
    lengths = np.array([e.Length for e in rods.Edges])
    np.testing.assert_allclose(lengths, result.metrics["rod_length"], rtol=1e-12)
    nodes = Part.Shape()
    nodes.importBrepFromString(result.nodes_brep())
    pts = np.array([v.Point for v in nodes.Vertexes])
    np.testing.assert_allclose(pts, result.vertices[result.nodes], atol=1e-9)
