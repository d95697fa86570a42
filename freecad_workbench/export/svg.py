"""SVG export of flat panels: the same arrangement as the DXF, in millimetres.

    tessella.export_svg(flat, "panels.svg", layout=layout, kerf=0.0)

One group per panel with classes cut (red), fold (blue, dashed), label (black);
the group's `data-id` attribute, its <title> and its label text hold the panel
ID as typed (any text, escaped); its `id` attribute is the ID itself when that
is a plain XML name (letters, digits, '-', '_', '.'), else a derived unique
`panel-<n>`. Sheets are grey rectangles, each of its own size, laid out in a
grid of about A-series landscape proportions (export/_arrange.py). A layout is
matched to the panels by ID. SVG's y axis points down: the drawing is mirrored
in y so it reads like the DXF.
"""

import re
from xml.sax.saxutils import escape, quoteattr

import numpy as np

from ..fabrication import cut_outline
from . import _arrange

_XML_NAME = re.compile(r"[^\W\d][\w.\-]*\Z")


def svg_ids(ids):
    """The `id` attribute per panel: the ID when it is a plain XML name not used
    before, else panel-<n> (n = 1-based position, made unique)."""
    used, out = set(), []
    for n, pid in enumerate(ids, 1):
        name = pid if _XML_NAME.match(pid) and pid not in used else f"panel-{n}"
        while name in used:
            name += "_"
        used.add(name)
        out.append(name)
    return out


def export_svg(flat, path, layout=None, kerf=0.0):
    """Write the flat panels to `path` (SVG, mm). Returns a dict summary.

    Raises ValueError for a negative kerf, a kerf other than the layout's, or a
    layout that does not hold exactly these panels (matched by ID)."""
    flat = list(flat)
    if layout is not None:
        kerf = _arrange.layout_kerf(layout, kerf)
    cuts = [cut_outline(f, kerf) for f in flat]
    placements, sheets = _arrange.arrange(flat, layout)
    placed = [_arrange.transform(c, *pl) for c, pl in zip(cuts, placements)]
    pts = [p for p in placed] + [np.array([[s[0], s[1]], [s[2], s[3]]]) for s in sheets]
    allp = np.vstack(pts) if pts else np.zeros((1, 2))
    lo, hi = allp.min(axis=0), allp.max(axis=0)
    label_room = max((0.03 * (s[3] - s[1]) for s in sheets), default=0.0)
    pad = 0.02 * float(max(hi - lo)) + 1.0
    lo, hi = lo - pad, hi + pad + np.array([0.0, label_room])
    w, h = hi - lo

    def xy(p):
        return f"{p[0] - lo[0]:.6f},{hi[1] - p[1]:.6f}"

    out = [
        '<?xml version="1.0" encoding="UTF-8"?>',
        f'<svg xmlns="http://www.w3.org/2000/svg" width="{w:.3f}mm" height="{h:.3f}mm" '
        f'viewBox="0 0 {w:.6f} {h:.6f}">',
        "<style>.cut{fill:none;stroke:#d00;stroke-width:0.5}"
        ".fold{stroke:#00c;stroke-width:0.5;stroke-dasharray:8,4}"
        ".label{fill:none;stroke:#000;stroke-width:0.3}.sheet{fill:none;stroke:#888;stroke-width:1}"
        "text{font-family:sans-serif}</style>",
    ]
    for s, (x0, y0, x1, y1, label) in enumerate(sheets):
        out.append(f'<rect class="sheet" data-sheet="{s + 1}" x="{x0 - lo[0]:.6f}" '
                   f'y="{hi[1] - y1:.6f}" width="{x1 - x0:.6f}" height="{y1 - y0:.6f}"/>')
        out.append(f'<text x="{x0 - lo[0]:.3f}" y="{hi[1] - y1 - 0.01 * (y1 - y0):.3f}" '
                   f'font-size="{0.02 * (y1 - y0):.3f}">{escape(label)}</text>')
    for f, cut, pl, sid in zip(flat, placed, placements, svg_ids([f.id for f in flat])):
        th = _arrange.text_height(f.outline)
        out.append(f"<g id={quoteattr(sid)} data-id={quoteattr(f.id)}>")
        out.append(f"<title>{escape(f.id)}</title>")
        out.append('<polygon class="cut" points="' + " ".join(xy(p) for p in cut) + '"/>')
        for a, b, signed in f.folds:
            pa, pb = _arrange.transform([f.outline[a], f.outline[b]], *pl)
            out.append(f'<line class="fold" x1="{pa[0] - lo[0]:.6f}" y1="{hi[1] - pa[1]:.6f}" '
                       f'x2="{pb[0] - lo[0]:.6f}" y2="{hi[1] - pb[1]:.6f}">'
                       f"<title>{escape(_arrange.fold_text(signed))}</title></line>")
        for p0, p1 in _arrange.grain_arrow(f.outline, f.u_direction):
            q0, q1 = _arrange.transform([p0, p1], *pl)
            out.append(f'<polyline class="label" points="{xy(q0)} {xy(q1)}"/>')
        c = _arrange.transform([_arrange.centroid(f.outline)], *pl)[0]
        out.append(f'<text x="{c[0] - lo[0]:.3f}" y="{hi[1] - c[1]:.3f}" font-size="{th:.3f}" '
                   f'text-anchor="middle">{escape(f.id)}</text>')
        out.append("</g>")
    out.append("</svg>")
    with open(path, "w", encoding="utf-8") as fh:
        fh.write("\n".join(out) + "\n")
    return {"path": str(path), "panels": len(flat), "sheets": len(sheets), "kerf": kerf,
            "width_mm": float(w), "height_mm": float(h)}


def export_family_svg(flat, result, families, path, kerf=0.0):
    """One template per panel family (labelled PF-001, ...) and, under the
    drawing, the list of each family's members (see export_family_dxf).
    Returns export_svg's summary plus "families" and "member_lines"."""
    from ..families import members_lines, template_parts

    parts = template_parts(flat, result, families)
    summary = export_svg(parts, path, kerf=kerf)
    lines = members_lines(result, families)
    w, h = summary["width_mm"], summary["height_mm"]
    size = min(max(0.008 * w, 20.0), 200.0)
    new_h = h + (1.6 * len(lines) + 1.0) * size
    with open(path, encoding="utf-8") as fh:
        text = fh.read()
    head = (f'width="{w:.3f}mm" height="{h:.3f}mm" viewBox="0 0 {w:.6f} {h:.6f}"')
    if head not in text:  # pragma: no cover - export_svg writes exactly this
        raise RuntimeError("unexpected SVG header")
    text = text.replace(head, f'width="{w:.3f}mm" height="{new_h:.3f}mm" '
                              f'viewBox="0 0 {w:.6f} {new_h:.6f}"', 1)
    out = ['<g class="members">']
    for i, line in enumerate(lines):
        out.append(f'<text x="{size:.3f}" y="{h + (1.6 * i + 1.6) * size:.3f}" '
                   f'font-size="{size:.3f}" xml:space="preserve">{escape(line)}</text>')
    out.append("</g>")
    text = text.replace("</svg>", "\n".join(out) + "\n</svg>")
    with open(path, "w", encoding="utf-8") as fh:
        fh.write(text)
    summary.update(families=len(parts), member_lines=len(lines), height_mm=float(new_h))
    return summary
