"""tessella.planarize on faces built here, checked with FreeCAD: a sphere's
latitude/longitude grid is planar already and stays put; on a trimmed freeform
face every node stays within the band (FreeCAD's own distance) and the
boundary nodes on the trim; the report's figures recounted."""

import math

import FreeCAD
import numpy as np
import Part
import pytest

import freecad_workbench as tessella
from conftest import diagonal_distance
from freecad_workbench import planarize

V = FreeCAD.Vector


def quads(r):
    nodes = set(r.nodes.tolist())
    return [k for k, p in enumerate(r.panels) if len(p) == 4 and all(int(v) in nodes for v in p)]


def test_sphere_grid_is_left_as_it_is():
    face = Part.makeSphere(5000).Faces[0]
    r = tessella.panelize(face, method="iso_grid", u_count=24, v_count=12)
    r2, rep = planarize(r)
    assert rep["converged"] and rep["planar_before"] == rep["quads"] > 200
    assert np.abs(r2.vertices - r.vertices).max() <= 1e-9
    assert max(diagonal_distance(r.vertices[list(r.panels[k])]) for k in quads(r)) < 1e-6


@pytest.fixture(scope="module")
def domed_face():
    """A 16 x 11 m shell, 1.4 m rise, leaning to one side, with a round
    opening (not a bundled example)."""
    pts = [[V(16000.0 * i / 8, 11000.0 * j / 6,
              1400.0 * math.sin(math.pi * i / 8) * math.sin(math.pi * j / 6) + 250.0 * i / 8)
            for j in range(7)] for i in range(9)]
    s = Part.BSplineSurface()
    s.interpolate(pts)
    hole = Part.makeCylinder(1500, 6000, V(8000, 5500, -2000))
    return s.toShape().cut(hole).Faces[0]


