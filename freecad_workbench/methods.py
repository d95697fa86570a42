"""THE declaration of the methods and their parameters, as the C++ core declares
them (cpp_core/include/tessella/methods.h; one source of truth: names, kinds,
units, defaults, ranges, labels, tooltips, property groups and names).

    import freecad_workbench as tessella
    m = tessella.METHODS["guide_line_scaling"]
    [p.name for p in m]                 # its parameters, own first, then the shared ones
    p = m.params["rod_length"]
    p.type, p.unit, p.default, p.minimum, p.maximum, p.label, p.doc, p.property

The console API, the Panelization properties, make_panelization, the task panel
and the preferences page all derive from these.
"""

from dataclasses import dataclass, field

from . import core

#: FreeCAD property type of each parameter kind (units: App::PropertyLength for
#: "mm", App::PropertyAngle for "deg").
PROPERTY_TYPES = {
    "bool": "App::PropertyBool",
    "int": "App::PropertyInteger",
    "choice": "App::PropertyEnumeration",
    "int_list": "App::PropertyIntegerList",
    "curves": "App::PropertyLinkSubList",
    "uv_curves": "App::PropertyLinkSubList",
}


@dataclass(frozen=True)
class Param:
    """One parameter of a method (see the module docstring)."""

    name: str  # console keyword
    type: str  # "float", "int", "bool", "choice", "int_list", "curves", "uv_curves"
    unit: str  # "mm", "deg" or "" (a plain number or a count)
    default: object
    minimum: float
    maximum: float
    label: str
    doc: str
    group: str  # property group of the Panelization
    property: str  # the Panelization property that stores it
    choices: tuple = ()
    shared: bool = False  # a pipeline parameter every method accepts
    #: parameters this one replaces when not at its default (a document leaves them out)
    replaces: tuple = ()

    @property
    def property_type(self):
        """The FreeCAD property type that stores this parameter (with its unit)."""
        if self.type == "float":
            return {"mm": "App::PropertyLength", "deg": "App::PropertyAngle"}.get(
                self.unit, "App::PropertyFloat")
        return PROPERTY_TYPES[self.type]


@dataclass(frozen=True)
class Method:
    """One method: its name, label, one-line doc and parameters (name -> Param)."""

    name: str
    label: str
    doc: str
    params: dict = field(default_factory=dict)

    def __iter__(self):
        return iter(self.params.values())

    def __getitem__(self, name):
        return self.params[name]

    def __len__(self):
        return len(self.params)


def _load():
    methods = {}
    for m in core.method_declarations():
        params = {}
        for p in m["params"]:
            d = dict(p)
            d["choices"] = tuple(d.get("choices", ()))
            d["replaces"] = tuple(d.get("replaces", ()))
            params[d["name"]] = Param(**d)
        methods[m["name"]] = Method(m["name"], m["label"], m["doc"], params)
    return methods


#: Every method by name, in the order the user sees them.
METHODS = _load()


def parameters_by_property():
    """{property name: [Param of every method that stores it there]}, in
    declaration order: one document property may serve several methods."""
    out = {}
    for m in METHODS.values():
        for p in m:
            out.setdefault(p.property, []).append(p)
    return out


def methods_using(prop):
    """The methods that read the Panelization property `prop`."""
    return tuple(m.name for m in METHODS.values() if any(p.property == prop for p in m))


def _fmt(x):
    if isinstance(x, float):
        return f"{x:g}"
    if isinstance(x, (list, tuple)):
        return "none" if not x else ", ".join(map(str, x))
    return str(x)


def markdown_tables():
    """The parameter reference (docs/parameters.md), generated from the declarations."""
    lines = ["# Method parameters", "",
             "Generated from the C++ declarations (`cpp_core/src/methods/*/declarations.cpp`)",
             "by `freecad_workbench.methods.markdown_tables()`; a test keeps it current.",
             "Every parameter is a keyword of `tessella.panelize` and a property of the",
             "`Panelization` object.", ""]
    for m in METHODS.values():
        lines += [f"## `{m.name}`: {m.label}", "", m.doc[0].upper() + m.doc[1:] + ".", "",
                  "| keyword | property | kind | unit | default | range | meaning |",
                  "|---|---|---|---|---|---|---|"]
        for p in m:
            rng = f"{_fmt(p.minimum)} .. {_fmt(p.maximum)}" if p.type in ("float", "int") else (
                " / ".join(p.choices) if p.choices else f"{_fmt(p.minimum)} .. {_fmt(p.maximum)} items")
            lines.append(f"| `{p.name}` | `{p.property}` | {p.type} | {p.unit or '-'} | "
                         f"{_fmt(p.default)} | {rng} | {p.doc} |")
        lines.append("")
    return "\n".join(lines)
