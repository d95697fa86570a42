"""What every Tessella App proxy shares: adding properties (so old documents
upgrade), reading quantities, JSON-safe persistence, property status bits, and
the hook through which the GUI gives restored objects their view providers.

No GUI imports here, nor anywhere in features/ (tests/python/test_layering.py
checks it): the GUI package sets `view_provider_hook` when it is imported
(freecad_workbench/gui/__init__.py; freecad_workbench/__init__.py imports it
whenever FreeCAD's GUI is up, so documents opened before the workbench was
activated get their view providers too).
"""

import FreeCAD

#: Version of the properties layout; onDocumentRestored upgrades older documents.
#: 2: Samples holds the sample count itself (schema 1 stored 0 for "the core's default").
SCHEMA_VERSION = 2

# Property status bits (App::PropertyType) for addProperty's `attr` argument.
PROP_READONLY = 1
PROP_OUTPUT = 8
READONLY_OUTPUT = PROP_READONLY | PROP_OUTPUT
# The names the feature modules have always used.
_PROP_READONLY = PROP_READONLY
_PROP_OUTPUT = PROP_OUTPUT
_READONLY_OUTPUT = READONLY_OUTPUT

#: Set by the GUI package: callable(view_object, class_name) that attaches the
#: named view provider class to the view object. None without the GUI.
view_provider_hook = None

def value_of(quantity):
    """Float value of a property that may be a Base.Quantity (mm, deg) or a number."""
    return float(getattr(quantity, "Value", quantity))


def add_property(obj, type_name, name, group, doc, default=None, attr=0, enum=None):
    """Add a property only if it is missing (so old documents can be upgraded).

    Returns True when the property was added (and the default applied).
    """
    if name in obj.PropertiesList:
        return False
    obj.addProperty(type_name, name, group, doc, attr)
    if enum is not None:
        setattr(obj, name, list(enum))
    if default is not None:
        setattr(obj, name, default)
    return True


def _upgrade_enumeration(obj, name, values):
    """Give an enumeration saved by an older version the values this one knows."""
    try:
        known = list(obj.getEnumerationsOfProperty(name))
    except Exception:  # pragma: no cover - very old FreeCAD
        return
    if known != values:
        current = getattr(obj, name)
        setattr(obj, name, values)
        if current in values:
            setattr(obj, name, current)


class _StateMixin:
    """JSON-safe persistence for FreeCAD 0.20 on Python 3.11 (both protocols)."""

    def _state(self):
        return {"schema": SCHEMA_VERSION}

    def _restore(self, state):
        self._cache = None
        self._failed = None
        if isinstance(state, dict):
            self.schema = int(state.get("schema", SCHEMA_VERSION))
        else:
            self.schema = SCHEMA_VERSION

    def _ensure_runtime(self):
        for name in ("_cache", "_failed"):
            if not hasattr(self, name):
                setattr(self, name, None)
        if not hasattr(self, "schema"):
            self.schema = SCHEMA_VERSION

    def dumps(self):
        return self._state()

    def loads(self, state):
        self._restore(state)
        return None

    def __getstate__(self):
        return self._state()

    def __setstate__(self, state):
        self._restore(state)



def _attach_view_provider(obj, class_name):
    """Give an object made without the GUI (or by an older version) its view
    provider `class_name`, through view_provider_hook (set by the GUI package)."""
    if not FreeCAD.GuiUp:
        return
    vobj = getattr(obj, "ViewObject", None)
    if vobj is None or getattr(vobj, "Proxy", None) is not None:
        return
    hook = view_provider_hook
    if hook is None:
        FreeCAD.Console.PrintWarning(
            f"Tessella: no view provider for {obj.Label}: the GUI package is not loaded\n")
        return
    try:
        hook(vobj, class_name)
    except Exception as exc:  # a missing icon must not stop a document from opening
        FreeCAD.Console.PrintWarning(f"Tessella: no view provider for {obj.Label}: {exc}\n")
