"""App proxies of the parametric Panelization feature and its three children.

Document layout (one Panelization = four objects):

    Panelization  (App::FeaturePython, proxy `Panelization`)
        Source -> (face owner, ["FaceN"]), Method, Size, UCount, VCount, ...
        read-only summary: PanelCount, RodCount, NodeCount, ...
    Panels        (Part::FeaturePython, proxy `PanelizationPart`, Role "Panels")
    Rods          (Part::FeaturePython, proxy `PanelizationPart`, Role "Rods")
    Nodes         (Part::FeaturePython, proxy `PanelizationPart`, Role "Nodes")

Each child links to its parent (`Base`), so FreeCAD's dependency graph always
recomputes the parent first. The parent keeps the panelization result in a cache
on its proxy; a child's execute takes its shape from that cache, recomputing it
on demand (e.g. after a document was reopened and only a child is touched).
The three shapes are all built inside the parent's execute, so a failure leaves
every child as it was (never a half-built set).
The cache is keyed by the inputs (the face's BRep and the parameters); the
panel types are cached on it per tolerance, and each child remembers which
result, ID format (and tolerance) its outputs came from, so a recompute that
changes none of them (a bare touch) rebuilds nothing.

FROZEN: the module path `freecad_workbench.features.panelization` and the class
names `Panelization` and `PanelizationPart` are stored in every saved .FCStd.
"""

import hashlib
import itertools
import json

import FreeCAD

from .. import selection

# The shared helpers live in features/base.py; they stay importable from here
# (other code imports them from this module).
from .base import (  # noqa: F401
    _PROP_OUTPUT,
    _PROP_READONLY,
    _READONLY_OUTPUT,
    SCHEMA_VERSION,
    _attach_view_provider,
    _StateMixin,
    _upgrade_enumeration,
    add_property,
    value_of,
)
from .user_errors import reports_user_errors


def _declared_properties():
    """{property: [Param, ...]} of every method parameter (freecad_workbench.methods)."""
    from ..methods import parameters_by_property

    return parameters_by_property()


def __getattr__(name):
    """METHOD_PROPERTIES / BD_PROPERTIES, derived from the declarations on first use."""
    if name == "METHOD_PROPERTIES":
        return _method_properties()
    if name == "BD_PROPERTIES":
        return tuple(n for n, m in _method_properties().items() if m == ("boundary_driven",))
    raise AttributeError(name)


def _methods_of(params):
    from ..methods import METHODS

    return [m.name for m in METHODS.values() if any(p is q for p in params for q in m)]


def _method_properties():
    """Method-specific properties and the methods that use them (the editor
    hides the others); the shared pipeline properties are always shown."""
    from ..methods import methods_using

    return {prop: methods_using(prop) for prop, params in _declared_properties().items()
            if not all(p.shared for p in params)}


def _defaults_by_method():
    """{property: {method: declared default}} of the properties that methods
    share with different defaults (Quadrangulate: boundary_driven True,
    curvature_lines False)."""
    out = {}
    for prop, params in _declared_properties().items():
        if params[0].type in ("curves", "uv_curves", "int_list"):
            continue
        defaults = {}
        for p in params:
            for m in _methods_of([p]):
                defaults[m] = p.default
        if len(set(map(repr, defaults.values()))) > 1:
            out[prop] = defaults
    return out


def _same_value(raw, default):
    value = value_of(raw) if hasattr(raw, "Value") else raw
    if isinstance(default, float):
        return abs(float(value) - default) <= 1e-12 * max(1.0, abs(default))
    return value == default


#: Roles of the children, in tree order.
ROLES = ("Panels", "Rods", "Nodes")


def _api():
    from .. import api

    return api




def is_panelization(obj):
    return isinstance(getattr(obj, "Proxy", None), Panelization)


def is_panelization_part(obj, role=None):
    proxy = getattr(obj, "Proxy", None)
    if not isinstance(proxy, PanelizationPart):
        return False
    return role is None or getattr(obj, "Role", None) == role


