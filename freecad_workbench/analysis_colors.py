"""Analysis colours: per-panel and per-rod values mapped to colours (no GUI needed).

The view providers use this to colour the Panels (by deviation, planarity, area,
irregularity, type, family or class) and the Rods (by length); the legend shows the same scale.
"""

import numpy as np

#: Perceptually ordered colour stops (dark blue -> teal -> green -> yellow), the
#: order of viridis, sampled by hand at five points.
_STOPS = np.array(
    [
        [0.267, 0.005, 0.329],
        [0.231, 0.322, 0.545],
        [0.129, 0.569, 0.549],
        [0.369, 0.788, 0.384],
        [0.993, 0.906, 0.144],
    ]
)

#: What each child can be coloured by: mode -> (property of the child, unit).
PANEL_MODES = {
    "Deviation": ("Deviation", "mm"),
    "Planarity": ("Planarity", ""),
    "Area": ("Area", "m²"),
    "Irregular": ("Irregular", ""),
    "Type": ("PanelType", "type"),
    "Family": ("PanelFamily", "family"),  # empty while FamilyTolerance is 0
    "Class": ("PanelClass", "0 flat, 1 cold-bent, 2 curved"),
}
ROD_MODES = {"Length": ("RodLengths", "mm")}


def scale(values):
    """(vmin, vmax) of the values; a constant set gets a unit-wide range."""
    values = np.asarray(values, dtype=float)
    if values.size == 0:
        return 0.0, 1.0
    lo, hi = float(values.min()), float(values.max())
    if hi <= lo:
        hi = lo + 1.0
    return lo, hi


def colors(values, vmin=None, vmax=None):
    """RGB tuples (0..1) for the values, linear between vmin and vmax."""
    values = np.asarray(values, dtype=float)
    lo, hi = scale(values) if vmin is None or vmax is None else (vmin, vmax)
    t = np.clip((values - lo) / (hi - lo), 0.0, 1.0) * (len(_STOPS) - 1)
    i = np.minimum(t.astype(int), len(_STOPS) - 2)
    f = (t - i)[:, None]
    rgb = _STOPS[i] * (1 - f) + _STOPS[i + 1] * f
    return [tuple(float(c) for c in row) for row in rgb]


def values_for(obj, mode):
    """(values, unit) shown for a Panels or Rods child in `mode`."""
    modes = PANEL_MODES if obj.Role == "Panels" else ROD_MODES
    prop, unit = modes[mode]
    values = np.asarray(getattr(obj, prop), dtype=float)
    if prop == "Area":
        values = values / 1e6  # mm² -> m²
    return values, unit


def per_face(shape, item_colors):
    """Expand one colour per sub-shape of a compound into one colour per face
    (a bent n-gon panel is a compound of several flat triangles)."""
    out = []
    for child, color in zip(shape.childShapes(), item_colors):
        out.extend([color] * max(1, len(child.Faces)))
    return out
