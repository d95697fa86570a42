"""View providers of the Panelization object and its Panels / Rods / Nodes children.

FROZEN: the module path `freecad_workbench.gui.view_providers` and the class names
`ViewProviderPanelization` and `ViewProviderPanelizationPart` are stored in the
GuiDocument.xml of every .FCStd saved from the GUI.
"""

from .common import ICON_DIR, icon_path  # noqa: F401  (imported from here by older code)


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

    def doubleClicked(self, vobj):
        """Double-click in the tree: edit in the task panel."""
        import FreeCADGui as Gui

        if Gui.Control.activeDialog():
            return False
        Gui.ActiveDocument.setEdit(vobj.Object.Name)
        return True

    def setEdit(self, vobj, mode=0):
        if mode != 0:
            return None  # transform etc.: FreeCAD's default behaviour
        import FreeCADGui as Gui

        from .task_panel import PanelizationTaskPanel

        Gui.Control.showDialog(PanelizationTaskPanel(obj=vobj.Object))
        return True

    def unsetEdit(self, vobj, mode=0):
        if mode != 0:
            return None
        import FreeCADGui as Gui

        Gui.Control.closeDialog()
        return True

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
        """Deleting the Panelization deletes its Panels, Rods and Nodes too, and
        shows its source face again (hidden when the panels were made)."""
        from ..features.panelization import children_of

        obj = vobj.Object
        doc = obj.Document
        for child in children_of(obj):
            if doc.getObject(child.Name) is not None:
                doc.removeObject(child.Name)
        for source in obj.Proxy.source_objects(obj):
            if getattr(source, "ViewObject", None) is not None:
                source.ViewObject.Visibility = True
        from . import legend

        legend.relayout()  # the children's legends went with them
        return True

    def updateData(self, obj, prop):
        return None

    def onChanged(self, vobj, prop):
        return None


class ViewProviderPanelizationPart(_VPState):
    """Panels, Rods or Nodes: a normal Part view with the role's icon, and
    analysis colours: Panels by deviation, planarity, area or irregularity,
    Rods by length (view property ColorBy), with a colour-bar legend."""

    def __init__(self, vobj):
        vobj.Proxy = self

    def attach(self, vobj):
        from .id_labels import IdLabels

        self.ViewObject = vobj
        self.Object = vobj.Object
        self.id_labels = IdLabels()
        self._add_view_properties(vobj)

    def _modes(self):
        from .. import analysis_colors

        role = getattr(self.Object, "Role", "Nodes")
        if role == "Panels":
            return ["Shape"] + list(analysis_colors.PANEL_MODES)
        if role == "Rods":
            return ["Shape"] + list(analysis_colors.ROD_MODES)
        return ["Shape"]

    def _add_view_properties(self, vobj):
        if "ColorBy" not in vobj.PropertiesList:
            vobj.addProperty("App::PropertyEnumeration", "ColorBy", "Analysis",
                             "Colour each panel / rod by a measured value (with a legend)")
            vobj.ColorBy = self._modes()
            vobj.ColorBy = "Shape"
        elif list(vobj.getEnumerationsOfProperty("ColorBy")) != self._modes():
            # A document saved before a mode was added (Family): the new list,
            # the chosen mode kept when it still exists.
            chosen = vobj.ColorBy
            vobj.ColorBy = self._modes()
            vobj.ColorBy = chosen if chosen in self._modes() else "Shape"
        if "ShowIds" not in vobj.PropertiesList:  # documents saved before it get it on open
            vobj.addProperty("App::PropertyBool", "ShowIds", "Labels",
                             "Show each panel / rod / node ID as text in the 3D view")

    def getIcon(self):
        obj = getattr(self, "Object", None)
        role = getattr(obj, "Role", "Panels") if obj is not None else "Panels"
        return icon_path("Tessella_" + role)

    def updateData(self, obj, prop):
        vobj = getattr(self, "ViewObject", None)
        if vobj is None:
            return
        if prop in ("Shape", "Deviation", "Planarity", "Area", "Irregular", "PanelType",
                    "PanelFamily", "PanelClass", "RodLengths"):
            if getattr(vobj, "ColorBy", "Shape") != "Shape":
                self.apply_colors(vobj)
        if prop in ("Shape", "PanelIds", "RodIds", "NodeIds") and getattr(vobj, "ShowIds", False):
            self._labels().refresh(vobj)

    def onChanged(self, vobj, prop):
        if prop == "ColorBy":
            self.apply_colors(vobj)
        elif prop == "ShowIds":
            self._labels().refresh(vobj)
        elif prop == "Visibility":
            self._labels().follow_visibility(vobj)
            if getattr(vobj, "ColorBy", "Shape") != "Shape":
                from . import legend

                legend.relayout()  # a hidden object's legend goes, the others close up

    def _labels(self):
        if getattr(self, "id_labels", None) is None:
            from .id_labels import IdLabels

            self.id_labels = IdLabels()
        return self.id_labels

    def apply_colors(self, vobj):
        """Colour faces (Panels) or edges (Rods) by the chosen value; draw the legend."""
        from .. import analysis_colors

        obj = vobj.Object
        mode = getattr(vobj, "ColorBy", "Shape")
        self._remove_legend(vobj)
        if mode == "Shape" or obj.Shape.isNull():
            if obj.Role == "Panels":
                vobj.DiffuseColor = [vobj.ShapeColor]
            elif obj.Role == "Rods" and "LineColorArray" in vobj.PropertiesList:
                vobj.LineColorArray = [vobj.LineColor]
            return
        values, unit = analysis_colors.values_for(obj, mode)
        if len(values) == 0:
            return
        lo, hi = analysis_colors.scale(values)
        item_colors = analysis_colors.colors(values, lo, hi)
        if obj.Role == "Panels":
            vobj.DiffuseColor = analysis_colors.per_face(obj.Shape, item_colors)
        elif "LineColorArray" in vobj.PropertiesList:
            vobj.LineColorArray = item_colors
        self._add_legend(vobj, f"{obj.Label}: {mode}", lo, hi, unit)

    # ------------------------------------------------------------------ legend
    def _add_legend(self, vobj, title, lo, hi, unit):
        from .. import analysis_colors
        from . import legend

        legend.show(vobj, title, lo, hi, unit, analysis_colors.colors)

    def _remove_legend(self, vobj):
        from . import legend

        legend.hide(vobj)

    def onDelete(self, vobj, subelements):
        self._remove_legend(vobj)
        self._labels().remove(vobj)
        return True

    def has_legend(self):
        """Whether the colour-bar legend is in the scene (for tests)."""
        from . import legend

        vobj = getattr(self, "ViewObject", None)
        entry = legend.entry_of(vobj) if vobj is not None else None
        return entry is not None and vobj.RootNode.findChild(entry["node"]) >= 0
