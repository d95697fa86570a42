"""Tessella_Panelize. Importing this module registers the command with FreeCADGui
(gui/register.py imports every command module).

Every command echoes the equivalent Python through Gui.doCommand, so a recorded
macro replays it without the GUI.
"""

import math

import FreeCAD
import FreeCADGui as Gui

from .common import DocumentCommand, selected_face, selected_faces, warn  # noqa: F401

_warn = warn  # the name other modules imported from here

#: The message shown when the selection is not exactly one face.
SELECT_ONE_FACE = (
    "Select a face to panelize (click a face of a surface in the 3D view), or several "
    "faces (Ctrl+click; of one object or several), or an object, then run Panelize again."
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


class PanelizeCommand(DocumentCommand):
    """Tessella_Panelize: panelize the selected face (task panel with a live preview)."""

    ICON = "Tessella_Panelize"
    MENU_TEXT = "Panelize face(s)"
    TOOL_TIP = ("Cut the selected face (or several faces: one envelope, joined "
                "along their shared edges) into panels, rods and nodes: a task panel "
                "with a live preview sets the method and its parameters. "
                "Select a face first")

    def IsActive(self):
        """Greyed out until a face (or several faces) is selected, and while
        a task panel is open (Activated still checks, for a replayed macro)."""
        if FreeCAD.ActiveDocument is None or Gui.Control.activeDialog():
            return False
        return selected_face() is not None or selected_faces() is not None

    def Activated(self):
        pick = selected_face()
        several = selected_faces() if pick is None else None
        if several is not None:  # several faces (of one object or more): one envelope
            self._open(several, selection_shape(several))
            return
        if pick is None:
            warn("Tessella: Panelize", SELECT_ONE_FACE)
            return
        obj, sub = pick
        from .. import selection

        try:
            face = selection.one_face(pick)
        except (ValueError, TypeError):
            warn("Tessella: Panelize", f"{obj.Label} has no {sub}. " + SELECT_ONE_FACE)
            return
        self._open((obj, sub), face)

    def _open(self, source, shape):
        if Gui.Control.activeDialog():
            warn("Tessella: Panelize", "Close the open task panel first.")
            return
        from . import preferences, task_panel

        prefs = preferences.defaults()
        size = prefs["size"] or default_size(shape, prefs["panels_across"])
        # The task panel previews live and creates the objects on OK; the face's
        # selection highlight would hide the preview under it.
        Gui.Control.showDialog(task_panel.PanelizationTaskPanel(source=source, size=size))
        Gui.Selection.clearSelection()


def selection_shape(source):
    """The faces a [(object, ['FaceN', ...]), ...] source names, as one compound."""
    import Part

    from .. import selection

    return Part.Compound(selection.faces_of(source))


Gui.addCommand("Tessella_Panelize", PanelizeCommand())

#: This module's commands, in toolbar order (gui/register.py lists them all).
COMMANDS = ["Tessella_Panelize"]
