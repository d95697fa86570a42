"""Document-free console API: a face in, numpy arrays out.

    import freecad_workbench as tessella
    r = tessella.panelize(face, method="iso_grid", size=1500.0)
    r.vertices, r.uv, r.panels, r.rods, r.metrics, r.summary

`face` may be a Part.Face, a Part.Shape holding exactly one face, or a
(document_object, "FaceN") pair as FreeCAD's selection gives it.
All lengths are in mm.
"""

import time
from dataclasses import dataclass, field

import numpy as np

from . import core

#: Keyword parameters every grid method accepts, with their types; they fill
#: core.GridClipParams (the first three) or the measurement step.
CLIP_PARAMS = {"sliver_fraction": float, "trim_deflection": float, "max_panels": int}
COMMON_PARAMS = tuple(CLIP_PARAMS) + ("min_angle", "samples")


@dataclass(frozen=True)
class MethodSpec:
    """How one method plugs in: its own keyword parameters (name -> type), the
    factory of its core params struct, and the core function (face, params) -> PanelMesh.
    A struct with a `clip` member gets the CLIP_PARAMS. `converters` holds the
    non-numeric keyword parameters: name -> function(params_struct, value) that
    checks the value and stores it (e.g. guide edges discretized into polylines)."""

    params: dict
    make_params: object
    run: object
    #: run accepts progress=callable(fraction, stage) -> bool (False cancels)
    reports_progress: bool = False
    converters: dict = field(default_factory=dict)


#: Points per guide edge handed to the core (which resamples and projects them).
GUIDE_POINTS = 512


def edge_polyline(edge, points=GUIDE_POINTS):
    """(N,3) float64 points along a Part.Edge (or a one-edge shape / wire), in mm."""
    from .selection import one_edge

    edge = one_edge(edge, context="guides")
    if edge.Length <= 0:
        raise ValueError("guides: a guide edge has no length")
    pts = edge.discretize(Number=int(points))
    return np.array([[p.x, p.y, p.z] for p in pts], dtype=np.float64)


def _guides(count):
    """Converter of `guides`: exactly `count` edges -> polylines on the params struct."""

    def convert(p, value):
        from .selection import edges_of

        value = edges_of(value, context="guides")  # (obj, "EdgeN") is one guide
        if len(value) != count:
            raise ValueError(f"guides must hold exactly {count} edge(s), got {len(value)}")
        polylines = [edge_polyline(e) for e in value]
        if count == 1:
            p.guide = polylines[0]
        else:
            p.guides = polylines

    return convert


#: How a parameter is shown (task panel): label and unit ("mm", "deg", "" for a
#: plain number; None for a count). A new method adds its parameters here.
PARAM_INFO = {
    "size": ("Size", "mm"),
    "u_count": ("U count (0: use size)", None),
    "v_count": ("V count (0: use size)", None),
    "sliver_fraction": ("Sliver fraction", ""),
    "min_angle": ("Min angle", "deg"),
    "max_panels": ("Max panels", None),
    "rho": ("Rho (IDW power)", ""),
    "skew_ratio": ("Skew ratio (min/max angle)", ""),
    "smoothing_iterations": ("Smoothing iterations", None),
    "quadrangulate": ("Quadrangulate", bool),
    "rod_length": ("Rod length", "mm"),
    "advance": ("Advance (0: rod length)", "mm"),
    "triangulate": ("Triangulate", bool),
    "boundary_divisions": ("Boundary divisions (0: rod length)", None),
    "map_in_uv": ("Map curves in (u,v)", bool),
    "max_deviation": ("Deviation bound", "mm"),
    "max_size": ("Max panel size", "mm"),
    "diagonal_deviation": ("Diagonal bound (0: 2 x bound)", "mm"),
    "sample_step": ("Sample step (of the span)", ""),
    "max_refinements": ("Max refinements", None),
    "edge_share": ("Edge share (0: try 1, 0.7, 0.5)", ""),
    "max_step": ("Max step (of the span)", ""),
    "max_iterations": ("Max iterations", None),
    "tolerance": ("Tolerance", ""),
}

#: How many guide edges each guide-line method takes (its `guides` keyword).
GUIDE_COUNT = {"guide_line_scaling": 1, "two_guide_lines": 2, "guide_line_diamond": 2}

