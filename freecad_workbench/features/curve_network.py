"""App proxy of the CurveNetwork feature: the traced BDCurves (or the
preliminary network) of a boundary_driven Panelization, as a compound of
polylines, so the document can show the curves next to the final panels.

    net = tessella.make_curve_network(panelization)       # Show = "Curves"
    net.Show = "Network"                                  # the preliminary BDMesh edges

FROZEN: the module path `freecad_workbench.features.curve_network` and the class
name `CurveNetwork` are stored in every saved .FCStd.
"""

import FreeCAD

from .base import _PROP_READONLY, _READONLY_OUTPUT, _StateMixin, add_property
from .panelization import is_panelization
from .user_errors import reports_user_errors

SHOW = ("Curves", "Network")


class CurveNetwork(_StateMixin):
    def __init__(self, obj, parent=None):
        self._restore(None)
        self.setup_properties(obj)
        if parent is not None:
            obj.Base = parent
        obj.Proxy = self

    def setup_properties(self, obj):
        add_property(obj, "App::PropertyLink", "Base", "Base",
                     "The boundary_driven Panelization whose curves are shown", attr=_PROP_READONLY)
        add_property(obj, "App::PropertyEnumeration", "Show", "Base",
                     "Curves: the traced BDCurves; Network: the preliminary mesh's edges",
                     default="Curves", enum=SHOW)
        add_property(obj, "App::PropertyInteger", "CurveCount", "Data",
                     "Number of traced curves", attr=_READONLY_OUTPUT)
        add_property(obj, "App::PropertyInteger", "NetworkPanels", "Data",
                     "Faces of the preliminary network", attr=_READONLY_OUTPUT)

    def onDocumentRestored(self, obj):
        self._ensure_runtime()
        self.setup_properties(obj)

    @reports_user_errors
    def execute(self, obj):
        import Part

        from ..boundary_driven import boundary_driven_stages

        parent = obj.Base
        if parent is None or not is_panelization(parent):
            raise ValueError("Base must link to a Panelization object")
        method, params = parent.Proxy.parameters(parent)
        if method != "boundary_driven":
            raise ValueError(f"{parent.Label} uses {method}, not boundary_driven: no curves")
        face_arg, _ = parent.Proxy.source_face(parent)
        for name in ("sliver_fraction", "min_angle", "samples"):
            params.pop(name, None)  # measurement parameters, not the method's
        stages = boundary_driven_stages(face_arg, **params)
        edges = []
        if obj.Show == "Curves":
            for xyz, closed in zip(stages["curves_xyz"], stages["curves_closed"]):
                pts = []
                for p in list(xyz) + ([xyz[0]] if closed else []):
                    v = FreeCAD.Vector(*p)
                    if not pts or (v - pts[-1]).Length > 1e-9 * max(1.0, v.Length):
                        pts.append(v)
                if len(pts) >= 2:
                    edges.append(Part.makePolygon(pts))
        else:
            xyz = stages["network_xyz"]
            for a, b in stages["network_edges"]:
                if (xyz[a] != xyz[b]).any():
                    edges.append(Part.makeLine(FreeCAD.Vector(*xyz[a]), FreeCAD.Vector(*xyz[b])))
        obj.Shape = Part.makeCompound(edges)
        obj.CurveCount = len(stages["curves_xyz"])
        obj.NetworkPanels = len(stages["network_panels"])
