"""DXF export of flat panels for CAM (ezdxf).

    s = tessella.export_dxf(flat, "panels.dxf", layout=layout)
    s["paths"]              # panels_sheet01.dxf, panels_sheet02.dxf, ... (one per sheet)
    s["segments_per_part"]  # {"max", "mean", "min", "total"}: cut-path segments (an arc = 1)

Defaults are what a CAM operator imports (see docs/fabrication.md, "DXF and SVG"):

- `per_sheet` (default: True when a nesting layout is given): one file per sheet,
  named <stem>_sheetNN.dxf, with the origin at the sheet's lower-left corner and
  all geometry inside [0, W] x [0, H]; False: one drawing, sheets side by side.
  Without a layout there are no sheets: one drawing, the panels in rows.
- `blocks` (default False): exploded geometry, every part transformed to its place
  on the sheet; True: one block per part (a safe, unique block name derived from
  the ID) inserted with its rotation.
- `cut_path` "nominal" (default: the CAM applies its own kerf compensation) or
  "compensated" (the outline grown by kerf/2): exactly one closed LWPOLYLINE per part
  on layer CUT. `reference=True` also writes the other one on REFERENCE (not
  plotted, never cut).
- cut paths: `simplify_tolerance` (default 1e-3 mm) removes collinear points and
  sub-micron jogs (no point is moved, corners stay); `arcs` (default True) fits
  runs of points along curved trim edges with arcs (LWPOLYLINE bulges) within
  `chord_tolerance` (default 0.05 mm) of the polyline; arcs=False: polylines.
- layers: CUT (cut paths only), FOLD (fold LINEs only, exact angle as XDATA
  TESSELLA: "fold", a, b, signed degrees), LABEL (the part ID as typed, the
  orientation arrow along the surface's u direction, the fold texts "V 12.3456°" /
  "M ...", sheet captions), ENGRAVE (the ID and arrow instead, with
  id_layer="ENGRAVE"), SHEET_REF (the sheet frame, not plotted), REFERENCE.
  Every CUT polyline carries XDATA TESSELLA: "part", its index, its ID.

Units: millimetres ($INSUNITS = 4, $MEASUREMENT = 1).
"""

import hashlib
import math
import os
import re

import numpy as np

from ..fabrication import cut_outline
from . import _arrange
from . import cut_path as cp

APPID = "TESSELLA"
LAYERS = {"CUT": 1, "FOLD": 5, "LABEL": 7, "ENGRAVE": 3, "REFERENCE": 8, "SHEET_REF": 9}
NON_PLOTTING = ("REFERENCE", "SHEET_REF")
CUT_PATHS = ("nominal", "compensated")
ID_LAYERS = ("LABEL", "ENGRAVE")
MAX_BLOCK_NAME = 64
_UNSAFE = re.compile(r"[^A-Za-z0-9_.-]+")


def check_ids(ids):
    """Every ID a user can type is accepted; an empty ID or one with a control character
    (a DXF text cannot hold it) is a ValueError."""
    for i, pid in enumerate(ids):
        if not isinstance(pid, str) or not pid:
            raise ValueError(f"panel {i} has no ID ({pid!r}): every panel needs a non-empty ID")
        bad = [c for c in pid if ord(c) < 32 or ord(c) == 127]
        if bad:
            raise ValueError(f"panel ID {pid!r} holds a control character ({bad[0]!r}); "
                             "a DXF text cannot show it")


def block_names(ids):
    """A deterministic, unique, DXF-safe block name per ID (input order).

    An ID made of letters, digits, '_', '.', '-' (at most 64 characters) is its own
    name; any other is reduced to those characters (runs of others become '_',
    ASCII only, at most 64) plus '_' and 8 hex digits of its SHA-1. Names are
    compared without case (DXF table names are case-insensitive); a repeat gets
    '_2', '_3', ...
    """
    used, out = set(), []
    for pid in ids:
        base = _UNSAFE.sub("_", pid)
        if base != pid or len(base) > MAX_BLOCK_NAME:
            digest = hashlib.sha1(pid.encode("utf-8")).hexdigest()[:8]
            base = f"{base.strip('_')[:MAX_BLOCK_NAME - 9] or 'PART'}_{digest}"
        name, n = base, 1
        while name.lower() in used:
            n += 1
            name = f"{base}_{n}"
        used.add(name.lower())
        out.append(name)
    return out


