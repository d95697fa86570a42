"""Document-free console API: a face in, numpy arrays out.

    import freecad_workbench as tessella
    r = tessella.panelize(face, method="iso_grid", size=1500.0)
    r.vertices, r.uv, r.panels, r.rods, r.metrics, r.summary

`face` may be a Part.Face, a Part.Shape holding exactly one face, or a
(document_object, "FaceN") pair as FreeCAD's selection gives it.
All lengths are in mm.
"""

import re
import time
from dataclasses import dataclass, field

import numpy as np

from . import core

from .methods import METHODS, Method, Param  # noqa: F401  (THE declarations, from the core)

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


#: How many guide edges each guide-line method takes (its `guides` keyword).
GUIDE_COUNT = {
    name: int(m.params["guides"].minimum) for name, m in METHODS.items() if "guides" in m.params
}

PANEL_ID_FORMAT = "P-{:04d}"
ROD_ID_FORMAT = "R-{:04d}"
NODE_ID_FORMAT = "N-{:04d}"


_CONTROL = re.compile("[\x00-\x1f\x7f]")


def format_ids(fmt, count, what="panel", faces=None):
    """IDs fmt.format(1), ..., fmt.format(count): any text a user can type around a
    number field (``ROOF/A:{:03d}``, spaces, unicode). With `faces` (each item's
    source face, 0-based) a format may name the face: ``F{face}-P-{:04d}``
    numbers the items of each face from 1 and puts the face (1-based) in front.
    Raises ValueError for a format that is not one, gives an empty ID or an ID
    with a control character, or gives two items the same ID (e.g. no number
    field): IDs name parts on drawings and schedules, so they are refused
    rather than silently suffixed."""
    name = f"{what.capitalize()}IdFormat"
    if not isinstance(fmt, str) or not fmt:
        raise ValueError(f"{name} must be a text like P-{{:04d}}, got {fmt!r}")
    per_face = faces is not None and "{face" in fmt
    seen = {}
    out = []
    counter = {}
    for k in range(1, count + 1):
        face = int(faces[k - 1]) + 1 if faces is not None and len(faces) >= k else 1
        number = counter[face] = counter.get(face, 0) + 1
        try:
            text = fmt.format(number if per_face else k, face=face)
        except (IndexError, KeyError, ValueError, TypeError, AttributeError):
            raise ValueError(f"{name} {fmt!r} is not a format like P-{{:04d}} "
                             "(or F{face}-P-{:04d})") from None
        if not text.strip() or _CONTROL.search(text):
            raise ValueError(f"{name} {fmt!r} gives {what} {k} the ID {text!r} "
                             "(empty or with a control character)")
        if text in seen:
            raise ValueError(f"{name} {fmt!r} gives {what}s {seen[text]} and {k} the same ID "
                             f"{text!r}: put the number in it, e.g. {{:04d}}")
        seen[text] = k
        out.append(text)
    return out


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
    #: the core's summary: counts, stats, and the short-rod stage's shortest_rod,
    #: min_rod_length (the limit used, mm), merged_rods and short_rods (left under it)
    summary: dict = field(default_factory=dict)
    #: (F,2) int64 vertex pairs: diagonals along which a method folded a quad
    #: into two flat triangles (walking_agent's hard bound); see metrics["fold_angle"].
    folds: np.ndarray = field(default_factory=lambda: np.zeros((0, 2), dtype=np.int64))
    #: (P,), (N,), (E,) int64: the source face (0-based, in the order the faces
    #: were given) of each panel, vertex (its first face on a shared edge) and
    #: rod (the lower face on a shared edge); all 0 for one face.
    panel_face: np.ndarray = field(default_factory=lambda: np.zeros(0, dtype=np.int64))
    vertex_face: np.ndarray = field(default_factory=lambda: np.zeros(0, dtype=np.int64))
    rod_face: np.ndarray = field(default_factory=lambda: np.zeros(0, dtype=np.int64))
    #: how many faces the panels were made on
    face_count: int = 1
    _mesh: object = field(default=None, repr=False)
    #: the core's result: keeps the parsed face (unfolding and flattening reuse it)
    _core: object = field(default=None, repr=False)
    #: the core.FaceSet of a face-set result (flattening reuses its faces)
    _face_set: object = field(default=None, repr=False)
    #: Python formats of the IDs from the item number (1-based); a Panelization
    #: sets them from its PanelIdFormat / RodIdFormat / NodeIdFormat. Every
    #: writer (unfold, nest, DXF, SVG, schedules, structural export) reads the IDs here.
    panel_id_format: str = PANEL_ID_FORMAT
    rod_id_format: str = ROD_ID_FORMAT
    node_id_format: str = NODE_ID_FORMAT

    @property
    def surface(self):
        """The core.SurfaceFace the panels were built on (None if not kept)."""
        return getattr(self._core, "face", None)

    @property
    def face_index(self):
        """The source face (0-based) of each panel: panel_face (rods: rod_face,
        nodes: node_face)."""
        return self.panel_face

    @property
    def node_face(self):
        """The source face (0-based) of each node (self.nodes order; a node on a
        shared edge: its first face)."""
        return self.vertex_face[self.nodes] if len(self.vertex_face) else self.vertex_face

    @property
    def panel_ids(self):
        """One ID per panel (panel order), from panel_id_format (see format_ids)."""
        return format_ids(self.panel_id_format, len(self.panels), "panel", self.panel_face)

    @property
    def rod_ids(self):
        return format_ids(self.rod_id_format, len(self.rods), "rod", self.rod_face)

    @property
    def node_ids(self):
        """One ID per node (self.nodes order)."""
        faces = self.vertex_face[self.nodes] if len(self.vertex_face) else None
        return format_ids(self.node_id_format, len(self.nodes), "node", faces)

    @property
    def node_id_by_vertex(self):
        """{vertex index: node ID} for the vertices that are nodes (rod ends)."""
        return {int(v): nid for v, nid in zip(self.nodes, self.node_ids)}

    def panels_brep(self, planar_tolerance=None):
        """BRep string of a compound with one sub-shape per panel (panel order)."""
        if planar_tolerance is None:
            planar_tolerance = 1e-6 * max(self.summary.get("model_size", 1.0), 1.0)
        return core.panels_to_brep(self._mesh, planar_tolerance)

    def panels_shape(self, planar_tolerance=None):
        """The panels as one Part.Compound, one sub-shape per panel (panel order):
        the faces of panels_brep() (the core decides each face: flat on its
        plane, bilinear, pieces, fan; core.panel_faces), built in this process
        without the BRep text round trip, which costs several times more
        (bench/document_speed.py). Unlike panels_brep(), neighbours do not
        share edges. Needs FreeCAD's Part module."""
        import FreeCAD
        import Part

        if planar_tolerance is None:
            planar_tolerance = 1e-6 * max(self.summary.get("model_size", 1.0), 1.0)
        d = core.panel_faces(self._mesh, planar_tolerance)
        vec = FreeCAD.Vector
        xyz = [vec(*p) for p in self.vertices.tolist()]
        corners, offsets = d["corners"].tolist(), d["corner_offsets"].tolist()
        origin, normal = d["origin"].tolist(), d["normal"].tolist()
        tolerance = d["tolerance"].tolist()
        faces = []
        for f, bilinear in enumerate(d["bilinear"].tolist()):
            pts = [xyz[i] for i in corners[offsets[f]:offsets[f + 1]]]
            if bilinear:
                patch = Part.BezierSurface()  # degree 1 x 1, poles in corner order
                for (i, j), q in zip(((1, 1), (2, 1), (2, 2), (1, 2)), pts):
                    patch.setPole(i, j, q)
                faces.append(patch.toShape())
            else:
                wire = Part.makePolygon(pts + pts[:1])
                if tolerance[f] > 1e-7:
                    wire.fixTolerance(tolerance[f])
                faces.append(Part.Face(Part.Plane(vec(*origin[f]), vec(*normal[f])), wire))
        first = d["panel_offsets"].tolist()
        return Part.makeCompound([
            Part.makeCompound(faces[first[k]:first[k + 1]]) if compound else faces[first[k]]
            for k, compound in enumerate(d["compound"].tolist())])

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
    allowed = set(METHODS[method].params)
    unknown = sorted(set(params) - allowed)
    if unknown:
        raise ValueError(
            f"unknown parameter(s) {unknown} for method {method!r}; accepted: {sorted(allowed)}"
        )


