"""GUI test of the first impression (run like gui_test_panelize.py, see tests/gui/README).

`examples/demo.py` writes tessella_demo.FCStd without the GUI. Opened in the
GUI, its objects are visible: the panels of every run in view (their boxes
projected inside the viewport), laid out side by side (no two runs' boxes
overlap), coloured by deviation (several colours, a legend), the sources
hidden, an isometric camera. Saved from the GUI and reopened, the user's own
display choices are kept.
"""

import os
import subprocess
import sys
import tempfile

import FreeCAD
import FreeCADGui as Gui

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import gui_harness  # noqa: E402
from gui_harness import check, ensure_workbench, process_events  # noqa: E402

REPO = os.environ.get("TESSELLA_ROOT") or os.path.dirname(os.path.dirname(
    os.path.dirname(os.path.abspath(__file__))))


def box_corners(bb):
    return [FreeCAD.Vector(x, y, z) for x in (bb.XMin, bb.XMax) for y in (bb.YMin, bb.YMax)
            for z in (bb.ZMin, bb.ZMax)]


def test_demo_document_opens_visible():
    from freecad_workbench.features.panelization import children_of, is_panelization
    from freecad_workbench.gui import legend

    ensure_workbench()
    out = tempfile.mkdtemp(prefix="tessella_demo_")
    env = dict(os.environ, PYTHONPATH=f"/usr/lib/freecad-python3/lib:{REPO}")
    proc = subprocess.run(["/usr/bin/python3", os.path.join(REPO, "examples", "demo.py"),
                           "--out", out, "--no-plot"], capture_output=True, text=True,
                          timeout=600, env=env, stdin=subprocess.DEVNULL)
    path = os.path.join(out, "tessella_demo.FCStd")
    if not check("demo: document written", proc.returncode == 0 and os.path.exists(path),
                 proc.stderr[-2000:]):
        return
    doc = FreeCAD.openDocument(path)
    try:
        for _ in range(5):
            process_events()
        parents = [o for o in doc.Objects if is_panelization(o)]
        check("demo: six runs", len(parents) == 6, str(len(parents)))
        panels = [[c for c in children_of(p) if c.Role == "Panels"][0] for p in parents]
        check("demo: the panels are shown", all(c.ViewObject.Visibility for c in panels),
              str([(c.Label, c.Visibility, c.ViewObject.Visibility) for c in panels]))
        check("demo: the source faces are hidden",
              all(not p.Source[0].ViewObject.Visibility for p in parents))
        coloured = [c for c in panels if c.ViewObject.ColorBy == "Deviation"
                    and len({tuple(col) for col in c.ViewObject.DiffuseColor}) > 1]
        check("demo: panels coloured by deviation (several colours each)",
              len(coloured) >= 3, f"{len(coloured)} of {len(panels)}")
        check("demo: a legend per coloured object",
              all(legend.entry_of(c.ViewObject) is not None for c in coloured))
        boxes = [c.Shape.BoundBox for c in panels]
        overlaps = [(i, j) for i in range(len(boxes)) for j in range(i + 1, len(boxes))
                    if boxes[i].XMax > boxes[j].XMin and boxes[j].XMax > boxes[i].XMin
                    and boxes[i].YMax > boxes[j].YMin and boxes[j].YMax > boxes[i].YMin]
        check("demo: runs side by side, not over each other", not overlaps, str(overlaps))

        view = Gui.getDocument(doc.Name).ActiveView
        width, height = (int(v) for v in view.getSize())
        outside = []
        for c, bb in zip(panels, boxes):
            for corner in box_corners(bb):
                x, y = view.getPointOnScreen(corner)
                if not (-1 <= x <= width + 1 and -1 <= y <= height + 1):
                    outside.append((c.Label, round(x), round(y)))
        check("demo: every run inside the view", not outside,
              f"{outside[:4]} (view {width} x {height})")
        direction = view.getViewDirection()
        iso = FreeCAD.Vector(-1, 1, -1).normalize()  # FreeCAD's isometric: from front right top
        check("demo: isometric camera", abs(abs(direction.dot(iso)) - 1.0) < 1e-3,
              str(direction))

        # Saved from the GUI, the user's display is kept as it is.
        source = parents[0].Source[0]
        source.ViewObject.Visibility = True
        panels[0].ViewObject.ColorBy = "Shape"
        saved = os.path.join(out, "saved_from_gui.FCStd")
        doc.saveAs(saved)
        FreeCAD.closeDocument(doc.Name)
        doc = FreeCAD.openDocument(saved)
        for _ in range(5):
            process_events()
        parents = [o for o in doc.Objects if is_panelization(o)]
        first = [c for c in children_of(parents[0]) if c.Role == "Panels"][0]
        check("demo: a GUI-saved document keeps the user's display",
              parents[0].Source[0].ViewObject.Visibility and first.ViewObject.ColorBy == "Shape",
              f"{parents[0].Source[0].ViewObject.Visibility} {first.ViewObject.ColorBy}")
    finally:
        FreeCAD.closeDocument(doc.Name)


# FreeCAD runs this file as a script: run the tests, write the result, quit.
ensure_workbench()
gui_harness.run("Tessella demo GUI test", (test_demo_document_opens_visible,),
                "tessella_gui_demo_result.json")
