"""Panel classes (issue 16 part 3): flat, cold-bent, curved; checked against
closed forms, recounted, and followed through the document, the schedules
and the fabrication output."""

import math
import os

import FreeCAD
import numpy as np
import Part
import pytest

import freecad_workbench as tessella
from freecad_workbench import fabrication
from freecad_workbench.export.schedule_csv import write_panel_schedule
from freecad_workbench.panel_classes import classify

V = FreeCAD.Vector
EXAMPLES = os.path.join(os.path.dirname(__file__), "..", "..", "examples")


def twisted_square(side, lift):
    """The square [0, side]^2 with one corner lifted by `lift`: the distance
    between its diagonals is lift * side / sqrt(4 side^2 + 2 lift^2)."""
    return np.array([[0, 0, 0], [side, 0, 0], [side, side, lift], [0, side, 0]], dtype=float)


def test_classes_of_twisted_squares_follow_the_closed_form():
    side = 1000.0
    lifts = [0.0, 1.0, 10.0, 25.0, 60.0]
    vertices = np.concatenate([twisted_square(side, h) for h in lifts])
    panels = [tuple(range(4 * k, 4 * k + 4)) for k in range(len(lifts))]
    cls = classify(vertices, panels)
    expect = [h * side / math.sqrt(4 * side ** 2 + 2 * h ** 2) for h in lifts]
    assert cls.warp == pytest.approx(expect, rel=1e-12, abs=1e-12)
    # Limit: 1% of the longest diagonal (the lifted corner's).
    limits = [0.01 * math.sqrt(2 * side ** 2 + h ** 2) for h in lifts]
    assert cls.limit == pytest.approx(limits, rel=1e-12)
    assert cls.names == ["flat", "flat", "cold-bent", "cold-bent", "curved"]
    assert cls.counts == {"flat": 2, "cold-bent": 2, "curved": 1}
    # An absolute limit replaces the ratio; a tighter flat tolerance.
    cls = classify(vertices, panels, flat_tolerance=0.1, cold_bend_warp=5.0)
    assert cls.names == ["flat", "cold-bent", "cold-bent", "curved", "curved"]
    # A triangle is flat; a bent pentagon is measured against its best plane.
    tri = classify(np.array([[0, 0, 0], [1000, 0, 50], [0, 1000, 900]], float), [(0, 1, 2)])
    assert tri.names == ["flat"] and tri.warp[0] == 0.0
    penta = np.array([[0, 0, 0], [1000, 0, 0], [1500, 800, 0], [500, 1400, 0],
                      [-300, 700, 40]], float)
    p = classify(penta, [(0, 1, 2, 3, 4)])
    c = penta.mean(axis=0)
    normal = np.linalg.svd(penta - c)[2][-1]
    assert p.warp[0] == pytest.approx(2 * np.abs((penta - c) @ normal).max(), rel=1e-9)


@pytest.mark.parametrize("params, message", [
    ({"flat_tolerance": 0.0}, "flat_tolerance"),
    ({"cold_bend_ratio": 2.0}, "cold_bend_ratio"),
    ({"cold_bend_warp": -1.0}, "cold_bend_warp"),
])
def test_bad_parameters_are_refused(params, message):
    r = tessella.panelize(Part.makePlane(3000, 2000), method="iso_grid", size=1000.0)
    with pytest.raises(ValueError, match=message):
        tessella.panel_classes(r, **params)


@pytest.fixture(scope="module")
def dome():
    return Part.read(os.path.join(EXAMPLES, "chen_shan_dome.brep")).Faces[0]


