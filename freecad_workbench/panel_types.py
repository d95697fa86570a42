"""Panel types: panels that are the same part for the workshop.

Two panels are one type when they have the same number of corners and all
their corner-to-corner distances agree within `tolerance` (mm) for some
cyclic relabelling of the corners, forwards or mirrored. All pairwise
distances fix a polygon up to a rigid motion or a mirror image, and a flat
part cut from a sheet can be turned over, so a mirror image is the same part.

Distances are compared after rounding to the tolerance grid, so two panels
whose distances straddle a rounding boundary can land in different types:
the count is exact for repeated panels (equal to the last digit) and an upper
bound otherwise.
"""

import numpy as np


def _signature(points, tolerance):
    n = len(points)
    d = np.linalg.norm(points[:, None, :] - points[None, :, :], axis=2)
    q = np.rint(d / tolerance).astype(np.int64)
    best = None
    for order in (np.arange(n), np.arange(n)[::-1]):
        for shift in range(n):
            idx = np.roll(order, -shift)
            key = tuple(q[np.ix_(idx, idx)][np.triu_indices(n, 1)])
            if best is None or key < best:
                best = key
    return (n, best)


def panel_types(result, tolerance=1.0):
    """Type index per panel (0, 1, ... in order of first appearance)."""
    if not tolerance > 0:
        raise ValueError(f"tolerance must be > 0 mm, got {tolerance!r}")
    types, seen = [], {}
    for panel in result.panels:
        key = _signature(np.asarray(result.vertices[list(panel)], dtype=float), tolerance)
        types.append(seen.setdefault(key, len(seen)))
    return np.asarray(types, dtype=np.int64)