#: The methods, by name. A new method adds one entry here.
METHODS = {
    "iso_grid": MethodSpec(
        {"size": float, "u_count": int, "v_count": int},
        lambda: core.IsoGridParams(),
        lambda surface, p, progress=None: core.iso_grid(surface, p, progress),
        reports_progress=True,
    ),
    "equal_size_grid": MethodSpec(
        {"size": float},
        lambda: core.EqualSizeGridParams(),
        lambda surface, p, progress=None: core.equal_size_grid(surface, p, progress),
        reports_progress=True,
    ),
    # Seed 001: lines that follow the trims (docs/boundary_driven.md).
    "boundary_driven": MethodSpec(
        {
            "size": float,
            "rho": float,
            "skew_ratio": float,
            "smoothing_iterations": int,
            "quadrangulate": bool,
            "source_loops": list,
            "extra_curves": list,
            "corner_angle": float,
            "min_edge_fraction": float,
            "angle_target": float,
            "trim_deflection": float,
            "max_panels": int,
        },
        lambda: core.BoundaryDrivenParams(),
        lambda surface, p: core.boundary_driven(surface, p),
    ),
    "guide_line_scaling": MethodSpec(
        {"rod_length": float, "advance": float, "merge_fraction": float,
         "guide_tolerance": float, "max_curves": int, "finish_sweep": bool, "stagger": bool,
         "trim_deflection": float, "max_panels": int},
        lambda: core.GuideLineScalingParams(),
        lambda surface, p: core.guide_line_scaling(surface, p),
        converters={"guides": _guides(GUIDE_COUNT["guide_line_scaling"])},
    ),
    # GSM run once per guide; the cells between the two curve sets (diamonds).
    "guide_line_diamond": MethodSpec(
        {"rod_length": float, "advance": float, "finish_sweep": bool, "triangulate": bool,
         "guide_tolerance": float, "max_curves": int, "trim_deflection": float,
         "max_panels": int},
        lambda: core.GuideLineDiamondParams(),
        lambda surface, p: core.guide_line_diamond(surface, p),
        converters={"guides": _guides(GUIDE_COUNT["guide_line_diamond"])},
    ),
    "two_guide_lines": MethodSpec(
        {"rod_length": float, "triangulate": bool, "boundary_divisions": int, "map_in_uv": bool,
         "corner_angle": float, "guide_tolerance": float, "max_curves": int, "trim_deflection": float,
         "max_panels": int},
        lambda: core.TwoGuideLinesParams(),
        lambda surface, p: core.two_guide_lines(surface, p),
        converters={"guides": _guides(GUIDE_COUNT["two_guide_lines"])},
    ),
    # Seed 000 (docs/walking_agent.md): adaptive quads with a hard deviation bound.
    "walking_agent": MethodSpec(
        {
            "max_deviation": float,
            "max_size": float,
            "diagonal_deviation": float,
            "sample_step": float,
            "start": str,
            "max_refinements": int,
            "edge_share": float,
        },
        lambda: core.WalkingAgentParams(),
        lambda surface, p: core.walking_agent(surface, p),
    ),
    # Its rivals from the thesis' comparison (section 5).
    "gradient_descent": MethodSpec(
        {"max_deviation": float, "sample_step": float, "max_step": float, "start": str},
        lambda: core.GradientDescentParams(),
        lambda surface, p: core.gradient_descent(surface, p),
    ),
    "relaxed_grid": MethodSpec(
        {
            "u_count": int,
            "v_count": int,
            "max_iterations": int,
            "tolerance": float,
            "weight": float,
            "max_panels": int,
        },
        lambda: core.RelaxedGridParams(),
        lambda surface, p: core.relaxed_grid(surface, p),
    ),
}

PANEL_ID_FORMAT = "P-{:04d}"
ROD_ID_FORMAT = "R-{:04d}"
NODE_ID_FORMAT = "N-{:04d}"