def children_of(parent):
    """The Panels, Rods and Nodes objects of a Panelization, in ROLES order."""
    found = {}
    for o in parent.InList:
        if is_panelization_part(o) and getattr(o, "Base", None) == parent:
            found.setdefault(o.Role, o)
    return [found[r] for r in ROLES if r in found]


class _Cache:
    """A panelization result and what is built from it (not saved): the
    shapes, and the panel types per tolerance (computed on first use).
    `serial` tells results apart: a child whose outputs came from this serial
    (and the same ID format and tolerance) has nothing to redo."""

    _serials = itertools.count(1)

    def __init__(self, signature, result, shapes):
        self.signature = signature
        self.result = result
        self.shapes = shapes
        self.serial = next(self._serials)
        self._types = {}
        self._families = {}

    def panel_types(self, length_tol, angle_tol=0.5):
        """(type index per panel, type count) of the unfolded panels
        (members.panel_types' rule, in the core)."""
        key = (float(length_tol), float(angle_tol))
        if key not in self._types:
            from .. import core

            p = core.PanelTypeParams()
            p.length_tol, p.angle_tol = key
            t = core.mesh_panel_types(self.result._mesh, core.UnfoldParams(), p)
            self._types[key] = (t.type.tolist(), int(t.count))
        return self._types[key]

    def panel_families(self, tolerance, mirror=True):
        """families.PanelFamilies of the 3D panels (families.panel_families)."""
        key = (float(tolerance), bool(mirror))
        if key not in self._families:
            from .. import families

            self._families[key] = families.panel_families(self.result, *key)
        return self._families[key]


def _check_edge_count(obj, param, edges):
    """A user's sentence for a guide link that holds the wrong number of edges
    (typically: the guide's object was deleted)."""
    need = int(param.minimum)
    if need <= len(edges) <= int(param.maximum):
        return
    what = "one edge" if need == 1 else f"{need} edges"
    held = {0: "none"}.get(len(edges), str(len(edges)))
    raise ValueError(f"{obj.Method} needs {what} in {param.property}, it links {held}: "
                     f"edit the Panelization and pick {what} (Pick edges...)")