def _number(name, value, kind):
    try:
        if isinstance(value, bool) or kind is bool:
            return bool(value) if kind is bool else int(value)
        number = float(value)
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be a number, got {value!r}") from None
    if kind is int and number.is_integer():
        return int(number)
    return number


def core_values(method, params, surface=None):
    """The keyword parameters as the core takes them ({name: value}): numbers as
    numbers, guide edges as (N,3) polylines, (u,v) curves as (N,2) arrays. Raises
    ValueError naming the parameter when a value has the wrong kind; the ranges
    are checked by the core (from the same declarations)."""
    _check_kwargs(method, params)
    declared = METHODS[method].params
    values = {}
    for name, value in params.items():
        kind = declared[name].type
        if kind == "float":
            values[name] = _number(name, value, float)
        elif kind == "int":
            values[name] = _number(name, value, int)
        elif kind == "bool":
            values[name] = _number(name, value, bool)
        elif kind == "choice":
            values[name] = str(value)
        elif kind == "int_list":
            try:
                values[name] = [int(k) for k in value]
            except (TypeError, ValueError):
                raise ValueError(f"{name} must be a list of whole numbers, got {value!r}") from None
        elif kind == "curves":
            values[name] = _curves(name, value, int(declared[name].minimum),
                                   int(declared[name].maximum))
        elif kind == "uv_curves":
            values[name] = _uv_curves(name, value, surface)
        else:  # pragma: no cover - a kind the core added without a converter here
            raise ValueError(f"{name}: unsupported parameter kind {kind!r}")
    return values


