"""Regenerates the README screenshots (run by `make screenshots`):
docs/toolbar.png (the Tessella toolbar), docs/task_panel.png (the task panel
with its summary), docs/preview.png (the live preview in the 3D view) and
docs/analysis_colors.png (panels coloured by deviation with the legend).

    QTWEBENGINE_DISABLE_SANDBOX=1 xvfb-run -a -s "-screen 0 1600x1000x24" freecad tests/gui/make_screenshots.py
"""
import os
import sys

import FreeCAD
import FreeCADGui as Gui

REPO = os.environ.get("TESSELLA_ROOT") or os.path.dirname(os.path.dirname(os.path.dirname(
    os.path.abspath(__file__))))
DOCS = os.path.join(REPO, "docs")


def main():
    from PySide import QtGui

    if "TessellaWorkbench" not in Gui.listWorkbenches():
        sys.path.insert(0, REPO)
        with open(os.path.join(REPO, "InitGui.py"), encoding="utf-8") as f:
            exec(compile(f.read(), "InitGui.py", "exec"), {"__builtins__": __builtins__}, {})
    import Part
    import freecad_workbench as tessella
    from freecad_workbench.features.panelization import children_of
    from freecad_workbench.gui import task_panel

    Gui.activateWorkbench("TessellaWorkbench")
    doc = FreeCAD.newDocument("Screenshots")
    shape = Part.Shape()
    shape.read(os.path.join(REPO, "examples", "trimmed_bspline_holes.brep"))
    src = doc.addObject("Part::Feature", "Surface")
    src.Shape = shape
    doc.recompute()
    view = Gui.ActiveDocument.ActiveView
    view.viewIsometric()
    view.fitAll()
    QtGui.QApplication.processEvents()
    for bar in Gui.getMainWindow().findChildren(QtGui.QToolBar):
        if bar.windowTitle() == "Tessella":
            bar.grab().save(os.path.join(DOCS, "toolbar.png"))
    # Task panel with the live preview.
    Gui.Selection.addSelection(doc.Name, src.Name, "Face1")
    Gui.runCommand("Tessella_Panelize")
    panel = task_panel.active()
    panel.widget("size").setProperty("rawValue", 800.0)
    panel.timer.stop()
    panel.update_preview()
    QtGui.QApplication.processEvents()
    panel.form.resize(380, panel.form.sizeHint().height())
    panel.form.grab().save(os.path.join(DOCS, "task_panel.png"))
    view.saveImage(os.path.join(DOCS, "preview.png"), 1000, 650, "White")
    panel.accept()
    QtGui.QApplication.processEvents()
    src.ViewObject.Visibility = False
    parent = [o for o in doc.Objects if o.TypeId == "App::FeaturePython"][0]
    kids = {c.Role: c for c in children_of(parent)}
    kids["Panels"].ViewObject.ColorBy = "Deviation"
    kids["Nodes"].ViewObject.Visibility = False
    QtGui.QApplication.processEvents()
    view.fitAll()
    view.saveImage(os.path.join(DOCS, "analysis_colors.png"), 1200, 800, "White")
    FreeCAD.closeDocument(doc.Name)


try:
    main()
finally:
    os._exit(0)
