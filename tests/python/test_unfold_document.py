"""The parametric Unfold object (headless FreeCAD): its flat wires against the 3D
Panels child's faces (FreeCAD's own edge lengths), nesting on/off, bad options
leaving the document untouched, one undo step, save and reopen."""

import os
import re

import FreeCAD  # noqa: F401  (before Part)
import Part

import pytest

import freecad_workbench as tessella
from freecad_workbench.features import panelization as pfeat


@pytest.fixture()
def doc(freeform_face):
    d = FreeCAD.newDocument("TessellaUnfoldTest")
    src = d.addObject("Part::Feature", "Surface")
    src.Shape = freeform_face
    d.recompute()
    p = tessella.make_panelization((src, "Face1"), method="equal_size_grid", size=1500.0)
    name = d.Name
    yield d, p
    if name in FreeCAD.listDocuments():
        FreeCAD.closeDocument(name)


def panels_child(p):
    return [c for c in pfeat.children_of(p) if c.Role == "Panels"][0]


def boundary_edges(shape):
    """Edges of the panel's outline: a triangulated n-gon is a shell of several
    faces; its boundary edges belong to one face only."""
    def key(e):
        ends = [tuple(round(c, 6) for c in v.Point) for v in e.Vertexes]
        return tuple(sorted(ends))

    edges = [e for f in shape.Faces for e in f.Edges]
    keys = [key(e) for e in edges]
    return [e for e, k in zip(edges, keys) if keys.count(k) == 1]


def check_against_panels(u, p):
    faces = panels_child(p).Shape.childShapes()
    flats = u.Shape.childShapes()
    assert len(flats) == len(faces) == p.PanelCount
    assert list(u.PanelIds) == list(panels_child(p).PanelIds)
    for flat, face in zip(flats, faces):
        wire = [s for s in flat.childShapes() if s.ShapeType == "Wire"][0]
        assert wire.isClosed()
        l3 = sorted(e.Length for e in boundary_edges(face))
        l2 = sorted(e.Length for e in wire.Edges)
        assert len(l2) == len(l3)
        assert max(abs(a - b) for a, b in zip(l2, l3)) < 1e-6
        assert abs(flat.BoundBox.ZMin) < 1e-12 and abs(flat.BoundBox.ZMax) < 1e-12


def test_make_unfold_and_nest(doc):
    d, p = doc
    u = tessella.make_unfold(p)
    check_against_panels(u, p)
    # laid out beside the model in the XY plane, not over it
    model, flat = panels_child(p).Shape.BoundBox, u.Shape.BoundBox
    assert flat.XMin > model.XMax and abs(flat.YMin - model.YMin) < 1e-6, (flat, model)
    assert u.SheetCount == 0 and u.FoldedPanels > 0 and len(u.FoldAngles) == p.PanelCount
    u.Nest = True
    u.SheetWidth, u.SheetHeight = 4000.0, 2500.0
    d.recompute()
    assert u.isValid() and u.SheetCount >= 1 and 0 < u.Utilization < 1
    check_against_panels(u, p)
    from freecad_workbench.export import _arrange

    _res, flat, lay = u.Proxy.compute(u)
    origins = _arrange.sheet_origins(lay)  # sheets in a grid
    local = u.Placement.inverse().toMatrix()  # the sheets in the Unfold's own frame
    for part, f in zip(u.Shape.childShapes(), flat):
        bb = part.transformed(local).BoundBox
        x0, y0 = origins[lay.placements[lay.index(f.id)].sheet]
        assert bb.XMin >= x0 + 10 - 1e-6 and bb.XMax <= x0 + 4000 - 10 + 1e-6
        assert bb.YMin >= y0 + 10 - 1e-6 and bb.YMax <= y0 + 2500 - 10 + 1e-6
    # parametric: a coarser panelization re-unfolds
    u.Nest = False
    p.Size = 2500.0
    d.recompute()
    assert u.isValid()
    check_against_panels(u, p)
    # a sheet too small for a panel: the Unfold reports it in Status (no
    # traceback), draws the panels in rows and nests nothing
    u.Nest = True
    u.SheetWidth, u.SheetHeight = 300.0, 300.0
    d.recompute()
    assert u.isValid() and u.SheetCount == 0, u.Status
    assert u.Status.startswith("Not nested: ") and "smallest sheet that fits" in u.Status
    check_against_panels(u, p)


