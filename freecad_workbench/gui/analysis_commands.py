"""Analysis commands: histograms of panel deviation, rod length and panel area,
as a PNG file and in a FreeCAD dialog."""

import os
import tempfile

import FreeCAD
import FreeCADGui as Gui

from .common import DocumentCommand, echo, object_ref, selected_panelization, warn  # noqa: F401

_dialogs = []  # keep open dialogs alive


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


class HistogramsCommand(DocumentCommand):
    """Tessella_Histograms: histograms of the selected Panelization."""

    ICON = "Tessella_Histograms"
    MENU_TEXT = "Histograms"
    TOOL_TIP = ("Histograms of panel deviation, rod length and panel area of the "
                "selected Panelization (PNG file and a dialog)")

    def IsActive(self):
        return FreeCAD.ActiveDocument is not None and selected_panelization() is not None

    def Activated(self):
        obj = selected_panelization()
        if obj is None:
            warn("Tessella: Histograms", "Select a Panelization (or its Panels, Rods or Nodes) first.")
            return
        path = histogram_path(obj)
        if echo("Tessella: Histograms", f"tessella.histograms({object_ref(obj)}, {path!r})",
                "Histograms"):
            show_image(path, f"Tessella: {obj.Label} histograms")


Gui.addCommand("Tessella_Histograms", HistogramsCommand())
COMMANDS = ["Tessella_Histograms"]
