"""The workbench without its compiled core (a fresh Addon Manager install, before
`make build`): the toolbar and menu still appear, and every command says the one
command that builds the core instead of the workbench failing on import.

Imports nothing of Tessella but this file (the core import is what failed)."""

import os

import FreeCAD
import FreeCADGui as Gui

#: The commands of the full workbench (gui/register.py), as placeholders.
COMMANDS = ["Tessella_Panelize", "Tessella_Histograms", "Tessella_Unfold",
            "Tessella_ExportFlat", "Tessella_Schedules"]

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def build_hint():
    """What to run, where."""
    return (f"Tessella's compiled core is not built yet. In a terminal run:\n\n"
            f"    cd {ROOT} && make build\n\n"
            "then restart FreeCAD (make build installs what is missing on Debian "
            "bookworm and compiles the C++ core).")


class NeedsBuild:
    """A command that only tells the user to build the core."""

    def __init__(self, name):
        self.name = name

    def GetResources(self):
        icon = os.path.join(ROOT, "resources", "icons", f"{self.name}.svg")
        return {"Pixmap": icon if os.path.isfile(icon) else "",
                "MenuText": self.name.replace("Tessella_", "") + " (core not built)",
                "ToolTip": build_hint()}

    def IsActive(self):
        return True

    def Activated(self):
        FreeCAD.Console.PrintError(build_hint().replace("\n\n", " ") + "\n")
        try:
            from PySide import QtGui

            QtGui.QMessageBox.warning(Gui.getMainWindow(), "Tessella", build_hint())
        except ImportError:
            pass


def register():
    """Register the placeholders; returns their names (toolbar and menu order)."""
    for name in COMMANDS:
        if name not in Gui.listCommands():
            Gui.addCommand(name, NeedsBuild(name))
    return list(COMMANDS)
