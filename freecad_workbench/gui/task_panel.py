"""Task panel of Tessella_Panelize and of editing a Panelization (double-click).

Values are shown with units; every change re-runs the panelization after a
short pause (debounced) and draws its rods as a preview in the 3D view, with a
summary line. Nothing touches the document before OK: OK creates the objects
(one undo step, echoed as Python) or, when editing, writes the changed
properties in one transaction; Cancel leaves the document exactly as it was.
"""

import time

import FreeCAD
import FreeCADGui as Gui

from .. import api, selection

#: Debounce between the last change and the preview.
PREVIEW_DELAY_MS = 250
#: Above this many estimated panels a coarse preview (about COARSE_PANELS) comes first.
COARSE_ABOVE = 3000
COARSE_PANELS = 800
#: Samples per panel edge for the preview's deviation figure (the object uses 8).
PREVIEW_SAMPLES = 3

_active = None


def active():
    """The open Tessella task panel, if any (tests press its buttons)."""
    return _active


def _quantity_box(unit, value, minimum=0.0, maximum=1e9):
    """A FreeCAD quantity spin box (parses '1.5 m'); a plain spin box as fallback."""
    from PySide import QtGui

    try:
        box = Gui.UiLoader().createWidget("Gui::QuantitySpinBox")
        box.setProperty("unit", unit)
        box.setProperty("minimum", minimum)
        box.setProperty("maximum", maximum)
        box.setProperty("rawValue", float(value))
        return box
    except Exception:
        box = QtGui.QDoubleSpinBox()
        box.setRange(minimum, maximum)
        box.setDecimals(3)
        box.setSuffix(" " + unit)
        box.setValue(float(value))
        return box


def _value(box):
    raw = box.property("rawValue")
    return float(raw) if raw is not None else float(box.value())


