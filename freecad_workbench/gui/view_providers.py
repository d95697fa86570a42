"""View providers of the Panelization object and its Panels / Rods / Nodes children.

FROZEN: the module path `freecad_workbench.gui.view_providers` and the class names
`ViewProviderPanelization` and `ViewProviderPanelizationPart` are stored in the
GuiDocument.xml of every .FCStd saved from the GUI.
"""

import os

ICON_DIR = os.path.join(
    os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))),
    "resources",
    "icons",
)


def icon_path(name):
    """Absolute path of resources/icons/<name>.svg."""
    return os.path.join(ICON_DIR, name + ".svg")


class _VPState:
    """JSON-safe persistence (FreeCAD 0.20 on Python 3.11 needs both protocols)."""

    def dumps(self):
        return {"schema": 1}

    def loads(self, state):
        return None

    def __getstate__(self):
        return self.dumps()

    def __setstate__(self, state):
        self.loads(state)


class ViewProviderPanelization(_VPState):
    """Tree entry of a Panelization: no geometry of its own, claims its three children."""

    def __init__(self, vobj):
        vobj.Proxy = self

    def attach(self, vobj):
        self.ViewObject = vobj
        self.Object = vobj.Object
        try:
            from pivy import coin

            vobj.addDisplayMode(coin.SoGroup(), "Default")
        except Exception:  # pivy missing: the object simply has nothing to draw
            pass

    def getDisplayModes(self, vobj):
        return ["Default"]

    def getDefaultDisplayMode(self):
        return "Default"

    def setDisplayMode(self, mode):
        return mode

    def getIcon(self):
        return icon_path("Tessella_Panelization")

    def _object(self):
        obj = getattr(self, "Object", None)
        if obj is None:
            vobj = getattr(self, "ViewObject", None)
            obj = getattr(vobj, "Object", None)
        return obj

    def claimChildren(self):
        from ..features.panelization import children_of

        obj = self._object()
        if obj is None:
            return []
        try:
            return children_of(obj)
        except Exception:
            return []

    def onDelete(self, vobj, subelements):
        """Deleting the Panelization deletes its Panels, Rods and Nodes too."""
        from ..features.panelization import children_of

        obj = vobj.Object
        doc = obj.Document
        for child in children_of(obj):
            if doc.getObject(child.Name) is not None:
                doc.removeObject(child.Name)
        return True

    def updateData(self, obj, prop):
        return None

    def onChanged(self, vobj, prop):
        return None


class ViewProviderPanelizationPart(_VPState):
    """Panels, Rods or Nodes: a normal Part view with the role's icon."""

    def __init__(self, vobj):
        vobj.Proxy = self

    def attach(self, vobj):
        self.ViewObject = vobj
        self.Object = vobj.Object

    def getIcon(self):
        obj = getattr(self, "Object", None)
        role = getattr(obj, "Role", "Panels") if obj is not None else "Panels"
        return icon_path("Tessella_" + role)

    def updateData(self, obj, prop):
        return None

    def onChanged(self, vobj, prop):
        return None