def test_iso_grid_moves_within_the_band_and_keeps_its_trims(domed_face):
    """An iso grid on a freeform face does not follow a conjugate network: it
    cannot become planar inside a 20 mm band (the report says how far it got),
    but every node must stay inside the band and on its trim."""
    r = tessella.panelize(domed_face, method="iso_grid", size=1000.0)
    r2, rep = planarize(r, planarity_tolerance=1.0, max_deviation=20.0)
    assert rep["max_planarity_after"] < rep["max_planarity_before"]
    # Independently: the quads within the tolerance and the worst, recounted.
    d = [diagonal_distance(r2.vertices[list(r2.panels[k])]) for k in quads(r2)]
    assert sum(x <= 1.0 for x in d) == rep["planar_after"]
    assert max(d) == pytest.approx(rep["max_planarity_after"], rel=1e-9)
    # Every moved node within 20 mm of the surface (FreeCAD's distance).
    moved = np.nonzero(np.linalg.norm(r2.vertices - r.vertices, axis=1) > 0)[0]
    assert len(moved) > 10
    for v in moved[:: max(1, len(moved) // 40)]:
        assert domed_face.distToShape(Part.Vertex(V(*r2.vertices[v])))[0] <= 20.0 + 1e-6
    # Boundary nodes (on the outer trim and the opening) stay on the trim.
    tol = 1e-6 * domed_face.BoundBox.DiagonalLength
    on_trim = 0
    for v in r.nodes:
        if min(w.distToShape(Part.Vertex(V(*r.vertices[v])))[0] for w in domed_face.Wires) <= tol:
            on_trim += 1
            y = V(*r2.vertices[v])
            assert min(w.distToShape(Part.Vertex(y))[0] for w in domed_face.Wires) <= tol
    assert on_trim > 20


def test_bad_parameters(domed_face):
    r = tessella.panelize(domed_face, method="iso_grid", size=2000.0)
    with pytest.raises(ValueError, match="planarity_tolerance"):
        planarize(r, planarity_tolerance=0.0)
    with pytest.raises(ValueError, match="max_deviation"):
        planarize(r, max_deviation=-5.0)


def test_boundary_nodes_slide_along_their_trims(domed_face):
    """Boundary nodes slide along the trims (issue 16: "keeps boundary nodes
    on their trims, sliding along them, and corner nodes fixed"): those that
    moved are still on the trim (FreeCAD's distance, within 1e-6 of the
    model's size), and the four corners of the outer trim stay put."""
    r = tessella.panelize(domed_face, method="curvature_lines", size=1000.0)
    r2, rep = planarize(r, planarity_tolerance=1.0, max_deviation=20.0)
    assert rep["sliding_nodes"] > 10
    tol = 1e-6 * domed_face.BoundBox.DiagonalLength
    slid = 0
    for v in r.nodes:
        x = V(*r.vertices[v])
        if min(w.distToShape(Part.Vertex(x))[0] for w in domed_face.Wires) > tol:
            continue
        y = V(*r2.vertices[v])
        if (y - x).Length > 1e-9:
            slid += 1
            assert min(w.distToShape(Part.Vertex(y))[0] for w in domed_face.Wires) <= tol
    assert slid > 5
    for corner in domed_face.OuterWire.Vertexes:
        p = np.array([corner.X, corner.Y, corner.Z])
        k = int(np.argmin(np.linalg.norm(r.vertices - p, axis=1)))
        if np.linalg.norm(r.vertices[k] - p) <= tol:
            assert np.array_equal(r2.vertices[k], r.vertices[k])
    # Without sliding every boundary node stays exactly.
    r3, rep3 = planarize(r, slide_on_trims=False)
    assert rep3["sliding_nodes"] == 0


def test_planarize_step_of_a_document_panelization(domed_face, tmp_path):
    """The Panelization's Planarize option (with PlanarityTolerance and
    PlanarizeMaxDeviation): the document's result is the console's
    panelize(..., planarize=True), it recomputes when a setting changes,
    survives saving and reopening, and face sets are refused clearly."""
    doc = FreeCAD.newDocument("PlanarizeStep")
    try:
        src = doc.addObject("Part::Feature", "Shell")
        src.Shape = domed_face
        doc.recompute()
        p = tessella.make_panelization((src, "Face1"), method="curvature_lines", size=1200.0,
                                       planarize=True)
        assert p.Planarize and float(p.PlanarityTolerance) == 1.0
        res = p.Proxy.result(p).result
        console = tessella.panelize(domed_face, method="curvature_lines", size=1200.0,
                                    planarize=True)
        assert np.array_equal(res.vertices, console.vertices)
        rep = res.summary["planarize"]
        assert rep["planar_after"] >= rep["planar_before"]
        plain = tessella.panelize(domed_face, method="curvature_lines", size=1200.0)
        assert not np.array_equal(res.vertices, plain.vertices)
        p.PlanarizeMaxDeviation = 5.0
        doc.recompute()
        tight = p.Proxy.result(p).result
        assert tight.summary["planarize"]["max_node_deviation_after"] <= 5.0 + 1e-6
        path = str(tmp_path / "planarize.FCStd")
        doc.saveAs(path)
        vertices = tight.vertices.copy()
    finally:
        FreeCAD.closeDocument(doc.Name)
    doc = FreeCAD.openDocument(path)
    try:
        p = [o for o in doc.Objects if o.Name.startswith("Panelization")][0]
        assert p.Planarize and float(p.PlanarizeMaxDeviation) == pytest.approx(5.0)
        p.touch()
        doc.recompute()
        assert np.array_equal(p.Proxy.result(p).result.vertices, vertices)
    finally:
        FreeCAD.closeDocument(doc.Name)
    with pytest.raises(ValueError, match="planarize works on one face"):
        tessella.panelize_faces(Part.makeBox(3000, 3000, 3000), method="iso_grid",
                                size=1000.0, planarize=True)
    with pytest.raises(ValueError, match="planarity_tolerance"):
        tessella.panelize(domed_face, method="iso_grid", size=2000.0, planarize=True,
                          planarity_tolerance=0.0)


def test_progress_and_cancel(domed_face):
    """planarize reports its rounds and stops when the sink says so (a
    cancelled run raises, it returns no half-moved result)."""
    r = tessella.panelize(domed_face, method="iso_grid", size=1000.0)
    stages = []

    def progress(fraction, stage):
        stages.append((fraction, stage))
        return True

    moved, rep = planarize(r, progress=progress)
    assert rep["iterations"] > 0 and rep["seconds"] > 0
    assert any(stage == "planarizing" for _, stage in stages)
    assert all(0.0 <= f <= 1.0 for f, _ in stages)
    again, _ = planarize(r)
    assert np.array_equal(moved.vertices, again.vertices)  # the sink changes nothing
    with pytest.raises(tessella.Cancelled, match="cancelled"):
        planarize(r, progress=lambda f, s: False)
