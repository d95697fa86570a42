"""Regenerates the README screenshots (run by `make screenshots`):
docs/toolbar.png (the Tessella toolbar), docs/task_panel.png (the task panel
with its summary), docs/preview.png (the live preview in the 3D view) and
docs/analysis_colors.png (panels coloured by deviation with the legend),
docs/id_labels.png (panel IDs in the 3D view, ShowIds) and
docs/demo_document.png (out/tessella_demo.FCStd as it opens in FreeCAD).

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
    # "Current": the legend's label colours are chosen for the view's own background.
    view.saveImage(os.path.join(DOCS, "analysis_colors.png"), 1200, 800, "Current")
    FreeCAD.closeDocument(doc.Name)
    id_labels(shape)
    demo_document()


def id_labels(shape):
    """Panel IDs in the 3D view (ShowIds) on panels coarse enough to read them."""
    import freecad_workbench as tessella
    from freecad_workbench.features.panelization import children_of
    from PySide import QtGui

    doc = FreeCAD.newDocument("IdLabels")
    src = doc.addObject("Part::Feature", "Surface")
    src.Shape = shape
    parent = tessella.make_panelization((src, "Face1"), method="iso_grid", size=2500.0)
    kids = {c.Role: c for c in children_of(parent)}
    kids["Nodes"].ViewObject.Visibility = False
    kids["Panels"].ViewObject.ShowIds = True
    QtGui.QApplication.processEvents()
    view = Gui.ActiveDocument.ActiveView
    view.viewTop()
    view.fitAll()
    view.saveImage(os.path.join(DOCS, "id_labels.png"), 1200, 800, "Current")
    FreeCAD.closeDocument(doc.Name)


def demo_document():
    """The demo's document written headless, opened as a user opens it."""
    import subprocess
    import tempfile

    from PySide import QtGui

    out = tempfile.mkdtemp(prefix="tessella_demo_")
    env = dict(os.environ, PYTHONPATH=f"/usr/lib/freecad-python3/lib:{REPO}")
    subprocess.run(["/usr/bin/python3", os.path.join(REPO, "examples", "demo.py"), "--out", out,
                    "--no-plot"], check=True, env=env, stdin=subprocess.DEVNULL,
                   stdout=subprocess.DEVNULL)
    doc = FreeCAD.openDocument(os.path.join(out, "tessella_demo.FCStd"))
    for _ in range(5):
        QtGui.QApplication.processEvents()
    Gui.getDocument(doc.Name).ActiveView.saveImage(
        os.path.join(DOCS, "demo_document.png"), 1400, 700, "Current")
    FreeCAD.closeDocument(doc.Name)


try:
    main()
finally:
    os._exit(0)
