"""Picking sub-elements in the 3D view for a task panel: one selection gate
class, for faces and for edges.

    gate = ElementGate(selection.FACE, on_pick=panel.use_face, exclude=panel._is_own)
    gate.start()   # only faces of other objects can be selected now
    gate.stop()
"""

import FreeCAD
import FreeCADGui as Gui

from .. import selection


class ElementGate:
    """A selection gate (FreeCAD asks allow()) that lets only sub-elements of one
    kind ('Face' or 'Edge') of objects with a shape through, minus the objects
    exclude(obj) refuses, and an observer that hands every pick to on_pick(obj, sub)."""

    def __init__(self, kind, on_pick, exclude=None):
        self.kind = kind
        self.on_pick = on_pick
        self.exclude = exclude
        self._observer = None
        self.active = False

    def accepts(self, obj, sub):
        return selection.is_element(sub, self.kind) and hasattr(obj, "Shape") \
            and not (self.exclude is not None and self.exclude(obj))

    # FreeCAD's selection gate protocol
    def allow(self, doc, obj, sub):
        return self.accepts(obj, sub)

    def start(self):
        """Clear the selection and let only this kind through until stop()."""
        Gui.Selection.clearSelection()
        self._observer = _Observer(self)
        Gui.Selection.addSelectionGate(self)
        Gui.Selection.addObserver(self._observer)
        self.active = True

    def stop(self):
        if self.active:
            Gui.Selection.removeSelectionGate()
            self.active = False
        if self._observer is not None:
            Gui.Selection.removeObserver(self._observer)
            self._observer = None


class _Observer:
    """Selection observer of an ElementGate (FreeCAD's observer protocol)."""

    def __init__(self, gate):
        self.gate = gate

    def addSelection(self, doc, obj_name, sub, pnt):
        obj = FreeCAD.getDocument(doc).getObject(obj_name)
        if obj is not None and selection.is_element(sub, self.gate.kind):
            self.gate.on_pick(obj, sub)
