"""The form of the Panelization task panel: which parameter rows a method shows
and the widgets of those rows.

`rows_for(method)` is the one place that says which parameters a method shows
and how (label, unit, kind, the Panelization property that stores it, a
tooltip, the range): all of it comes from the method declarations
(freecad_workbench.methods, declared in C++).

`ParameterForm` builds the widgets (face row, method choice, the method's rows
rebuilt when the method changes, a Guides row for the guide-line methods, the
common rows, live preview switch and summary) and reads the values back.
"""

from dataclasses import dataclass

import FreeCADGui as Gui

from .. import api

#: Parameters every method shows in fixed rows below the method's own rows.
COMMON = ("sliver_fraction", "min_angle", "max_panels")


@dataclass(frozen=True)
class ParamRow:
    """How one parameter is shown in the task panel."""

    name: str  # keyword of api.panelize / make_panelization
    label: str
    unit: str  # "mm", "deg" or "" (a plain number or count)
    kind: str  # "bool", "count", "number", "quantity", "choice", "int_list" or "linked"
    prop: str  # the Panelization property that stores it
    tooltip: str
    minimum: float = 0.0
    maximum: float = 1e9
    decimals: int = 4
    choices: tuple = ()


def property_of(name):
    """The Panelization property storing a make_panelization keyword (or None)."""
    from ..make import _param_to_property

    return _param_to_property().get(name)


_KINDS = {"bool": "bool", "int": "count", "choice": "choice", "int_list": "int_list",
          "uv_curves": "linked"}


def _describe(p):
    """The row of declared parameter p."""
    kind = _KINDS.get(p.type) or ("number" if p.unit == "" else "quantity")
    tooltip = f"{p.doc} (the Panelization's {p.property} property)"
    decimals = 0 if kind in ("bool", "count") else (6 if p.maximum <= 1.0 else 4)
    return ParamRow(p.name, p.label, p.unit, kind, p.property, tooltip, p.minimum, p.maximum,
                    decimals, tuple(p.choices))


def rows_for(method):
    """The rows of a method's parameters, in declaration order: every declared
    parameter but the common ones (their own rows) and the guide curves (picked)."""
    return [_describe(p) for p in api.METHODS[method]
            if p.name not in COMMON and p.type != "curves"]


def common_rows():
    """The rows every method shows (sliver fraction, min angle, max panels)."""
    shared = next(iter(api.METHODS.values())).params
    return [_describe(shared[name]) for name in COMMON]


def planarize_rows():
    """The rows of the planarize step (any method; one face's panels), from
    planarization.OPTIONS."""
    from ..planarization import OPTIONS

    rows = []
    for name, (prop, kind, _default, unit, label, doc) in OPTIONS.items():
        rows.append(ParamRow(name, label, unit, "bool" if kind == "bool" else "quantity", prop,
                             f"{doc} (the Panelization's {prop} property)", 1e-6, 1e6,
                             0 if kind == "bool" else 3))
    return rows


def guides_needed(method):
    """How many guide edges the method needs (0: none, or optional)."""
    return api.GUIDE_COUNT.get(method, 0)


def guides_taken(method):
    """How many guide edges the method takes at most (0: it takes none):
    chebyshev_net needs none and takes two."""
    params = api.METHODS[method].params
    return int(params["guides"].maximum) if "guides" in params else 0


def default_of(method, name):
    """The core's default for a parameter (from the method declarations)."""
    return api.METHODS[method].params[name].default


#: Parameters whose declared default (0) means "the user must choose": the
#: form suggests a working value instead (suggested_value) so no method opens
#: with an error.
SUGGESTED = ("rod_length", "max_deviation")


def largest_curvature(faces, samples=9):
    """The largest principal curvature (1/mm) on a grid of samples of each face."""
    k = 0.0
    for face in faces or []:
        try:
            u0, u1, v0, v1 = face.ParameterRange
            for i in range(samples):
                for j in range(samples):
                    u = u0 + (u1 - u0) * (i + 0.5) / samples
                    v = v0 + (v1 - v0) * (j + 0.5) / samples
                    k = max(k, max(abs(c) for c in face.curvatureAt(u, v)))
        except Exception:  # noqa: BLE001  (a face OCCT cannot sample: no suggestion from it)
            continue
    return k


