"""Panel classes: flat, cold-bent or curved (console API; issue 16 part 3).

    import freecad_workbench as tessella
    r = tessella.panelize(face, method="curvature_lines", size=1500.0)
    r2, report = tessella.planarize(r)
    cls = tessella.panel_classes(r2, flat_tolerance=1.0, cold_bend_ratio=0.01)
    cls.names          # "flat" / "cold-bent" / "curved" per panel
    cls.labels         # 0 / 1 / 2 per panel
    cls.warp           # mm per panel
    cls.counts         # {"flat": ..., "cold-bent": ..., "curved": ...}

Every result's summary holds the counts at the defaults
(`r.summary["panel_classes"]`) and its metrics the warp (`r.metrics["panel_warp"]`).
Warp: a quad's distance between its diagonals (what planarize drives); any
other panel twice its vertices' largest distance from their least-squares
plane; a triangle 0. A panel is flat within `flat_tolerance` (mm), cold-bent
within `cold_bend_warp` (mm) when set, else within `cold_bend_ratio` x its
longest diagonal, curved beyond. The 1% default is a placeholder for early
design: how far a pane may be cold-bent depends on its thickness, build-up
and size (Datsiou & Overend 2016); use the glass supplier's figure. Rules in
the core: cpp_core/include/tessella/panel_classes.h.
"""

from dataclasses import dataclass, field

import numpy as np

from . import core

#: Class names, by label.
CLASS_NAMES = ("flat", "cold-bent", "curved")
FLAT_TOLERANCE = 1.0  # mm
COLD_BEND_RATIO = 0.01


@dataclass
class PanelClasses:
    """Each panel's class (see the module docstring). Arrays are numpy."""

    labels: np.ndarray  # (P,) int: 0 flat, 1 cold-bent, 2 curved
    warp: np.ndarray  # (P,) mm
    limit: np.ndarray  # (P,) mm: the panel's cold-bending limit
    flat_tolerance: float = FLAT_TOLERANCE
    cold_bend_ratio: float = COLD_BEND_RATIO
    cold_bend_warp: float = 0.0
    counts: dict = field(init=False)

    def __post_init__(self):
        n = np.bincount(self.labels, minlength=3)
        self.counts = {name: int(n[k]) for k, name in enumerate(CLASS_NAMES)}

    @property
    def names(self):
        return [CLASS_NAMES[int(k)] for k in self.labels]


def classify(vertices, panels, flat_tolerance=FLAT_TOLERANCE, cold_bend_ratio=COLD_BEND_RATIO,
             cold_bend_warp=0.0):
    """PanelClasses of panels given as vertex index lists into `vertices` (n,3)."""
    p = _params(flat_tolerance, cold_bend_ratio, cold_bend_warp)
    xyz = np.asarray(vertices, dtype=float).reshape(-1, 3)
    return _classes(core.classify_panels([xyz[list(panel)] for panel in panels], p), p)


def classify_mesh(mesh, flat_tolerance=FLAT_TOLERANCE, cold_bend_ratio=COLD_BEND_RATIO,
                  cold_bend_warp=0.0):
    """classify() of a core PanelMesh's panels, without copying them into
    Python first (a result's own panels: 7,800 of them took 12 ms that way)."""
    p = _params(flat_tolerance, cold_bend_ratio, cold_bend_warp)
    return _classes(core.classify_mesh_panels(mesh, p), p)


def _params(flat_tolerance, cold_bend_ratio, cold_bend_warp):
    from .fabrication import _check_number

    # Numbers here; their ranges are the core's (classify_panels checks them).
    p = core.PanelClassParams()
    p.flat_tolerance = _check_number("flat_tolerance (mm)", flat_tolerance, -1e300, 1e300)
    p.cold_bend_ratio = _check_number("cold_bend_ratio", cold_bend_ratio, -1e300, 1e300)
    p.cold_bend_warp = _check_number("cold_bend_warp (mm)", cold_bend_warp, -1e300, 1e300)
    return p


def _classes(c, p):
    return PanelClasses(np.asarray(c.label, dtype=np.int64), np.asarray(c.warp),
                        np.asarray(c.limit), p.flat_tolerance, p.cold_bend_ratio,
                        p.cold_bend_warp)


def panel_classes(result, flat_tolerance=FLAT_TOLERANCE, cold_bend_ratio=COLD_BEND_RATIO,
                  cold_bend_warp=0.0):
    """PanelClasses of a result's panels (a face or a face set; any object with
    `vertices` and `panels`)."""
    return classify(result.vertices, result.panels, flat_tolerance, cold_bend_ratio,
                    cold_bend_warp)
