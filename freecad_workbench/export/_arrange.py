"""Where each flat panel goes in a drawing: nested sheets side by side, or (without
a layout) simple rows. Shared by the DXF and SVG writers."""

import math

import numpy as np


def sheet_gap(layout):
    return max(100.0, 0.1 * layout.sheet_width)


def arrange(flat, layout=None):
    """Returns (placements, sheets): per panel (x, y, angle_deg) such that a drawing
    point = R(angle) outline point + (x, y); sheets = list of (x0, y0, x1, y1, label)."""
    flat = list(flat)
    if layout is not None:
        if len(layout.placements) != len(flat):
            raise ValueError(
                f"the layout holds {len(layout.placements)} panels but {len(flat)} were given: "
                "nest the same list you export"
            )
        gap = sheet_gap(layout)
        out = []
        for pl in layout.placements:
            x0 = pl.sheet * (layout.sheet_width + gap)
            out.append((x0 + pl.offset[0], pl.offset[1], pl.angle))
        sheets = []
        for s in range(layout.sheet_count):
            x0 = s * (layout.sheet_width + gap)
            label = (f"Sheet {s + 1}/{layout.sheet_count}  {layout.sheet_width:g} x "
                     f"{layout.sheet_height:g} mm  utilization {100 * layout.sheet_utilization[s]:.1f}%")
            sheets.append((x0, 0.0, x0 + layout.sheet_width, layout.sheet_height, label))
        return out, sheets
    # No layout: rows of panels at their own orientation, left to right, bottom to top.
    boxes = [(f.outline.min(axis=0), f.outline.max(axis=0)) for f in flat]
    sizes = [hi - lo for lo, hi in boxes]
    gap = 0.1 * float(np.median([max(s) for s in sizes])) if sizes else 0.0
    row_width = 1.3 * math.sqrt(sum(float(s[0] + gap) * float(s[1] + gap) for s in sizes) or 1.0)
    out, x, y, row_h = [], 0.0, 0.0, 0.0
    for (lo, hi), size in zip(boxes, sizes):
        if x > 0 and x + size[0] > row_width:
            x, y, row_h = 0.0, y + row_h + gap, 0.0
        out.append((x - lo[0], y - lo[1], 0.0))
        x += size[0] + gap
        row_h = max(row_h, size[1])
    return out, []


def transform(points, x, y, angle):
    a = math.radians(angle)
    rot = np.array([[math.cos(a), -math.sin(a)], [math.sin(a), math.cos(a)]])
    return np.asarray(points, dtype=float) @ rot.T + np.array([x, y])


def centroid(outline):
    """Area centroid of a polygon (falls back to the vertex mean if degenerate)."""
    p = np.asarray(outline, dtype=float)
    q = np.roll(p, -1, axis=0)
    c = p[:, 0] * q[:, 1] - q[:, 0] * p[:, 1]
    a = c.sum() / 2
    if abs(a) < 1e-12:
        return p.mean(axis=0)
    return np.array([((p[:, 0] + q[:, 0]) * c).sum(), ((p[:, 1] + q[:, 1]) * c).sum()]) / (6 * a)


def text_height(outline):
    lo, hi = np.min(outline, axis=0), np.max(outline, axis=0)
    return float(np.clip(0.06 * min(hi - lo), 2.0, 80.0))


def grain_arrow(outline, u_direction):
    """Orientation mark: an arrow along the surface's u direction below the label.
    Returns three segments ((x0, y0), (x1, y1))."""
    c = centroid(outline)
    h = text_height(outline)
    d = np.asarray(u_direction, dtype=float)
    n = np.array([-d[1], d[0]])
    length = 4 * h
    start = c - 1.5 * h * n - 0.5 * length * d
    tip = start + length * d
    head = 0.6 * h
    return [
        (tuple(start), tuple(tip)),
        (tuple(tip), tuple(tip - head * d + 0.5 * head * n)),
        (tuple(tip), tuple(tip - head * d - 0.5 * head * n)),
    ]