def _id_xdata(index, pid):
    # XDATA strings are limited to 255 bytes: the ID in pieces of at most 60 characters
    pieces = [pid[k:k + 60] for k in range(0, len(pid), 60)]
    return [(1000, "part"), (1071, int(index))] + [(1000, s) for s in pieces]


def id_from_xdata(tags):
    """The part index and ID stored on a CUT polyline (inverse of what export_dxf writes)."""
    tags = list(tags)
    index = [v for c, v in tags if c == 1071][0]
    strings = [v for c, v in tags if c == 1000]
    return int(index), "".join(strings[1:])


def _sheet_file(path, s, count):
    root, ext = os.path.splitext(str(path))
    width = max(2, len(str(count)))
    return f"{root}_sheet{s + 1:0{width}d}{ext or '.dxf'}"


def _keep_indices(f, n_points):
    """Outline indices that must stay vertices of the cut path: a curved patch's
    corners (a flat panel's corners are kept where its outline turns: fold ends along
    a curved trim edge may lie on an arc, within the chord tolerance)."""
    keep = set(getattr(f, "corner_index", []) or [])
    return sorted(k for k in keep if 0 <= k < n_points)


def _readable(rot):
    rot = (rot + 180.0) % 360.0 - 180.0
    if rot > 90:
        rot -= 180
    elif rot < -90:
        rot += 180
    return rot


class _Drawing:
    """One DXF document being written (layers, blocks, extents)."""

    def __init__(self, layers):
        import ezdxf
        from ezdxf import units

        self.doc = ezdxf.new("R2010")
        self.doc.units = units.MM
        self.doc.header["$MEASUREMENT"] = 1
        self.doc.appids.new(APPID)
        for name in layers:
            layer = self.doc.layers.add(name, color=LAYERS[name])
            if name in NON_PLOTTING:
                layer.dxf.plot = 0
        self.msp = self.doc.modelspace()
        self.lo = np.array([math.inf, math.inf])
        self.hi = -self.lo

    def grow(self, pts):
        pts = np.atleast_2d(np.asarray(pts, dtype=float))
        self.lo = np.minimum(self.lo, pts.min(axis=0))
        self.hi = np.maximum(self.hi, pts.max(axis=0))

    def save(self, path, extents=None):
        lo, hi = (extents if extents is not None else (self.lo, self.hi))
        if np.all(np.isfinite(lo)):
            self.doc.header["$EXTMIN"] = (float(lo[0]), float(lo[1]), 0.0)
            self.doc.header["$EXTMAX"] = (float(hi[0]), float(hi[1]), 0.0)
        self.doc.saveas(path)


def _place(pts, place):
    return _arrange.transform(pts, *place) if place is not None else np.asarray(pts, dtype=float)


def _write_part(dw, layout_space, f, index, name, cut, ref, place, opts):
    """Write one part: into a block (inserted at `place`) or exploded (transformed)."""
    from ezdxf.enums import TextEntityAlignment

    x, y, angle = place
    if opts["blocks"]:
        target = dw.doc.blocks.new(name=name)
        local = None  # geometry in the part's own frame
        text_rot = 0.0
    else:
        target = layout_space
        local = (x, y, angle)
        text_rot = angle
    path = cut if local is None else cut.transformed(*local)
    e = target.add_lwpolyline(path.lwpolyline_points(), format="xyseb", close=True,
                              dxfattribs={"layer": "CUT"})
    e.set_xdata(APPID, _id_xdata(index, f.id))
    if ref is not None:
        rpath = ref if local is None else ref.transformed(*local)
        target.add_lwpolyline(rpath.lwpolyline_points(), format="xyseb", close=True,
                              dxfattribs={"layer": "REFERENCE"})
    world = cut.transformed(x, y, angle)
    dw.grow(world.points)
    outline = np.asarray(f.outline, dtype=float)
    h = _arrange.text_height(outline)
    for a, b, signed in getattr(f, "folds", []):
        pa, pb = _place(outline[[a, b]], local)
        line = target.add_line(tuple(map(float, pa)), tuple(map(float, pb)),
                               dxfattribs={"layer": "FOLD"})
        line.set_xdata(APPID, [(1000, "fold"), (1071, int(a)), (1071, int(b)),
                               (1040, float(signed))])
        mid = pa + 0.3 * (pb - pa)  # off the centre, where the ID goes
        rot = _readable(math.degrees(math.atan2(pb[1] - pa[1], pb[0] - pa[0])))
        t = target.add_text(_arrange.fold_text(signed), dxfattribs={
            "layer": "LABEL", "height": 0.6 * h, "rotation": rot})
        t.set_placement((float(mid[0]), float(mid[1])), align=TextEntityAlignment.BOTTOM_CENTER)
    id_layer = opts["id_layer"]
    width = float(np.ptp(outline[:, 0]))
    h_id = max(min(h, 0.8 * width / max(1.0, 0.6 * len(f.id))), 0.5)
    c = _place([_arrange.centroid(outline)], local)[0]
    t = target.add_text(_arrange.dxf_text(f.id), dxfattribs={"layer": id_layer, "height": h_id,
                                           "rotation": _readable(text_rot)})
    t.set_placement((float(c[0]), float(c[1])), align=TextEntityAlignment.MIDDLE_CENTER)
    for p0, p1 in _arrange.grain_arrow(outline, f.u_direction):
        q0, q1 = _place([p0, p1], local)
        target.add_line(tuple(map(float, q0)), tuple(map(float, q1)),
                        dxfattribs={"layer": id_layer})
    if opts["blocks"]:
        layout_space.add_blockref(name, (float(x), float(y)), dxfattribs={"rotation": float(angle)})


