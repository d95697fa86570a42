"""Where each flat panel goes in a drawing: nested sheets in a grid, or (without
a layout) simple rows. Shared by the DXF and SVG writers.

A nesting layout is matched to the panels BY ID (`match`): the panel list may
come in any order, and a layout that does not hold exactly these panels (an ID
missing, extra or given twice, another outline under the same ID) raises
ValueError naming the first mismatch.

    sheet_placements(flat, layout)  # per panel (sheet, x, y, angle), sheet-local
    sheet_origins(layout)           # per sheet (x0, y0): its corner in one drawing
    arrange(flat, layout)           # per panel (x, y, angle) in one drawing + sheet frames

A drawing point = R(angle) outline point + (x, y). Sheets are laid out in a grid
(sheet 1 top left, left to right, then down) whose column count makes the
drawing about as wide as an A-series landscape page (sqrt(2) : 1).
"""

import math

import numpy as np


def sheet_gap(layout):
    """Free space between two sheets of a drawing (mm)."""
    width = max((w for w, _ in _sizes(layout)), default=layout.sheet_width)
    return max(100.0, 0.1 * width)


def _sizes(layout):
    sizes = getattr(layout, "sheet_sizes", None)
    if sizes:
        return [tuple(map(float, s)) for s in sizes]
    return [(float(layout.sheet_width), float(layout.sheet_height))] * int(layout.sheet_count)


def layout_kerf(layout, kerf):
    """The kerf of a nested layout wins; a different non-zero kerf is an error (the
    cut paths were nested at the layout's kerf)."""
    if kerf and layout.kerf and abs(kerf - layout.kerf) > 1e-12:
        raise ValueError(f"kerf {kerf} differs from the kerf the layout was nested with "
                         f"({layout.kerf}): nest again with kerf={kerf}")
    if kerf and not layout.kerf:
        raise ValueError(f"the layout was nested without kerf: nest again with kerf={kerf}")
    return layout.kerf


def fold_text(angle):
    """'V 12.3456°' (valley) / 'M ...' (mountain) seen from the panel's front."""
    return f"{'V' if angle > 0 else 'M'} {abs(angle):.4f}°"


def dxf_text(text):
    """Text for a DXF TEXT entity that shows `text` as typed: DXF reads '%%c',
    '%%d', '%%p', ... as symbols, so when '%%' occurs every '%' is written '%%%'."""
    text = str(text)
    return text.replace("%", "%%%") if "%%" in text else text


def match(flat, layout):
    """Per flat panel, the index of its entry in the layout (found by ID).

    Raises ValueError naming the first mismatch: a panel without an ID or whose
    ID is given twice, a panel the layout does not hold, a layout entry no panel
    has, or a panel whose outline differs from the one nested under its ID."""
    flat = list(flat)
    ids = list(layout.ids)
    if len(ids) != len(layout.placements):
        raise ValueError(f"the layout has {len(ids)} IDs for {len(layout.placements)} placements")
    where = {}
    for j, pid in enumerate(ids):
        if pid in where:
            raise ValueError(f"the layout holds ID {pid!r} twice (entries {where[pid]} and {j})")
        where[pid] = j
    seen = {}
    out = []
    for i, f in enumerate(flat):
        pid = getattr(f, "id", None)
        if pid in seen:
            raise ValueError(f"panel ID {pid!r} is given twice (panels {seen[pid]} and {i}): "
                             "IDs must be unique")
        seen[pid] = i
        if pid not in where:
            raise ValueError(f"panel {pid!r} is not in the layout ({len(flat)} panels given, "
                             f"{len(ids)} nested): nest the panels you export")
        out.append(where[pid])
    if len(flat) != len(ids):
        extra = next(pid for pid in ids if pid not in seen)
        raise ValueError(f"the layout holds panel {extra!r}, which is not among the "
                         f"{len(flat)} panels given ({len(ids)} nested): nest the panels "
                         "you export")
    nominal = getattr(layout, "panel_outlines", None)
    if nominal:
        for f, j in zip(flat, out):
            a = np.asarray(f.outline, dtype=float)
            b = np.asarray(nominal[j], dtype=float)
            scale = max(1.0, float(np.abs(b).max()) if b.size else 1.0)
            if a.shape != b.shape or not np.allclose(a, b, rtol=0.0, atol=1e-9 * scale):
                raise ValueError(f"panel {f.id!r} is not the panel the layout nested under "
                                 "that ID (its outline differs): nest the panels you export")
    return out


def sheet_placements(flat, layout):
    """Per flat panel (sheet, x, y, angle_deg) in its sheet's own frame (origin at
    the sheet's lower left corner), matched to the layout by ID."""
    out = []
    for j in match(flat, layout):
        pl = layout.placements[j]
        out.append((int(pl.sheet), float(pl.offset[0]), float(pl.offset[1]), float(pl.angle)))
    return out


def grid_columns(sizes, gap, aspect=math.sqrt(2.0)):
    """Columns of the sheet grid: the drawing's width / height closest to `aspect`
    (on a log scale; fewer columns on a tie)."""
    n = len(sizes)
    if n <= 1:
        return max(n, 1)
    cw = max(w for w, _ in sizes) + gap
    ch = max(h for _, h in sizes) + gap
    best = None
    for c in range(1, n + 1):
        rows = math.ceil(n / c)
        if c > 1 and math.ceil(n / (c - 1)) == rows:
            continue  # a column more without a row less
        err = abs(math.log((c * cw - gap) / (rows * ch - gap)) - math.log(aspect))
        if best is None or err < best[0] - 1e-12:
            best = (err, c)
    return best[1]


def sheet_origins(layout):
    """Per sheet (x0, y0): the lower left corner of sheet s in one drawing. Sheets
    sit in a grid of equal cells (the largest sheet plus a gap), sheet 1 top left,
    all coordinates >= 0."""
    sizes = _sizes(layout)
    gap = sheet_gap(layout)
    cols = grid_columns(sizes, gap)
    rows = math.ceil(len(sizes) / cols) if sizes else 0
    cw = max((w for w, _ in sizes), default=0.0) + gap
    ch = max((h for _, h in sizes), default=0.0) + gap
    return [((s % cols) * cw, (rows - 1 - s // cols) * ch) for s in range(len(sizes))]


def sheet_label(layout, s):
    w, h = _sizes(layout)[s]
    return (f"Sheet {s + 1}/{layout.sheet_count}  {w:g} x {h:g} mm  "
            f"utilization {100 * layout.sheet_utilization[s]:.1f}%")


def arrange(flat, layout=None):
    """Returns (placements, sheets): per panel (x, y, angle_deg) such that a drawing
    point = R(angle) outline point + (x, y); sheets = list of (x0, y0, x1, y1, label),
    each frame its own sheet's size. With a layout, panels are matched to it by ID
    (see `match`)."""
    flat = list(flat)
    if layout is not None:
        local = sheet_placements(flat, layout)
        origins = sheet_origins(layout)
        out = [(origins[s][0] + x, origins[s][1] + y, angle) for s, x, y, angle in local]
        sheets = []
        for s, ((x0, y0), (w, h)) in enumerate(zip(origins, _sizes(layout))):
            sheets.append((x0, y0, x0 + w, y0 + h, sheet_label(layout, s)))
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