def test_make_unfold_errors_leave_document_untouched(doc):
    d, p = doc
    names = sorted(o.Name for o in d.Objects)
    with pytest.raises(ValueError, match="Panelization"):
        tessella.make_unfold(d.getObject("Surface"))
    with pytest.raises(ValueError, match="kerf"):
        tessella.make_unfold(p, kerf=-1.0)
    with pytest.raises(ValueError, match="does not fit"):
        tessella.make_unfold(p, nest=True, sheet_width=500.0, sheet_height=500.0)
    with pytest.raises(ValueError, match="unknown"):
        tessella.make_unfold(p, sheet=3)
    assert sorted(o.Name for o in d.Objects) == names


def test_one_undo_step_and_reopen(doc, tmp_path):
    d, p = doc
    d.UndoMode = 1
    d.clearUndos()
    u = tessella.make_unfold(p, nest=True, sheet_width=4000.0, sheet_height=2500.0, kerf=0.2)
    assert d.UndoCount == 1 and d.UndoNames == ["Unfold"]
    name = u.Name
    d.undo()
    assert d.getObject(name) is None
    d.redo()
    u = d.getObject(name)
    assert u is not None
    d.recompute()
    sheets = u.SheetCount
    assert sheets >= 1
    path = str(tmp_path / "unfold.FCStd")
    d.saveAs(path)
    FreeCAD.closeDocument(d.Name)
    d2 = FreeCAD.openDocument(path)
    try:
        u2 = d2.getObject(name)
        assert u2.Proxy.__class__.__module__ == "freecad_workbench.features.unfold"
        assert u2.SheetCount == sheets and abs(u2.Kerf.Value - 0.2) < 1e-12
        u2.touch()
        d2.recompute()
        assert u2.isValid() and u2.SheetCount == sheets
    finally:
        FreeCAD.closeDocument(d2.Name)


def test_make_schedules_match_the_objects(doc):
    d, p = doc
    sheets = tessella.make_schedules(p)
    assert [s.TypeId for s in sheets] == ["Spreadsheet::Sheet"] * 3
    panels, rods, nodes = sheets
    child = panels_child(p)
    faces = child.Shape.childShapes()
    ids = list(child.PanelIds)
    assert panels.get("A1") == "ID" and panels.get(f"A{len(ids) + 1}") == ids[-1]
    # the area column (3D panel model) against FreeCAD's own face areas: a
    # quantity in mm², displayed in m²
    header = [panels.get(f"{c}1") for c in "ABCDEFGHIJKLMN"]
    col = "ABCDEFGHIJKLMN"[header.index("Area")]
    assert panels.getDisplayUnit(f"{col}2") == "m^2"
    for k, face in enumerate(faces):
        area = panels.get(f"{col}{k + 2}")
        assert str(area.Unit) == str(FreeCAD.Units.Area)
        assert area.Value == pytest.approx(face.Area, rel=1e-6)
    # planarity in percent of the panel's edge: against the Panels property
    col = "ABCDEFGHIJKLMN"[header.index("Planarity (% of edge)")]
    planarity = list(child.Planarity)
    for k in range(len(faces)):
        assert panels.get(f"{col}{k + 2}") == pytest.approx(100.0 * planarity[k], rel=1e-12)
    rods_child = [c for c in pfeat.children_of(p) if c.Role == "Rods"][0]
    assert [rods.get(f"{c}1") for c in "ABCD"] == ["ID", "Node A", "Node B", "Length"]
    for k, edge in enumerate(rods_child.Shape.childShapes()[:50]):
        assert rods.get(f"A{k + 2}") == rods_child.RodIds[k]
        assert rods.get(f"D{k + 2}").Value == pytest.approx(edge.Length, rel=1e-9)
    nodes_child = [c for c in pfeat.children_of(p) if c.Role == "Nodes"][0]
    assert nodes.get(f"A{len(nodes_child.NodeIds) + 1}") == nodes_child.NodeIds[-1]
    # the rods column: every rod meeting the node, by ID, with two angles each
    header = [nodes.get(f"{c}1") for c in "ABCDEFGHIJ"]
    rods_col = "ABCDEFGHIJ"[header.index("Rods (azimuth, elevation)")]
    count_col = "ABCDEFGHIJ"[header.index("Rod count")]
    rod_ids = set(rods_child.RodIds)
    for k in range(min(40, len(nodes_child.NodeIds))):
        text = nodes.get(f"{rods_col}{k + 2}")
        entries = re.findall(r"(\S+) \((-?[0-9.]+)°, (-?[0-9.]+)°\)", text)
        assert len(entries) == int(nodes.get(f"{count_col}{k + 2}")) > 0, text
        assert all(rid in rod_ids for rid, _a, _e in entries), text
        assert text == ", ".join(f"{r} ({a}°, {e}°)" for r, a, e in entries)
    with pytest.raises(ValueError):
        tessella.make_schedules(d.getObject("Surface"))


