"""Family regularization (issue 17, part 2): small node moves that make the
panels of each family congruent within a tighter tolerance.

    import freecad_workbench as tessella
    r = tessella.panelize(face, method="iso_grid", size=1500.0)
    r2, report = tessella.regularize_families(r, family_tolerance=2.0, tolerance=0.5,
                                              max_deviation=2.0)
    report["families_before"], report["families_after"]   # at `tolerance`
    report["max_move"], report["max_node_deviation"]      # mm

Families are grouped as tessella.panel_families groups them (at
`family_tolerance`); each round every family's mean shape is placed on its
members and the free nodes move half way to the mean of the places their
panels ask of them, held within `max_deviation` (mm) of the surface. Nodes on
the face's boundary and the outlines of boundary pieces do not move (so
boundary nodes stay on their trims). The round with the fewest families at
`tolerance` is kept; the metrics are measured again on the moved nodes. One
face's result (not a face set). Core: cpp_core/include/tessella/family_regularization.h.
"""

from . import _core


def regularize_families(result, family_tolerance=2.0, tolerance=0.5, max_deviation=None,
                        mirror=True, max_iterations=50, samples=8):
    """(new result, report dict). max_deviation defaults to family_tolerance."""
    from . import api

    if getattr(result, "_face_set", None) is not None or result._core is None:
        raise ValueError("regularize_families: give one face's result (not a face set)")
    p = _core.FamilyRegularizationParams()
    p.family_tolerance = float(family_tolerance)
    p.tolerance = float(tolerance)
    p.max_deviation = float(family_tolerance if max_deviation is None else max_deviation)
    p.mirror = bool(mirror)
    p.max_iterations = int(max_iterations)
    moved, rep = _core.regularize_families(result._core, p, int(samples))
    out = api.single_face_result(moved, result.method, None, result.params)
    report = {name: getattr(rep, name) for name in (
        "families", "families_before", "families_after", "max_error_before", "max_error_after",
        "max_move", "max_node_deviation", "moved_nodes", "iterations")}
    out.summary["regularization"] = report
    return out, report