def _nice(x):
    """x rounded to 1, 2 or 5 times a power of ten (at most x)."""
    import math

    if not x > 0:
        return 0.0
    e = 10.0 ** math.floor(math.log10(x))
    for m in (5, 2, 1):
        if m * e <= x:
            return m * e
    return e


def suggested_value(name, size, curvature):
    """A working value for a SUGGESTED parameter: the rod length of the guide-line
    methods is the panel size; a deviation bound is the sagitta of a panel of
    that size on the most curved part of the face (k s^2 / 8), at least
    1/1000 of the size."""
    size = float(size or 1000.0)
    if name == "rod_length":
        return size
    if name == "max_deviation":
        return _nice(max(curvature * size * size / 8.0, 1e-3 * size))
    raise KeyError(name)


def initial_values(obj=None, size=None):
    """Values to show: the object's properties (edit) or the defaults (new)."""
    from ..make import _param_to_property

    values = {}
    if obj is not None:
        for name, prop in _param_to_property().items():
            if hasattr(obj, prop) and not isinstance(getattr(obj, prop), (list, tuple)):
                v = getattr(obj, prop)
                values[name] = float(v.Value) if hasattr(v, "Value") else v
            elif name == "source_loops" and hasattr(obj, prop):
                values[name] = [int(k) for k in getattr(obj, prop)]
        out = {"method": obj.Method, "values": values, "obj": obj,
               "sliver_fraction": float(obj.SliverFraction),
               "min_angle": float(obj.MinAngle.Value), "max_panels": int(obj.MaxPanels)}
        for r in planarize_rows():
            v = getattr(obj, r.prop, None)
            if v is not None:
                out[r.name] = float(v.Value) if hasattr(v, "Value") else bool(v)
        return out
    from . import preferences

    prefs = preferences.defaults()
    values["size"] = size or 1000.0
    if prefs["max_deviation"] > 0:
        values["max_deviation"] = prefs["max_deviation"]
    return {"method": prefs["method"], "values": values,
            "sliver_fraction": prefs["sliver_fraction"], "min_angle": prefs["min_angle"],
            "max_panels": prefs["max_panels"]}


# ------------------------------------------------------------------ widgets
_UI_LOADER = []


def _release_widget(widget):
    """Takes a widget out of its form and hands it to Python, which deletes it
    (and forgets its wrapper) once the last reference goes."""
    widget.hide()
    widget.setParent(None)


def _ui_loader():
    """One Gui.UiLoader for the session: a throwaway loader, once collected, takes
    the C++ side of the widgets it made with it ("Internal C++ object already
    deleted"), which turned quantity fields into plain spin boxes after a few
    method switches (1.2 m read as 1.2 mm)."""
    if not _UI_LOADER:
        _UI_LOADER.append(Gui.UiLoader())
    return _UI_LOADER[0]


def quantity_box(unit, value, minimum=0.0, maximum=1e9):
    """A FreeCAD quantity spin box (parses '1.5 m', '30 deg'). Only if FreeCAD
    cannot make one at all, a plain spin box, said in the Report view."""
    from PySide import QtGui

    try:
        box = _ui_loader().createWidget("Gui::QuantitySpinBox")
        box.setProperty("unit", unit)
        box.setProperty("minimum", minimum)
        box.setProperty("maximum", maximum)
        box.setProperty("rawValue", float(value))
        return box
    except Exception as e:  # noqa: BLE001  (FreeCAD without its quantity widget)
        FreeCAD.Console.PrintWarning(
            f"Tessella: no quantity field available ({e}); values are in {unit}\n")
        box = QtGui.QDoubleSpinBox()
        box.setRange(minimum, maximum)
        box.setDecimals(3)
        box.setSuffix(" " + unit)
        box.setValue(float(value))
        return box


def value(box):
    """The float value of a quantity or double spin box."""
    raw = box.property("rawValue")
    return float(raw) if raw is not None else float(box.value())


def read(box):
    """The value of any row widget (bool, int, float, a choice or a list of ints)."""
    from PySide import QtGui

    if isinstance(box, QtGui.QCheckBox):
        return bool(box.isChecked())
    if isinstance(box, QtGui.QComboBox):
        return str(box.currentText())
    if isinstance(box, QtGui.QLineEdit):
        return [int(k) for k in box.text().replace(",", " ").split()]
    return value(box) if box.property("rawValue") is not None or \
        hasattr(box, "decimals") else int(box.value())