class Panelization(_StateMixin):
    """Proxy of the parent object: parameters, the face link and the summary."""

    def __init__(self, obj):
        self._restore(None)
        self.setup_properties(obj)
        obj.Proxy = self

    # ---------------------------------------------------------------- properties
    def setup_properties(self, obj):
        """Add every property this version knows (missing ones only)."""
        api = _api()
        add_property(obj, "App::PropertyLinkSub", "Source", "Input",
                     "The face to panelize: (object, ['FaceN']); several faces of the object, "
                     "or the object itself (all its faces), make one envelope")
        add_property(obj, "App::PropertyLinkSubList", "MoreSources", "Input",
                     "Faces of other objects panelized with Source's as one envelope (where "
                     "they touch along edges they do not share, the faces are sewn)")
        methods = list(api.METHODS)
        add_property(obj, "App::PropertyEnumeration", "Method", "Panelization",
                     "; ".join(f"{m.name}: {m.doc}" for m in api.METHODS.values()),
                     default="iso_grid", enum=methods)
        _upgrade_enumeration(obj, "Method", methods)
        # One property per declared parameter (a property several methods share
        # documents each method's meaning); added when missing, so older
        # documents upgrade.
        for prop, params in _declared_properties().items():
            first = params[0]
            docs = {}
            for p in params:
                docs.setdefault(p.doc, []).append(p)
            doc = first.doc if len(docs) == 1 else "; ".join(
                f"{', '.join(_methods_of(group))}: {text}" for text, group in docs.items())
            default = None if first.type in ("curves", "uv_curves", "int_list") else first.default
            add_property(obj, first.property_type, prop, first.group, doc, default=default,
                         enum=list(first.choices) if first.type == "choice" else None)
            if first.type == "choice":
                _upgrade_enumeration(obj, prop, list(first.choices))
        from ..planarization import OPTIONS as PLANARIZE_OPTIONS

        for _name, (prop, kind, default, _unit, _label, doc) in PLANARIZE_OPTIONS.items():
            add_property(obj, "App::PropertyBool" if kind == "bool" else "App::PropertyLength",
                         prop, "Planarize", doc, default=default)
        add_property(obj, "App::PropertyString", "PanelIdFormat", "Output",
                     "Python format of the panel IDs from the panel number, e.g. P-{:04d}",
                     default="P-{:04d}")
        add_property(obj, "App::PropertyString", "RodIdFormat", "Output",
                     "Python format of the rod IDs from the rod number, e.g. R-{:04d}",
                     default="R-{:04d}")
        add_property(obj, "App::PropertyString", "NodeIdFormat", "Output",
                     "Python format of the node IDs from the node number, e.g. N-{:04d}",
                     default="N-{:04d}")
        ro = _READONLY_OUTPUT
        for name, type_name, doc in (
            ("PanelCount", "App::PropertyInteger", "Number of panels"),
            ("RodCount", "App::PropertyInteger", "Number of rods (panel edges)"),
            ("NodeCount", "App::PropertyInteger", "Number of nodes"),
            ("MergedSlivers", "App::PropertyInteger", "Boundary slivers merged into neighbours"),
            ("IrregularPanels", "App::PropertyInteger",
             "Panels that are not quads, too skewed or too small"),
            ("MaxDeviation", "App::PropertyLength", "Largest panel-to-surface distance"),
            ("MeanDeviation", "App::PropertyLength", "Mean of the per-panel deviations"),
            ("QuadShare", "App::PropertyFloat", "Fraction of panels that are quads (0..1)"),
            ("Folds", "App::PropertyInteger",
             "Quads folded into two flat triangles to hold the deviation bound"),
        ):
            add_property(obj, type_name, name, "Summary", doc, attr=ro)
        self._update_editor_modes(obj)

    def _update_editor_modes(self, obj):
        if "Method" not in obj.PropertiesList:
            return
        for name, methods in _method_properties().items():
            if name in obj.PropertiesList:
                obj.setEditorMode(name, 0 if obj.Method in methods else 2)

    def onChanged(self, obj, prop):
        if prop == "Method":
            self._update_editor_modes(obj)
            if "Restore" not in obj.State:
                self._take_method_defaults(obj)

    @staticmethod
    def _take_method_defaults(obj):
        """A property that methods share with different defaults, still at one
        of their defaults (not set by the user), takes the new method's: a
        curvature_lines panelization otherwise recomputed with boundary_driven's
        quadrangulation and smoothing, which the console did not run."""
        method = obj.Method
        for prop, defaults in _defaults_by_method().items():
            if method not in defaults or prop not in obj.PropertiesList:
                continue
            current = getattr(obj, prop)
            if any(_same_value(current, d) for d in defaults.values()) and not _same_value(
                    current, defaults[method]):
                setattr(obj, prop, defaults[method])

    def onDocumentRestored(self, obj):
        self._ensure_runtime()
        if getattr(self, "schema", SCHEMA_VERSION) < 2 and getattr(obj, "Samples", None) == 0:
            obj.Samples = _api().METHODS[obj.Method].params["samples"].default
        self.schema = SCHEMA_VERSION
        self.setup_properties(obj)
        _attach_view_provider(obj, "ViewProviderPanelization")

    # ------------------------------------------------------------ computation
    def source_face(self, obj):
        """((object, 'FaceN'), label) of the linked face; ValueError when unusable."""
        src = obj.Source
        if not src or src[0] is None:
            raise ValueError(f"{obj.Label}: no source face (set Source to a face)")
        owner, sub = selection.face_link(src, context=f"{obj.Label}: Source")
        named = [s for s in (src[1] or []) if s]
        label = f"{owner.Label}.{sub}" if named else owner.Label
        return (owner, sub), label

    def source_links(self, obj):
        """[(object, ['FaceN', ...]), ...]: Source's object first, then
        MoreSources' ([] = all the object's faces)."""
        src = obj.Source
        if not src or src[0] is None:
            raise ValueError(f"{obj.Label}: no source face (set Source to a face)")
        more = list(getattr(obj, "MoreSources", None) or [])
        return selection.face_set_links([src] + more, context=f"{obj.Label}: Source")

    def source_objects(self, obj):
        """The document objects whose faces are panelized (Source's, MoreSources')."""
        found = [obj.Source[0]] if obj.Source and obj.Source[0] is not None else []
        for owner, _subs in getattr(obj, "MoreSources", None) or []:
            if owner is not None and owner not in found:
                found.append(owner)
        return found

    def source_faces(self, obj):
        """(faces, label, count) of the Source and MoreSources: the Part.Faces
        they name (one, the listed ones, or all faces of an object that names none)."""
        links = self.source_links(obj)
        faces = selection.faces_of(links, context=f"{obj.Label}: Source")
        if len(faces) == 1:
            return faces, self.source_face(obj)[1], 1
        if len(links) > 1:
            return faces, f"{len(faces)} faces of {len(links)} objects", len(faces)
        owner, subs = links[0]
        named = f"{len(subs)} faces" if subs else f"all {len(faces)} faces"
        return faces, f"{owner.Label} ({named})", len(faces)

    def parameters(self, obj):
        """(method, keyword parameters for api.panelize) from the properties:
        every declared parameter of the method whose property differs from the
        declared default (at the default the core uses its own, the same value)."""
        method = obj.Method
        params = {}
        for p in _api().METHODS[method]:
            if p.property not in obj.PropertiesList:
                continue
            if p.type in ("curves", "uv_curves"):
                edges = self.linked_edges(obj, p.property)
                if p.type == "curves":
                    _check_edge_count(obj, p, edges)
                if edges or p.type == "curves":
                    params[p.name] = edges
                continue
            raw = getattr(obj, p.property)
            if p.type == "float":
                value = value_of(raw)
            elif p.type == "int":
                value = int(raw)
            elif p.type == "bool":
                value = bool(raw)
            elif p.type == "int_list":
                value = [int(k) for k in raw]
            else:
                value = str(raw)
            if value != p.default:
                params[p.name] = value
        for p in _api().METHODS[method]:  # e.g. iso_grid's counts replace its size
            if p.name in params:
                for other in p.replaces:
                    params.pop(other, None)
        from ..planarization import OPTIONS as PLANARIZE_OPTIONS

        if bool(getattr(obj, "Planarize", False)):  # the step after the method
            for name, (prop, kind, _d, _u, _l, _doc) in PLANARIZE_OPTIONS.items():
                raw = getattr(obj, prop)
                params[name] = bool(raw) if kind == "bool" else value_of(raw)
        return method, params

    def guide_edges(self, obj):
        """The linked guide edges (Part.Edge / Part.Wire shapes, in link order)."""
        edges = self.linked_edges(obj, "Guides")
        if not edges:
            raise ValueError(f"{obj.Label}: {obj.Method} needs guide edges (set Guides)")
        return edges

    def linked_edges(self, obj, prop):
        """The edges (Part.Edge / Part.Wire shapes, in link order) a link-list property names."""
        return selection.edges_of(getattr(obj, prop) or [], context=f"{obj.Label}: {prop}")

    def _signature(self, obj):
        api = _api()
        faces, _label, count = self.source_faces(obj)
        if count == 1:
            face_arg, _ = self.source_face(obj)
            brep = api.face_to_brep(face_arg)
        else:
            import Part

            face_arg = None
            brep = Part.Compound(faces).exportBrepToString()
        method, params = self.parameters(obj)
        digest = hashlib.sha1(brep.encode("utf-8", "surrogateescape")).hexdigest()
        plain = {}
        for k, v in params.items():
            if isinstance(v, list) and v and hasattr(v[0], "exportBrepToString"):
                # shapes (guide edges): keyed by their geometry
                v = [hashlib.sha1(e.exportBrepToString().encode("utf-8", "surrogateescape"))
                     .hexdigest() for e in v]
            plain[k] = v
        key = json.dumps([method, sorted(plain.items()), digest])
        return key, (face_arg, brep), method, params

    def result(self, obj):
        """The cached result for the current face and parameters (built if needed).

        Raises ValueError / RuntimeError with a readable message when the
        panelization cannot be built.
        """
        api = _api()
        signature, (face_arg, brep), method, params = self._signature(obj)
        cache = getattr(self, "_cache", None)
        if cache is not None and cache.signature == signature:
            self._apply_id_formats(obj, cache.result)
            return cache
        failed = getattr(self, "_failed", None)
        if failed is not None and failed[0] == signature:
            raise failed[1](failed[2])
        try:
            # The face serialized once per recompute: the signature's BRep.
            if face_arg is None:  # several faces: one envelope, joined along shared edges
                res = api.panelize_faces_brep(brep, method=method, **params)
            else:
                res = api.panelize_brep(brep, method=method, **params)
            shapes = self._shapes(res)
        except (ValueError, TypeError, RuntimeError) as exc:
            self._cache = None
            self._failed = (signature, type(exc), str(exc))
            raise
        self._failed = None
        self._cache = _Cache(signature, res, shapes)
        self._apply_id_formats(obj, res)
        return self._cache

    @staticmethod
    def _apply_id_formats(obj, res):
        """The document's ID formats on the result: every consumer (Panels, Unfold,
        schedules, exports) reads its IDs from the result (api.format_ids checks them)."""
        api = _api()
        for prop, attr, default in (("PanelIdFormat", "panel_id_format", api.PANEL_ID_FORMAT),
                                    ("RodIdFormat", "rod_id_format", api.ROD_ID_FORMAT),
                                    ("NodeIdFormat", "node_id_format", api.NODE_ID_FORMAT)):
            setattr(res, attr, getattr(obj, prop, "") or default)

    @staticmethod
    def _shapes(res):
        """Panels, Rods and Nodes compounds of a result, checked against its counts.

        The panels are built here from the core's face list (res.panels_shape:
        no BRep text round trip, measured several times cheaper), while the
        core writes the rods' BRep on a second thread (its calls release the
        GIL; each shape is built alone, so the result is the same)."""
        import Part
        from concurrent.futures import ThreadPoolExecutor

        expected = {"Panels": len(res.panels), "Rods": len(res.rods), "Nodes": len(res.nodes)}
        shapes = {}

        def check(role, shape):
            n = len(shape.childShapes()) if not shape.isNull() else 0
            if n != expected[role]:
                raise RuntimeError(f"{role}: the core built {n} shapes for {expected[role]} items")
            shapes[role] = shape

        def read(text):
            shape = Part.Shape()
            shape.importBrepFromString(text, False)
            return shape

        with ThreadPoolExecutor(max_workers=1) as pool:
            rods = pool.submit(res.rods_brep)
            check("Panels", res.panels_shape())
            check("Nodes", read(res.nodes_brep()))
            check("Rods", read(rods.result()))
        return {role: shapes[role] for role in ROLES}

    def seed(self, obj, res):
        """Start from a result computed for exactly these properties (make_panelization
        and the task panel compute once, with progress; the recompute reuses it)."""
        signature = self._signature(obj)[0]
        self._failed = None
        self._cache = _Cache(signature, res, self._shapes(res))

    @reports_user_errors
    def execute(self, obj):
        cache = self.result(obj)
        res = cache.result
        s = res.summary
        dev = res.metrics.get("panel_deviation")
        obj.PanelCount = int(s.get("panel_count", len(res.panels)))
        obj.RodCount = int(s.get("rod_count", len(res.rods)))
        obj.NodeCount = int(s.get("node_count", len(res.nodes)))
        obj.MergedSlivers = int(s.get("merged_slivers", 0))
        obj.IrregularPanels = int(s.get("irregular_count", int(res.irregular.sum())))
        obj.MaxDeviation = float(dev.max()) if dev is not None and len(dev) else 0.0
        obj.MeanDeviation = float(dev.mean()) if dev is not None and len(dev) else 0.0
        obj.QuadShare = float(s.get("quad_share", 0.0))
        if "Folds" in obj.PropertiesList:
            obj.Folds = int(s.get("fold_count", 0))
        for warning in result_warnings(s):
            FreeCAD.Console.PrintWarning(f"Tessella: {obj.Label}: {warning}\n")