def _stats(values):
    v = np.asarray(values, dtype=float)
    if len(v) == 0:
        return {"max": 0, "mean": 0.0, "min": 0, "total": 0}
    return {"max": int(v.max()), "mean": float(v.mean()), "min": int(v.min()), "total": int(v.sum())}


def export_dxf(flat, path, layout=None, kerf=0.0, *, per_sheet=None, blocks=False,
               cut_path="nominal", reference=False, arcs=True,
               chord_tolerance=cp.DEFAULT_CHORD_TOLERANCE,
               simplify_tolerance=cp.DEFAULT_SIMPLIFY_TOLERANCE, id_layer="LABEL"):
    """Write the flat panels (or flattened patches) as DXF R2010 for CAM.

    Options (keyword only) are described in the module docstring and in
    docs/fabrication.md. Returns a summary dict: paths (the files written), path
    (the path given), panels, sheets, kerf, cut_path, segments (cut-path segments
    per part, input order; an arc counts once), segments_per_part (max/mean/min/
    total), arcs, raw_segments_per_part (the same for the unsimplified path),
    block_names (blocks=True).

    Raises ValueError for a negative kerf or tolerance, an unknown option value,
    per_sheet=True without a layout, a layout of a different panel list, and an
    empty panel ID or one with a control character.
    """
    if cut_path not in CUT_PATHS:
        raise ValueError(f"cut_path must be one of {CUT_PATHS}, got {cut_path!r}")
    if id_layer not in ID_LAYERS:
        raise ValueError(f"id_layer must be one of {ID_LAYERS}, got {id_layer!r}")
    if per_sheet is None:
        per_sheet = layout is not None
    elif per_sheet and layout is None:
        raise ValueError("per_sheet=True needs a nesting layout (there are no sheets without one)")
    chord_tolerance = cp._check_tolerance("chord_tolerance (mm)", chord_tolerance)
    simplify_tolerance = cp._check_tolerance("simplify_tolerance (mm)", simplify_tolerance)
    flat = list(flat)
    check_ids([getattr(f, "id", None) for f in flat])
    if layout is not None:
        kerf = _arrange.layout_kerf(layout, kerf)
    nominal = [np.asarray(f.outline, dtype=float) for f in flat]
    grown = [cut_outline(f, kerf) for f in flat]  # validates kerf
    placements, sheets = _arrange.arrange(flat, layout)
    names = block_names([f.id for f in flat])
    opts = {"blocks": bool(blocks), "id_layer": id_layer}

    def processed(points, f):
        keep = _keep_indices(f, len(points)) if len(points) == len(f.outline) else []
        return cp.make_cut_path(points, simplify_tolerance, chord_tolerance, bool(arcs), keep)

    cuts, refs = [], []
    for f, nom, gro in zip(flat, nominal, grown):
        main, other = (nom, gro) if cut_path == "nominal" else (gro, nom)
        cuts.append(processed(main, f))
        refs.append(processed(other, f) if reference else None)
    raw = [len(nom) if cut_path == "nominal" else len(gro) for nom, gro in zip(nominal, grown)]

    layers = ["CUT", "FOLD", "LABEL"]
    if id_layer == "ENGRAVE":
        layers.append("ENGRAVE")
    if reference:
        layers.append("REFERENCE")
    if sheets:
        layers.append("SHEET_REF")

    paths = []
    if per_sheet:
        # each part on the sheet the layout put its ID on, in sheet coordinates
        local = _arrange.sheet_placements(flat, layout)
        for s, (x0, y0, x1, y1, label) in enumerate(sheets):
            dw = _Drawing(layers)
            dw.doc.header.custom_vars.append("Sheet", label)
            for i, (sheet, x, y, angle) in enumerate(local):
                if sheet == s:
                    _write_part(dw, dw.msp, flat[i], i, names[i], cuts[i], refs[i],
                                (x, y, angle), opts)
            frame = dw.msp.add_lwpolyline([(0.0, 0.0), (x1 - x0, 0.0), (x1 - x0, y1 - y0),
                                           (0.0, y1 - y0)], close=True,
                                          dxfattribs={"layer": "SHEET_REF"})
            frame.set_xdata(APPID, [(1000, "sheet"), (1071, s), (1000, label[:200])])
            p = _sheet_file(path, s, len(sheets))
            dw.save(p, extents=((0.0, 0.0), (x1 - x0, y1 - y0)))
            paths.append(p)
    else:
        dw = _Drawing(layers)
        for i, f in enumerate(flat):
            _write_part(dw, dw.msp, f, i, names[i], cuts[i], refs[i], placements[i], opts)
        for s, (x0, y0, x1, y1, label) in enumerate(sheets):
            frame = dw.msp.add_lwpolyline([(x0, y0), (x1, y0), (x1, y1), (x0, y1)], close=True,
                                          dxfattribs={"layer": "SHEET_REF"})
            frame.set_xdata(APPID, [(1000, "sheet"), (1071, s), (1000, label[:200])])
            dw.msp.add_text(label, dxfattribs={"layer": "LABEL", "height": 0.02 * (y1 - y0),
                                               "insert": (x0, y1 + 0.01 * (y1 - y0))})
            dw.grow([(x0, y0), (x1, y1 + 0.03 * (y1 - y0))])
        dw.save(str(path))
        paths.append(str(path))

    segments = [c.segment_count for c in cuts]
    summary = {
        "path": str(path), "paths": paths, "panels": len(flat), "sheets": len(sheets),
        "kerf": kerf, "cut_path": cut_path, "per_sheet": bool(per_sheet), "blocks": bool(blocks),
        "segments": segments, "segments_per_part": _stats(segments),
        "arcs": int(sum(c.arc_count for c in cuts)), "raw_segments_per_part": _stats(raw),
    }
    if blocks:
        summary["block_names"] = names
    return summary


