"""describe(): the text shown when a panel, rod or node is clicked, checked
against the document's own figures (headless, no GUI)."""
import FreeCAD
import Part
import pytest

import freecad_workbench as tessella
from freecad_workbench.features.panelization import children_of
from freecad_workbench.gui.selection_feedback import describe


@pytest.fixture(scope="module")
def kids():
    doc = FreeCAD.newDocument("SelFeedback")
    src = doc.addObject("Part::Feature", "Cyl")
    src.Shape = Part.makeCylinder(2000, 3000)
    parent = tessella.make_panelization((src, "Face1"), size=1000.0)
    doc.recompute()
    yield {c.Role: c for c in children_of(parent)}
    FreeCAD.closeDocument(doc.Name)


def test_panel_face_maps_to_its_panel(kids):
    panels = kids["Panels"]
    for k in (0, 5, len(panels.PanelIds) - 1):
        text = describe(panels, f"Face{k + 1}")  # every cylinder panel is one flat face
        assert text.startswith(panels.PanelIds[k] + " (quad)")
        assert f"{panels.Deviation[k]:.3f} mm" in text
        assert f"{panels.Area[k] / 1e6:.3f} m²" in text


def test_rod_and_node(kids):
    rods, nodes = kids["Rods"], kids["Nodes"]
    assert describe(rods, "Edge2") == f"{rods.RodIds[1]}: length {rods.RodLengths[1]:.2f} mm"
    # The edge really is that long (independent of the stored list).
    assert rods.Shape.Edges[1].Length == pytest.approx(rods.RodLengths[1], rel=1e-12)
    text = describe(nodes, "Vertex3")
    assert text.startswith(f"{nodes.NodeIds[2]}: valence {nodes.Valence[2]}")


def test_foreign_or_unknown_selection_gives_nothing(kids):
    assert describe(kids["Panels"], "Edge1") is None
    assert describe(kids["Panels"], "Face99999") is None
    assert describe(kids["Rods"], "") is None
    assert describe(object(), "Face1") is None
