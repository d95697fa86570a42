"""Task panel of Tessella_Panelize and of editing a Panelization (double-click).

Values are shown with units; every change re-runs the panelization after a
short pause (debounced) and draws its rods as a preview in the 3D view, with a
summary line. Nothing touches the document before OK: OK creates the objects
(one undo step, echoed as Python) or, when editing, writes the changed
properties in one transaction; Cancel leaves the document exactly as it was.

The panel is assembled from three parts: the form (gui/task_form.py: the
widgets, built from task_form.rows_for(method)), picking (gui/picking.py: one
selection gate class for the face and the guide edges) and the preview
(gui/preview.py).
"""

import FreeCADGui as Gui

from .. import api, selection
from . import task_form
from .common import object_ref
from .picking import ElementGate
from .preview import (  # noqa: F401  (the benchmark and tests read them here)
    COARSE_ABOVE,
    COARSE_PANELS,
    PREVIEW_DELAY_MS,
    PREVIEW_SAMPLES,
    Preview,
)

_value = task_form.value  # tests read the widgets through it

_active = None


def active():
    """The open Tessella task panel, if any (tests press its buttons)."""
    return _active


class PanelizationTaskPanel:
    """source=(object, 'FaceN') to create; obj=<Panelization> to edit."""

    def __init__(self, source=None, obj=None, size=None):
        global _active
        self.source, self.obj = source, obj
        self.picked = None  # a new source face chosen in the panel (edit mode)
        self.guides = self._initial_guides()
        self.guides_changed = False
        self._picking = None  # the active ElementGate
        self.preview = None
        initial = task_form.initial_values(obj, size)
        initial["faces"] = self._source_shapes()
        self.form_parts = task_form.ParameterForm(
            "Tessella: edit panelization" if obj else "Tessella: panelize",
            self._source_text(), initial, self._guides_text,
            self.schedule_preview, self.set_picking, self.set_picking_guides)
        f = self.form_parts
        self.form = f.widget
        self.source_label, self.pick, self.method = f.source_label, f.pick, f.method
        self.sliver, self.min_angle, self.max_panels = f.sliver, f.min_angle, f.max_panels
        self.live, self.summary = f.live, f.summary
        self.preview = Preview(self._preview_inputs, self.summary, self.live, f.stop_preview)
        self.timer = self.preview.timer
        _active = self
        self.schedule_preview()

    # ---------------------------------------------------------- form (views)
    @property
    def widgets(self):
        """The inputs of the chosen method's rows, by parameter name."""
        return self.form_parts.widgets

    @property
    def values(self):
        return self.form_parts.values

    @property
    def guides_label(self):
        return self.form_parts.guides_label

    @property
    def guides_pick(self):
        return self.form_parts.guides_pick

    def widget(self, name):
        """The input of a method parameter (tests set values through it)."""
        return self.widgets[name]

    def guides_needed(self, method=None):
        """How many guide edges the method needs (0: none, or optional)."""
        return task_form.guides_needed(method or self.method.currentText())

    def guides_taken(self, method=None):
        """How many guide edges the method takes at most (0: none)."""
        return task_form.guides_taken(method or self.method.currentText())

    def parameters(self):
        """(method, keyword parameters) as the panel shows them."""
        return self.form_parts.parameters(self.guides)

    # -------------------------------------------------------------- sources
    def _initial_guides(self):
        if self.obj is None or "Guides" not in self.obj.PropertiesList:
            return []
        return selection.links_of(self.obj.Guides or [])

    def _guides_text(self):
        if not self.guides:
            return "(none: pick)"
        return ", ".join(f"{o.Label}.{s}" if s else o.Label for o, s in self.guides)

    def _source_text(self):
        if self.obj is not None:
            try:
                return self.obj.Proxy.source_faces(self.obj)[1]
            except (ValueError, TypeError):
                return "(none)"
        if isinstance(self.source, list):  # several faces: [(object, [subs]), ...]
            if len(self.source) > 1:
                count = len(selection.faces_of(self.source))
                return f"{count} faces of {len(self.source)} objects"
            obj, sub = self.source[0]
        else:
            obj, sub = self.source
        if isinstance(sub, (list, tuple)):  # several faces of one object
            return f"{obj.Label} ({len(sub)} faces)" if sub else f"{obj.Label} (all faces)"
        return f"{obj.Label}.{sub}"

    def _source_shapes(self):
        """The source's Part faces (none if they cannot be read: no suggestion then)."""
        try:
            if self.obj is not None:
                return self.obj.Proxy.source_faces(self.obj)[0]
            return selection.faces_of(self.source)
        except (ValueError, TypeError):
            return []

    def face_arg(self):
        if self.picked is not None:
            return self.picked
        if self.obj is not None:
            if self.obj.Proxy.source_faces(self.obj)[2] > 1:
                return self.obj.Proxy.source_links(self.obj)
            return self.obj.Proxy.source_face(self.obj)[0]
        return self.source

    # -------------------------------------------------------------- picking
    def set_picking(self, on):
        """Pick a face in the 3D view: a selection gate lets only faces through."""
        self._stop_picking()
        self._uncheck(self.guides_pick)
        if on:
            self._start_picking(selection.FACE, self.use_face)

    def set_picking_guides(self, on):
        """Pick guide edges in the 3D view through an edges-only selection gate."""
        self._stop_picking()
        self._uncheck(self.pick)
        if on:
            self.guides = []  # picked anew (for optional guides: none, if none is picked)
            self.guides_changed = True
            self.form_parts.show_guides()
            self._start_picking(selection.EDGE, self.add_guide)

    def _start_picking(self, kind, on_pick):
        self._picking = ElementGate(kind, on_pick, exclude=self._is_own)
        self._picking.start()

    def _stop_picking(self):
        if self._picking is not None:
            self._picking.stop()
            self._picking = None

    def _is_own(self, obj):
        """The panelization's own objects cannot be its source or guides."""
        if self.obj is None:
            return False
        return obj == self.obj or getattr(obj, "Base", None) == self.obj

    @staticmethod
    def _uncheck(button):
        """Release the other pick button without running its handler."""
        if button is not None and button.isChecked():
            button.blockSignals(True)
            button.setChecked(False)
            button.blockSignals(False)

    def use_face(self, obj, sub):
        """Take (obj, 'FaceN') as the face to panelize and preview it."""
        if self.obj is None:
            self.source = (obj, sub)
        else:
            self.picked = (obj, sub)
        self.source_label.setText(f"{obj.Label}.{sub}")
        self.pick.setChecked(False)  # ends picking
        self.schedule_preview()

    def add_guide(self, obj, sub):
        """Append a guide edge; picking ends when the method has all it needs."""
        self.guides.append((obj, sub))
        self.guides_changed = True
        self.form_parts.show_guides()
        if len(self.guides) >= self.guides_taken():
            self.guides_pick.setChecked(False)
            Gui.Selection.clearSelection()
        self.schedule_preview()

    # -------------------------------------------------------------- preview
    def _preview_inputs(self):
        method, params = self.parameters()
        need, take = self.guides_needed(method), self.guides_taken(method)
        picked = len(params.get("guides") or [])
        if need and picked < need:
            what = "one guide edge" if need == 1 else f"{need} guide edges"
            raise ValueError(f"Pick {what} (Pick edges…): {method} grows its panels from "
                             f"{'it' if need == 1 else 'them'}")
        if not need and 0 < picked < take:  # optional guides, half picked
            raise ValueError(f"Pick {take} guide edges or none (Pick edges…): {method} takes "
                             f"them as its generators")
        return self.face_arg(), method, params

    def schedule_preview(self, *args):
        if self.preview is not None:  # (not while the form is being built)
            self.preview.schedule()

    def update_preview(self):
        """Panelize with the shown values and draw the rods; coarse first if large."""
        self.preview.update()

    def remove_preview(self):
        self.preview.remove()

    @property
    def preview_node(self):
        return self.preview.node

    @property
    def preview_count(self):
        """Previews drawn (tests and the benchmark read it)."""
        return self.preview.count

    @property
    def preview_seconds(self):
        return self.preview.seconds

    @property
    def last_result(self):
        return self.preview.last_result

    @property
    def last_error(self):
        return self.preview.last_error

    # ---------------------------------------------------------------- buttons
    def getStandardButtons(self):
        from PySide import QtGui

        return int(QtGui.QDialogButtonBox.Ok | QtGui.QDialogButtonBox.Cancel)

    def accept(self):
        """OK: create (new) or write the changed properties (edit); one undo step."""
        from .common import warn

        self.timer.stop()
        self.preview.cancel()  # OK computes the result itself
        method, params = self.parameters()
        try:
            if self.obj is None:
                self._create(method, params)
            else:
                self._apply(method, params)
        except Exception as exc:
            if isinstance(exc, api.Cancelled) or "cancelled by the user" in str(exc):
                # Stopped in the progress dialog: nothing failed, nothing was made.
                self.summary.setText("Cancelled: nothing was created or changed.")
                return False
            warn("Tessella: Panelize", f"Panelize failed: {exc}")
            return False  # keep the panel open to fix the values
        self._close()
        return True

    def reject(self):
        self.timer.stop()
        self.preview.cancel()
        self._close()
        self._restore_selection()
        return True

    def _close(self):
        global _active
        self._stop_picking()
        self.remove_preview()
        if _active is self:
            _active = None
        Gui.Control.closeDialog()
        if self.obj is not None and Gui.ActiveDocument is not None:
            Gui.ActiveDocument.resetEdit()

    def _restore_selection(self):
        """Cancel of a new panelization: the face(s) selected again, as before the
        command (the panel cleared the selection under its preview)."""
        if self.obj is not None or not self.source:
            return
        links = self.source if isinstance(self.source, list) else [self.source]
        try:
            for obj, sub in links:
                for name in (sub if isinstance(sub, (list, tuple)) else [sub]) or [""]:
                    Gui.Selection.addSelection(obj.Document.Name, obj.Name, name)
        except Exception:  # noqa: BLE001  (the object may be gone: nothing to select)
            pass

    def _create(self, method, params):
        links = self.source if isinstance(self.source, list) else [self.source]
        source = ", ".join(f"({object_ref(obj)}, {sub!r})" for obj, sub in links)
        if isinstance(self.source, list):
            source = f"[{source}]"

        def literal(key, value):
            if key == "guides":  # document objects: write how to find them
                return "[" + ", ".join(f"({object_ref(g[0])}, {g[1]!r})" if isinstance(g, tuple)
                                       else object_ref(g) for g in value) + "]"
            return repr(value)

        args = ", ".join(f"{k}={literal(k, v)}" for k, v in params.items())
        # gui_progress() is None in a headless replay of the recorded macro.
        call = ("tessella.make_panelization("
                f"{source}, "
                f"method={method!r}, {args}, progress=tessella.gui_progress())")
        Gui.doCommand("import freecad_workbench as tessella")
        Gui.doCommand(call)
        Gui.Selection.clearSelection()

    def _apply(self, method, params):
        from ..progress import gui_progress

        obj = self.obj
        # Computed once with a cancellable progress dialog; the recompute reuses it.
        progress = gui_progress("Tessella: panelize")
        try:
            result = api.panelize_source(self.face_arg(), method=method, progress=progress,
                                         **params)
        finally:
            if progress is not None:
                progress.close()
        doc = obj.Document
        doc.openTransaction("Edit panelization")
        try:
            # The changes go through Gui.doCommand, as the first OK's
            # make_panelization does: the Python console shows them and a
            # recorded macro replays them (the replay recomputes for itself).
            ref = object_ref(obj)
            lines = []
            if self.picked is not None:
                lines.append(f"{ref}.Source = ({object_ref(self.picked[0])}, "
                             f"[{self.picked[1]!r}])")
                lines.append(f"{ref}.MoreSources = []")  # the picked face alone
            lines.append(f"{ref}.Method = {method!r}")
            if method == "iso_grid":  # counts of 0 mean: use the size
                params.setdefault("u_count", 0)
                params.setdefault("v_count", 0)
            for name, value in params.items():
                if name == "guides":
                    links = selection.link_sub_list(selection.edge_links(value))
                    items = ", ".join(f"({object_ref(o)}, {list(subs)!r})" for o, subs in links)
                    lines.append(f"{ref}.Guides = [{items}]")
                    continue
                lines.append(f"{ref}.{task_form.property_of(name)} = {value!r}")
            if "guides" not in params and self.guides_taken(method) and self.guides_changed:
                lines.append(f"{ref}.Guides = []")  # optional guides picked anew: none
            for line in lines:
                Gui.doCommand(line)
            obj.Proxy.seed(obj, result)  # the result computed above, not again
            Gui.doCommand(f"FreeCAD.getDocument({doc.Name!r}).recompute()")
        except Exception:
            doc.abortTransaction()
            raise
        doc.commitTransaction()
