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
        source = obj.Source[0] if obj.Source else None
        if source is not None and getattr(source, "ViewObject", None) is not None:
            source.ViewObject.Visibility = True
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
        self.ViewObject = vobj
        self.Object = vobj.Object
        self._legend = None
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
        if "ColorBy" in vobj.PropertiesList:
            return
        vobj.addProperty("App::PropertyEnumeration", "ColorBy", "Analysis",
                         "Colour each panel / rod by a measured value (with a legend)")
        vobj.ColorBy = self._modes()
        vobj.ColorBy = "Shape"

    def getIcon(self):
        obj = getattr(self, "Object", None)
        role = getattr(obj, "Role", "Panels") if obj is not None else "Panels"
        return icon_path("Tessella_" + role)

    def updateData(self, obj, prop):
        if prop in ("Shape", "Deviation", "Planarity", "Area", "Irregular", "PanelType",
                    "RodLengths"):
            vobj = getattr(self, "ViewObject", None)
            if vobj is not None and getattr(vobj, "ColorBy", "Shape") != "Shape":
                self.apply_colors(vobj)

    def onChanged(self, vobj, prop):
        if prop == "ColorBy":
            self.apply_colors(vobj)

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
        try:
            from pivy import coin
        except ImportError:
            return
        from .. import analysis_colors

        hud = coin.SoSeparator()
        hud.setName("TessellaLegend")
        cam = coin.SoOrthographicCamera()
        cam.viewportMapping = coin.SoCamera.LEAVE_ALONE
        cam.position = coin.SbVec3f(0, 0, 5)
        cam.height = 2.0
        hud.addChild(cam)
        light = coin.SoLightModel()
        light.model = coin.SoLightModel.BASE_COLOR
        hud.addChild(light)
        steps = 16
        x0, x1, y0, y1 = 0.80, 0.88, -0.6, 0.6
        coords = coin.SoCoordinate3()
        points = []
        for k in range(steps):
            ya = y0 + (y1 - y0) * k / steps
            yb = y0 + (y1 - y0) * (k + 1) / steps
            points += [(x0, ya, 0), (x1, ya, 0), (x1, yb, 0), (x0, yb, 0)]
        coords.point.setValues(0, len(points), points)
        material = coin.SoMaterial()
        bar = analysis_colors.colors([lo + (hi - lo) * (k + 0.5) / steps for k in range(steps)],
                                     lo, hi)
        material.diffuseColor.setValues(0, steps, bar)
        binding = coin.SoMaterialBinding()
        binding.value = coin.SoMaterialBinding.PER_FACE
        faces = coin.SoFaceSet()
        faces.numVertices.setValues(0, steps, [4] * steps)
        for node in (coords, material, binding, faces):
            hud.addChild(node)
        text_color = coin.SoBaseColor()
        text_color.rgb = (0.1, 0.1, 0.1)
        hud.addChild(text_color)
        for y, label in ((y1 + 0.08, title), (y1 - 0.02, f"{hi:.4g} {unit}"),
                         (0.5 * (y0 + y1), f"{0.5 * (lo + hi):.4g} {unit}"),
                         (y0 - 0.02, f"{lo:.4g} {unit}")):
            sep = coin.SoSeparator()
            move = coin.SoTranslation()
            move.translation = (x0 - 0.02 if label == title else x1 + 0.02, y, 0)
            text = coin.SoText2()
            text.string = label
            if label == title:
                text.justification = coin.SoText2.RIGHT
            sep.addChild(move)
            sep.addChild(text)
            hud.addChild(sep)
        vobj.RootNode.addChild(hud)
        self._legend = hud

    def _remove_legend(self, vobj):
        legend = getattr(self, "_legend", None)
        if legend is not None and vobj.RootNode.findChild(legend) >= 0:
            vobj.RootNode.removeChild(legend)
        self._legend = None

    def has_legend(self):
        """Whether the colour-bar legend is in the scene (for tests)."""
        vobj = getattr(self, "ViewObject", None)
        legend = getattr(self, "_legend", None)
        return vobj is not None and legend is not None and vobj.RootNode.findChild(legend) >= 0
