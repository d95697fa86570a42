"""Sheets (issue 12, part 5): a part that fits no sheet is named together with
the smallest sheet that fits every part; the Unfold shows it as its Status
without a traceback; stock sheet sizes (each sheet the smallest that holds its
parts); the SVG lays sheets out in a grid. Sizes are checked with FreeCAD's own
bounding boxes of the rotated outlines, layouts read back from the SVG."""

import math
import os
import re
import subprocess
import sys
import xml.etree.ElementTree as ET

import FreeCAD  # noqa: F401  (before Part)
import numpy as np
import Part
import pytest

import freecad_workbench as tessella
from conftest import make_round_trimmed_face

SVG = {"s": "http://www.w3.org/2000/svg"}
ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


@pytest.fixture(scope="module")
def face():
    return make_round_trimmed_face()


@pytest.fixture(scope="module")
def flat(face):
    """A default-like 1.2 m grid: its boundary panels do not fit 2500 x 1250."""
    return tessella.unfold(tessella.panelize(face, method="iso_grid", size=1200.0))


@pytest.fixture(scope="module")
def fine(face):
    return tessella.unfold(tessella.panelize(face, method="iso_grid", size=700.0))


def wire(points):
    pts = [FreeCAD.Vector(float(x), float(y), 0) for x, y in points]
    return Part.makePolygon(pts + [pts[0]])


def boxes(outline, rotations):
    """FreeCAD's bounding box (width, height) of the outline turned by each allowed angle."""
    out = []
    for k in range(rotations):
        w = wire(outline)
        w.rotate(FreeCAD.Vector(0, 0, 0), FreeCAD.Vector(0, 0, 1), 360.0 * k / rotations)
        bb = w.BoundBox
        out.append((bb.XLength, bb.YLength))
    return out


def fits(outline, width, height, margin, rotations):
    return any(w + 2 * margin <= width and h + 2 * margin <= height
               for w, h in boxes(outline, rotations))


def suggested(message):
    m = re.search(r"the smallest sheet that fits every part is (\d+) x (\d+) mm", message)
    assert m, message
    return float(m.group(1)), float(m.group(2))


# ------------------------------------------------------------ the message

@pytest.mark.parametrize("margin, rotations", [(10.0, 4), (25.0, 1), (10.0, 8)])
def test_a_part_that_fits_no_sheet_is_named_with_the_smallest_sheet(flat, margin, rotations):
    with pytest.raises(ValueError) as err:
        tessella.nest(flat, 2500, 1250, margin=margin, rotations=rotations)
    msg = str(err.value)
    named = msg.split(" (")[0]
    too_big = [f.id for f in flat if not fits(f.outline, 2500, 1250, margin, rotations)]
    assert too_big and named == too_big[0], msg  # the first part that fits nowhere
    assert "2500 x 1250 mm" in msg and f"margin {margin:g} mm" in msg
    if len(too_big) > 1:
        assert f"and {len(too_big) - 1} more part" in msg
    w, h = suggested(msg)
    assert (w, h) == tessella.smallest_sheet(flat, margin=margin, rotations=rotations)
    # every part fits the suggestion (FreeCAD's boxes) and the nesting takes it ...
    assert all(fits(f.outline, w, h, margin, rotations) for f in flat)
    lay = tessella.nest(flat, w, h, margin=margin, rotations=rotations)
    assert lay.sheet_count >= 1
    # ... a millimetre less either way does not fit ...
    assert not all(fits(f.outline, w - 1, h, margin, rotations) for f in flat)
    assert not all(fits(f.outline, w, h - 1, margin, rotations) for f in flat)
    with pytest.raises(ValueError, match="does not fit"):
        tessella.nest(flat, w - 1, h, margin=margin, rotations=rotations)
    # ... and no whole-mm sheet of less area fits every part (brute force)
    all_boxes = [boxes(f.outline, rotations) for f in flat]
    widths = sorted({math.ceil(bw + 2 * margin) for b in all_boxes for bw, _ in b})
    heights = sorted({math.ceil(bh + 2 * margin) for b in all_boxes for _, bh in b})
    best = min(W * H for W in widths for H in heights
               if all(any(bw + 2 * margin <= W and bh + 2 * margin <= H for bw, bh in b)
                      for b in all_boxes))
    assert w * h == best