def make_widget(row, initial):
    """The input widget of one row, showing `initial`."""
    from PySide import QtGui

    if row.kind == "choice":
        box = QtGui.QComboBox()
        box.addItems(list(row.choices))
        if initial in row.choices:
            box.setCurrentIndex(list(row.choices).index(initial))
    elif row.kind == "int_list":
        box = QtGui.QLineEdit(", ".join(str(int(k)) for k in (initial or [])))
        box.setPlaceholderText("e.g. 0, 2 (empty: all)")
    elif row.kind == "bool":
        box = QtGui.QCheckBox()
        box.setChecked(bool(initial))
    elif row.kind == "count":
        box = QtGui.QSpinBox()
        box.setRange(int(row.minimum), int(row.maximum))
        box.setValue(int(initial))
    elif row.kind == "number":
        box = QtGui.QDoubleSpinBox()
        box.setRange(row.minimum, row.maximum)
        box.setDecimals(row.decimals)
        box.setSingleStep(0.05)
        box.setValue(float(initial))
    else:
        box = quantity_box(row.unit, initial, row.minimum, row.maximum)
    box.setToolTip(row.tooltip)
    return box


def on_change(box, slot):
    """Call slot whenever the widget's value changes."""
    sig = (getattr(box, "valueChanged", None) or getattr(box, "toggled", None)
           or getattr(box, "currentIndexChanged", None) or getattr(box, "editingFinished", None))
    if sig is not None:
        sig.connect(slot)


