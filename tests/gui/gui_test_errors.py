"""GUI test of user errors in a recompute (run like gui_test_panelize.py, see tests/gui/README).

A deleted source face, a deleted guide edge and a sheet too small for a panel
each give the object's state (Invalid in the tree, or the Unfold's Status) and
one clear line in the report view: no Python traceback, the label once. After
such an error the report view still shows later errors, and fixing the input
recomputes the object.
"""

import os
import sys

import FreeCAD
import FreeCADGui as Gui

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import gui_harness  # noqa: E402
from gui_harness import check, ensure_workbench, process_events  # noqa: E402


def report_text():
    from PySide import QtGui

    view = Gui.getMainWindow().findChild(QtGui.QTextEdit, "Report view")
    return view.toPlainText() if view is not None else ""


class ReportSince:
    """The report view's text written inside the with block."""

    def __enter__(self):
        self.start = len(report_text())
        return self

    def __exit__(self, *exc):
        process_events()
        self.text = report_text()[self.start:]
        return False


def test_user_errors_without_traceback():
    import Part

    import freecad_workbench as tessella

    ensure_workbench()
    check("errors: the report view exists", bool(report_text()))
    doc = FreeCAD.newDocument("TessellaErrors")
    try:
        src = doc.addObject("Part::Feature", "Roof")
        src.Shape = Part.makePlane(6000, 4000)
        plate = doc.addObject("Part::Feature", "Plate")
        plate.Shape = Part.makePlane(10000, 8000)
        guide = doc.addObject("Part::Feature", "GuideLine")
        guide.Shape = Part.makePlane(10000, 8000).Edges[0]
        doc.recompute()
        p = tessella.make_panelization((src, "Face1"), method="iso_grid", size=1000.0)
        g = tessella.make_panelization((plate, "Face1"), method="guide_line_scaling",
                                       rod_length=1000.0, guides=[(guide, "Edge1")])
        u = tessella.make_unfold(p)
        check("errors: all valid before", p.isValid() and g.isValid() and u.isValid())

        with ReportSince() as source_gone:
            doc.removeObject("Roof")
            doc.recompute()
        text = source_gone.text
        check("errors: deleted source marks the Panelization", not p.isValid(), str(p.State))
        check("errors: deleted source in one line", text.count(f"Tessella: {p.Label}: ") == 1
              and "no source face" in text, text)
        check("errors: no traceback for a deleted source", "Traceback" not in text
              and "File \"" not in text, text)
        check("errors: the label once", f"{p.Label}: {p.Label}" not in text, text)

        with ReportSince() as guide_gone:
            doc.removeObject("GuideLine")
            doc.recompute()
        text = guide_gone.text
        check("errors: deleted guide marks the Panelization", not g.isValid(), str(g.State))
        check("errors: deleted guide in a user's words",
              text.count(f"Tessella: {g.Label}: ") == 1 and "needs one edge in Guides" in text
              and "Pick edges" in text, text)
        check("errors: no traceback for a missing guide", "Traceback" not in text, text)

        with ReportSince() as later:
            FreeCAD.Console.PrintError("a later error\n")
        check("errors: the report view shows later errors", "a later error" in later.text,
              later.text)

        # Fixed input: a new source recomputes the Panelization (and its Unfold).
        roof = doc.addObject("Part::Feature", "Roof2")
        roof.Shape = Part.makePlane(6000, 4000)
        p.Source = (roof, ["Face1"])
        doc.recompute()
        check("errors: relinked source recomputes", p.isValid() and p.PanelCount == 24,
              f"{p.State} {p.PanelCount}")

        with ReportSince() as sheet:
            u.Nest = True
            u.SheetWidth, u.SheetHeight = 300.0, 300.0
            doc.recompute()
        text = sheet.text
        check("errors: a sheet too small is the Unfold's Status",
              u.isValid() and u.Status.startswith("Not nested: "), u.Status)
        check("errors: a sheet too small in one line, no traceback",
              text.count(f"Tessella: {u.Label}: Not nested") == 1 and "Traceback" not in text,
              text)
    finally:
        FreeCAD.closeDocument(doc.Name)


# FreeCAD runs this file as a script: run the tests, write the result, quit.
ensure_workbench()
gui_harness.run("Tessella GUI errors test", [test_user_errors_without_traceback],
                "tessella_gui_errors_result.json")
