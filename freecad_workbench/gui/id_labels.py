"""Panel / rod / node IDs as text in the 3D view (view property ShowIds).

One label per item, at the panel's centre (mean of its corners), the rod's
midpoint or the node, so a fitter can match the model against the schedules.
The labels hang in their own switch under the object's root node, drawn over
the surface (a panel's centre lies on or under a curved panel): they follow
the object's placement, hide with it and go with it. Above MAX_LABELS items a
label per item is unreadable and slow to draw: only the first MAX_LABELS get
one, and the report view says so.
"""

import FreeCAD

#: The most labels drawn for one object.
MAX_LABELS = 5000

_ID_PROPERTY = {"Panels": "PanelIds", "Rods": "RodIds", "Nodes": "NodeIds"}


def anchors(obj):
    """[(x, y, z)] label positions of obj's items (in its own frame), in ID order."""
    shape = obj.Shape.copy()
    shape.Placement = FreeCAD.Placement()  # the root node applies the placement
    role = obj.Role
    if role == "Panels":
        out = []
        for part in shape.childShapes():
            pts = [v.Point for v in part.Vertexes]
            n = max(len(pts), 1)
            out.append(tuple(sum((p[k] for p in pts), 0.0) / n for k in range(3)))
        return out
    if role == "Rods":
        return [tuple(e.valueAt(0.5 * (e.FirstParameter + e.LastParameter))) for e in shape.Edges]
    return [tuple(v.Point) for v in shape.Vertexes]


def ids_of(obj):
    return list(getattr(obj, _ID_PROPERTY.get(obj.Role, ""), []) or [])


def build(obj, color=(0.05, 0.05, 0.05), font_size=11):
    """A new coin switch holding one SoText2 per item of obj (at most MAX_LABELS)."""
    from pivy import coin

    ids, points = ids_of(obj), anchors(obj)
    count = min(len(ids), len(points))
    if count > MAX_LABELS:
        FreeCAD.Console.PrintWarning(
            f"Tessella: {obj.Label}: {count} IDs, labels drawn for the first {MAX_LABELS} "
            "only (the schedules list all)\n")
        count = MAX_LABELS
    switch = coin.SoSwitch()
    switch.setName("TessellaIdLabels")
    group = coin.SoSeparator()
    base = coin.SoBaseColor()
    base.rgb = color
    font = coin.SoFont()
    font.size = font_size
    group.addChild(base)
    group.addChild(font)
    if hasattr(coin, "SoDepthBuffer"):  # a centre lies on or under a curved panel: draw on top
        depth = coin.SoDepthBuffer()
        depth.test = False
        group.addChild(depth)
    for k in range(count):
        label = coin.SoSeparator()
        where = coin.SoTranslation()
        where.translation = points[k]
        text = coin.SoText2()
        text.string = ids[k]
        text.justification = coin.SoText2.CENTER
        label.addChild(where)
        label.addChild(text)
        group.addChild(label)
    switch.addChild(group)
    switch.whichChild = 0
    return switch


class IdLabels:
    """The labels of one view object: shown, refreshed, hidden, removed."""

    def __init__(self):
        self.node = None

    def refresh(self, vobj):
        """Rebuild after a change of ShowIds, the shape or the IDs."""
        self.remove(vobj)
        if not getattr(vobj, "ShowIds", False) or vobj.Object.Shape.isNull():
            return
        self.node = build(vobj.Object)
        vobj.RootNode.addChild(self.node)
        self.follow_visibility(vobj)

    def follow_visibility(self, vobj):
        if self.node is not None:
            self.node.whichChild = 0 if vobj.Visibility else -1

    def remove(self, vobj):
        if self.node is not None:
            vobj.RootNode.removeChild(self.node)
            self.node = None

    def texts(self):
        """The label strings in the scene (for tests); [] when none is shown."""
        if self.node is None or self.node.whichChild.getValue() < 0:
            return []
        return [child.getChild(1).string.getValues()[0] for child in self.label_nodes()]

    def label_nodes(self):
        """The per-item separators (translation, text), in ID order."""
        if self.node is None:
            return []
        group = self.node.getChild(0)
        items = [group.getChild(k) for k in range(group.getNumChildren())]
        return [n for n in items if n.isOfType(_separator_type())]


def _separator_type():
    from pivy import coin

    return coin.SoSeparator.getClassTypeId()
