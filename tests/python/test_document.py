"""The parametric Panelization in a FreeCAD document (headless): creation, the
children's shapes and data, recompute on parameter and source changes, save and
reopen, bad input leaving the document untouched, and one undo step."""

import json
import math
import os
import sys

import pytest

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
for _p in ("/usr/lib/freecad-python3/lib", REPO):
    if _p not in sys.path:
        sys.path.append(_p)

import FreeCAD  # noqa: E402  (before Part, or Part segfaults)
import Part  # noqa: E402
import numpy as np  # noqa: E402

import freecad_workbench as tessella  # noqa: E402
from freecad_workbench.features import panelization as feat  # noqa: E402

SIZE = 1500.0
HOLE_RADIUS = 1200.0
HOLE_CENTER = (4500.0, 3750.0)


def _bspline_face():
    """A doubly curved 9000 x 7500 mm cubic B-spline patch."""
    heights = [
        [0, 700, 700, 0],
        [500, 1800, 1600, 400],
        [400, 1500, 1900, 600],
        [0, 600, 800, 100],
    ]
    poles = [[FreeCAD.Vector(3000.0 * i, 2500.0 * j, heights[i][j]) for j in range(4)]
             for i in range(4)]
    surf = Part.BSplineSurface()
    surf.buildFromPolesMultsKnots(poles, [4, 4], [4, 4], [0.0, 1.0], [0.0, 1.0],
                                  False, False, 3, 3)
    return surf.toShape()


def _make_source(doc):
    """Part::Cut of the B-spline face by a vertical cylinder: a face with a hole.

    Returns (cut, surface feature, cylinder feature)."""
    surface = doc.addObject("Part::Feature", "Surface")
    surface.Shape = _bspline_face()
    cyl = doc.addObject("Part::Cylinder", "Hole")
    cyl.Radius = HOLE_RADIUS
    cyl.Height = 10000.0
    cyl.Placement.Base = FreeCAD.Vector(HOLE_CENTER[0], HOLE_CENTER[1], -5000.0)
    cut = doc.addObject("Part::Cut", "Cut")
    cut.Base = surface
    cut.Tool = cyl
    doc.recompute()
    assert len(cut.Shape.Faces) == 1, "the cut must leave exactly one face"
    assert len(cut.Shape.Faces[0].Wires) == 2, "the face must have an outer wire and a hole"
    return cut, surface, cyl


@pytest.fixture
def doc():
    d = FreeCAD.newDocument("TessellaDocTest")
    name = d.Name
    yield d
    if name in FreeCAD.listDocuments():
        FreeCAD.closeDocument(name)


@pytest.fixture
def source(doc):
    return _make_source(doc)


def _children(parent):
    kids = feat.children_of(parent)
    assert [k.Role for k in kids] == list(feat.ROLES)
    return kids


def _api_result(parent):
    """A fresh console-API result for the parent's current source and parameters."""
    method, params = parent.Proxy.parameters(parent)
    face_arg, _ = parent.Proxy.source_face(parent)
    return tessella.panelize(face_arg, method=method, **params)


def _check_consistent(parent):
    """The parent's summary and the three children agree with a fresh API run."""
    assert parent.isValid(), parent.State
    r = _api_result(parent)
    panels, rods, nodes = _children(parent)
    for o in (panels, rods, nodes):
        assert o.isValid(), (o.Label, o.State)
        assert not o.Shape.isNull()
    n_p, n_r, n_n = len(r.panels), len(r.rods), len(r.nodes)
    assert n_p > 0 and n_r > 0 and n_n > 0
    assert (parent.PanelCount, parent.RodCount, parent.NodeCount) == (n_p, n_r, n_n)
    assert parent.PanelCount == r.summary["panel_count"]
    assert parent.MergedSlivers == r.summary["merged_slivers"]
    assert parent.IrregularPanels == r.summary["irregular_count"]
    assert parent.QuadShare == pytest.approx(r.summary["quad_share"])
    dev = r.metrics["panel_deviation"]
    assert parent.MaxDeviation.Value == pytest.approx(float(dev.max()), rel=1e-9, abs=1e-9)
    assert parent.MeanDeviation.Value == pytest.approx(float(dev.mean()), rel=1e-9, abs=1e-9)
    # One sub-shape per panel / rod / node, in order, with matching IDs and data.
    assert len(panels.Shape.childShapes()) == n_p
    assert len(rods.Shape.childShapes()) == n_r
    assert len(nodes.Shape.childShapes()) == n_n
    assert all(e.ShapeType == "Edge" for e in rods.Shape.childShapes())
    assert all(v.ShapeType == "Vertex" for v in nodes.Shape.childShapes())
    assert list(panels.PanelIds) == r.panel_ids
    assert panels.PanelIds[0] == "P-0001" and len(set(panels.PanelIds)) == n_p
    assert list(rods.RodIds) == r.rod_ids
    assert list(nodes.NodeIds) == r.node_ids
    np.testing.assert_allclose(rods.RodLengths, r.metrics["rod_length"], rtol=1e-9)
    assert list(nodes.Valence) == [int(v) for v in r.metrics["node_valence"]]
    # The rod edges really have the listed lengths, the nodes sit on the vertices.
    edge_lengths = [e.Length for e in rods.Shape.childShapes()]
    np.testing.assert_allclose(edge_lengths, rods.RodLengths, rtol=1e-6)
    pts = np.array([[v.X, v.Y, v.Z] for v in nodes.Shape.childShapes()])
    np.testing.assert_allclose(pts, r.vertices[r.nodes], atol=1e-6)
    return r


