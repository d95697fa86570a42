"""Planarization (issue 16, part 2): node moves that make every quad planar
within a tolerance while the nodes stay within a band around the surface.

    import freecad_workbench as tessella
    r = tessella.panelize(face, method="iso_grid", size=1500.0)
    r2, report = tessella.planarize(r, planarity_tolerance=1.0, max_deviation=20.0)
    report["planar_before"], report["planar_after"], report["quads"]
    report["max_planarity_after"], report["max_node_deviation_after"]   # mm
    r2.metrics["panel_deviation"]     # each quad's flat piece against the surface

A damped Gauss-Newton solver in the core (cpp_core/include/tessella/planarize.h):
the quads' diagonal distances (Huber-weighted: a quad far off planar counts
linearly), a hard band of `max_deviation` around the surface and a fairness
term, each step solved by Eigen's conjugate gradients; `closeness=0` drops
the band (what libigl's planarize_quad_mesh does). Boundary nodes slide along
their trims (`slide_on_trims`, exactly on the trim after every step) except at
trim corners; the outlines of boundary pieces stay. Quads along a conjugate
network (method="curvature_lines") can be made planar inside a narrow band;
an iso grid on a freeform face cannot, and the report says how far it got.
One face's result (not a face set).
"""

from . import _core

REPORT_FIELDS = ("quads", "planar_before", "planar_after", "max_planarity_before",
                 "max_planarity_after", "max_node_deviation_before",
                 "max_node_deviation_after", "max_move", "iterations", "converged",
                 "sliding_nodes", "seconds")


#: The planarize step as keywords of panelize / make_panelization (the step
#: runs after the method when `planarize` is on) and the Panelization
#: properties that store them: keyword -> (property, kind, default, unit,
#: label, doc). One face's panels only.
OPTIONS = {
    "planarize": ("Planarize", "bool", False, "", "Planarize",
                  "After the method, move the nodes so that the quads become planar while "
                  "every node stays within the band around the surface (tessella.planarize)"),
    "planarity_tolerance": ("PlanarityTolerance", "float", 1.0, "mm", "Planarity tolerance",
                            "A quad is planar when its diagonals pass within this"),
    "planarize_max_deviation": ("PlanarizeMaxDeviation", "float", 20.0, "mm", "Planarize band",
                                "Largest distance of a node from the surface the planarize "
                                "step allows"),
}


def pop_options(params):
    """The planarize keywords taken out of `params` (a dict of panelize keywords),
    with their defaults; raises ValueError for a bad value."""
    out = {}
    for name, (_prop, kind, default, _unit, _label, _doc) in OPTIONS.items():
        value = params.pop(name, default)
        if kind == "bool":
            if not isinstance(value, (bool, int)):
                raise ValueError(f"{name} must be True or False, got {value!r}")
            value = bool(value)
        else:
            try:
                value = float(value)
            except (TypeError, ValueError):
                raise ValueError(f"{name} (mm) must be a number, got {value!r}") from None
            if not value > 0:
                raise ValueError(f"{name} (mm) must be above 0, got {value!r}")
        out[name] = value
    return out


def apply_options(result, options, progress=None):
    """`result` planarized as `options` (pop_options') say: the same result when
    the step is off; the report in `summary["planarize"]`."""
    if not options.get("planarize"):
        return result
    out, _report = planarize(result, planarity_tolerance=options["planarity_tolerance"],
                             max_deviation=options["planarize_max_deviation"],
                             progress=progress)
    out.params = {**result.params, **options}
    return out


def refuse_on_face_sets(options):
    if options.get("planarize"):
        raise ValueError("planarize works on one face's panels: pick one face (the step "
                         "is not built for face sets)")


def planarize(result, planarity_tolerance=1.0, max_deviation=20.0, closeness=0.1,
              fairness=0.001, max_iterations=200, samples=8, progress=None,
              slide_on_trims=True):
    """(new result, report dict); see the module docstring."""
    from . import api

    if getattr(result, "_face_set", None) is not None or result._core is None:
        raise ValueError("planarize: give one face's result (not a face set)")
    p = _core.PlanarizeParams()
    p.planarity_tolerance = float(planarity_tolerance)
    p.max_deviation = float(max_deviation)
    p.closeness = float(closeness)
    p.fairness = float(fairness)
    p.max_iterations = int(max_iterations)
    p.slide_on_trims = bool(slide_on_trims)
    moved, rep = _core.planarize(result._core, p, int(samples), progress)
    out = api.single_face_result(moved, result.method, None, result.params)
    report = {name: getattr(rep, name) for name in REPORT_FIELDS}
    out.summary["planarize"] = report
    return out, report