def export_family_dxf(flat, result, families, path, **options):
    """Write one template per panel family (its unfolded template panel,
    labelled with the family name PF-001, ...) and, below the drawing on layer
    LABEL, the list of each family's members (freecad_workbench.families).

    `flat`: the result's unfolded panels (fabrication.unfold(result));
    `families`: tessella.panel_families(result, ...). Options as export_dxf
    (keyword only; no layout: templates are drawn in rows; nest every panel
    cut to its template with fabrication.nest_families). Returns export_dxf's
    summary plus "families" and "member_lines"."""
    import ezdxf

    from ..families import members_lines, template_parts

    if options.get("layout") is not None or options.get("per_sheet"):
        raise ValueError("the family templates are drawn without a layout: nest the panels "
                         "by family with fabrication.nest_families and export_dxf")
    options.pop("layout", None)
    parts = template_parts(flat, result, families)
    summary = export_dxf(parts, path, **options)
    lines = members_lines(result, families)
    doc = ezdxf.readfile(str(path))
    lo, hi = doc.header.get("$EXTMIN", (0, 0, 0)), doc.header.get("$EXTMAX", (0, 0, 0))
    width = max(float(hi[0]) - float(lo[0]), 1.0)
    height = min(max(0.008 * width, 20.0), 200.0)
    y = float(lo[1]) - 2.0 * height
    msp = doc.modelspace()
    for line in lines:
        msp.add_text(line, dxfattribs={"layer": "LABEL", "height": height,
                                       "insert": (float(lo[0]), y)})
        y -= 1.6 * height
    doc.header["$EXTMIN"] = (float(lo[0]), y, 0.0)
    doc.saveas(str(path))
    summary.update(families=len(parts), member_lines=len(lines))
    return summary