def test_stock_sizes_that_fit_no_part_name_it_and_the_sheet(flat):
    with pytest.raises(ValueError) as err:
        tessella.nest(flat, stock_sizes=[(2500, 1250), (2000, 1000)])
    msg = str(err.value)
    assert "any stock size (2000 x 1000, 2500 x 1250 mm)" in msg
    assert suggested(msg) == tessella.smallest_sheet(flat)


def test_bad_stock_sizes(flat):
    for bad, match in (([], "empty"), ([(0, 100)], "width"), ([(100,)], "width, height"),
                       ("abc", "width, height"), ([(3000, "x")], "height"),
                       ([(3000, 15)], "margin"), (12, "list")):
        with pytest.raises(ValueError, match=match):
            tessella.nest(flat, stock_sizes=bad)


# ------------------------------------------------------------ stock sizes

def check_sheets(parts, lay):
    """Every part on a sheet of the layout's own size, inside the margin, no two
    parts on one sheet closer than the spacing (FreeCAD distances)."""
    by_id = {f.id: f for f in parts}
    on = {}
    for j, pid in enumerate(lay.ids):
        s = lay.placements[j].sheet
        w, h = lay.sheet_size(s)
        pts = lay.placed_outline(j)
        # the placed outline is the part's outline moved rigidly
        l2 = np.linalg.norm(np.roll(pts, -1, axis=0) - pts, axis=1)
        assert np.allclose(l2, by_id[pid].edge_lengths, atol=1e-6)
        assert pts[:, 0].min() >= lay.margin - 1e-6 and pts[:, 0].max() <= w - lay.margin + 1e-6
        assert pts[:, 1].min() >= lay.margin - 1e-6 and pts[:, 1].max() <= h - lay.margin + 1e-6
        on.setdefault(s, []).append(wire(pts))
    assert sorted(on) == list(range(lay.sheet_count))
    for wires in on.values():
        for a in range(len(wires)):
            for b in range(a + 1, len(wires)):
                assert wires[a].distToShape(wires[b])[0] >= lay.spacing - 1e-3
    return on


def test_each_sheet_takes_the_smallest_stock_size_its_parts_need(fine):
    stock = [(3000, 1500), (1250, 1000), (2500, 1250)]
    lay = tessella.nest(fine, stock_sizes=stock)
    again = tessella.nest(fine, stock_sizes=stock)
    assert again.placements == lay.placements and again.sheet_sizes == lay.sheet_sizes
    assert len(lay.sheet_sizes) == lay.sheet_count
    assert all(s in [(3000.0, 1500.0), (1250.0, 1000.0), (2500.0, 1250.0)] for s in lay.sheet_sizes)
    # a few small parts: their one sheet shrinks to the smallest stock size holding them
    few = sorted(fine, key=lambda f: f.area)[:2]
    small = tessella.nest(few, stock_sizes=stock)
    if all(fits(p.outline, 1250, 1000, small.margin, small.rotations) for p in few) and \
            tessella.nest(few, 1250, 1000).sheet_count == 1:
        assert small.sheet_sizes == [(1250.0, 1000.0)]
    on = check_sheets(fine, lay)
    by_id = {f.id: f for f in fine}
    for s in range(lay.sheet_count):
        w, h = lay.sheet_size(s)
        parts = [by_id[lay.ids[j]] for j in lay.on_sheet(s)]
        area = sum(Part.Face(wire(p.outline)).Area for p in parts)
        assert lay.sheet_utilization[s] == pytest.approx(area / (w * h), rel=1e-9)
        for sw, sh in stock:  # no smaller stock size holds this sheet's parts on one sheet
            if sw * sh >= w * h:
                continue
            if all(fits(p.outline, sw, sh, lay.margin, lay.rotations) for p in parts):
                assert tessella.nest(parts, sw, sh).sheet_count > 1
    total = sum(Part.Face(wire(f.outline)).Area for f in fine)
    assert lay.utilization == pytest.approx(total / sum(w * h for w, h in lay.sheet_sizes))
    assert len(on) == lay.sheet_count


