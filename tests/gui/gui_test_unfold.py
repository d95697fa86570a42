"""GUI test of Tessella_Unfold (run like gui_test_panelize.py, see tests/gui/README).

No selection -> a message naming the Panelization, nothing created; a selected
Panelization (or its Panels child) -> one Unfold per run, one undo step, its view
provider and icon, the echoed Python call; save and reopen restores the view provider.
"""

import glob
import os
import sys
import tempfile

import FreeCAD
import FreeCADGui as Gui

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import gui_harness  # noqa: E402
from gui_harness import (  # noqa: E402
    REPO, DialogCatcher, check, command_active, ensure_workbench, process_events,
    recorded_commands,
)


def unfolds(doc):
    from freecad_workbench.features.unfold import Unfold

    return [o for o in doc.Objects if isinstance(getattr(o, "Proxy", None), Unfold)]


def test_unfold_command():
    import Part

    ensure_workbench()
    Gui.activateWorkbench("TessellaWorkbench")
    process_events()
    items = Gui.activeWorkbench().getToolbarItems().get("Tessella", [])
    check("toolbar holds Tessella_Unfold", "Tessella_Unfold" in items, str(items))

    import freecad_workbench as tessella
    from freecad_workbench.features.panelization import children_of

    doc = FreeCAD.newDocument("TessellaGuiUnfold")
    try:
        surf = doc.addObject("Part::Feature", "Surface")
        surf.Shape = Part.makeCylinder(3000, 4000).Faces[0]
        doc.recompute()
        p = tessella.make_panelization((surf, "Face1"), method="iso_grid", u_count=12, v_count=4)
        doc.clearUndos()
        before = sorted(o.Name for o in doc.Objects)

        Gui.Selection.clearSelection()
        with DialogCatcher() as dc:
            Gui.runCommand("Tessella_Unfold")
        check("no selection: nothing created", sorted(o.Name for o in doc.Objects) == before)
        check("no selection: no undo step", doc.UndoCount == 0, str(doc.UndoNames))
        check("no selection: Unfold greyed out", not command_active("Tessella_Unfold"))
        check("no selection: no message box", not dc.texts, str(dc.texts))

        Gui.Selection.addSelection(doc.Name, surf.Name, "Face1")
        with DialogCatcher() as dc:
            Gui.runCommand("Tessella_Unfold")
        check("a face selected: nothing created", sorted(o.Name for o in doc.Objects) == before)

        with recorded_commands() as echoed:
            Gui.Selection.clearSelection()
            Gui.Selection.addSelection(doc.Name, p.Name)
            check("Panelization selected: Unfold enabled", command_active("Tessella_Unfold"))
            with DialogCatcher() as dc:
                Gui.runCommand("Tessella_Unfold")
        process_events()
        us = unfolds(doc)
        if check("Panelization selected: one Unfold", len(us) == 1, str(dc.texts)):
            u = us[0]
            check("Unfold valid", u.isValid() and len(u.Shape.childShapes()) == p.PanelCount,
                  str(u.State))
            check("one undo step named Unfold", doc.UndoNames == ["Unfold"], str(doc.UndoNames))
            check("echoed make_unfold", any("tessella.make_unfold(" in e for e in echoed),
                  str(echoed))
            vp = u.ViewObject.Proxy
            check("view provider", type(vp).__name__ == "ViewProviderUnfold", type(vp).__name__)
            icon = vp.getIcon() if vp else ""
            check("icon file exists", bool(icon) and os.path.isfile(icon), repr(icon))
        # Export: no Unfold selected -> message; selected -> a DXF that reads back
        from freecad_workbench.gui import fabrication_commands as fc

        Gui.Selection.clearSelection()
        with DialogCatcher() as dc:
            Gui.runCommand("Tessella_ExportFlat")
        check("export greyed out without an Unfold selected",
              not command_active("Tessella_ExportFlat"))
        out = os.path.join(tempfile.mkdtemp(prefix="tessella_gui_"), "flat.dxf")
        original_ask = fc.ask_path
        fc.ask_path = lambda obj: out
        try:
            Gui.Selection.addSelection(doc.Name, us[0].Name)
            with DialogCatcher() as dc:
                Gui.runCommand("Tessella_ExportFlat")
        finally:
            fc.ask_path = original_ask
        # CAM default: one file per sheet (flat_sheet01.dxf, ...), one cut path per panel
        written = sorted(glob.glob(out[:-4] + "_sheet*.dxf")) if us[0].Nest else [out]
        if check("export wrote the DXF", bool(written) and all(os.path.isfile(w) for w in written),
                 str(dc.texts)):
            import ezdxf
            from freecad_workbench.export.dxf import id_from_xdata

            names = sorted(id_from_xdata(e.get_xdata("TESSELLA"))[1] for w in written
                           for e in ezdxf.readfile(w).modelspace().query('LWPOLYLINE[layer=="CUT"]'))
            check("DXF holds one cut path per panel", names == sorted(us[0].PanelIds), str(names[:5]))
        Gui.Selection.clearSelection()
        with DialogCatcher() as dc:
            Gui.runCommand("Tessella_Schedules")
        check("schedules greyed out without a selection", not command_active("Tessella_Schedules"))
        undo_before = doc.UndoCount
        Gui.Selection.addSelection(doc.Name, p.Name)
        with DialogCatcher() as dc:
            Gui.runCommand("Tessella_Schedules")
        sheets = [o for o in doc.Objects if o.TypeId == "Spreadsheet::Sheet"]
        check("schedules: three spreadsheets", len(sheets) == 3, str(dc.texts))
        check("schedules: one undo step", doc.UndoCount == undo_before + 1
              and doc.UndoNames[0] == "Schedules", str(doc.UndoNames))
        if sheets:
            check("schedules: panel rows", sheets[0].get(f"A{p.PanelCount + 1}")
                  == f"P-{p.PanelCount:04d}", str(sheets[0].get("A2")))
        doc.undo()
        check("schedules: undo removes them",
              not [o for o in doc.Objects if o.TypeId == "Spreadsheet::Sheet"])
        panels = [c for c in children_of(p) if c.Role == "Panels"][0]
        Gui.Selection.clearSelection()
        Gui.Selection.addSelection(doc.Name, panels.Name)
        with DialogCatcher():
            Gui.runCommand("Tessella_Unfold")
        check("Panels child selected: a second Unfold", len(unfolds(doc)) == 2)
        doc.undo()
        check("undo removes it", len(unfolds(doc)) == 1)

        path = os.path.join(tempfile.mkdtemp(prefix="tessella_gui_"), "unfold.FCStd")
        doc.saveAs(path)
        FreeCAD.closeDocument(doc.Name)
        doc = FreeCAD.openDocument(path)
        process_events()
        us = unfolds(doc)
        if check("reopened: Unfold found", len(us) == 1):
            check("reopened: view provider restored",
                  type(us[0].ViewObject.Proxy).__name__ == "ViewProviderUnfold")
    finally:
        Gui.Selection.clearSelection()
        for name in list(FreeCAD.listDocuments()):
            FreeCAD.closeDocument(name)


# FreeCAD runs this file as a script: run the tests, write the result, quit.
ensure_workbench()
gui_harness.run('Tessella GUI unfold test', (test_unfold_command,), 'tessella_gui_unfold_result.json')