class PanelizationTaskPanel:
    """source=(object, 'FaceN') to create; obj=<Panelization> to edit."""

    def __init__(self, source=None, obj=None, size=None):
        from PySide import QtCore, QtGui

        global _active
        self.source, self.obj = source, obj
        self.preview_node = None
        self.last_result = None
        self.last_error = None
        self.preview_count = 0  # previews drawn (tests and the benchmark read it)
        self.preview_seconds = 0.0
        p = self._initial(size)

        self.form = QtGui.QWidget()
        self.form.setWindowTitle("Tessella: edit panelization" if obj else "Tessella: panelize")
        form = QtGui.QFormLayout(self.form)
        self.source_label = QtGui.QLabel(self._source_text())
        self.pick = QtGui.QPushButton("Pick face...")
        self.pick.setCheckable(True)
        self.pick.setToolTip("Then click a face in the 3D view (only faces can be selected)")
        self.pick.toggled.connect(self.set_picking)
        row = QtGui.QHBoxLayout()
        row.addWidget(self.source_label, 1)
        row.addWidget(self.pick)
        form.addRow("Face", row)
        self.picked = None  # a new source face chosen in the panel (edit mode)
        self._gate = self._observer = None
        self.method = QtGui.QComboBox()
        self.method.addItems(list(api.METHODS))
        self.method.setCurrentIndex(list(api.METHODS).index(p["method"]))
        form.addRow("Method", self.method)
        # The chosen method's own parameters, rebuilt when the method changes.
        self.method_box = QtGui.QWidget()
        self.method_form = QtGui.QFormLayout(self.method_box)
        self.method_form.setContentsMargins(0, 0, 0, 0)
        form.addRow(self.method_box)
        self.widgets = {}
        self.values = dict(p["values"])  # last value of every parameter seen
        self.guides = self._initial_guides()
        self.guides_changed = False
        self._build_method_rows()
        self.method.currentIndexChanged.connect(self._method_changed)
        self.sliver = self._make_widget("sliver_fraction", p["sliver_fraction"])
        form.addRow("Sliver fraction", self.sliver)
        self.min_angle = self._make_widget("min_angle", p["min_angle"])
        form.addRow("Min angle", self.min_angle)
        self.max_panels = self._make_widget("max_panels", p["max_panels"])
        form.addRow("Max panels", self.max_panels)
        self.live = QtGui.QCheckBox("Live preview")
        self.live.setChecked(True)
        form.addRow(self.live)
        self.summary = QtGui.QLabel("")
        self.summary.setWordWrap(True)
        form.addRow(self.summary)

        self.timer = QtCore.QTimer()
        self.timer.setSingleShot(True)
        self.timer.setInterval(PREVIEW_DELAY_MS)
        self.timer.timeout.connect(self.update_preview)
        for signal in (self.method.currentIndexChanged, self.live.toggled):
            signal.connect(self.schedule_preview)
        for box in (self.sliver, self.min_angle, self.max_panels):
            self._connect(box)
        _active = self
        self.schedule_preview()

    # ----------------------------------------------------------------- values
    def _initial(self, size):
        """Values to show: the object's properties (edit) or the defaults (new)."""
        from ..make import _PARAM_TO_PROPERTY

        values = {}
        if self.obj is not None:
            o = self.obj
            for name, prop in _PARAM_TO_PROPERTY.items():
                if hasattr(o, prop):
                    v = getattr(o, prop)
                    values[name] = float(v.Value) if hasattr(v, "Value") else v
            return {"method": o.Method, "values": values,
                    "sliver_fraction": float(o.SliverFraction),
                    "min_angle": float(o.MinAngle.Value), "max_panels": int(o.MaxPanels)}
        from . import preferences

        prefs = preferences.defaults()
        values["size"] = size or 1000.0
        if prefs["max_deviation"] > 0:
            values["max_deviation"] = prefs["max_deviation"]
        return {"method": prefs["method"], "values": values,
                "sliver_fraction": prefs["sliver_fraction"], "min_angle": prefs["min_angle"],
                "max_panels": prefs["max_panels"]}

    # ------------------------------------------------------ parameter widgets
    def _make_widget(self, name, value):
        from PySide import QtGui

        label, unit = api.PARAM_INFO.get(name, (name, ""))
        if unit is bool:
            box = QtGui.QCheckBox()
            box.setChecked(bool(value))
            return box
        if unit is None:  # a count
            box = QtGui.QSpinBox()
            # counts where 0 means "off" or "derive it" start at 0
            zero_ok = name.endswith("_count") or name in ("max_refinements", "boundary_divisions")
            box.setRange(0 if zero_ok else 1, 100000000)
            box.setValue(int(value))
            return box
        if unit == "":
            box = QtGui.QDoubleSpinBox()
            box.setRange(0.0, 1e9)
            box.setDecimals(6 if name == "tolerance" else 4)
            box.setSingleStep(0.05)
            box.setValue(float(value))
            return box
        return _quantity_box(unit, value, 0.0, 180.0 if unit == "deg" else 1e9)

    def _connect(self, box):
        sig = getattr(box, "valueChanged", None) or getattr(box, "toggled", None)
        if sig is not None:
            sig.connect(self.schedule_preview)

    def _default_of(self, method, name):
        """The core's default for a parameter (from the method's params struct)."""
        struct = api.METHODS[method].make_params()
        return getattr(struct, name, 0)

    def _build_method_rows(self):
        """One row per numeric or yes/no parameter of the chosen method that the
        Panelization stores (the common ones have their own rows below)."""
        from ..make import _PARAM_TO_PROPERTY

        while self.method_form.rowCount():
            self.method_form.removeRow(0)
        self.widgets = {}
        method = self.method.currentText()
        common = ("sliver_fraction", "min_angle", "max_panels", "trim_deflection", "samples")
        self._add_guides_row(method)
        for name, kind in api.METHODS[method].params.items():
            if kind not in (int, float, bool) or name in common or name not in _PARAM_TO_PROPERTY:
                continue  # e.g. guide curves: picked, not typed
            value = self.values.get(name, self._default_of(method, name))
            box = self._make_widget(name, value)
            self._connect(box)
            self.widgets[name] = box
            self.method_form.addRow(api.PARAM_INFO.get(name, (name, ""))[0], box)

    # ------------------------------------------------------------ guide edges
    def guides_needed(self, method=None):
        """How many guide edges the method takes (0: none)."""
        method = method or self.method.currentText()
        return api.GUIDE_COUNT.get(method, 0) \
            if "guides" in api.METHODS[method].converters else 0

    def _add_guides_row(self, method):
        from PySide import QtGui

        self.guides_label = self.guides_pick = None
        need = self.guides_needed(method)
        if not need:
            return
        self.guides_label = QtGui.QLabel(self._guides_text())
        self.guides_label.setWordWrap(True)
        pick = QtGui.QPushButton("Pick edges...")
        pick.setCheckable(True)
        pick.setToolTip(f"Then click {need} edge(s) in the 3D view (only edges can be selected)")
        pick.toggled.connect(self.set_picking_guides)
        self.guides_pick = pick
        row = QtGui.QHBoxLayout()
        row.addWidget(self.guides_label, 1)
        row.addWidget(pick)
        self.method_form.addRow("Guides", row)

    def _guides_text(self):
        if not self.guides:
            return "(none: pick)"
        return ", ".join(f"{o.Label}.{s}" if s else o.Label for o, s in self.guides)

    def set_picking_guides(self, on):
        """Pick guide edges in the 3D view through an edges-only selection gate."""
        panel = self

        class EdgeGate:
            def allow(self, doc, obj, sub):
                return selection.is_element(sub, selection.EDGE) and hasattr(obj, "Shape") \
                    and not panel._is_own(obj)

        class Picker:
            def addSelection(self, doc, obj_name, sub, pnt):
                obj = FreeCAD.getDocument(doc).getObject(obj_name)
                if obj is not None and selection.is_element(sub, selection.EDGE):
                    panel.add_guide(obj, sub)

        self._stop_picking()
        self._uncheck(self.pick)
        if on:
            self.guides = []
            self.guides_label.setText(self._guides_text())
            Gui.Selection.clearSelection()
            self._gate, self._observer = EdgeGate(), Picker()
            Gui.Selection.addSelectionGate(self._gate)
            Gui.Selection.addObserver(self._observer)

    def add_guide(self, obj, sub):
        """Append a guide edge; picking ends when the method has all it needs."""
        self.guides.append((obj, sub))
        self.guides_changed = True
        self.guides_label.setText(self._guides_text())
        if len(self.guides) >= self.guides_needed():
            self.guides_pick.setChecked(False)
            Gui.Selection.clearSelection()
        self.schedule_preview()

    def _method_changed(self, *args):
        for name, box in self.widgets.items():
            self.values[name] = self._read(box)
        self._build_method_rows()

    @staticmethod
    def _read(box):
        if hasattr(box, "isChecked") and not hasattr(box, "value"):
            return bool(box.isChecked())
        return _value(box) if box.property("rawValue") is not None or \
            hasattr(box, "decimals") else int(box.value())

    def _initial_guides(self):
        if self.obj is None or "Guides" not in self.obj.PropertiesList:
            return []
        return selection.links_of(self.obj.Guides or [])

    def _source_text(self):
        if self.obj is not None:
            src = self.obj.Source
            subs = [s for s in (src[1] or []) if s] if src else []
            return f"{src[0].Label}.{subs[0]}" if src and src[0] and subs else "(none)"
        return f"{self.source[0].Label}.{self.source[1]}"

    def face_arg(self):
        if self.picked is not None:
            return self.picked
        if self.obj is not None:
            return self.obj.Proxy.source_face(self.obj)[0]
        return self.source

    # --------------------------------------------------------- face picking
    def set_picking(self, on):
        """Pick a face in the 3D view: a selection gate lets only faces through."""
        panel = self

        class FaceGate:
            def allow(self, doc, obj, sub):
                return selection.is_element(sub, selection.FACE) and hasattr(obj, "Shape") \
                    and not panel._is_own(obj)

        class Picker:
            def addSelection(self, doc, obj_name, sub, pnt):
                obj = FreeCAD.getDocument(doc).getObject(obj_name)
                if obj is not None and selection.is_element(sub, selection.FACE):
                    panel.use_face(obj, sub)

        self._stop_picking()
        self._uncheck(getattr(self, "guides_pick", None))
        if on:
            Gui.Selection.clearSelection()
            self._gate, self._observer = FaceGate(), Picker()
            Gui.Selection.addSelectionGate(self._gate)
            Gui.Selection.addObserver(self._observer)

    def _is_own(self, obj):
        """The panelization's own objects cannot be its source."""
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

    def _stop_picking(self):
        if self._gate is not None:
            Gui.Selection.removeSelectionGate()
            self._gate = None
        if self._observer is not None:
            Gui.Selection.removeObserver(self._observer)
            self._observer = None

    def use_face(self, obj, sub):
        """Take (obj, 'FaceN') as the face to panelize and preview it."""
        if self.obj is None:
            self.source = (obj, sub)
        else:
            self.picked = (obj, sub)
        self.source_label.setText(f"{obj.Label}.{sub}")
        self.pick.setChecked(False)  # ends picking
        self.schedule_preview()

    def parameters(self):
        """(method, keyword parameters) as the panel shows them."""
        method = self.method.currentText()
        params = {name: self._read(box) for name, box in self.widgets.items()}
        if method == "iso_grid":
            # Counts replace the size (the core takes one or the other).
            if params.get("u_count") or params.get("v_count"):
                params.pop("size", None)
            else:
                params.pop("u_count", None)
                params.pop("v_count", None)
        if self.guides_needed(method):
            params["guides"] = [(o, s) if s else o for o, s in self.guides]
        params.update(sliver_fraction=float(self.sliver.value()),
                      min_angle=_value(self.min_angle), max_panels=int(self.max_panels.value()))
        for name in list(params):  # only what this method takes
            spec = api.METHODS[method]
            if name not in spec.params and name not in spec.converters \
                    and name not in api.COMMON_PARAMS:
                params.pop(name)
        return method, params

    def widget(self, name):
        """The input of a method parameter (tests set values through it)."""
        return self.widgets[name]

    # ---------------------------------------------------------------- preview
    def schedule_preview(self, *args):
        if self.live.isChecked():
            self.timer.start()
        else:
            self.remove_preview()

    def update_preview(self):
        """Panelize with the shown values and draw the rods; coarse first if large."""
        method, params = self.parameters()
        started = time.perf_counter()
        try:
            face = self.face_arg()
            size = params.get("size")
            if size and "u_count" not in params:
                import math

                area = api.face_to_shape(face).Area
                estimate = area / (size * size)
                if estimate > COARSE_ABOVE:
                    coarse = dict(params, size=math.sqrt(area / COARSE_PANELS), samples=2)
                    self._draw(api.panelize(face, method=method, **coarse), coarse=True)
            result = api.panelize(face, method=method, samples=PREVIEW_SAMPLES, **params)
        except Exception as exc:  # shown in the panel, never raised into the GUI
            self.last_result, self.last_error = None, str(exc)
            self.remove_preview()
            self.summary.setText(f"<span style='color:#b00020'>{exc}</span>")
            return
        self.last_result, self.last_error = result, None
        self._draw(result)
        self.preview_seconds = time.perf_counter() - started

    def _draw(self, result, coarse=False):
        self.remove_preview()
        try:
            from pivy import coin
        except ImportError:
            coin = None
        view = getattr(Gui.ActiveDocument, "ActiveView", None) if Gui.ActiveDocument else None
        if coin is not None and view is not None and hasattr(view, "getSceneGraph"):
            node = coin.SoSeparator()
            node.setName("TessellaPreview")
            color = coin.SoBaseColor()
            from . import preferences

            color.rgb = preferences.defaults()["preview_color"] if not coarse else (0.6, 0.6, 0.6)
            style = coin.SoDrawStyle()
            style.lineWidth = 2
            coords = coin.SoCoordinate3()
            pts = [tuple(map(float, p)) for p in result.vertices]
            coords.point.setValues(0, len(pts), pts)
            lines = coin.SoIndexedLineSet()
            index = []
            for a, b in result.rods:
                index += [int(a), int(b), -1]
            lines.coordIndex.setValues(0, len(index), index)
            for child in (color, style, coords, lines):
                node.addChild(child)
            view.getSceneGraph().addChild(node)
            self.preview_node = node
        s = result.summary
        dev = s["panel_deviation"]["max"] if s["panel_deviation"]["count"] else 0.0
        prefix = "Coarse preview: " if coarse else ""
        self.summary.setText(
            f"{prefix}{s['panel_count']} panels, {s['rod_count']} rods, {s['node_count']} nodes, "
            f"max deviation {dev:.2f} mm, {s['irregular_count']} irregular")
        self.preview_count += 1
        from PySide import QtGui

        QtGui.QApplication.processEvents()

    def remove_preview(self):
        node = self.preview_node
        self.preview_node = None
        if node is None or Gui.ActiveDocument is None:
            return
        view = getattr(Gui.ActiveDocument, "ActiveView", None)
        if view is not None and hasattr(view, "getSceneGraph"):
            graph = view.getSceneGraph()
            if graph.findChild(node) >= 0:
                graph.removeChild(node)

    # ---------------------------------------------------------------- buttons
    def getStandardButtons(self):
        from PySide import QtGui

        return int(QtGui.QDialogButtonBox.Ok | QtGui.QDialogButtonBox.Cancel)

    def accept(self):
        """OK: create (new) or write the changed properties (edit); one undo step."""
        from .common import warn

        self.timer.stop()
        method, params = self.parameters()
        try:
            if self.obj is None:
                self._create(method, params)
            else:
                self._apply(method, params)
        except Exception as exc:
            warn("Tessella: Panelize", f"Panelize failed: {exc}")
            return False  # keep the panel open to fix the values
        self._close()
        return True

    def reject(self):
        self.timer.stop()
        self._close()
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

    def _create(self, method, params):
        obj, sub = self.source

        def ref(o):
            return f"FreeCAD.getDocument({o.Document.Name!r}).getObject({o.Name!r})"

        def literal(key, value):
            if key == "guides":  # document objects: write how to find them
                return "[" + ", ".join(f"({ref(g[0])}, {g[1]!r})" if isinstance(g, tuple)
                                       else ref(g) for g in value) + "]"
            return repr(value)

        args = ", ".join(f"{k}={literal(k, v)}" for k, v in params.items())
        # gui_progress() is None in a headless replay of the recorded macro.
        call = ("tessella.make_panelization("
                f"(FreeCAD.getDocument({obj.Document.Name!r}).getObject({obj.Name!r}), {sub!r}), "
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
            result = api.panelize(self.face_arg(), method=method, progress=progress, **params)
        finally:
            if progress is not None:
                progress.close()
        doc = obj.Document
        doc.openTransaction("Edit panelization")
        try:
            from ..make import _PARAM_TO_PROPERTY

            if self.picked is not None:
                obj.Source = (self.picked[0], [self.picked[1]])
            obj.Method = method
            if method == "iso_grid":  # counts of 0 mean: use the size
                params.setdefault("u_count", 0)
                params.setdefault("v_count", 0)
            for name, value in params.items():
                if name == "guides":
                    obj.Guides = selection.link_sub_list(selection.edge_links(value))
                    continue
                setattr(obj, _PARAM_TO_PROPERTY[name], value)
            obj.Proxy.seed(obj, result)
            doc.recompute()
        except Exception:
            doc.abortTransaction()
            raise
        doc.commitTransaction()