def _panel_area(parent):
    return sum(s.Area for s in _children(parent)[0].Shape.childShapes())


def _count_hits_in_hole(parent, center=HOLE_CENTER, radius=HOLE_RADIUS):
    """Panel centroids (projected on XY) lying well inside the hole."""
    n = 0
    for s in _children(parent)[0].Shape.childShapes():
        c = s.CenterOfMass if hasattr(s, "CenterOfMass") else s.BoundBox.Center
        if math.hypot(c.x - center[0], c.y - center[1]) < 0.7 * radius:
            n += 1
    return n


def _names(doc):
    return sorted(o.Name for o in doc.Objects)


# --------------------------------------------------------------------- creation
def test_make_panelization_builds_parent_and_children(doc, source):
    cut = source[0]
    p = tessella.make_panelization((cut, "Face1"), method="iso_grid", size=SIZE)
    assert p.TypeId == "App::FeaturePython"
    assert type(p.Proxy).__module__ == "freecad_workbench.features.panelization"
    assert type(p.Proxy).__name__ == "Panelization"
    assert p.Source[0] == cut and list(p.Source[1]) == ["Face1"]
    assert p.Method == "iso_grid" and p.Size.Value == pytest.approx(SIZE)
    assert len(doc.Objects) == 3 + 4
    kids = _children(p)
    for k in kids:
        assert k.TypeId == "Part::FeaturePython"
        assert type(k.Proxy).__name__ == "PanelizationPart"
        assert k.Base == p
    r = _check_consistent(p)
    # The hole is respected: panel area close to the trimmed face's area, far
    # below the untrimmed patch, and no panel in the middle of the hole.
    face = cut.Shape.Faces[0]
    full = source[1].Shape.Faces[0].Area
    assert _panel_area(p) == pytest.approx(face.Area, rel=0.05)
    assert _panel_area(p) < full - 0.5 * math.pi * HOLE_RADIUS**2
    assert _count_hits_in_hole(p) == 0
    assert r.summary["face_area"] == pytest.approx(face.Area, rel=1e-3)


def test_single_face_object_is_accepted(doc):
    surface = doc.addObject("Part::Feature", "Surface")
    surface.Shape = _bspline_face()
    doc.recompute()
    p = tessella.make_panelization(surface, method="equal_size_grid", size=2000.0)
    assert list(p.Source[1]) == ["Face1"] and p.Method == "equal_size_grid"
    _check_consistent(p)


def test_proxies_persist_json_safe_state(doc, source):
    p = tessella.make_panelization((source[0], "Face1"), size=SIZE)
    for o in [p] + _children(p):
        for state in (o.Proxy.dumps(), o.Proxy.__getstate__()):
            assert json.loads(json.dumps(state)) == state
            assert "_cache" not in json.dumps(state)


# --------------------------------------------------------- parametric updates
def test_parameter_change_recomputes_children(doc, source):
    p = tessella.make_panelization((source[0], "Face1"), size=SIZE)
    before = (p.PanelCount, p.RodCount, p.NodeCount)
    p.Size = SIZE / 2
    doc.recompute()
    after = _check_consistent(p)
    assert p.PanelCount > 2 * before[0]
    assert p.RodCount > before[1] and p.NodeCount > before[2]
    assert len(after.panels) == p.PanelCount
    # Counts override the size for iso_grid.
    p.UCount = 5
    p.VCount = 4
    doc.recompute()
    _check_consistent(p)
    assert p.PanelCount <= 5 * 4 + 4  # at most the grid (plus a few hole splits)
    # Another method.
    p.UCount = 0
    p.VCount = 0
    p.Method = "equal_size_grid"
    p.Size = 2500.0
    doc.recompute()
    _check_consistent(p)


def test_source_dimension_change_updates(doc, source):
    cut, surface, cyl = source
    p = tessella.make_panelization((cut, "Face1"), size=1000.0)
    area_before = _panel_area(p)
    cyl.Radius = 2000.0
    doc.recompute()
    _check_consistent(p)
    area_after = _panel_area(p)
    expected_drop = math.pi * (2000.0**2 - HOLE_RADIUS**2)  # in plan; the surface is tilted
    assert area_before - area_after > 0.8 * expected_drop
    assert _count_hits_in_hole(p, radius=2000.0) == 0


