"""Planarization (issue 16, part 2): node moves that make every quad planar
within a tolerance while the nodes stay within a band around the surface.

    import freecad_workbench as tessella
    r = tessella.panelize(face, method="iso_grid", size=1500.0)
    r2, report = tessella.planarize(r, planarity_tolerance=1.0, max_deviation=20.0)
    report["planar_before"], report["planar_after"], report["quads"]
    report["max_planarity_after"], report["max_node_deviation_after"]   # mm
    r2.metrics["panel_deviation"]     # each quad's flat piece against the surface

A local/global solver in the core (cpp_core/include/tessella/planarize.h):
each round projects every quad's corners onto its best-fit plane and every
node into the band of `max_deviation` around the surface, then solves one
sparse system (Eigen's sparse Cholesky, factored once) for the nodes;
`closeness=0` drops the band (what libigl's planarize_quad_mesh does). Nodes
on the face's boundary and boundary pieces stay where they are (on their
trims). A layout whose lines do not follow a conjugate network (an iso grid
on a freeform face) cannot be made planar inside a narrow band; the report
says how far it got. One face's result (not a face set).
"""

from . import _core

REPORT_FIELDS = ("quads", "planar_before", "planar_after", "max_planarity_before",
                 "max_planarity_after", "max_node_deviation_before",
                 "max_node_deviation_after", "max_move", "iterations", "converged")


def planarize(result, planarity_tolerance=1.0, max_deviation=20.0, closeness=0.1,
              fairness=0.001, max_iterations=200, samples=8, progress=None):
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
    moved, rep = _core.planarize(result._core, p, int(samples), progress)
    out = api.single_face_result(moved, result.method, None, result.params)
    report = {name: getattr(rep, name) for name in REPORT_FIELDS}
    out.summary["planarize"] = report
    return out, report