def test_classes_add_up_and_planarize_makes_panels_flat(dome):
    r = tessella.panelize(dome, method="curvature_lines", size=1500.0)
    counts = r.summary["panel_classes"]
    assert sum(counts.values()) == len(r.panels)
    assert counts == tessella.panel_classes(r).counts
    # The result classifies its own mesh in the core (classify_mesh); the
    # same figures as from its vertices and panels, bit for bit.
    assert np.array_equal(r.metrics["panel_warp"], tessella.panel_classes(r).warp)
    # The warp recomputed from the vertices for the quads.
    quads = [k for k, p in enumerate(r.panels) if len(p) == 4]
    for k in quads[::50]:
        a, b, c, d = r.vertices[list(r.panels[k])]
        n = np.cross(c - a, d - b)
        assert r.metrics["panel_warp"][k] == pytest.approx(abs((b - a) @ n) / np.linalg.norm(n),
                                                           rel=1e-9, abs=1e-9)
    r2, _ = tessella.planarize(r)
    after = r2.summary["panel_classes"]
    assert after["flat"] > counts["flat"]
    assert after["flat"] >= 0.9 * len(r2.panels)


def test_schedule_column_and_fabrication_by_class(dome, tmp_path):
    r = tessella.panelize(dome, method="iso_grid", size=3000.0)
    cls = tessella.panel_classes(r, cold_bend_ratio=0.005)
    assert cls.counts["curved"] > 0 and cls.counts["flat"] + cls.counts["cold-bent"] > 0
    write_panel_schedule(r, tmp_path / "panels.csv", classes=cls)
    import csv

    with open(tmp_path / "panels.csv", newline="") as f:
        rows = list(csv.DictReader(f))
    assert [row["class"] for row in rows] == cls.names
    assert [float(row["warp_mm"]) for row in rows] == pytest.approx(cls.warp.tolist())
    flat = fabrication.by_class(r, cls, dome, subdivisions=4)
    assert [f.id for f in flat] == list(r.panel_ids)
    for k, f in enumerate(flat):
        if cls.labels[k] == 2:
            assert isinstance(f, fabrication.FlatPatch) and f.strain_max >= 0
        else:
            assert isinstance(f, fabrication.FlatPanel)
            # Unfolded exactly: each outline edge as long as in 3D.
            ring = r.vertices[list(r.panels[k])]
            edges3d = np.linalg.norm(np.roll(ring, -1, axis=0) - ring, axis=1)
            assert f.edge_lengths == pytest.approx(edges3d, rel=1e-9, abs=1e-6)


def test_document_classes_colours_save_and_reopen(dome, tmp_path):
    doc = FreeCAD.newDocument("PanelClasses")
    try:
        src = doc.addObject("Part::Feature", "Dome")
        src.Shape = dome
        doc.recompute()
        p = tessella.make_panelization((src, "Face1"), method="iso_grid", size=3000.0)
        doc.recompute()
        panels = [c for c in doc.Objects if getattr(c, "Role", "") == "Panels"][0]
        n = len(panels.PanelIds)
        assert panels.FlatPanels + panels.ColdBentPanels + panels.CurvedPanels == n
        assert len(panels.PanelClass) == len(panels.Warp) == n
        before = panels.CurvedPanels
        panels.ColdBendWarp = 1.5  # a tighter absolute limit: more need a mould
        doc.recompute()
        assert panels.CurvedPanels > before
        expect = tessella.panel_classes(p.Proxy.result(p).result, cold_bend_warp=1.5)
        assert list(panels.PanelClass) == expect.labels.tolist()
        sheets = tessella.make_schedules(p)
        ps = [s for s in sheets if s.Name.startswith("PanelSchedule")][0]
        assert ps.get("P1") == "Class"
        u = tessella.make_unfold(p, by_panel_class=True)
        assert u.Status == "OK" and u.MaxStrain > 0
        path = str(tmp_path / "classes.FCStd")
        doc.saveAs(path)
    finally:
        FreeCAD.closeDocument(doc.Name)
    doc = FreeCAD.openDocument(path)
    try:
        panels = [c for c in doc.Objects if getattr(c, "Role", "") == "Panels"][0]
        assert float(panels.ColdBendWarp) == pytest.approx(1.5)
        assert panels.CurvedPanels == len([c for c in panels.PanelClass if c == 2])
        u = [o for o in doc.Objects if o.Name.startswith("Unfold")][0]
        assert u.ByPanelClass
    finally:
        FreeCAD.closeDocument(doc.Name)