def result_warnings(summary):
    """What a user should know of a result that holds (the Report view shows
    them; the batch CLI prints them): where a method that need not tile the
    face (the guide-line methods) leaves it uncovered or overlaps; where two
    faces of a set do not meet node to node along their edge; a set's
    faces boundary_driven's size was too coarse for, meshed finer; a set's
    faces without area, left out."""
    out = []
    if summary.get("coverage_warning"):
        out.append(summary["coverage_warning"])
    if summary.get("join_warning"):
        out.append(summary["join_warning"])
    smaller = summary.get("faces_at_a_smaller_size") or {}
    if smaller:
        listed = ", ".join(f"face {f + 1} at {size:.4g} mm" for f, size in smaller.items())
        out.append(f"the size is too coarse for {len(smaller)} face(s), meshed finer: {listed}")
    skipped = summary.get("skipped_faces") or {}
    if skipped:
        listed = ", ".join(f"face {f + 1} ({why})" for f, why in skipped.items())
        out.append(f"{len(skipped)} face(s) without area left out: {listed}")
    return out

class PanelizationPart(_StateMixin):
    """Proxy of the Panels, Rods and Nodes children (Role tells which)."""

    def __init__(self, obj, parent=None, role="Panels"):
        if role not in ROLES:
            raise ValueError(f"role must be one of {ROLES}, got {role!r}")
        self._restore(None)
        add_property(obj, "App::PropertyString", "Role", "Base",
                     "Panels, Rods or Nodes", default=role, attr=_PROP_READONLY)
        self.setup_properties(obj)
        if parent is not None:
            obj.Base = parent
        obj.Proxy = self

    def setup_properties(self, obj):
        role = obj.Role
        add_property(obj, "App::PropertyLink", "Base", "Base",
                     "The Panelization this part belongs to", attr=_PROP_READONLY)
        ro = _READONLY_OUTPUT
        if role == "Panels":
            add_property(obj, "App::PropertyStringList", "PanelIds", "Data",
                         "Panel IDs, one per sub-shape", attr=ro)
            # Per-panel figures (mm, mm²), for schedules and analysis colours.
            add_property(obj, "App::PropertyFloatList", "Deviation", "Data",
                         "Largest panel-to-surface distance per panel (mm)", attr=ro)
            add_property(obj, "App::PropertyFloatList", "Planarity", "Data",
                         "Diagonal distance / mean edge per panel", attr=ro)
            add_property(obj, "App::PropertyFloatList", "Area", "Data",
                         "Panel area per panel (mm²)", attr=ro)
            add_property(obj, "App::PropertyIntegerList", "Irregular", "Data",
                         "1 where a panel is irregular, else 0", attr=ro)
            add_property(obj, "App::PropertyLength", "TypeTolerance", "Types",
                         "Flat panels whose edges agree within this (and corner and fold "
                         "angles within 0.5 deg) are one type", default=1.0)
            add_property(obj, "App::PropertyIntegerList", "PanelType", "Data",
                         "Type index per panel (congruent panels share one)", attr=ro)
            add_property(obj, "App::PropertyInteger", "TypeCount", "Data",
                         "Number of different panel types", attr=ro)
            # Panel families (freecad_workbench.families): panels one template
            # serves within FamilyTolerance; 0 = not computed.
            add_property(obj, "App::PropertyLength", "FamilyTolerance", "Families",
                         "Panels whose corners lie within this of a shared template's (after "
                         "the best rigid alignment) form one family; 0 = off", default=0.0)
            add_property(obj, "App::PropertyBool", "Mirror", "Families",
                         "A family's template may also serve its mirror image (turned over)",
                         default=True)
            add_property(obj, "App::PropertyIntegerList", "PanelFamily", "Data",
                         "Family index per panel (empty while FamilyTolerance is 0)", attr=ro)
            add_property(obj, "App::PropertyIntegerList", "FamilyTemplates", "Data",
                         "Panel index of each family's template", attr=ro)
            add_property(obj, "App::PropertyInteger", "FamilyCount", "Families",
                         "Number of panel families (0 while FamilyTolerance is 0)", attr=ro)
            add_property(obj, "App::PropertyInteger", "LargestFamily", "Families",
                         "Panels in the largest family", attr=ro)
            add_property(obj, "App::PropertyFloat", "PanelsPerFamily", "Families",
                         "Mean number of panels per family", attr=ro)
            add_property(obj, "App::PropertyLength", "FamilyMaxError", "Families",
                         "Largest corner distance of a panel to its family's template", attr=ro)
            # Panel classes (freecad_workbench.panel_classes): flat, cold-bent, curved.
            add_property(obj, "App::PropertyLength", "FlatTolerance", "Classes",
                         "A panel warped no more than this (a quad: the distance between its "
                         "diagonals) is flat", default=1.0)
            add_property(obj, "App::PropertyFloat", "ColdBendRatio", "Classes",
                         "A panel warped no more than this ratio of its longest diagonal can be "
                         "cold-bent from flat sheet (1% default: a placeholder, use the "
                         "supplier's figure)", default=0.01)
            add_property(obj, "App::PropertyLength", "ColdBendWarp", "Classes",
                         "Cold-bending limit in mm (0: ColdBendRatio x the diagonal)", default=0.0)
            add_property(obj, "App::PropertyIntegerList", "PanelClass", "Data",
                         "Class per panel: 0 flat, 1 cold-bent, 2 curved", attr=ro)
            add_property(obj, "App::PropertyFloatList", "Warp", "Data",
                         "Warp per panel (mm)", attr=ro)
            add_property(obj, "App::PropertyInteger", "FlatPanels", "Classes",
                         "Panels within FlatTolerance", attr=ro)
            add_property(obj, "App::PropertyInteger", "ColdBentPanels", "Classes",
                         "Panels within the cold-bending limit", attr=ro)
            add_property(obj, "App::PropertyInteger", "CurvedPanels", "Classes",
                         "Panels beyond it (need a mould)", attr=ro)
        elif role == "Rods":
            add_property(obj, "App::PropertyStringList", "RodIds", "Data",
                         "Rod IDs, one per edge", attr=ro)
            add_property(obj, "App::PropertyFloatList", "RodLengths", "Data",
                         "Rod lengths in mm, one per edge", attr=ro)
        elif role == "Nodes":
            add_property(obj, "App::PropertyStringList", "NodeIds", "Data",
                         "Node IDs, one per vertex", attr=ro)
            add_property(obj, "App::PropertyIntegerList", "Valence", "Data",
                         "Number of rods meeting at each node", attr=ro)

    def onDocumentRestored(self, obj):
        self._ensure_runtime()
        self.setup_properties(obj)
        _attach_view_provider(obj, "ViewProviderPanelizationPart")

    @reports_user_errors
    def execute(self, obj):
        parent = obj.Base
        if parent is None or not is_panelization(parent):
            raise ValueError("Base must link to a Panelization object")
        cache = parent.Proxy.result(parent)
        res = cache.result
        role = obj.Role
        # What this child's outputs depend on: the result, its ID format and
        # (Panels) the type tolerance. Unchanged (a bare touch, or a parent
        # change that left the result as it was): nothing to rebuild.
        if role == "Panels":
            tol = max(value_of(obj.TypeTolerance), 1e-6)
            inputs = (cache.serial, res.panel_id_format, tol,
                      value_of(obj.FamilyTolerance), bool(obj.Mirror),
                      value_of(obj.FlatTolerance), float(obj.ColdBendRatio),
                      value_of(obj.ColdBendWarp))
        elif role == "Rods":
            inputs = (cache.serial, res.rod_id_format)
        else:
            inputs = (cache.serial, res.node_id_format)
        if getattr(self, "_applied", None) == inputs:
            return
        self._applied = None
        if role == "Panels":  # before the shape, so a colouring by family sees them
            self._apply_families(obj, cache)
            self._apply_classes(obj)
        obj.Shape = cache.shapes[role]
        if role == "Panels":
            obj.PanelIds = res.panel_ids  # the parent's PanelIdFormat (checked there)
            obj.Deviation = res.metrics["panel_deviation"].tolist()
            obj.Planarity = res.metrics["panel_planarity"].tolist()
            obj.Area = res.metrics["panel_area"].tolist()
            obj.Irregular = res.irregular.astype(int).tolist()
            kinds, count = cache.panel_types(tol)
            obj.PanelType = kinds
            obj.TypeCount = count
        elif role == "Rods":
            obj.RodIds = list(res.rod_ids)
            obj.RodLengths = res.metrics["rod_length"].tolist()
        elif role == "Nodes":
            obj.NodeIds = list(res.node_ids)
            obj.Valence = [int(x) for x in res.metrics["node_valence"]]
        self._applied = inputs

    @staticmethod
    def _apply_families(obj, cache):
        """PanelFamily and the family figures from FamilyTolerance / Mirror
        (all empty / 0 while FamilyTolerance is 0)."""
        tol = value_of(obj.FamilyTolerance)
        if tol < 0:
            raise ValueError(f"{obj.Label}: FamilyTolerance must be >= 0 mm (0 = off), got {tol}")
        if tol == 0:
            fam = None
        else:
            fam = cache.panel_families(tol, bool(obj.Mirror))
        s = fam.summary() if fam is not None else {}
        obj.PanelFamily = fam.labels.tolist() if fam is not None else []
        obj.FamilyTemplates = fam.templates.tolist() if fam is not None else []
        obj.FamilyCount = int(s.get("families", 0))
        obj.LargestFamily = int(s.get("largest_family", 0))
        obj.PanelsPerFamily = float(s.get("mean_panels_per_family", 0.0))
        obj.FamilyMaxError = float(s.get("max_error", 0.0))

    def _apply_classes(self, obj):
        """PanelClass, Warp and the class counts from FlatTolerance /
        ColdBendRatio / ColdBendWarp."""
        cls = self.classes(obj)
        obj.PanelClass = cls.labels.tolist()
        obj.Warp = cls.warp.tolist()
        obj.FlatPanels = cls.counts["flat"]
        obj.ColdBentPanels = cls.counts["cold-bent"]
        obj.CurvedPanels = cls.counts["curved"]

    def classes(self, obj):
        """panel_classes.PanelClasses of a Panels object at its FlatTolerance /
        ColdBendRatio / ColdBendWarp: what schedules and the Unfold use. Raises
        ValueError (naming the object) for a bad setting."""
        from ..panel_classes import panel_classes

        parent = obj.Base
        res = parent.Proxy.result(parent).result
        try:
            return panel_classes(res, value_of(obj.FlatTolerance), float(obj.ColdBendRatio),
                                 value_of(obj.ColdBendWarp))
        except ValueError as exc:
            raise ValueError(f"{obj.Label}: {exc}") from None

    def families(self, obj):
        """families.PanelFamilies of a Panels object at its FamilyTolerance / Mirror
        (None while FamilyTolerance is 0): what schedules, drawings and nesting use."""
        if obj.Role != "Panels" or "FamilyTolerance" not in obj.PropertiesList:
            return None
        tol = value_of(obj.FamilyTolerance)
        if tol <= 0:
            return None
        parent = obj.Base
        return parent.Proxy.result(parent).panel_families(tol, bool(obj.Mirror))
