"""GUI commands. Importing this module registers them with FreeCADGui.

Every command echoes the equivalent Python through Gui.doCommand, so a recorded
macro replays it without the GUI.
"""

import math

import FreeCAD
import FreeCADGui as Gui

from .view_providers import icon_path

#: The message shown when the selection is not exactly one face.
SELECT_ONE_FACE = (
    "Select exactly one face to panelize (click a face of a surface in the 3D view), "
    "then run Panelize again."
)


def _nice_round(x):
    """x rounded down to 1, 2, 2.5 or 5 times a power of ten."""
    if not (x > 0 and math.isfinite(x)):
        return 0.0
    exp = math.floor(math.log10(x))
    base = 10.0**exp
    for step in (5.0, 2.5, 2.0, 1.0):
        if x >= step * base:
            return step * base
    return base


def default_size(face, panels_across=8):
    """A panel size giving roughly panels_across x panels_across panels on the face."""
    try:
        area = face.Area
    except Exception:
        area = 0.0
    size = _nice_round(math.sqrt(area) / panels_across) if area > 0 else 0.0
    if size <= 0:
        size = _nice_round(face.BoundBox.DiagonalLength / (1.5 * panels_across))
    return size or 1.0


def selected_face():
    """(object, 'FaceN') when exactly one face is selected, else None.

    A selected object without a sub-element counts when its shape has one face.
    """
    from .. import selection

    try:
        return selection.face_link(Gui.Selection.getSelectionEx())
    except (ValueError, TypeError):
        return None


def _warn(title, text):
    FreeCAD.Console.PrintWarning(f"Tessella: {text}\n")
    try:
        from PySide import QtGui

        QtGui.QMessageBox.warning(Gui.getMainWindow(), title, text)
    except ImportError:
        pass


class PanelizeCommand:
    """Tessella_Panelize: panelize the selected face with an iso grid."""

    def GetResources(self):
        return {
            "Pixmap": icon_path("Tessella_Panelize"),
            "MenuText": "Panelize face",
            "ToolTip": (
                "Cut the selected face into panels, rods and nodes: a task panel "
                "with a live preview sets the method and its parameters"
            ),
        }

    def IsActive(self):
        return FreeCAD.ActiveDocument is not None

    def Activated(self):
        pick = selected_face()
        if pick is None:
            _warn("Tessella: Panelize", SELECT_ONE_FACE)
            return
        obj, sub = pick
        from .. import selection

        try:
            face = selection.one_face(pick)
        except (ValueError, TypeError):
            _warn("Tessella: Panelize", f"{obj.Label} has no {sub}. " + SELECT_ONE_FACE)
            return
        if Gui.Control.activeDialog():
            _warn("Tessella: Panelize", "Close the open task panel first.")
            return
        from . import preferences, task_panel

        prefs = preferences.defaults()
        size = prefs["size"] or default_size(face, prefs["panels_across"])
        # The task panel previews live and creates the objects on OK.
        Gui.Control.showDialog(task_panel.PanelizationTaskPanel(source=(obj, sub), size=size))


Gui.addCommand("Tessella_Panelize", PanelizeCommand())

from . import analysis_commands  # noqa: E402  (registers its commands)

#: Command names, in toolbar order (used by InitGui.py).
COMMANDS = ["Tessella_Panelize"] + analysis_commands.COMMANDS

from . import fabrication_commands  # noqa: E402  (registers Tessella_Unfold)

COMMANDS += fabrication_commands.COMMANDS
