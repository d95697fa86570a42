"""Selection feedback: clicking a panel, rod or node in the 3D view shows its ID
and figures in the status bar (and the report view).

`describe(obj, sub)` is plain logic (no GUI) so tests can call it headless.
"""

import numpy as np


def _face_to_panel(shape):
    """Index of the panel owning each face of the Panels compound."""
    owner = []
    for p, child in enumerate(shape.childShapes()):
        owner.extend([p] * max(1, len(child.Faces)))
    return owner


def describe(obj, sub):
    """One line about the picked sub-element of a Panels / Rods / Nodes child,
    or None when it is not one of ours (or not a face / edge / vertex we map)."""
    role = getattr(obj, "Role", None)
    if role not in ("Panels", "Rods", "Nodes") or not sub:
        return None
    try:
        if role == "Panels" and sub.startswith("Face"):
            p = _face_to_panel(obj.Shape)[int(sub[4:]) - 1]
            corners = len(obj.Shape.childShapes()[p].Vertexes)
            kind = {3: "triangle", 4: "quad"}.get(corners, f"{corners}-gon")
            text = f"{obj.PanelIds[p]} ({kind})"
            if len(obj.Deviation) > p:
                text += (f": deviation {obj.Deviation[p]:.3f} mm, planarity {obj.Planarity[p]:.4f},"
                         f" area {obj.Area[p] / 1e6:.3f} m²")
                if obj.Irregular[p]:
                    text += ", irregular"
            return text
        if role == "Rods" and sub.startswith("Edge"):
            r = int(sub[4:]) - 1
            return f"{obj.RodIds[r]}: length {obj.RodLengths[r]:.2f} mm"
        if role == "Nodes" and sub.startswith("Vertex"):
            n = int(sub[6:]) - 1
            p = np.array(obj.Shape.Vertexes[n].Point) / 1000.0
            return (f"{obj.NodeIds[n]}: valence {obj.Valence[n]}, "
                    f"at ({p[0]:.3f}, {p[1]:.3f}, {p[2]:.3f}) m")
    except (IndexError, ValueError):
        return None
    return None


class SelectionFeedback:
    """FreeCAD selection observer writing describe() into the status bar."""

    def addSelection(self, doc, obj_name, sub, pnt):
        import FreeCAD
        import FreeCADGui as Gui

        document = FreeCAD.getDocument(doc)
        obj = document.getObject(obj_name) if document else None
        text = describe(obj, sub) if obj is not None else None
        if text:
            Gui.getMainWindow().statusBar().showMessage("Tessella: " + text)
            FreeCAD.Console.PrintMessage(f"Tessella: {text}\n")


_observer = None


def install():
    """Register the observer once per FreeCAD session."""
    global _observer
    if _observer is None:
        import FreeCADGui as Gui

        _observer = SelectionFeedback()
        Gui.Selection.addObserver(_observer)
    return _observer
