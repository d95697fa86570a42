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

FROZEN: the module path `freecad_workbench.features.panelization` and the class
names `Panelization` and `PanelizationPart` are stored in every saved .FCStd.
"""

import hashlib
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

#: Methods of seed 000 and where the agents may start.
AGENT_METHODS = ("walking_agent", "gradient_descent", "relaxed_grid")
AGENT_STARTS = ("u_min_v_min", "u_max_v_min", "u_min_v_max", "u_max_v_max", "max_curvature")

#: Which method uses which parameter property (others are hidden in the editor).
_GRIDS = ("iso_grid", "equal_size_grid")
#: Method-specific properties and the methods that use them (others hide them).
METHOD_PROPERTIES = {
    "Size": _GRIDS + ("boundary_driven",),
    "UCount": ("iso_grid", "relaxed_grid"),
    "VCount": ("iso_grid", "relaxed_grid"),
    "DeviationBound": ("walking_agent", "gradient_descent"),
    "MaxSize": ("walking_agent",),
    "DiagonalDeviation": ("walking_agent",),
    "SampleStep": ("walking_agent", "gradient_descent"),
    "Start": ("walking_agent", "gradient_descent"),
    "MaxRefinements": ("walking_agent",),
    "EdgeShare": ("walking_agent",),
    "MaxStep": ("gradient_descent",),
    "MaxIterations": ("relaxed_grid",),
    "Tolerance": ("relaxed_grid",),
    "Rho": ("boundary_driven",),
    "SkewRatio": ("boundary_driven",),
    "SmoothingIterations": ("boundary_driven",),
    "Quadrangulate": ("boundary_driven",),
    "SourceLoops": ("boundary_driven",),
    "RodLength": ("guide_line_scaling", "two_guide_lines", "guide_line_diamond"),
    "Advance": ("guide_line_scaling", "guide_line_diamond"),
    "Triangulate": ("two_guide_lines", "guide_line_diamond"),
    "BoundaryDivisions": ("two_guide_lines",),
    "MapInUV": ("two_guide_lines",),
    "Guides": ("guide_line_scaling", "two_guide_lines", "guide_line_diamond"),
}
#: The properties only boundary_driven uses.
BD_PROPERTIES = tuple(n for n, m in METHOD_PROPERTIES.items() if m == ("boundary_driven",))

#: Roles of the children, in tree order.
ROLES = ("Panels", "Rods", "Nodes")


def _api():
    from .. import api

    return api


def _core_defaults():
    """Defaults of the core's parameter structs (one source of truth)."""
    from .. import core

    clip = core.GridClipParams()
    irregular = core.IrregularParams()
    return {
        "sliver_fraction": float(clip.sliver_fraction),
        "max_panels": int(clip.max_panels),
        "min_angle": float(irregular.min_angle_deg),
    }


