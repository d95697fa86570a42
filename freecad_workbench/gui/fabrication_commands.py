"""Fabrication commands: Tessella_Unfold (imported by gui/commands.py)."""

import FreeCAD
import FreeCADGui as Gui

from .view_providers import icon_path

SELECT_PANELIZATION = (
    "Select one Panelization (or one of its Panels, Rods or Nodes) in the tree, "
    "then run Unfold again."
)


def selected_panelization():
    """The selected Panelization (a selected child counts as its parent), else None."""
    from ..selection import panelization_of

    return panelization_of(Gui.Selection.getSelection())


class UnfoldCommand:
    """Tessella_Unfold: flat outlines (true edge lengths, folds) of a Panelization."""

    def GetResources(self):
        return {
            "Pixmap": icon_path("Tessella_Unfold"),
            "MenuText": "Unfold panels",
            "ToolTip": ("Draw every panel of the selected Panelization flat with true edge "
                        "lengths and fold lines (set Nest and the sheet size in the property "
                        "view to lay them out on stock sheets)"),
        }

    def IsActive(self):
        return FreeCAD.ActiveDocument is not None

    def Activated(self):
        from .commands import _warn

        obj = selected_panelization()
        if obj is None:
            _warn("Tessella: Unfold", SELECT_PANELIZATION)
            return
        call = ("tessella.make_unfold("
                f"FreeCAD.getDocument({obj.Document.Name!r}).getObject({obj.Name!r}))")
        try:
            Gui.doCommand("import freecad_workbench as tessella")
            Gui.doCommand(call)
        except Exception as exc:
            _warn("Tessella: Unfold", f"Unfold failed: {exc}")
            return
        Gui.Selection.clearSelection()


SELECT_UNFOLD = "Select one Unfold object in the tree, then run Export flat panels again."


def selected_unfold():
    from ..selection import unfold_of

    return unfold_of(Gui.Selection.getSelection())


def ask_path(obj):
    """The file to write (a save dialog); None when cancelled. Tests replace this."""
    from PySide import QtGui

    path, _ = QtGui.QFileDialog.getSaveFileName(
        Gui.getMainWindow(), "Export flat panels", obj.Label + ".dxf",
        "DXF (*.dxf);;SVG (*.svg)")
    return path or None


class ExportFlatCommand:
    """Tessella_ExportFlat: write the selected Unfold to DXF or SVG."""

    def GetResources(self):
        return {
            "Pixmap": icon_path("Tessella_Unfold"),
            "MenuText": "Export flat panels (DXF/SVG)",
            "ToolTip": ("Write the selected Unfold's panels to a DXF (layers CUT, FOLD, LABEL; "
                        "one block per panel; mm) or an SVG file"),
        }

    def IsActive(self):
        return FreeCAD.ActiveDocument is not None

    def Activated(self):
        from .commands import _warn

        obj = selected_unfold()
        if obj is None:
            _warn("Tessella: Export", SELECT_UNFOLD)
            return
        path = ask_path(obj)
        if not path:
            return
        call = ("tessella.export_unfold("
                f"FreeCAD.getDocument({obj.Document.Name!r}).getObject({obj.Name!r}), {path!r})")
        try:
            Gui.doCommand("import freecad_workbench as tessella")
            Gui.doCommand(call)
        except Exception as exc:
            _warn("Tessella: Export", f"Export failed: {exc}")


class SchedulesCommand:
    """Tessella_Schedules: panel, rod and node schedules as spreadsheets."""

    def GetResources(self):
        return {
            "Pixmap": icon_path("Tessella_Panelization"),
            "MenuText": "Schedules (spreadsheets)",
            "ToolTip": ("Add panel, rod and node schedules of the selected Panelization as "
                        "spreadsheets (a snapshot: run again after changes)"),
        }

    def IsActive(self):
        return FreeCAD.ActiveDocument is not None

    def Activated(self):
        from .commands import _warn

        obj = selected_panelization()
        if obj is None:
            _warn("Tessella: Schedules", SELECT_PANELIZATION.replace("Unfold", "Schedules"))
            return
        call = ("tessella.make_schedules("
                f"FreeCAD.getDocument({obj.Document.Name!r}).getObject({obj.Name!r}))")
        try:
            Gui.doCommand("import freecad_workbench as tessella")
            Gui.doCommand(call)
        except Exception as exc:
            _warn("Tessella: Schedules", f"Schedules failed: {exc}")


Gui.addCommand("Tessella_Unfold", UnfoldCommand())
Gui.addCommand("Tessella_ExportFlat", ExportFlatCommand())
Gui.addCommand("Tessella_Schedules", SchedulesCommand())

COMMANDS = ["Tessella_Unfold", "Tessella_ExportFlat", "Tessella_Schedules"]
