"""What the GUI commands and task panels share: icons, the warning box, the
selection gates (what the user has selected, or None), echoing a command's
Python through Gui.doCommand, and the base class of the commands.

The command modules (commands, analysis_commands, fabrication_commands) import
this module and never each other; gui/register.py imports them all.
FreeCADGui is imported inside the functions, so this module (like
view_providers, which takes icon_path from here) loads without side effects.
"""

import os

import FreeCAD

ICON_DIR = os.path.join(
    os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))),
    "resources",
    "icons",
)


def icon_path(name):
    """Absolute path of resources/icons/<name>.svg."""
    return os.path.join(ICON_DIR, name + ".svg")


# ------------------------------------------------------------------ messages
def warn(title, text):
    """Tell the user: the report view and a warning box."""
    FreeCAD.Console.PrintWarning(f"Tessella: {text}\n")
    try:
        import FreeCADGui as Gui
        from PySide import QtGui

        QtGui.QMessageBox.warning(Gui.getMainWindow(), title, text)
    except ImportError:
        pass


_warn = warn  # the name the modules used


# ---------------------------------------------------------- selection gates
def selected_face():
    """(object, 'FaceN') when exactly one face is selected, else None.

    A selected object without a sub-element counts when its shape has one face.
    """
    import FreeCADGui as Gui

    from .. import selection

    try:
        return selection.face_link(Gui.Selection.getSelectionEx())
    except (ValueError, TypeError):
        return None


def selected_faces():
    """[(object, ['FaceN', ...]), ...] when two or more faces are selected (of
    one object or several, or an object of several faces), else None."""
    import FreeCADGui as Gui

    from .. import selection

    sel = Gui.Selection.getSelectionEx()
    try:
        links = selection.face_set_links(sel)
        if len(selection.faces_of(links)) < 2:
            return None
        return links
    except (ValueError, TypeError):
        return None


def selected_panelization():
    """The one selected Panelization (a selected child, Unfold or other object
    whose Base is a Panelization counts as it), else None."""
    import FreeCADGui as Gui

    from ..selection import panelization_of

    return panelization_of(Gui.Selection.getSelection())


def selected_unfold():
    """The one selected Unfold object, else None."""
    import FreeCADGui as Gui

    from ..selection import unfold_of

    return unfold_of(Gui.Selection.getSelection())


# ------------------------------------------------------------------- echoing
def object_ref(obj):
    """Python that finds a document object again (in a replayed macro)."""
    return f"FreeCAD.getDocument({obj.Document.Name!r}).getObject({obj.Name!r})"


def echo(title, call, failure):
    """Run `call` (a line of Python using `tessella`) through Gui.doCommand, so a
    recorded macro replays it. On an error: a warning box "<failure> failed: ..."
    and False."""
    import FreeCADGui as Gui

    try:
        Gui.doCommand("import freecad_workbench as tessella")
        Gui.doCommand(call)
    except Exception as exc:
        warn(title, f"{failure} failed: {exc}")
        return False
    return True


# ------------------------------------------------------------------ commands
class DocumentCommand:
    """Base of the Tessella commands: active while a document is open; the
    resources come from the class attributes."""

    ICON = "Tessella_Panelization"
    MENU_TEXT = ""
    TOOL_TIP = ""

    def GetResources(self):
        return {"Pixmap": icon_path(self.ICON), "MenuText": self.MENU_TEXT,
                "ToolTip": self.TOOL_TIP}

    def IsActive(self):
        return FreeCAD.ActiveDocument is not None