@dataclass
class PanelizeResult:
    """Everything one panelization produced. Arrays are numpy, lengths in mm."""

    method: str
    params: dict
    vertices: np.ndarray  # (N,3) float64
    uv: np.ndarray  # (N,2) float64
    normals: np.ndarray  # (N,3) unit face normals at the nodes
    panels: list  # list of tuples of vertex indices, CCW seen from the normal
    rods: np.ndarray  # (E,2) int64 vertex indices, a < b: straight members node to node
    metrics: dict  # name -> numpy array (see METRIC_NAMES)
    irregular: np.ndarray  # (P,) bool
    #: (K,) int64: the vertices that are nodes (rod ends: grid nodes, grid/trim
    #: crossings, trim corners); the others only shape boundary panels' outlines.
    nodes: np.ndarray = field(default_factory=lambda: np.zeros(0, dtype=np.int64))
    summary: dict = field(default_factory=dict)
    #: (F,2) int64 vertex pairs: diagonals along which a method folded a quad
    #: into two flat triangles (walking_agent's hard bound); see metrics["fold_angle"].
    folds: np.ndarray = field(default_factory=lambda: np.zeros((0, 2), dtype=np.int64))
    _mesh: object = field(default=None, repr=False)

    @property
    def panel_ids(self):
        return [PANEL_ID_FORMAT.format(i + 1) for i in range(len(self.panels))]

    @property
    def rod_ids(self):
        return [ROD_ID_FORMAT.format(i + 1) for i in range(len(self.rods))]

    @property
    def node_ids(self):
        """One ID per node (self.nodes order)."""
        return [NODE_ID_FORMAT.format(i + 1) for i in range(len(self.nodes))]

    @property
    def node_id_by_vertex(self):
        """{vertex index: node ID} for the vertices that are nodes (rod ends)."""
        return {int(v): NODE_ID_FORMAT.format(k + 1) for k, v in enumerate(self.nodes)}

    def panels_brep(self, planar_tolerance=None):
        """BRep string of a compound with one sub-shape per panel (panel order)."""
        if planar_tolerance is None:
            planar_tolerance = 1e-6 * max(self.summary.get("model_size", 1.0), 1.0)
        return core.panels_to_brep(self._mesh, planar_tolerance)

    def rods_brep(self):
        """BRep string of a compound with one edge per rod (rod order)."""
        return core.rods_to_brep(self._mesh)

    def nodes_brep(self):
        """BRep string of a compound with one vertex per node (vertex order)."""
        return core.nodes_to_brep(self._mesh)  # one vertex per node, self.nodes order


METRIC_NAMES = (
    "panel_deviation",
    "panel_planarity",
    "panel_area",
    "panel_min_angle",
    "panel_max_angle",
    "rod_length",
    "node_valence",
    "fold_angle",  # one per fold (see PanelizeResult.folds), degrees
)


def face_to_brep(face):
    """BRep string of one face from a Part.Face, a one-face shape or (obj, 'FaceN')."""
    return face_to_shape(face).exportBrepToString()


def face_to_shape(face):
    """The Part.Face named by a Part.Face, a one-face shape, a document object or
    (obj, 'FaceN') (see freecad_workbench.selection)."""
    from .selection import one_face

    return one_face(face)


def _check_kwargs(method, params):
    if method not in METHODS:
        raise ValueError(f"method must be one of {sorted(METHODS)}, got {method!r}")
    allowed = set(METHODS[method].params) | set(METHODS[method].converters) | set(COMMON_PARAMS)
    unknown = sorted(set(params) - allowed)
    if unknown:
        raise ValueError(
            f"unknown parameter(s) {unknown} for method {method!r}; accepted: {sorted(allowed)}"
        )


def _set(struct, name, value, kind):
    what = "a list" if kind is list else "a number"
    try:
        value = kind(value)
        setattr(struct, name, value)
    except (TypeError, ValueError) as exc:
        if isinstance(exc, ValueError) and kind is list:
            raise  # the core's own message (e.g. an unusable extra curve)
        raise ValueError(f"{name} must be {what}, got {value!r}") from None


def _method_params(method, params):
    spec = METHODS[method]
    p = spec.make_params()
    for name, kind in spec.params.items():
        if name in params:
            _set(p, name, params[name], kind)
    for name, convert in spec.converters.items():
        if name in params:
            convert(p, params[name])
    if hasattr(p, "clip"):
        clip = core.GridClipParams()
        for name, kind in CLIP_PARAMS.items():
            if name in params:
                _set(clip, name, params[name], kind)
        p.clip = clip
    return p


