"""Analysis commands: histograms of panel deviation, rod length and panel area,
as a PNG file and in a FreeCAD dialog."""

import os
import tempfile

import FreeCAD
import FreeCADGui as Gui

from .view_providers import icon_path

_dialogs = []  # keep open dialogs alive


def selected_panelization():
    """The Panelization selected (directly or through one of its children), or None."""
    from ..selection import panelization_of

    return panelization_of(Gui.Selection.getSelection())


def histogram_path(obj):
    """Next to the saved document, else in the temporary folder."""
    folder = os.path.dirname(obj.Document.FileName) if obj.Document.FileName else tempfile.gettempdir()
    return os.path.join(folder, f"{obj.Document.Name}_{obj.Name}_histograms.png")


def show_image(path, title):
    from PySide import QtGui

    dialog = QtGui.QDialog(Gui.getMainWindow())
    dialog.setWindowTitle(title)
    dialog.setObjectName("TessellaHistograms")
    layout = QtGui.QVBoxLayout(dialog)
    label = QtGui.QLabel()
    label.setPixmap(QtGui.QPixmap(path))
    layout.addWidget(label)
    caption = QtGui.QLabel(f"Saved as {path}")
    caption.setTextInteractionFlags(caption.textInteractionFlags() | 1)  # selectable
    layout.addWidget(caption)
    dialog.show()
    _dialogs.append(dialog)
    return dialog


class HistogramsCommand:
    """Tessella_Histograms: histograms of the selected Panelization."""

    def GetResources(self):
        return {
            "Pixmap": icon_path("Tessella_Histograms"),
            "MenuText": "Histograms",
            "ToolTip": "Histograms of panel deviation, rod length and panel area of the "
                       "selected Panelization (PNG file and a dialog)",
        }

    def IsActive(self):
        return FreeCAD.ActiveDocument is not None

    def Activated(self):
        obj = selected_panelization()
        if obj is None:
            from .commands import _warn

            _warn("Tessella: Histograms", "Select a Panelization (or its Panels, Rods or Nodes) first.")
            return
        path = histogram_path(obj)
        try:
            Gui.doCommand("import freecad_workbench as tessella")
            Gui.doCommand(f"tessella.histograms(App.getDocument({obj.Document.Name!r})"
                          f".getObject({obj.Name!r}), {path!r})")
        except Exception as exc:
            from .commands import _warn

            _warn("Tessella: Histograms", f"Histograms failed: {exc}")
            return
        show_image(path, f"Tessella: {obj.Label} histograms")


Gui.addCommand("Tessella_Histograms", HistogramsCommand())
COMMANDS = ["Tessella_Histograms"]
