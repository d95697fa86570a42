"""Boundary panels are modelled as what they are made of (issue 12, part 1): a flat
sheet, or a sheet bent along at most two lines between its nodes (one for a
quad), never a fan of folds; checked independently of the core on a trimmed,
doubly curved face that is not a bundled example (tests/python/conftest.py)."""

import math

import FreeCAD  # noqa: F401  (before Part)
import numpy as np
import Part
import pytest

import freecad_workbench as tessella

METHODS = [
    ("iso_grid", {"size": 1500.0}),
    ("iso_grid", {"size": 2500.0}),
    ("equal_size_grid", {"size": 2000.0}),
    ("relaxed_grid", {"u_count": 9, "v_count": 7}),
    ("walking_agent", {"max_deviation": 60.0}),
    # (at 1700-2000 mm its network overlaps near the notch by 3.7% of the
    # face: refused by the coverage check since issue 18)
    ("boundary_driven", {"size": 1400.0}),
    # (a fan of folds before stop 54: a rod nearly along the lower hole's rim)
    ("boundary_driven", {"size": 1200.0}),
]


@pytest.fixture(scope="module", params=METHODS, ids=lambda m: f"{m[0]}-{list(m[1].values())[0]}")
def run(request, freeform_face):
    method, params = request.param
    r = tessella.panelize(freeform_face, method=method, **params)
    return method, params, r, tessella.unfold(r)


def plane_distance(points):
    """Largest distance of the points from their least-squares plane (SVD)."""
    p = np.asarray(points, dtype=float)
    c = p.mean(axis=0)
    normal = np.linalg.svd(p - c)[2][-1]
    return float(np.max(np.abs((p - c) @ normal)))


def is_node_panel(r, p):
    nodes = set(int(v) for v in r.nodes)
    return all(int(v) in nodes for v in p)


#: boundary_driven adds no trim node (its layout is all quads), so a boundary
#: quad whose trim run curves away from its piece plane (its outline crosses
#: itself there) stays a curved piece, which unfolds as a fan of folds. Since
#: stop 54 the angle moves weigh the angle a rod makes with the trim itself
#: (no more 0.2-1 deg spikes, no outline crossing itself, no unfold failing):
#: at 1400 mm one quad by the lower hole slid its rim node so far round the
#: rim that its trim run does this. Over the bundled examples and this face
#: at 600-1500 mm: 3 such panels of 35,194 (5 before, and 5 results whose
#: unfold failed outright).
FAN_AT_THE_RIM = pytest.mark.xfail(
    strict=True, raises=AssertionError,
    reason="boundary_driven: a boundary quad whose trim run leaves its piece plane unfolds as a fan")


def test_no_fan_of_folds(run, request):
    method, params, r, flat = run
    if method == "boundary_driven" and params["size"] == 1400.0:
        request.applymarker(FAN_AT_THE_RIM)
    assert len(flat) == len(r.panels) > 20
    nodes = set(int(v) for v in r.nodes)
    for p, f in zip(r.panels, flat):
        quad = len(p) == 4 and is_node_panel(r, p)
        assert len(f.folds) <= (1 if quad else 2), (method, len(p), f.folds)
        for a, b, _ in f.folds:  # a fold runs between two nodes of the panel
            assert int(p[a]) in nodes and int(p[b]) in nodes
        assert not f.self_intersecting
        # no triangle of a piece turned over on its plane (that reads as a 180 deg
        # fold); boundary_driven's own layout folds a pentagon near this face's
        # notch over (175 deg between its node triangles: issue 18)
        if method != "boundary_driven":
            assert f.max_fold < 45.0, (method, f.id, f.max_fold)


def test_flat_pieces_are_flat_and_their_trim_edge_lies_on_the_plane(run, freeform_face):
    method, _, r, flat = run
    xyz = np.asarray(r.vertices)
    size = r.summary["model_size"]
    boundary = 0
    for p, f in zip(r.panels, flat):
        if is_node_panel(r, p):
            continue
        boundary += 1
        if not f.folds and f.max_fold < 1e-6:
            # flat: every outline point (trim edge included) on one plane
            assert plane_distance(xyz[list(p)]) < 1e-7 * size, method
    if method != "boundary_driven":  # it keeps quads at the trim
        assert boundary > 0


