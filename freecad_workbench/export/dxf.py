"""DXF export of flat panels (ezdxf): layers CUT, FOLD, LABEL (+ OUTLINE, SHEET).

    tessella.export_dxf(flat, "panels.dxf", layout=layout, kerf=0.0)

One block per panel (named by its ID) holding, in the panel's own flat frame:
CUT - the closed cutter path (the outline grown by kerf/2; the outline itself
for kerf 0); OUTLINE - the nominal outline when kerf > 0; FOLD - one line per
fold diagonal plus a text "V 12.3456°" (V = valley, M = mountain seen from the
front) and the exact angle as XDATA (appid TESSELLA: a, b, signed degrees);
LABEL - the panel ID and an arrow along the surface's u direction (orientation
mark). Each block is inserted once: on its sheet when a nesting layout is given
(sheets side by side along x, outlined on layer SHEET), else in simple rows.
Units: millimetres ($INSUNITS = 4, $MEASUREMENT = 1).
"""

import math

from ..fabrication import cut_outline
from . import _arrange

APPID = "TESSELLA"
LAYERS = {"CUT": 1, "FOLD": 5, "LABEL": 7, "OUTLINE": 8, "SHEET": 3}


def fold_text(angle):
    return f"{'V' if angle > 0 else 'M'} {abs(angle):.4f}°"


def _layout_kerf(layout, kerf):
    """The kerf of a nested layout wins; a different non-zero kerf is an error (the
    cut paths were nested at the layout's kerf)."""
    if kerf and layout.kerf and abs(kerf - layout.kerf) > 1e-12:
        raise ValueError(f"kerf {kerf} differs from the kerf the layout was nested with "
                         f"({layout.kerf}): nest again with kerf={kerf}")
    if kerf and not layout.kerf:
        raise ValueError(f"the layout was nested without kerf: nest again with kerf={kerf}")
    return layout.kerf


def export_dxf(flat, path, layout=None, kerf=0.0):
    """Write the flat panels to `path` (DXF R2010). Returns a dict summary.

    Raises ValueError for a negative kerf or a layout of a different panel list.
    """
    import ezdxf
    from ezdxf import units

    flat = list(flat)
    if layout is not None:
        kerf = _layout_kerf(layout, kerf)
    cuts = [cut_outline(f, kerf) for f in flat]  # validates kerf
    placements, sheets = _arrange.arrange(flat, layout)

    doc = ezdxf.new("R2010")
    doc.units = units.MM
    doc.header["$MEASUREMENT"] = 1
    doc.appids.new(APPID)
    for name, color in LAYERS.items():
        doc.layers.add(name, color=color)
    msp = doc.modelspace()

    for f, cut, (x, y, angle) in zip(flat, cuts, placements):
        block = doc.blocks.new(name=f.id)
        block.add_lwpolyline([tuple(map(float, p)) for p in cut], close=True,
                             dxfattribs={"layer": "CUT"})
        if kerf > 0:
            block.add_lwpolyline([tuple(map(float, p)) for p in f.outline], close=True,
                                 dxfattribs={"layer": "OUTLINE"})
        h = _arrange.text_height(f.outline)
        for a, b, signed in f.folds:
            pa, pb = f.outline[a], f.outline[b]
            line = block.add_line(tuple(map(float, pa)), tuple(map(float, pb)),
                                  dxfattribs={"layer": "FOLD"})
            line.set_xdata(APPID, [(1000, "fold"), (1071, int(a)), (1071, int(b)),
                                   (1040, float(signed))])
            mid = 0.5 * (pa + pb)
            rot = math.degrees(math.atan2(pb[1] - pa[1], pb[0] - pa[0]))
            if rot > 90 or rot < -90:
                rot -= 180 if rot > 0 else -180
            block.add_text(fold_text(signed), dxfattribs={
                "layer": "FOLD", "height": 0.6 * h, "rotation": rot,
                "insert": (float(mid[0]), float(mid[1]))})
        c = _arrange.centroid(f.outline)
        block.add_text(f.id, dxfattribs={"layer": "LABEL", "height": h,
                                         "insert": (float(c[0]) - 0.3 * len(f.id) * h,
                                                    float(c[1]))})
        for p0, p1 in _arrange.grain_arrow(f.outline, f.u_direction):
            block.add_line(p0, p1, dxfattribs={"layer": "LABEL"})
        msp.add_blockref(f.id, (float(x), float(y)), dxfattribs={"rotation": float(angle)})

    for x0, y0, x1, y1, label in sheets:
        msp.add_lwpolyline([(x0, y0), (x1, y0), (x1, y1), (x0, y1)], close=True,
                           dxfattribs={"layer": "SHEET"})
        msp.add_text(label, dxfattribs={"layer": "SHEET", "height": 0.02 * (y1 - y0),
                                        "insert": (x0, y1 + 0.01 * (y1 - y0))})
    doc.saveas(path)
    return {"path": str(path), "panels": len(flat), "sheets": len(sheets), "kerf": kerf}
