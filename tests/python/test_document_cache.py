"""What a recompute redoes: nothing on a bare touch, only the typing when the
type tolerance changes, only the IDs when an ID format changes, everything when
a parameter changes. Counted by wrapping the core calls (no timings)."""
import FreeCAD  # noqa: F401  (before Part)
import Part
import pytest

import freecad_workbench as tessella
from freecad_workbench import api, core
from freecad_workbench.features.panelization import children_of


@pytest.fixture
def counted(monkeypatch):
    calls = {"panelize": 0, "types": 0, "panel_faces": 0}

    def wrap(owner, name, key):
        original = getattr(owner, name)

        def counting(*args, **kwargs):
            calls[key] += 1
            return original(*args, **kwargs)

        monkeypatch.setattr(owner, name, counting)

    wrap(api, "panelize_brep", "panelize")
    wrap(core, "mesh_panel_types", "types")
    wrap(core, "panel_faces", "panel_faces")
    return calls


@pytest.fixture
def doc():
    d = FreeCAD.newDocument("CacheTest")
    yield d
    FreeCAD.closeDocument(d.Name)


def _panelization(doc):
    src = doc.addObject("Part::Feature", "Src")
    src.Shape = Part.makeCylinder(3000, 4000).Faces[0]
    doc.recompute()
    p = tessella.make_panelization((src, "Face1"), u_count=12, v_count=3)
    return p, children_of(p)


def _delta(calls, before):
    return {k: calls[k] - before[k] for k in calls}


def test_bare_touch_rebuilds_nothing(doc, counted):
    p, (panels, rods, nodes) = _panelization(doc)
    assert counted["types"] == 1
    shape_before, types_before = panels.Shape, list(panels.PanelType)
    before = dict(counted)
    p.touch()
    doc.recompute()
    assert _delta(counted, before) == {"panelize": 0, "types": 0, "panel_faces": 0}
    assert all(o.isValid() and "Touched" not in o.State for o in (p, panels, rods, nodes))
    assert list(panels.PanelType) == types_before and panels.TypeCount == 1
    assert panels.Shape.isPartner(shape_before)  # the same shape, not rebuilt
    assert len(panels.PanelIds) == 36 and len(rods.RodIds) == len(rods.Shape.Edges)
    # touching a child alone redoes nothing either
    panels.touch()
    doc.recompute()
    assert _delta(counted, before) == {"panelize": 0, "types": 0, "panel_faces": 0}


def test_tolerance_change_retypes_only(doc, counted):
    p, (panels, rods, nodes) = _panelization(doc)
    before = dict(counted)
    panels.TypeTolerance = 0.5
    doc.recompute()
    assert _delta(counted, before) == {"panelize": 0, "types": 1, "panel_faces": 0}
    assert panels.TypeCount == 1 and panels.isValid()
    panels.TypeTolerance = 1.0  # back to a tolerance typed before: cached
    doc.recompute()
    assert _delta(counted, before) == {"panelize": 0, "types": 1, "panel_faces": 0}


def test_id_format_change_renames_without_recomputing(doc, counted):
    p, (panels, rods, nodes) = _panelization(doc)
    before = dict(counted)
    p.PanelIdFormat = "ROOF-{:03d}"
    doc.recompute()
    assert _delta(counted, before) == {"panelize": 0, "types": 0, "panel_faces": 0}
    assert panels.PanelIds[0] == "ROOF-001" and panels.PanelIds[-1] == "ROOF-036"


def test_parameter_change_recomputes_everything_once(doc, counted):
    p, (panels, rods, nodes) = _panelization(doc)
    before = dict(counted)
    p.UCount = 16
    doc.recompute()
    assert _delta(counted, before) == {"panelize": 1, "types": 1, "panel_faces": 1}
    assert p.PanelCount == 48 and len(panels.PanelIds) == 48 == len(panels.PanelType)
    assert len(panels.Shape.childShapes()) == 48