def test_folds_only_above_the_tolerance_and_flat_panels_have_none(run):
    _, _, r, flat = run
    xyz = np.asarray(r.vertices)
    tol = tessella.fabrication.DEFAULT_FOLD_TOLERANCE
    for p, f in zip(r.panels, flat):
        for _, _, angle in f.folds:
            assert abs(angle) > tol
        if plane_distance(xyz[list(p)]) < 1e-9 * r.summary["model_size"]:
            assert f.folds == []


def test_nodes_stay_on_the_surface_and_the_deviation_counts_the_trim_edge(run, freeform_face):
    """Nodes are surface points; the reported deviation of every panel is at least
    the distance of its own outline points (the trim edge on the piece plane) from
    the surface, measured here with OCCT."""
    method, _, r, _ = run
    xyz = np.asarray(r.vertices)
    size = r.summary["model_size"]
    surface = freeform_face.Surface
    for v in r.nodes[:: max(1, len(r.nodes) // 200)]:
        p = FreeCAD.Vector(*map(float, xyz[v]))
        u, w = surface.parameter(p)
        assert (surface.value(u, w) - p).Length < 1e-6 * size
    dev = np.asarray(r.metrics["panel_deviation"])
    checked = 0
    for k, p in enumerate(r.panels):
        if is_node_panel(r, p):
            continue
        worst = 0.0
        for v in p:
            q = FreeCAD.Vector(*map(float, xyz[v]))
            u, w = surface.parameter(q)
            worst = max(worst, (surface.value(u, w) - q).Length)
        assert dev[k] >= worst * (1 - 1e-6) - 1e-9, (method, k, dev[k], worst)
        checked += 1
        if checked > 60:
            break


def test_unfolded_pieces_keep_their_lengths_and_cover_the_face(run, freeform_face):
    method, _, r, flat = run
    xyz = np.asarray(r.vertices)
    for p, f in zip(r.panels, flat):
        e3 = np.linalg.norm(np.roll(xyz[list(p)], -1, axis=0) - xyz[list(p)], axis=1)
        # exact up to rounding along a chain of triangles: 1e-9 of the panel's size
        assert np.allclose(f.edge_lengths, e3, rtol=1e-9, atol=1e-9 * e3.max())
    total = sum(f.area for f in flat)
    if method == "boundary_driven":
        # boundary_driven's pieces are bilinear-like quads bent once: their own area
        # (bilinear quads: the unfolded triangles are close to, not equal to, them)
        total_model = float(np.sum(r.metrics["panel_area"]))
        assert abs(total / total_model - 1) < 0.005
        return
    assert abs(total / freeform_face.Area - 1) < 0.005, (method, total / freeform_face.Area)


def test_panel_shapes_are_the_pieces(run):
    """The Panels compound holds one flat face per piece: as many faces as bends + 1."""
    method, _, r, flat = run
    shape = Part.Shape()
    shape.importBrepFromString(r.panels_brep())
    subs = shape.childShapes()
    assert len(subs) == len(r.panels)
    for p, f, s in zip(r.panels, flat, subs):
        if is_node_panel(r, p) and len(p) <= 4:
            continue
        for face in s.Faces:
            assert face.Surface.TypeId == "Part::GeomPlane", method


def test_too_many_nodes_split_by_a_new_rod_and_summary_reports_it(freeform_face):
    r = tessella.panelize(freeform_face, method="iso_grid", size=1500.0)
    s = r.summary
    nodes = set(int(v) for v in r.nodes)
    assert max(sum(int(v) in nodes for v in p) for p in r.panels) <= 5
    assert s["bend_count"] > 0 and s["split_panels"] >= 0
    # The new rods are rods: every panel's consecutive nodes are joined by one.
    rods = set(map(tuple, np.asarray(r.rods).reshape(-1, 2).tolist()))
    for p in r.panels:
        ns = [int(v) for v in p if int(v) in nodes]
        for a, b in zip(ns, ns[1:] + ns[:1]):
            assert (min(a, b), max(a, b)) in rods


def boundary_deviation_max(r):
    dev = np.asarray(r.metrics["panel_deviation"])
    return max(dev[k] for k, p in enumerate(r.panels) if not is_node_panel(r, p))


def test_boundary_deviation_refines_pieces_with_spaced_nodes(freeform_face):
    loose = tessella.panelize(freeform_face, method="iso_grid", size=2500.0, boundary_deviation=1e5)
    auto = tessella.panelize(freeform_face, method="iso_grid", size=2500.0)
    tight = tessella.panelize(freeform_face, method="iso_grid", size=2500.0, boundary_deviation=20.0)
    added = [r.summary["boundary_nodes_added"] for r in (loose, auto, tight)]
    assert added[0] <= added[1] <= added[2] and added[2] > added[0]
    assert boundary_deviation_max(tight) <= boundary_deviation_max(auto) <= boundary_deviation_max(loose)
    # the automatic allowance: the largest deviation of the full panels
    dev = np.asarray(auto.metrics["panel_deviation"])
    full = max(dev[k] for k, p in enumerate(auto.panels) if is_node_panel(auto, p) and len(p) == 4)
    assert boundary_deviation_max(auto) < boundary_deviation_max(loose)
    assert full > 0
    # new nodes are nodes on the trim, on the surface
    surface = freeform_face.Surface
    xyz = np.asarray(tight.vertices)
    for v in tight.nodes:
        q = FreeCAD.Vector(*map(float, xyz[v]))
        assert (surface.value(*surface.parameter(q)) - q).Length < 1e-6 * tight.summary["model_size"]
    with pytest.raises(ValueError, match="boundary_deviation"):
        tessella.panelize(freeform_face, method="iso_grid", size=2500.0, boundary_deviation=-1.0)


def test_same_input_same_pieces_bit_for_bit(freeform_face):
    a = tessella.panelize(freeform_face, method="equal_size_grid", size=2000.0)
    b = tessella.panelize(freeform_face, method="equal_size_grid", size=2000.0)
    assert np.array_equal(a.vertices, b.vertices) and a.panels == b.panels
    fa, fb = tessella.unfold(a), tessella.unfold(b)
    assert all(np.array_equal(x.outline, y.outline) and x.folds == y.folds for x, y in zip(fa, fb))
    assert math.isfinite(a.summary["panel_deviation"]["max"])


def _outline_corners(r, p):
    xyz = np.asarray(r.vertices)[list(p)]
    a, b = np.roll(xyz, 1, axis=0) - xyz, np.roll(xyz, -1, axis=0) - xyz
    cos = np.einsum("ij,ij->i", a, b) / (np.linalg.norm(a, axis=1) * np.linalg.norm(b, axis=1))
    return np.degrees(np.arccos(np.clip(cos, -1, 1)))


@pytest.mark.parametrize("name, size, before", [
    # a grid line along a hole's rim: a rod leaving its trim node at 0.03 deg
    # to the rim (the panel a knife edge 1.2 m long); at 900 mm 0.18 and 2.8
    # deg. (Where both panels at the spike are quads the union would need a
    # new rod and is not made: bench/boundary_outlines.py counts those left.)
    ("trimmed_bspline_holes", 1200.0, 0.03), ("trimmed_bspline_holes", 900.0, 0.18)])
def test_no_knife_edge_where_a_grid_line_runs_along_a_rim(name, size, before):
    import os
    from conftest import independent_coverage
    shape = Part.Shape()
    shape.read(os.path.join(os.path.dirname(__file__), "..", "..", "examples", name + ".brep"))
    face = shape.Faces[0]
    r = tessella.panelize(face, method="iso_grid", size=size)
    assert r.summary["merged_spikes"] >= 1
    sharpest = min(_outline_corners(r, p).min() for p in r.panels)
    assert sharpest > 5.0 > before, sharpest
    gap, extra = independent_coverage(face, r)  # the union covers what both did
    assert gap < 4e-3 and extra < 4e-3, (gap, extra)
    flat = tessella.unfold(r)
    assert not any(f.self_intersecting for f in flat)