def _curves(name, value, fewest, most):
    """`fewest` to `most` edges -> (N,3) polylines (a selection pair is one edge)."""
    from .selection import edges_of

    value = edges_of(value, context=name)
    if not fewest <= len(value) <= most:
        held = f"exactly {fewest}" if fewest == most else f"{fewest} to {most}"
        raise ValueError(f"{name} must hold {held} edge(s), got {len(value)}")
    return [edge_polyline(e) for e in value]


def _uv_curves(name, value, surface=None):
    """(N,2) (u,v) arrays; edges lying on the face (Part shapes, (obj, 'EdgeN')
    pairs: what a document links) are discretized and projected onto it."""
    curves = []
    for c in value:
        if not isinstance(c, np.ndarray) and (
                hasattr(c, "ShapeType") or hasattr(c, "Shape")
                or (isinstance(c, tuple) and len(c) == 2 and isinstance(c[1], str))):
            if surface is None:
                raise ValueError(f"{name}: edges need the face to be projected on")
            pts = edge_polyline(c, points=64)
            c = [surface.project(p)[0] for p in pts]
        a = np.asarray(c, dtype=np.float64)
        if a.ndim != 2 or a.shape[1] != 2:
            raise ValueError(f"{name}: each curve must be an (N, 2) array of (u, v) points")
        curves.append(a)
    return curves


#: Raised when a progress callback asked to stop (a RuntimeError).
Cancelled = core.Cancelled


def panelize(face, method="iso_grid", progress=None, **params):
    """Panelize one face. See the module docstring and README for parameters.

    progress: optional callable (fraction, stage) -> bool, called about every
    50 ms during long steps; returning False cancels (raises Cancelled).

    Raises ValueError for a bad parameter or an unusable face (the message names
    the parameter and its accepted range), RuntimeError if the geometry kernel fails.
    """
    return panelize_brep(face_to_brep(face), method, progress, **params)