def test_export_unfold_object(doc, tmp_path):
    import ezdxf

    d, p = doc
    u = tessella.make_unfold(p, nest=True, sheet_width=4000.0, sheet_height=2500.0)
    path = str(tmp_path / "u.dxf")
    # the exact form (one drawing, blocks, every outline point); the CAM defaults are
    # checked in test_dxf_cam.py
    s = tessella.export_unfold(u, path, per_sheet=False, blocks=True, arcs=False, simplify_tolerance=0)
    assert s["paths"] == [path]
    dxf = ezdxf.readfile(path)
    faces = panels_child(p).Shape.childShapes()
    for pid, face in zip(u.PanelIds, faces):
        cut = [e for e in dxf.blocks[pid] if e.dxftype() == "LWPOLYLINE" and e.dxf.layer == "CUT"][0]
        pts = [(x, y) for x, y, *_ in cut.get_points()]
        l2 = sorted(((pts[i][0] - pts[i - 1][0]) ** 2 + (pts[i][1] - pts[i - 1][1]) ** 2) ** 0.5
                    for i in range(len(pts)))
        l3 = sorted(e.Length for e in boundary_edges(face))
        assert max(abs(a - b) for a, b in zip(l2, l3)) < 1e-6
    cam = tessella.export_unfold(u, str(tmp_path / "cam.dxf"))  # default: one file per sheet
    assert len(cam["paths"]) == u.SheetCount and all(os.path.isfile(q) for q in cam["paths"])
    tessella.export_unfold(u, str(tmp_path / "u.svg"))
    assert os.path.getsize(str(tmp_path / "u.svg")) > 0
    with pytest.raises(ValueError, match="dxf or .svg"):
        tessella.export_unfold(u, str(tmp_path / "u.pdf"))
    with pytest.raises(ValueError, match="Unfold"):
        tessella.export_unfold(p, path)


def test_unfold_curved_panels(doc):
    d, p = doc
    u = tessella.make_unfold(p, curved_panels=True, subdivisions=4)
    assert u.isValid() and u.CurvedPanels and u.MaxStrain > 0
    assert len(u.Shape.childShapes()) == p.PanelCount and u.FoldedPanels == 0
    # the flattened outline of a curved panel is at least as long as its chords
    faces = panels_child(p).Shape.childShapes()
    for flat, face in zip(u.Shape.childShapes(), faces):
        wire = [s for s in flat.childShapes() if s.ShapeType == "Wire"][0]
        chords = sum(e.Length for e in boundary_edges(face))
        assert wire.Length >= chords * (1 - u.MaxStrain) - 1e-6
    with pytest.raises(ValueError, match="subdivisions"):
        tessella.make_unfold(p, curved_panels=True, subdivisions=0)