def test_parts_that_fit_only_one_stock_size_go_on_that_size(fine):
    def rect(pid, w, h):
        return tessella.FlatPanel(id=pid, outline=np.array([[0, 0], [w, 0], [w, h], [0, h]], float))

    parts = [rect(f"LONG-{k}", 2900, 300) for k in range(3)]
    parts += [rect(f"SQUARE-{k}", 1500, 1450) for k in range(2)]
    parts += list(fine[:6])
    lay = tessella.nest(parts, stock_sizes=[(3000, 800), (2000, 2000)])
    check_sheets(parts, lay)
    for j, pid in enumerate(lay.ids):
        size = lay.sheet_size(lay.placements[j].sheet)
        if pid.startswith("LONG"):
            assert size == (3000.0, 800.0)
        if pid.startswith("SQUARE"):
            assert size == (2000.0, 2000.0)


# ------------------------------------------------------------ the SVG grid

def test_svg_lays_sheets_out_in_a_grid_of_their_own_sizes(fine, tmp_path):
    lay = tessella.nest(fine, stock_sizes=[(1400, 1000), (1600, 1250)])
    assert lay.sheet_count >= 9
    path = str(tmp_path / "grid.svg")
    info = tessella.export_svg(fine[::-1], path, layout=lay)
    root = ET.parse(path).getroot()
    width = float(root.get("width").rstrip("m"))
    height = float(root.get("height").rstrip("m"))
    assert (width, height) == pytest.approx((info["width_mm"], info["height_mm"]), abs=1e-3)
    assert 1.0 <= width / height <= 2.0, (width, height)  # about A landscape, not one row
    rects = [(float(r.get("x")), float(r.get("y")), float(r.get("width")),
              float(r.get("height"))) for r in root.findall("s:rect", SVG)]
    assert len(rects) == lay.sheet_count
    assert [(w, h) for _, _, w, h in rects] == pytest.approx(lay.sheet_sizes)
    assert len({round(r[0]) for r in rects}) > 1 and len({round(r[1]) for r in rects}) > 1
    for a in range(len(rects)):  # frames apart
        for b in range(a + 1, len(rects)):
            xa, ya, wa, ha = rects[a]
            xb, yb, wb, hb = rects[b]
            assert xa + wa < xb or xb + wb < xa or ya + ha < yb or yb + hb < ya
    first = rects[0]  # sheet 1 top left
    assert first[0] == min(r[0] for r in rects) and first[1] == min(r[1] for r in rects)
    for g in root.findall("s:g", SVG):
        pid = g.get("data-id")
        j = lay.index(pid)
        x, y, w, h = rects[lay.placements[j].sheet]
        pts = np.array([[float(v) for v in p.split(",")]
                        for p in g.find("s:polygon", SVG).get("points").split()])
        local = np.column_stack([pts[:, 0] - x, (y + h) - pts[:, 1]])
        assert np.allclose(local, lay.placed_outline(j), atol=1e-5), pid


def test_dxf_sheet_frames_have_each_sheets_size(fine, tmp_path):
    import ezdxf

    lay = tessella.nest(fine, stock_sizes=[(1400, 1000), (1600, 1250)])
    path = str(tmp_path / "frames.dxf")
    tessella.export_dxf(fine, path, layout=lay, per_sheet=False)
    msp = ezdxf.readfile(path).modelspace()
    frames = []
    for e in msp.query("LWPOLYLINE"):
        if e.dxf.layer == "CUT":
            continue
        pts = np.array([(x, y) for x, y, *_ in e.get_points()])
        if len(pts) == 4:
            frames.append(tuple(np.round(pts.max(axis=0) - pts.min(axis=0), 6)))
    assert sorted(frames) == sorted(tuple(map(float, s)) for s in lay.sheet_sizes)


# ------------------------------------------------------------ the Unfold object