def panelize_source(source, method="iso_grid", progress=None, **params):
    """panelize() for a source naming one face, panelize_faces() for several
    (what the task panel previews: (obj, 'FaceN'), (obj, ['Face1', 'Face3']), obj)."""
    from .selection import faces_of

    if len(faces_of(source, context="source")) > 1:
        return panelize_faces(source, method=method, progress=progress, **params)
    return panelize(source, method=method, progress=progress, **params)


class PreparedRun:
    """A panelization with everything read from FreeCAD already (the face or
    faces parsed, the keywords checked and converted): run() touches no
    document object, so it may run on a worker thread (the core releases the
    GIL). What the task panel's preview computes off the GUI thread."""

    def __init__(self, source, method, params):
        from .selection import faces_of

        from .planarization import pop_options, refuse_on_face_sets

        faces = faces_of(source, context="source")
        params = dict(params)
        self.planarize = pop_options(params)
        self.method, self.params = method, params
        self.several = len(faces) > 1
        if self.several:
            refuse_on_face_sets(self.planarize)
            import Part

            self.brep = Part.Compound(faces).exportBrepToString()
            self.target = core.FaceSet.from_brep_string(self.brep)
            self.values = core_values(method, params)
        else:
            self.brep = face_to_brep(faces[0])
            self.target = core.SurfaceFace.from_brep_string(self.brep)
            self.values = core_values(method, params, self.target)

    def run(self, progress=None):
        """The result (raises Cancelled when progress says stop)."""
        if not self.several:
            from .planarization import apply_options

            res = panelize_surface(self.target, self.method, self.values, self.params, progress)
            return apply_options(res, self.planarize, progress)
        r = core.panelize_faces(self.target, self.method, self.values, progress, 0)
        return _face_set_result(r, self.method, self.values, self.params, self.target)


def panelize_brep(brep, method="iso_grid", progress=None, **params):
    """panelize() on a face given as its BRep string (what a document recompute
    already has: the face is serialized once)."""
    from .planarization import apply_options, pop_options

    params = dict(params)
    options = pop_options(params)  # the planarize step's keywords
    surface = core.SurfaceFace.from_brep_string(brep)
    values = core_values(method, params, surface)  # checks the keywords
    return apply_options(panelize_surface(surface, method, values, params, progress), options,
                         progress)


def panelize_surface(surface, method, values, params=None, progress=None):
    """The core pipeline on an already parsed core.SurfaceFace (one core call)."""
    r = core.panelize(surface, method, values, progress)
    return single_face_result(r, method, values, params)


def single_face_result(r, method, values, params):
    """The Python result of one face's core PanelizeResult (every item on face 0)."""
    result = _result(r, method, values, params)
    result.panel_face = np.zeros(len(result.panels), dtype=np.int64)
    result.vertex_face = np.zeros(len(result.vertices), dtype=np.int64)
    result.rod_face = np.zeros(len(result.rods), dtype=np.int64)
    return result


def panelize_faces(faces, method="iso_grid", progress=None, threads=0, **params):
    """Panelize several faces as one envelope: one result whose panels, rods and
    nodes cover all of them.

    faces: a shape (a shell, a solid, a compound: all its faces), a list of
    faces or shapes, a document object, (obj, ["Face1", "Face3"]), a list of
    such pairs. Faces of one shape share their common edges; along such an
    edge both faces get the same nodes (one node at each position, one rod per
    segment, no T-junction). Faces that touch along edges they do not share
    (of several objects, an unsewn STEP shell) are sewn first (within 1e-5 of
    the shape's size; `r.summary["sewn"]` tells).
    Faces are panelized side by side on `threads` threads (0: every core), with
    the same result for any count. `r.panel_face`, `r.vertex_face` and
    `r.rod_face` give each item's face (0-based, in the order given);
    `r.summary["faces"]` each face's own summary. The guide-line methods take
    one face.
    """
    from .selection import faces_of

    found = faces_of(faces, context="faces")
    import Part

    shape = found[0] if len(found) == 1 else Part.Compound(found)
    return panelize_faces_brep(shape.exportBrepToString(), method, progress, threads, **params)