def test_source_placement_change_updates(doc, source):
    cut, surface, cyl = source
    p = tessella.make_panelization((cut, "Face1"), size=SIZE)
    bb0 = _children(p)[0].Shape.BoundBox
    n0 = p.PanelCount
    surface.Placement.Base = FreeCAD.Vector(0, 0, 700.0)
    doc.recompute()
    _check_consistent(p)
    bb1 = _children(p)[0].Shape.BoundBox
    assert bb1.ZMin == pytest.approx(bb0.ZMin + 700.0, abs=1.0)
    assert bb1.ZMax == pytest.approx(bb0.ZMax + 700.0, abs=1.0)
    assert bb1.XMin == pytest.approx(bb0.XMin, abs=1.0)
    assert p.PanelCount == n0


def test_error_in_execute_leaves_children_intact(doc, source):
    p = tessella.make_panelization((source[0], "Face1"), size=SIZE)
    kids = _children(p)
    counts = [len(k.Shape.childShapes()) for k in kids]
    ids = list(kids[0].PanelIds)
    p.MaxPanels = 3  # the core refuses a grid with more panels than this
    doc.recompute()
    assert not p.isValid()
    assert "Invalid" in p.State or "Error" in " ".join(p.State)
    assert [len(k.Shape.childShapes()) for k in kids] == counts
    assert list(kids[0].PanelIds) == ids
    p.MaxPanels = 200000
    doc.recompute()
    _check_consistent(p)
    # A size of 0 with no counts is refused too (PropertyLength clamps -5 to 0).
    p.Size = -5.0
    doc.recompute()
    assert not p.isValid()
    assert [len(k.Shape.childShapes()) for k in kids] == counts
    p.Size = SIZE
    doc.recompute()
    _check_consistent(p)


# ----------------------------------------------------------- save and reopen
def test_save_reopen_and_modify(doc, source, tmp_path):
    cut = source[0]
    p = tessella.make_panelization((cut, "Face1"), size=SIZE)
    p.SliverFraction = 0.3
    doc.recompute()
    saved = {
        "parent": p.Name,
        "kids": [k.Name for k in _children(p)],
        "counts": (p.PanelCount, p.RodCount, p.NodeCount),
        "ids": list(_children(p)[0].PanelIds),
        "lengths": list(_children(p)[1].RodLengths),
        "valence": list(_children(p)[2].Valence),
    }
    saved["cut"] = cut.Name
    path = str(tmp_path / "panelization.FCStd")
    doc.saveAs(path)
    name = doc.Name
    FreeCAD.closeDocument(name)

    d2 = FreeCAD.openDocument(path)
    try:
        p2 = d2.getObject(saved["parent"])
        assert p2 is not None and isinstance(p2.Proxy, feat.Panelization)
        kids = _children(p2)
        assert [k.Name for k in kids] == saved["kids"]
        assert all(isinstance(k.Proxy, feat.PanelizationPart) for k in kids)
        assert (p2.PanelCount, p2.RodCount, p2.NodeCount) == saved["counts"]
        assert p2.Method == "iso_grid" and p2.Size.Value == pytest.approx(SIZE)
        assert p2.SliverFraction == pytest.approx(0.3)
        assert p2.Source[0].Name == saved["cut"] and list(p2.Source[1]) == ["Face1"]
        assert list(kids[0].PanelIds) == saved["ids"]
        assert list(kids[1].RodLengths) == pytest.approx(saved["lengths"])
        assert list(kids[2].Valence) == saved["valence"]
        assert [len(k.Shape.childShapes()) for k in kids] == list(saved["counts"])
        assert not any("Touched" in o.State for o in d2.Objects)
        # Only a child touched after reopening: it rebuilds from the parent on demand.
        kids[1].touch()
        d2.recompute()
        assert kids[1].isValid() and len(kids[1].Shape.childShapes()) == saved["counts"][1]
        # Modify the source after reopening: everything follows.
        area_before = _panel_area(p2)
        d2.getObject("Hole").Radius = 1800.0
        d2.recompute()
        _check_consistent(p2)
        drop = area_before - _panel_area(p2)
        assert drop > 0.8 * math.pi * (1800.0**2 - HOLE_RADIUS**2)
        assert _count_hits_in_hole(p2, radius=1800.0) == 0
    finally:
        FreeCAD.closeDocument(d2.Name)