def test_unfold_stock_sizes_and_status(face, tmp_path):
    doc = FreeCAD.newDocument("TessellaSheets")
    try:
        src = doc.addObject("Part::Feature", "Roof")
        src.Shape = face
        doc.recompute()
        p = tessella.make_panelization((src, "Face1"), method="iso_grid", size=1200.0)
        # the default sheet is too small for this grid's boundary panels: make_unfold
        # refuses, naming the part and the sheet that fits
        with pytest.raises(ValueError, match="smallest sheet that fits every part is"):
            tessella.make_unfold(p, nest=True)
        u = tessella.make_unfold(p, nest=True, stock_sizes=[(2500, 1250), (3000, 1500),
                                                             (4000, 2000)])
        assert list(u.StockSizes) == ["2500 x 1250", "3000 x 1500", "4000 x 2000"]
        assert u.Status == "OK" and u.SheetCount == len(u.SheetSizes) >= 1
        _res, flat, lay = u.Proxy.compute(u)
        assert list(u.SheetSizes) == [f"{w:g} x {h:g}" for w, h in lay.sheet_sizes]
        assert set(u.SheetSizes) <= {"2500 x 1250", "3000 x 1500", "4000 x 2000"}
        tessella.export_unfold(u, str(tmp_path / "u.svg"))
        rects = ET.parse(str(tmp_path / "u.svg")).getroot().findall("s:rect", SVG)
        assert [(float(r.get("width")), float(r.get("height"))) for r in rects] == lay.sheet_sizes
        # typed entries
        u.StockSizes = ["3000x1500 mm", "4000 × 2000"]
        doc.recompute()
        assert u.Status == "OK" and set(u.SheetSizes) <= {"3000 x 1500", "4000 x 2000"}
        u.StockSizes = ["3000 by 1500"]
        doc.recompute()
        assert u.isValid() and "StockSizes[0] '3000 by 1500'" in u.Status and u.SheetCount == 0
        # back to one sheet, too small: the Status names the part and the sheet
        u.StockSizes = []
        doc.recompute()
        assert u.isValid() and u.SheetCount == 0 and len(u.Shape.childShapes()) == p.PanelCount
        w, h = suggested(u.Status)
        assert (w, h) == tessella.smallest_sheet(flat)
        with pytest.raises(ValueError, match="does not fit"):
            tessella.export_unfold(u, str(tmp_path / "v.svg"))
        u.SheetWidth, u.SheetHeight = w, h
        doc.recompute()
        assert u.Status == "OK" and u.SheetCount >= 1
    finally:
        FreeCAD.closeDocument(doc.Name)


SCRIPT = """
import sys
sys.path.insert(0, {root!r})
import FreeCAD, Part
import freecad_workbench as tessella
doc = FreeCAD.newDocument("NoTraceback")
src = doc.addObject("Part::Feature", "Roof")
shape = Part.Shape()
shape.read({brep!r})
src.Shape = shape
doc.recompute()
p = tessella.make_panelization((src, "Face1"), method="iso_grid", size=1200.0)
u = tessella.make_unfold(p)
u.Nest = True
doc.recompute()
print("STATUS", u.isValid(), u.Status)
"""


def test_unfold_reports_a_sheet_that_is_too_small_without_a_traceback(face, tmp_path):
    brep = str(tmp_path / "roof.brep")
    face.exportBrep(brep)
    script = tmp_path / "run.py"
    script.write_text(SCRIPT.format(root=ROOT, brep=brep))
    cmd = "/usr/bin/freecadcmd"
    if not os.path.exists(cmd):
        pytest.skip("freecadcmd is not installed")
    out = subprocess.run([cmd, str(script)], capture_output=True, text=True, timeout=300,
                         cwd=str(tmp_path), env=dict(os.environ, PYTHONPATH=""))
    text = out.stdout + out.stderr
    assert "STATUS True Not nested: " in text, text[-3000:]
    assert "smallest sheet that fits every part" in text
    assert "Traceback" not in text, text[-3000:]
    # the report line: one line naming the object and the fitting sheet
    lines = [ln for ln in text.splitlines() if ln.startswith("Tessella: Unfold")]
    assert len(lines) == 1 and "smallest sheet that fits every part" in lines[0], text[-3000:]
    assert sys.executable  # the test process itself is unaffected
