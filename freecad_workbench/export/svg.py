"""SVG export of flat panels: the same arrangement as the DXF, in millimetres.

    tessella.export_svg(flat, "panels.svg", layout=layout, kerf=0.0)

Groups per panel (id = panel ID) with classes cut (red), fold (blue, dashed),
label (black); sheets as grey rectangles. SVG's y axis points down: the drawing
is mirrored in y so it reads like the DXF.
"""

from xml.sax.saxutils import escape

import numpy as np

from ..fabrication import cut_outline
from . import _arrange
from .dxf import _layout_kerf, fold_text


def export_svg(flat, path, layout=None, kerf=0.0):
    flat = list(flat)
    if layout is not None:
        kerf = _layout_kerf(layout, kerf)
    cuts = [cut_outline(f, kerf) for f in flat]
    placements, sheets = _arrange.arrange(flat, layout)
    placed = [_arrange.transform(c, *pl) for c, pl in zip(cuts, placements)]
    pts = [p for p in placed] + [np.array([[s[0], s[1]], [s[2], s[3]]]) for s in sheets]
    allp = np.vstack(pts) if pts else np.zeros((1, 2))
    lo, hi = allp.min(axis=0), allp.max(axis=0)
    pad = 0.02 * float(max(hi - lo)) + 1.0
    lo, hi = lo - pad, hi + pad
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
    for x0, y0, x1, y1, label in sheets:
        out.append(f'<rect class="sheet" x="{x0 - lo[0]:.6f}" y="{hi[1] - y1:.6f}" '
                   f'width="{x1 - x0:.6f}" height="{y1 - y0:.6f}"/>')
        out.append(f'<text x="{x0 - lo[0]:.3f}" y="{hi[1] - y1 - 5:.3f}" '
                   f'font-size="{0.02 * (y1 - y0):.3f}">{escape(label)}</text>')
    for f, cut, pl in zip(flat, placed, placements):
        th = _arrange.text_height(f.outline)
        out.append(f'<g id="{escape(f.id)}">')
        out.append('<polygon class="cut" points="' + " ".join(xy(p) for p in cut) + '"/>')
        for a, b, signed in f.folds:
            pa, pb = _arrange.transform([f.outline[a], f.outline[b]], *pl)
            out.append(f'<line class="fold" x1="{pa[0] - lo[0]:.6f}" y1="{hi[1] - pa[1]:.6f}" '
                       f'x2="{pb[0] - lo[0]:.6f}" y2="{hi[1] - pb[1]:.6f}">'
                       f"<title>{escape(fold_text(signed))}</title></line>")
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
    return {"path": str(path), "panels": len(flat), "sheets": len(sheets), "kerf": kerf}
