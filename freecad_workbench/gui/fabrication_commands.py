"""Fabrication commands: Tessella_Unfold, Tessella_ExportFlat, Tessella_Schedules."""

import FreeCAD
import FreeCADGui as Gui

from .common import (  # noqa: F401  (selected_*: the names tests and macros used)
    DocumentCommand,
    echo,
    object_ref,
    selected_panelization,
    selected_unfold,
    warn,
)

SELECT_PANELIZATION = (
    "Select one Panelization (or one of its Panels, Rods or Nodes) in the tree, "
    "then run Unfold again."
)
SELECT_UNFOLD = "Select one Unfold object in the tree, then run Export flat panels again."


class UnfoldCommand(DocumentCommand):
    """Tessella_Unfold: flat outlines (true edge lengths, folds) of a Panelization."""

    ICON = "Tessella_Unfold"
    MENU_TEXT = "Unfold panels"
    TOOL_TIP = ("Draw every panel of the selected Panelization flat with true edge "
                "lengths and fold lines (set Nest and the sheet size in the property "
                "view to lay them out on stock sheets)")

    def IsActive(self):
        return FreeCAD.ActiveDocument is not None and selected_panelization() is not None

    def Activated(self):
        obj = selected_panelization()
        if obj is None:
            warn("Tessella: Unfold", SELECT_PANELIZATION)
            return
        if echo("Tessella: Unfold", f"tessella.make_unfold({object_ref(obj)})", "Unfold"):
            Gui.Selection.clearSelection()


def ask_path(obj):
    """The file to write (a save dialog); None when cancelled. Tests replace this."""
    from PySide import QtGui

    path, _ = QtGui.QFileDialog.getSaveFileName(
        Gui.getMainWindow(), "Export flat panels", obj.Label + ".dxf",
        "DXF (*.dxf);;SVG (*.svg)")
    return path or None


class ExportFlatCommand(DocumentCommand):
    """Tessella_ExportFlat: write the selected Unfold to DXF or SVG."""

    ICON = "Tessella_ExportFlat"
    MENU_TEXT = "Export flat panels (DXF/SVG)"
    TOOL_TIP = ("Write the selected Unfold's panels to DXF for CAM (one file per sheet, "
                "layers CUT, FOLD, LABEL; mm) or to an SVG file")

    def IsActive(self):
        return FreeCAD.ActiveDocument is not None and selected_unfold() is not None

    def Activated(self):
        obj = selected_unfold()
        if obj is None:
            warn("Tessella: Export", SELECT_UNFOLD)
            return
        path = ask_path(obj)
        if not path:
            return
        echo("Tessella: Export", f"tessella.export_unfold({object_ref(obj)}, {path!r})", "Export")


class SchedulesCommand(DocumentCommand):
    """Tessella_Schedules: panel, rod and node schedules as spreadsheets."""

    ICON = "Tessella_Schedules"
    MENU_TEXT = "Schedules (spreadsheets)"
    TOOL_TIP = ("Add panel, rod and node schedules of the selected Panelization as "
                "spreadsheets (a snapshot: run again after changes)")

    def IsActive(self):
        return FreeCAD.ActiveDocument is not None and selected_panelization() is not None

    def Activated(self):
        obj = selected_panelization()
        if obj is None:
            warn("Tessella: Schedules", SELECT_PANELIZATION.replace("Unfold", "Schedules"))
            return
        echo("Tessella: Schedules", f"tessella.make_schedules({object_ref(obj)})", "Schedules")


Gui.addCommand("Tessella_Unfold", UnfoldCommand())
Gui.addCommand("Tessella_ExportFlat", ExportFlatCommand())
Gui.addCommand("Tessella_Schedules", SchedulesCommand())

COMMANDS = ["Tessella_Unfold", "Tessella_ExportFlat", "Tessella_Schedules"]