# --------------------------------------------------------------------- form
class ParameterForm:
    """The widgets of the task panel.

    initial: initial_values(); source_text: the face shown; guides_text():
    the guide edges shown; on_change(): any value changed; on_pick_face(on) /
    on_pick_guides(on): a Pick button was toggled.
    """

    def __init__(self, title, source_text, initial, guides_text, on_change_slot,
                 on_pick_face, on_pick_guides):
        from PySide import QtGui

        self._guides_text = guides_text
        self._faces = initial.get("faces")  # for suggested values (largest_curvature)
        self._curvature = None
        self._on_change = on_change_slot
        self._on_pick_guides = on_pick_guides
        self.widget = QtGui.QWidget()
        self.widget.setWindowTitle(title)
        form = QtGui.QFormLayout(self.widget)
        self.source_label = QtGui.QLabel(source_text)
        self.pick = QtGui.QPushButton("Pick face...")
        self.pick.setCheckable(True)
        self.pick.setToolTip("Then click a face in the 3D view (only faces can be selected)")
        self.pick.toggled.connect(on_pick_face)
        row = QtGui.QHBoxLayout()
        row.addWidget(self.source_label, 1)
        row.addWidget(self.pick)
        form.addRow("Face", row)
        self.method = QtGui.QComboBox()
        self.method.addItems(list(api.METHODS))
        self.method.setCurrentIndex(list(api.METHODS).index(initial["method"]))
        form.addRow("Method", self.method)
        # The chosen method's own parameters, rebuilt when the method changes.
        self.method_box = QtGui.QWidget()
        self.method_form = QtGui.QFormLayout(self.method_box)
        self.method_form.setContentsMargins(0, 0, 0, 0)
        form.addRow(self.method_box)
        self.widgets = {}
        self.values = dict(initial["values"])  # last value of every parameter seen
        self._obj = initial.get("obj")  # the edited object (linked curves are listed)
        self.guides_label = self.guides_pick = None
        self.build_method_rows()
        self.method.currentIndexChanged.connect(self._method_changed)
        self.common = {}
        for r in common_rows():
            box = make_widget(r, initial[r.name])
            self.common[r.name] = box
            form.addRow(r.label, box)
        from ..planarization import OPTIONS as PLANARIZE_OPTIONS

        self.planarize = {}
        for r in planarize_rows():
            box = make_widget(r, initial.get(r.name, PLANARIZE_OPTIONS[r.name][2]))
            self.planarize[r.name] = box
            form.addRow(r.label, box)
        self.sliver = self.common["sliver_fraction"]
        self.min_angle = self.common["min_angle"]
        self.max_panels = self.common["max_panels"]
        self.live = QtGui.QCheckBox("Live preview")
        self.live.setChecked(True)
        form.addRow(self.live)
        self.summary = QtGui.QLabel("")
        self.summary.setWordWrap(True)
        form.addRow(self.summary)
        self.stop_preview = QtGui.QPushButton("Stop preview")
        self.stop_preview.setToolTip("Stop the preview being computed (a large one runs in "
                                     "the background; FreeCAD stays usable meanwhile)")
        form.addRow(self.stop_preview)
        for signal in (self.method.currentIndexChanged, self.live.toggled):
            signal.connect(on_change_slot)
        for box in list(self.common.values()) + list(self.planarize.values()):
            on_change(box, on_change_slot)

    def current_method(self):
        return self.method.currentText()

    def build_method_rows(self):
        """One row per parameter of rows_for(the chosen method), after the Guides
        row of a guide-line method."""
        from PySide import QtGui

        # The old fields go to Python first: deleted by the layout in C++
        # only, a new field made at the same address came back as the stale,
        # deleted wrapper (the quantity field silently turned into a plain spin
        # box after a few method switches: 1.2 m read as 1.2 mm).
        for box in self.widgets.values():
            _release_widget(box)
        while self.method_form.rowCount():
            self.method_form.removeRow(0)
        self.widgets = {}
        method = self.current_method()
        self._add_guides_row(method)
        for r in rows_for(method):
            if r.kind == "linked":  # edges linked in the property editor: listed
                linked = len(getattr(self._obj, r.prop, None) or []) if self._obj else 0
                note = QtGui.QLabel(f"{linked} linked edge(s): set {r.prop} in the "
                                    "property editor")
                note.setToolTip(r.tooltip)
                self.method_form.addRow(r.label, note)
                continue
            initial = self.values.get(r.name, default_of(method, r.name))
            if r.name in SUGGESTED and not initial:
                initial = suggested_value(r.name, self.values.get("size"), self.curvature())
                self.values[r.name] = initial
            box = make_widget(r, initial)
            on_change(box, self._on_change)
            self.widgets[r.name] = box
            self.method_form.addRow(r.label, box)

    def _add_guides_row(self, method):
        from PySide import QtGui

        self.guides_label = self.guides_pick = None
        need, take = guides_needed(method), guides_taken(method)
        if not take:
            return
        self.guides_label = QtGui.QLabel(self._guides_text())
        self.guides_label.setWordWrap(True)
        pick = QtGui.QPushButton("Pick edges...")
        pick.setCheckable(True)
        if need:
            pick.setToolTip(f"Then click {need} edge(s) in the 3D view (only edges can be selected)")
        else:  # optional (chebyshev_net's generators): picking anew clears them
            pick.setToolTip(f"Then click {take} edges in the 3D view (only edges can be "
                            "selected); press again and pick none to clear them")
        pick.toggled.connect(self._on_pick_guides)
        self.guides_pick = pick
        row = QtGui.QHBoxLayout()
        row.addWidget(self.guides_label, 1)
        row.addWidget(pick)
        self.method_form.addRow("Guides" if need else "Guides (optional)", row)

    def curvature(self):
        """The source faces' largest curvature, sampled once."""
        if self._curvature is None:
            self._curvature = largest_curvature(self._faces)
        return self._curvature

    def show_guides(self):
        if self.guides_label is not None:
            self.guides_label.setText(self._guides_text())

    def _method_changed(self, *args):
        for name, box in self.widgets.items():
            self.values[name] = read(box)
        self.build_method_rows()

    def parameters(self, guides):
        """(method, keyword parameters) as the form shows them; guides: the picked
        [(object, 'EdgeN' or '')]."""
        method = self.current_method()
        params = {name: read(box) for name, box in self.widgets.items()}
        if method == "iso_grid":
            # Counts replace the size (the core takes one or the other).
            if params.get("u_count") or params.get("v_count"):
                params.pop("size", None)
            else:
                params.pop("u_count", None)
                params.pop("v_count", None)
        if guides_needed(method) or (guides_taken(method) and guides):  # optional: if picked
            params["guides"] = [(o, s) if s else o for o, s in guides]
        params.update(sliver_fraction=float(self.sliver.value()),
                      min_angle=value(self.min_angle), max_panels=int(self.max_panels.value()))
        for name in list(params):  # only what this method takes
            if name not in api.METHODS[method].params:
                params.pop(name)
        # The planarize step (any method): on or off, and its settings when on.
        step = {name: read(box) for name, box in self.planarize.items()}
        params.update(step if step.get("planarize") else {"planarize": False})
        return method, params