def _bd_defaults():
    from .. import core

    p = core.BoundaryDrivenParams()
    return {
        "rho": float(p.rho),
        "skew_ratio": float(p.skew_ratio),
        "smoothing_iterations": int(p.smoothing_iterations),
        "quadrangulate": bool(p.quadrangulate),
    }


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
    """A panelization result and the shapes built from it (not saved)."""

    def __init__(self, signature, result, shapes):
        self.signature = signature
        self.result = result
        self.shapes = shapes


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
        d = _core_defaults()
        add_property(obj, "App::PropertyLinkSub", "Source", "Input",
                     "The face to panelize: (object, ['FaceN'])")
        add_property(obj, "App::PropertyEnumeration", "Method", "Panelization",
                     "iso_grid: uniform in (u,v); equal_size_grid: lines spaced by arc length; "
                     "boundary_driven: quad mesh whose lines follow the trims",
                     default="iso_grid", enum=list(api.METHODS))
        _upgrade_enumeration(obj, "Method", list(api.METHODS))
        add_property(obj, "App::PropertyLength", "Size", "Panelization",
                     "Target panel edge length (equal_size_grid; iso_grid when "
                     "UCount and VCount are 0)", default=0.0)
        add_property(obj, "App::PropertyInteger", "UCount", "Panelization",
                     "iso_grid: panels across u; with VCount, replaces Size "
                     "(0 = use Size)", default=0)
        add_property(obj, "App::PropertyInteger", "VCount", "Panelization",
                     "iso_grid: panels across v; with UCount, replaces Size "
                     "(0 = use Size)", default=0)
        add_property(obj, "App::PropertyLinkSubList", "Guides", "Input",
                     "Guide curves (edges): one for guide_line_scaling, two for two_guide_lines "
                     "and guide_line_diamond; "
                     "an edit of a guide recomputes the grid")
        add_property(obj, "App::PropertyLength", "RodLength", "Guide lines",
                     "guide_line_scaling: target rod length L1 along the curves", default=0.0)
        add_property(obj, "App::PropertyLength", "Advance", "Guide lines",
                     "guide_line_scaling: step L between curves (0 = RodLength x sqrt(3)/2)",
                     default=0.0)
        add_property(obj, "App::PropertyBool", "Triangulate", "Guide lines",
                     "two_guide_lines, guide_line_diamond: split every cell along its "
                     "shorter diagonal", default=False)
        add_property(obj, "App::PropertyInteger", "BoundaryDivisions", "Guide lines",
                     "two_guide_lines: divide each boundary curve into this many equal chords "
                     "(0 = chords of RodLength)", default=0)
        add_property(obj, "App::PropertyBool", "MapInUV", "Guide lines",
                     "two_guide_lines: move the guide through the vertex pairs in (u,v) "
                     "(false: the paper's 3D scale/rotate/project)", default=True)
        add_property(obj, "App::PropertyFloat", "SliverFraction", "Panelization",
                     "Boundary panels smaller than this fraction of a full panel are merged "
                     "into a neighbour (also the area limit of an irregular panel)",
                     default=d["sliver_fraction"])
        add_property(obj, "App::PropertyAngle", "MinAngle", "Panelization",
                     "A panel with a corner angle below this is irregular",
                     default=d["min_angle"])
        add_property(obj, "App::PropertyInteger", "MaxPanels", "Panelization",
                     "Refuse to build more panels than this", default=d["max_panels"])
        add_property(obj, "App::PropertyString", "PanelIdFormat", "Output",
                     "Python format of the panel IDs from the panel number, e.g. P-{:04d}",
                     default="P-{:04d}")
        # boundary_driven (seed 001, docs/boundary_driven.md)
        bd = _bd_defaults()
        add_property(obj, "App::PropertyFloat", "Rho", "Boundary driven",
                     "Power of the inverse distance weighting of the direction field "
                     "(higher: the nearest trim dominates)", default=bd["rho"])
        add_property(obj, "App::PropertyFloat", "SkewRatio", "Boundary driven",
                     "Triangles whose smallest / largest corner angle is under this are removed",
                     default=bd["skew_ratio"])
        add_property(obj, "App::PropertyInteger", "SmoothingIterations", "Boundary driven",
                     "Laplacian smoothing passes (nodes stay on the surface and the trims)",
                     default=bd["smoothing_iterations"])
        add_property(obj, "App::PropertyBool", "Quadrangulate", "Boundary driven",
                     "Split every panel by centre and edge midpoints (all quads; curves are "
                     "then traced 2 x Size apart)", default=bd["quadrangulate"])
        add_property(obj, "App::PropertyIntegerList", "SourceLoops", "Boundary driven",
                     "Trim loops (0 = outer, then the holes) the direction field follows; "
                     "empty = all")
        self._setup_agent_properties(obj)
        add_property(obj, "App::PropertyLength", "TrimDeflection", "Advanced",
                     "Chord deflection of the trim polylines (0 = automatic)", default=0.0)
        add_property(obj, "App::PropertyInteger", "Samples", "Advanced",
                     "Samples per panel edge for the deviation measure (0 = core default)",
                     default=0)
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

    def _setup_agent_properties(self, obj):
        """Parameters of walking_agent, gradient_descent and relaxed_grid
        (docs/walking_agent.md); added when missing, so older documents upgrade."""
        from .. import core

        wa = core.WalkingAgentParams()
        gd = core.GradientDescentParams()
        rg = core.RelaxedGridParams()
        add_property(obj, "App::PropertyLength", "DeviationBound", "Agents",
                     "walking_agent: no panel deviates more than this from the surface; "
                     "gradient_descent: the target deviation", default=0.0)
        add_property(obj, "App::PropertyLength", "MaxSize", "Agents",
                     "walking_agent: longest panel edge (0 = no limit)", default=0.0)
        add_property(obj, "App::PropertyLength", "DiagonalDeviation", "Agents",
                     "walking_agent: bound of the diagonal walkers (0 = 2 x DeviationBound)",
                     default=0.0)
        add_property(obj, "App::PropertyFloat", "SampleStep", "Agents",
                     "Agents' sample step as a fraction of the parameter span (0.05 = thesis)",
                     default=float(wa.sample_step))
        add_property(obj, "App::PropertyEnumeration", "Start", "Agents",
                     "Where the agents start: a corner of the (u,v) domain or the point "
                     "of largest curvature", default=wa.start, enum=list(AGENT_STARTS))
        add_property(obj, "App::PropertyFloat", "EdgeShare", "Agents",
                     "walking_agent: the agents' edge rule uses this share of DeviationBound "
                     "(0 = try 1, 0.7, 0.5 and keep the fewest panels)",
                     default=float(wa.edge_share))
        add_property(obj, "App::PropertyInteger", "MaxRefinements", "Agents",
                     "walking_agent: rounds of the hard-bound refinement",
                     default=int(wa.max_refinements))
        add_property(obj, "App::PropertyFloat", "MaxStep", "Agents",
                     "gradient_descent: longest step, fraction of the parameter span",
                     default=float(gd.max_step))
        add_property(obj, "App::PropertyInteger", "MaxIterations", "Agents",
                     "relaxed_grid: iteration limit (UCount x VCount panels)",
                     default=int(rg.max_iterations))
        add_property(obj, "App::PropertyFloat", "Tolerance", "Agents",
                     "relaxed_grid: stop when no node moves more than this fraction "
                     "of the parameter span", default=float(rg.tolerance))

    def _update_editor_modes(self, obj):
        if "Method" not in obj.PropertiesList:
            return
        for name, methods in METHOD_PROPERTIES.items():
            if name in obj.PropertiesList:
                obj.setEditorMode(name, 0 if obj.Method in methods else 2)

    def onChanged(self, obj, prop):
        if prop == "Method":
            self._update_editor_modes(obj)

    def onDocumentRestored(self, obj):
        self._ensure_runtime()
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

    def parameters(self, obj):
        """(method, keyword parameters for api.panelize) from the properties."""
        method = obj.Method
        if method in _api().GUIDE_COUNT:
            params = {"rod_length": value_of(obj.RodLength), "guides": self.guide_edges(obj)}
            if method != "two_guide_lines" and value_of(obj.Advance) > 0:
                params["advance"] = value_of(obj.Advance)
            if method != "guide_line_scaling":
                params["triangulate"] = bool(obj.Triangulate)
            if method == "two_guide_lines":
                params["boundary_divisions"] = int(obj.BoundaryDivisions)
                params["map_in_uv"] = bool(obj.MapInUV)
            params["min_angle"] = value_of(obj.MinAngle)
            params["max_panels"] = int(obj.MaxPanels)
            if value_of(obj.TrimDeflection) > 0:
                params["trim_deflection"] = value_of(obj.TrimDeflection)
            if obj.Samples:
                params["samples"] = int(obj.Samples)
            return method, params
        if method in AGENT_METHODS:
            return method, self._agent_parameters(obj, method)
        if method == "iso_grid" and (obj.UCount or obj.VCount):
            # Counts replace the size (the core takes one or the other).
            params = {"u_count": int(obj.UCount), "v_count": int(obj.VCount)}
        else:
            params = {"size": value_of(obj.Size)}
        if method == "boundary_driven":
            params["rho"] = float(obj.Rho)
            params["skew_ratio"] = float(obj.SkewRatio)
            params["smoothing_iterations"] = int(obj.SmoothingIterations)
            params["quadrangulate"] = bool(obj.Quadrangulate)
            if obj.SourceLoops:
                params["source_loops"] = [int(k) for k in obj.SourceLoops]
        params["sliver_fraction"] = float(obj.SliverFraction)
        params["min_angle"] = value_of(obj.MinAngle)
        params["max_panels"] = int(obj.MaxPanels)
        if value_of(obj.TrimDeflection) > 0:
            params["trim_deflection"] = value_of(obj.TrimDeflection)
        if obj.Samples:
            params["samples"] = int(obj.Samples)
        return method, params

    def guide_edges(self, obj):
        """The linked guide edges (Part.Edge / Part.Wire shapes, in link order)."""
        edges = selection.edges_of(obj.Guides or [], context=f"{obj.Label}: Guides")
        if not edges:
            raise ValueError(f"{obj.Label}: {obj.Method} needs guide edges (set Guides)")
        return edges

    def _agent_parameters(self, obj, method):
        if method == "relaxed_grid":
            params = {
                "u_count": int(obj.UCount),
                "v_count": int(obj.VCount),
                "max_iterations": int(obj.MaxIterations),
                "tolerance": float(obj.Tolerance),
            }
        else:
            params = {
                "max_deviation": value_of(obj.DeviationBound),
                "sample_step": float(obj.SampleStep),
                "start": str(obj.Start),
            }
            if method == "walking_agent":
                params["max_size"] = value_of(obj.MaxSize)
                params["diagonal_deviation"] = value_of(obj.DiagonalDeviation)
                params["max_refinements"] = int(obj.MaxRefinements)
                params["edge_share"] = float(obj.EdgeShare)
            else:
                params["max_step"] = float(obj.MaxStep)
            params["sliver_fraction"] = float(obj.SliverFraction)
            if value_of(obj.TrimDeflection) > 0:
                params["trim_deflection"] = value_of(obj.TrimDeflection)
        params["min_angle"] = value_of(obj.MinAngle)
        params["max_panels"] = int(obj.MaxPanels)
        if obj.Samples:
            params["samples"] = int(obj.Samples)
        return params

    def _signature(self, obj):
        api = _api()
        face_arg, _ = self.source_face(obj)
        brep = api.face_to_brep(face_arg)
        method, params = self.parameters(obj)
        digest = hashlib.sha1(brep.encode("utf-8", "surrogateescape")).hexdigest()
        plain = {k: v for k, v in params.items() if k != "guides"}
        if "guides" in params:  # shapes: keyed by their geometry
            plain["guides"] = [
                hashlib.sha1(e.exportBrepToString().encode("utf-8", "surrogateescape")).hexdigest()
                for e in params["guides"]
            ]
        key = json.dumps([method, sorted(plain.items()), digest])
        return key, face_arg, method, params

    def result(self, obj):
        """The cached result for the current face and parameters (built if needed).

        Raises ValueError / RuntimeError with a readable message when the
        panelization cannot be built.
        """
        api = _api()
        signature, face_arg, method, params = self._signature(obj)
        cache = getattr(self, "_cache", None)
        if cache is not None and cache.signature == signature:
            return cache
        failed = getattr(self, "_failed", None)
        if failed is not None and failed[0] == signature:
            raise failed[1](failed[2])
        try:
            res = api.panelize(face_arg, method=method, **params)
            shapes = self._shapes(res)
        except (ValueError, TypeError, RuntimeError) as exc:
            self._cache = None
            self._failed = (signature, type(exc), str(exc))
            raise
        self._failed = None
        self._cache = _Cache(signature, res, shapes)
        return self._cache

    @staticmethod
    def _shapes(res):
        """Panels, Rods and Nodes compounds of a result, checked against its counts."""
        import Part

        expected = {"Panels": len(res.panels), "Rods": len(res.rods), "Nodes": len(res.nodes)}
        shapes = {}
        for role, make in (("Panels", res.panels_brep), ("Rods", res.rods_brep),
                           ("Nodes", res.nodes_brep)):
            shape = Part.Shape()
            shape.importBrepFromString(make(), False)
            n = len(shape.childShapes()) if not shape.isNull() else 0
            if n != expected[role]:
                raise RuntimeError(f"{role}: the core built {n} shapes for {expected[role]} items")
            shapes[role] = shape
        return shapes

    def seed(self, obj, res):
        """Start from a result computed for exactly these properties (make_panelization
        and the task panel compute once, with progress; the recompute reuses it)."""
        signature = self._signature(obj)[0]
        self._failed = None
        self._cache = _Cache(signature, res, self._shapes(res))

    def execute(self, obj):
        try:
            cache = self.result(obj)
        except Exception as exc:
            FreeCAD.Console.PrintError(f"Tessella: {obj.Label}: {exc}\n")
            raise
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

    def execute(self, obj):
        parent = obj.Base
        try:
            if parent is None or not is_panelization(parent):
                raise ValueError("Base must link to a Panelization object")
            cache = parent.Proxy.result(parent)
        except Exception as exc:
            FreeCAD.Console.PrintError(f"Tessella: {obj.Label}: {exc}\n")
            raise
        res = cache.result
        role = obj.Role
        obj.Shape = cache.shapes[role]
        if role == "Panels":
            fmt = getattr(parent, "PanelIdFormat", "") or "P-{:04d}"
            try:
                obj.PanelIds = [fmt.format(i + 1) for i in range(len(res.panels))]
            except (IndexError, KeyError, ValueError):
                raise ValueError(f"PanelIdFormat {fmt!r} is not a format like P-{{:04d}}")
            obj.Deviation = [float(x) for x in res.metrics["panel_deviation"]]
            obj.Planarity = [float(x) for x in res.metrics["panel_planarity"]]
            obj.Area = [float(x) for x in res.metrics["panel_area"]]
            obj.Irregular = [int(x) for x in res.irregular]
            from ..fabrication import unfold
            from ..members import panel_types

            kinds, count = panel_types(unfold(res), length_tol=max(value_of(obj.TypeTolerance), 1e-6))
            obj.PanelType = [int(x) for x in kinds]
            obj.TypeCount = int(count)
        elif role == "Rods":
            obj.RodIds = list(res.rod_ids)
            obj.RodLengths = [float(x) for x in res.metrics["rod_length"]]
        elif role == "Nodes":
            obj.NodeIds = list(res.node_ids)
            obj.Valence = [int(x) for x in res.metrics["node_valence"]]