def test_reopen_upgrades_missing_properties(doc, source, tmp_path):
    """A document from an older version (a property missing) gets it back on open."""
    p = tessella.make_panelization((source[0], "Face1"), size=SIZE)
    panels = _children(p)[0]
    p.removeProperty("Samples")
    p.removeProperty("QuadShare")
    panels.removeProperty("PanelIds")
    assert "Samples" not in p.PropertiesList
    path = str(tmp_path / "old.FCStd")
    doc.saveAs(path)
    names = (p.Name, panels.Name)
    FreeCAD.closeDocument(doc.Name)
    d2 = FreeCAD.openDocument(path)
    try:
        p2, panels2 = d2.getObject(names[0]), d2.getObject(names[1])
        # re-added with its declared default (the core's sample count)
        assert "Samples" in p2.PropertiesList
        assert p2.Samples == tessella.METHODS["iso_grid"].params["samples"].default == 8
        assert "QuadShare" in p2.PropertiesList
        assert "PanelIds" in panels2.PropertiesList
        assert sorted(p2.getEnumerationsOfProperty("Method")) == sorted(tessella.METHODS)
        p2.touch()
        d2.recompute()
        _check_consistent(p2)
    finally:
        FreeCAD.closeDocument(d2.Name)


# -------------------------------------------------------------------- bad input
@pytest.mark.parametrize(
    "source_kind, params",
    [
        ("edge", {"size": SIZE}),
        ("face", {"size": 0.0}),
        ("face", {"size": -100.0}),
        ("face", {"size": SIZE, "max_panels": 3}),
        ("face", {"size": SIZE, "no_such_parameter": 1}),
        ("face", {"size": SIZE, "sliver_fraction": "lots"}),
    ],
)
def test_bad_input_raises_and_creates_nothing(doc, source, source_kind, params):
    cut = source[0]
    before = _names(doc)
    src = (cut, "Edge1") if source_kind == "edge" else (cut, "Face1")
    with pytest.raises(ValueError):
        tessella.make_panelization(src, method="iso_grid", **params)
    assert _names(doc) == before


def test_bad_method_and_multi_face_object(doc, source):
    cut = source[0]
    before = _names(doc)
    with pytest.raises(ValueError):
        tessella.make_panelization((cut, "Face1"), method="voronoi", size=SIZE)
    box = doc.addObject("Part::Box", "Box")
    doc.recompute()
    before = _names(doc)
    with pytest.raises(ValueError):
        tessella.make_panelization((box, "Face99"), size=SIZE)
    assert _names(doc) == before
    # A whole object of several faces is one envelope (issue 14): its six faces,
    # joined along the box's edges; recomputes when the box changes.
    p = tessella.make_panelization(box, size=2.5)
    assert list(p.Source[1]) == [] and p.PanelCount == 6 * 16
    assert len(p.Proxy.result(p).result.summary["faces"]) == 6
    box.Length = 20
    doc.recompute()
    assert p.PanelCount == 4 * 32 + 2 * 16 and p.isValid()  # 20 x 10 sides, 10 x 10 ends


# ------------------------------------------------------------------------ undo
def test_one_undo_step_removes_all_four(doc):
    doc.UndoMode = 1
    cut, _, _ = _make_source(doc)
    doc.clearUndos()
    before = _names(doc)
    p = tessella.make_panelization((cut, "Face1"), size=SIZE)
    created = set(_names(doc)) - set(before)
    assert len(created) == 4 and p.Name in created
    assert doc.UndoCount == 1
    assert doc.UndoNames == ["Panelize"]
    doc.undo()
    assert _names(doc) == before
    doc.redo()
    assert set(_names(doc)) - set(before) == created
    doc.recompute()
    _check_consistent(doc.getObject(p.Name))


def test_failed_creation_leaves_no_undo_step(doc, source):
    doc.UndoMode = 1
    doc.clearUndos()
    before = _names(doc)
    with pytest.raises(ValueError):
        tessella.make_panelization((source[0], "Face1"), size=SIZE, max_panels=2)
    assert _names(doc) == before
    assert doc.UndoCount == 0


def test_panel_id_format_is_a_property(tmp_path):
    doc = FreeCAD.newDocument("IdFormat")
    try:
        src = doc.addObject("Part::Feature", "Plate")
        src.Shape = Part.makePlane(3000, 2000)
        doc.recompute()
        p = tessella.make_panelization((src, "Face1"), size=1000.0)
        panels = _children(p)[0]
        assert list(panels.PanelIds) == [f"P-{i:04d}" for i in range(1, 7)]
        p.PanelIdFormat = "ROOF-A-{:03d}"
        doc.recompute()
        assert list(panels.PanelIds) == [f"ROOF-A-{i:03d}" for i in range(1, 7)]
        p.PanelIdFormat = "{:d"  # not a format
        doc.recompute()
        assert not panels.isValid(), panels.State
        assert list(panels.PanelIds)[0] == "ROOF-A-001"  # the last good IDs stay
    finally:
        FreeCAD.closeDocument(doc.Name)
