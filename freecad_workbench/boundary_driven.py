"""The intermediate stages of method="boundary_driven" (seed 001), for display.

    import freecad_workbench as tessella
    s = tessella.boundary_driven_stages(face, size=900.0)
    s["curves_xyz"]      # list of (N,3) arrays: the traced BDCurves, mm
    s["network_xyz"], s["network_panels"]   # the preliminary BDMesh
    s["panels"]          # the final panels (as panelize() returns them)

Accepts the same keyword parameters as panelize(face, method="boundary_driven").
"""

import numpy as np

from . import api, core


def boundary_driven_stages(face, **params):
    """Traced curves, preliminary network and final mesh of one face."""
    method = "boundary_driven"
    values = api.core_values(method, params)
    surface = core.SurfaceFace.from_brep_string(api.face_to_brep(face))
    d = core.boundary_driven_stages(surface, core.boundary_driven_params(values))
    mesh = d["mesh"]
    return {
        "curves_uv": [np.asarray(c) for c in d["curves_uv"]],
        "curves_xyz": [np.asarray(c) for c in d["curves_xyz"]],
        "curves_closed": list(d["curves_closed"]),
        "network_uv": np.asarray(d["network_uv"]),
        "network_xyz": np.asarray(d["network_xyz"]),
        "network_loop": list(d["network_loop"]),
        "network_edges": [tuple(e) for e in d["network_edges"]],
        "network_panels": [tuple(p) for p in d["network_panels"]],
        "removed_triangles": int(d["removed_triangles"]),
        "collapsed_edges": int(d["collapsed_edges"]),
        "angle_moves": int(d["angle_moves"]),
        "vertices": np.asarray(mesh.xyz),
        "panels": [tuple(p) for p in mesh.panels],
    }