def _fold_angles(vertices, panels, folds):
    """Fold angle (degrees, 0 = flat) at each fold: the angle between the normals
    of the two triangles that share the fold diagonal."""
    if len(folds) == 0:
        return np.zeros(0)
    by_edge = {}
    for k, p in enumerate(panels):
        if len(p) != 3:
            continue
        for a, b in ((p[0], p[1]), (p[1], p[2]), (p[2], p[0])):
            by_edge.setdefault((min(a, b), max(a, b)), []).append(k)
    angles = []
    for a, b in folds:
        tris = by_edge.get((int(a), int(b)), [])
        if len(tris) != 2:
            angles.append(float("nan"))
            continue
        n = []
        for k in tris:
            p = vertices[list(panels[k])]
            c = np.cross(p[1] - p[0], p[2] - p[0])
            n.append(c / np.linalg.norm(c))
        angles.append(float(np.degrees(np.arccos(np.clip(np.dot(n[0], n[1]), -1.0, 1.0)))))
    return np.asarray(angles)


#: Raised when a progress callback asked to stop (a RuntimeError).
Cancelled = core.Cancelled


def panelize(face, method="iso_grid", progress=None, **params):
    """Panelize one face. See the module docstring and README for parameters.

    progress: optional callable (fraction, stage) -> bool, called about every
    50 ms during long steps; returning False cancels (raises Cancelled).

    Raises ValueError for a bad parameter or an unusable face (the message names
    the parameter and its accepted range), RuntimeError if the geometry kernel fails.
    """
    _check_kwargs(method, params)
    brep = face_to_brep(face)
    surface = core.SurfaceFace.from_brep_string(brep)
    spec = METHODS[method]
    method_params = _method_params(method, params)
    core.reset_surface_evaluations(surface)
    started = time.perf_counter()
    if spec.reports_progress:
        mesh = spec.run(surface, method_params, progress=progress)
    else:
        mesh = spec.run(surface, method_params)
    core_seconds = time.perf_counter() - started
    evaluations = int(core.surface_evaluations(surface))
    folds = np.asarray(core.mesh_folds(mesh), dtype=np.int64).reshape(-1, 2)

    mp = core.MetricsParams()
    if "samples" in params:
        _set(mp, "samples", params["samples"], int)
    m = core.measure_panels(surface, mesh, mp, progress)
    ip = core.IrregularParams()
    if "min_angle" in params:
        _set(ip, "min_angle_deg", params["min_angle"], float)
    if "sliver_fraction" in params:
        ip.min_area_fraction = float(params["sliver_fraction"])
    irregular = np.asarray(core.irregular_panels(mesh, m, ip), dtype=bool)
    nodes = core.node_data(surface, mesh)
    node_index = np.asarray(mesh.nodes, dtype=np.int64)

    verts = np.asarray(mesh.xyz)
    metrics = {
        "fold_angle": _fold_angles(verts, mesh.panels, folds),
        "panel_deviation": np.asarray(m.deviation),
        "panel_planarity": np.asarray(m.planarity),
        "panel_area": np.asarray(m.area),
        "panel_min_angle": np.asarray(m.min_angle),
        "panel_max_angle": np.asarray(m.max_angle),
        "rod_length": np.asarray(m.rod_length),
        "node_valence": np.asarray(nodes.valence)[node_index],
    }
    summary = {
        "panel_count": len(mesh.panels),
        "rod_count": int(mesh.rods.shape[0]),
        "node_count": int(len(node_index)),
        "merged_slivers": int(mesh.merged_slivers),
        "irregular_count": int(irregular.sum()),
        "quad_share": float(np.mean([len(p) == 4 for p in mesh.panels])) if mesh.panels else 0.0,
        "nominal_area": float(mesh.nominal_area),
        "face_area": float(surface.area()),
        "model_size": float(surface.model_size()),
        "fold_count": int(len(folds)),
        # Cost of the method call alone (no metrics): surface evaluations
        # (points, derivatives, projection steps) and wall time in seconds.
        "surface_evaluations": evaluations,
        "core_seconds": core_seconds,
    }
    for name in ("panel_deviation", "panel_planarity", "panel_area", "rod_length"):
        summary[name] = core.summarize(metrics[name])
    return PanelizeResult(
        method=method,
        params=dict(params),
        vertices=np.asarray(mesh.xyz),
        uv=np.asarray(mesh.uv),
        normals=np.asarray(nodes.normal),
        panels=[tuple(p) for p in mesh.panels],
        rods=np.asarray(mesh.rods, dtype=np.int64),
        metrics=metrics,
        irregular=irregular,
        nodes=node_index,
        summary=summary,
        folds=folds,
        _mesh=mesh,
    )