def panelize_faces_brep(brep, method="iso_grid", progress=None, threads=0, **params):
    """panelize_faces() on a shape given as its BRep string (a document
    recompute's: the faces serialized once)."""
    from .planarization import pop_options, refuse_on_face_sets

    params = dict(params)
    refuse_on_face_sets(pop_options(params))
    face_set = core.FaceSet.from_brep_string(brep)
    values = core_values(method, params)
    r = core.panelize_faces(face_set, method, values, progress, int(threads))
    return _face_set_result(r, method, values, params, face_set)


def _face_set_result(r, method, values, params, face_set):
    """The Python result of a core FaceSetResult on `face_set`."""
    result = _result(r.combined, method, values, params)
    result._face_set = face_set
    result.summary["sewn"] = face_set.sewn
    result.panel_face = np.asarray(r.panel_face, dtype=np.int64)
    result.vertex_face = np.asarray(r.vertex_face, dtype=np.int64)
    result.rod_face = np.asarray(r.rod_face, dtype=np.int64)
    n = len(r.face_summaries)
    result.face_count = n
    result.summary["faces"] = list(r.face_summaries)
    result.summary["face_count"] = n
    result.summary["shared_edges"] = r.shared_edges
    result.summary["shared_edge_nodes"] = r.shared_edge_nodes
    result.summary["shared_nodes_taken_over"] = r.shared_nodes_taken_over
    # Checked on the joined result: segments between consecutive nodes along
    # shared edges, those without a panel of each face along them (a
    # T-junction or a gap), and the warning saying where ("" when none).
    result.summary["shared_edge_segments"] = r.shared_edge_segments
    result.summary["unmatched_shared_segments"] = r.unmatched_shared_segments
    result.summary["join_warning"] = r.join_warning
    result.summary["faces_traced_across"] = r.faces_traced_across
    result.summary["faces_traced_across_surfaces"] = r.faces_traced_across_surfaces
    # boundary_driven: faces the set's size was too coarse for, meshed at the
    # first smaller size that works: {face index: size in mm}.
    result.summary["faces_at_a_smaller_size"] = {
        f: float(s) for f, s in enumerate(r.smaller_size) if s > 0}
    result.summary["skipped_faces"] = dict(r.skipped)
    # boundary_driven: faces whose share of curves traced across faces failed
    # the final check, meshed from their own curves (rows stop at their edges).
    result.summary["faces_retraced_alone"] = list(r.retraced_alone)
    return result


def _result(r, method, values, params):
    """The Python result of a core PanelizeResult."""
    mesh = r.mesh
    node_index = np.asarray(mesh.nodes, dtype=np.int64)
    m = r.metrics
    metrics = {
        "fold_angle": np.asarray(r.fold_angle),
        "panel_deviation": np.asarray(m.deviation),
        "panel_planarity": np.asarray(m.planarity),
        "panel_area": np.asarray(m.area),
        "panel_min_angle": np.asarray(m.min_angle),
        "panel_max_angle": np.asarray(m.max_angle),
        "rod_length": np.asarray(m.rod_length),
        "node_valence": np.asarray(r.valence)[node_index],
    }
    from .panel_classes import classify_mesh

    classes = classify_mesh(mesh)
    metrics["panel_warp"] = classes.warp
    summary = dict(r.summary)
    # At the defaults (flat within 1 mm, cold-bent within 1% of the diagonal).
    summary["panel_classes"] = dict(classes.counts)
    return PanelizeResult(
        method=method,
        params=dict(params if params is not None else values),
        vertices=np.asarray(mesh.xyz),
        uv=np.asarray(mesh.uv),
        normals=np.asarray(r.normals),
        panels=[tuple(p) for p in mesh.panels],
        rods=np.asarray(mesh.rods, dtype=np.int64),
        metrics=metrics,
        irregular=np.asarray(r.irregular, dtype=bool),
        nodes=node_index,
        summary=summary,
        folds=np.asarray(core.mesh_folds(mesh), dtype=np.int64).reshape(-1, 2),
        _mesh=mesh,
        _core=r,
    )
