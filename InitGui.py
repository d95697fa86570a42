# Tessella - FreeCAD GUI initialization: registers the Tessella workbench.
#
# FreeCAD 0.20 runs this file with exec() inside a function, without __file__:
# names defined at the top level here are not visible inside the class's methods,
# so the methods import what they need themselves.

import FreeCADGui


class TessellaWorkbench(FreeCADGui.Workbench):
    """Panels, rods and nodes from freeform surfaces."""

    MenuText = "Tessella"
    ToolTip = "Panelize freeform surfaces into panels, rods and nodes"
    Icon = ""

    def Initialize(self):
        import FreeCAD

        try:
            from freecad_workbench.gui import register  # registers every command
        except ImportError as exc:
            # Without the compiled core (a fresh Addon Manager install) the
            # commands say how to build it rather than the workbench failing.
            # (Loaded from its file: importing the package is what failed.)
            import importlib.util
            import os

            FreeCAD.Console.PrintWarning(f"Tessella: {exc}\n")
            spec = importlib.util.find_spec("freecad_workbench")
            path = os.path.join(list(spec.submodule_search_locations)[0], "gui",
                                "missing_core.py")
            loader = importlib.util.spec_from_file_location("tessella_missing_core", path)
            missing_core = importlib.util.module_from_spec(loader)
            loader.loader.exec_module(missing_core)
            names = missing_core.register()
            self.appendToolbar("Tessella", names)
            self.appendMenu("Tessella", names)
            return
        self.appendToolbar("Tessella", list(register.MENU))
        self.appendMenu("Tessella", list(register.MENU))
        from freecad_workbench.gui import preferences, selection_feedback

        selection_feedback.install()
        preferences.register()

    def Activated(self):
        pass

    def Deactivated(self):
        pass

    def ContextMenu(self, recipient):
        try:
            from freecad_workbench.gui import register
        except ImportError:
            return
        if recipient == "View":
            self.appendContextMenu("Tessella", list(register.MENU))

    def GetClassName(self):
        return "Gui::PythonWorkbench"


def _tessella_icon():
    """resources/icons/Tessella.svg, found through the package (no __file__ here)."""
    import importlib.util
    import os

    spec = importlib.util.find_spec("freecad_workbench")  # does not import it
    if spec is None or not spec.submodule_search_locations:
        return ""
    root = os.path.dirname(os.path.abspath(list(spec.submodule_search_locations)[0]))
    return os.path.join(root, "resources", "icons", "Tessella.svg")


TessellaWorkbench.Icon = _tessella_icon()
FreeCADGui.addWorkbench(TessellaWorkbench())
