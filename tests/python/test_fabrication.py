"""Fabrication output: unfold, nest, DXF/SVG. Every figure is checked against the
3D panels with formulas written here (numpy), the DXF is read back with ezdxf and
the nesting is checked with FreeCAD's own geometry (Part wires, distToShape)."""

import math
import os
import re
import xml.etree.ElementTree as ET

import FreeCAD  # noqa: F401  (before Part)
import Part
import numpy as np
import pytest

import freecad_workbench as tessella

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
EXAMPLES = os.path.join(REPO, "examples")


def load_face(name):
    shape = Part.Shape()
    shape.read(os.path.join(EXAMPLES, name + ".brep"))
    return shape.Faces[0]


@pytest.fixture(scope="module")
def freeform(freeform_face):
    r = tessella.panelize(freeform_face, method="equal_size_grid", size=1000.0)
    return r, tessella.unfold(r)


@pytest.fixture(scope="module")
def saddle():
    """Bent quads: a hyperbolic paraboloid z = xy/4000 on a 4000 x 4000 square."""
    pts = [[FreeCAD.Vector(x, y, x * y / 4000.0) for y in (-2000, 2000)] for x in (-2000, 2000)]
    s = Part.BezierSurface()
    s.increase(1, 1)
    for i in range(2):
        for j in range(2):
            s.setPole(i + 1, j + 1, pts[i][j])
    r = tessella.panelize(s.toShape(), method="iso_grid", u_count=5, v_count=4)
    return r, tessella.unfold(r)


def dihedral_quad(p, diag):
    """Angle (deg) between the planes of the two triangles of quad p split along diag."""
    if diag == (0, 2):
        t1, t2 = (0, 1, 2), (0, 2, 3)
    else:
        t1, t2 = (1, 2, 3), (1, 3, 0)

    def normal(t):
        n = np.cross(p[t[1]] - p[t[0]], p[t[2]] - p[t[0]])
        return n / np.linalg.norm(n)

    c = float(np.clip(np.dot(normal(t1), normal(t2)), -1.0, 1.0))
    return math.degrees(math.acos(c))


def check_flat_against_3d(r, flat, tol=1e-9):
    assert len(flat) == len(r.panels)
    assert [f.id for f in flat] == r.panel_ids
    for f, panel in zip(flat, r.panels):
        p = r.vertices[list(panel)]
        k = len(panel)
        assert f.outline.shape == (k, 2)
        l3 = np.linalg.norm(np.roll(p, -1, axis=0) - p, axis=1)
        l2 = np.linalg.norm(np.roll(f.outline, -1, axis=0) - f.outline, axis=1)
        assert np.max(np.abs(l3 - l2)) < tol * max(1.0, l3.max()), f.id
        for a, b, _ in f.folds:  # fold lines keep their 3D length too
            assert abs(np.linalg.norm(f.outline[a] - f.outline[b]) - np.linalg.norm(p[a] - p[b])) < 1e-6
        if k == 4:
            d02, d13 = dihedral_quad(p, (0, 2)), dihedral_quad(p, (1, 3))
            smaller = min(d02, d13)
            if smaller <= tessella.fabrication.DEFAULT_FOLD_TOLERANCE:
                assert f.fold is None and f.fold_angle == 0.0, f.id
            else:
                assert f.fold == ((0, 2) if d02 <= d13 else (1, 3)), f.id
                assert f.fold_angle == pytest.approx(smaller, abs=1e-7), f.id
                # valley seen from the front: the free diagonal's midpoint lies in
                # front of the fold's midpoint (front = the corner order's normal)
                a, b = f.fold
                c, d = [i for i in range(4) if i not in f.fold]
                n = np.cross(p[2] - p[0], p[3] - p[1])
                front = np.dot(0.5 * (p[c] + p[d]) - 0.5 * (p[a] + p[b]), n) > 0
                assert f.fold_valley == front, f.id
        if k <= 4:  # drawn counter-clockwise, seen from the front
            assert f.area > 0


def test_unfold_freeform_true_lengths(freeform):
    r, flat = freeform
    check_flat_against_3d(r, flat)
    assert any(f.fold for f in flat)


def test_unfold_saddle_folds(saddle):
    r, flat = saddle
    check_flat_against_3d(r, flat)
    assert all(len(p) == 4 for p in r.panels)
    assert all(f.fold is not None and f.fold_angle > 1.0 for f in flat)
    # Flat area of the two triangles = the area of the two 3D triangles.
    for f, panel in zip(flat, r.panels):
        p = r.vertices[list(panel)]
        a, b = f.fold
        c, d = [i for i in range(4) if i not in f.fold]
        area3 = 0.5 * (np.linalg.norm(np.cross(p[b] - p[a], p[c] - p[a]))
                       + np.linalg.norm(np.cross(p[b] - p[a], p[d] - p[a])))
        assert f.area == pytest.approx(area3, rel=1e-9)


def test_unfold_planar_panels_exact():
    r = tessella.panelize(load_face("plane"), method="iso_grid", size=700.0)
    flat = tessella.unfold(r)
    check_flat_against_3d(r, flat)
    for f, area in zip(flat, r.metrics["panel_area"]):
        assert f.fold is None and f.fold_angle == 0.0 and f.folds == []
        assert f.area == pytest.approx(area, rel=1e-9)


def test_unfold_rejects_bad_tolerance(saddle):
    r, _ = saddle
    with pytest.raises(ValueError, match="fold_tolerance"):
        tessella.unfold(r, fold_tolerance=-1)
    # a huge tolerance: no fold is drawn, the outline is the same
    flat = tessella.unfold(r, fold_tolerance=90)
    assert all(f.fold is None for f in flat)


# ---------------------------------------------------------------- nesting

SHEET = dict(sheet_width=3000.0, sheet_height=2000.0, margin=10.0, spacing=6.0, rotations=4)


@pytest.fixture(scope="module")
def layout(freeform):
    _, flat = freeform
    return tessella.nest(flat, **SHEET)


def wire(points):
    pts = [FreeCAD.Vector(float(x), float(y), 0) for x, y in points]
    return Part.makePolygon(pts + [pts[0]])


def inside(point, poly):
    """Even-odd point in polygon (numpy-free, independent of the core)."""
    x, y = point
    res = False
    n = len(poly)
    for i in range(n):
        (x1, y1), (x2, y2) = poly[i], poly[(i + 1) % n]
        if (y1 > y) != (y2 > y) and x < x1 + (y - y1) * (x2 - x1) / (y2 - y1):
            res = not res
    return res


def check_layout(flat, lay, kerf=0.0):
    n = len(flat)
    assert len(lay.placements) == n
    assert sorted(lay.ids) == sorted(f.id for f in flat) and len(set(lay.ids)) == n
    placed = [lay.placed_outline(i) for i in range(n)]
    margin = lay.margin
    for i, pts in enumerate(placed):
        s = lay.placements[i].sheet
        assert 0 <= s < lay.sheet_count
        assert pts[:, 0].min() >= margin - 1e-9 and pts[:, 1].min() >= margin - 1e-9
        assert pts[:, 0].max() <= lay.sheet_width - margin + 1e-9
        assert pts[:, 1].max() <= lay.sheet_height - margin + 1e-9
    assert {p.sheet for p in lay.placements} == set(range(lay.sheet_count))
    # No two parts on a sheet closer than the spacing (FreeCAD's distToShape), and
    # none inside another.
    wires = [wire(p) for p in placed]
    boxes = [(p.min(axis=0), p.max(axis=0)) for p in placed]
    for i in range(n):
        for j in range(i + 1, n):
            if lay.placements[i].sheet != lay.placements[j].sheet:
                continue
            (lo1, hi1), (lo2, hi2) = boxes[i], boxes[j]
            if np.any(lo1 > hi2 + lay.spacing) or np.any(lo2 > hi1 + lay.spacing):
                continue
            d = wires[i].distToShape(wires[j])[0]
            assert d >= lay.spacing - 1e-6, (lay.ids[i], lay.ids[j], d)
            assert not inside(placed[i][0], placed[j]) and not inside(placed[j][0], placed[i])
    # utilization recomputed from the outlines
    area = sum(abs(Part.Face(w).Area) for w in wires)
    assert lay.utilization == pytest.approx(
        area / (lay.sheet_count * lay.sheet_width * lay.sheet_height), rel=1e-6)


def test_nest_every_panel_once_inside_no_overlap(freeform, layout):
    _, flat = freeform
    check_layout(flat, layout)
    assert 0 < layout.utilization < 1


def test_nest_deterministic(freeform, layout):
    _, flat = freeform
    again = tessella.nest(flat, **SHEET)
    assert again.placements == layout.placements and again.sheet_count == layout.sheet_count


def test_nest_saddle_no_rotation_keeps_orientation(saddle):
    _, flat = saddle
    lay = tessella.nest(flat, sheet_width=2500, sheet_height=1250, margin=20, spacing=10,
                        rotations=1)
    check_layout(flat, lay)
    assert all(p.angle == 0.0 for p in lay.placements)


def test_nest_errors(saddle):
    _, flat = saddle
    with pytest.raises(ValueError, match="P-0001.*does not fit"):
        tessella.nest(flat, sheet_width=300, sheet_height=300)
    for bad in (dict(spacing=-1), dict(margin=-5), dict(sheet_width=-10), dict(rotations=0),
                dict(rotations=2.5), dict(kerf=-0.2), dict(sheet_height="x")):
        with pytest.raises(ValueError):
            tessella.nest(flat, **{**SHEET, **bad})


# ---------------------------------------------------------------- DXF / SVG

def read_dxf(path):
    import ezdxf

    doc = ezdxf.readfile(path)
    assert doc.header["$INSUNITS"] == 4  # millimetres
    for layer in ("CUT", "FOLD", "LABEL"):
        assert doc.layers.has_entry(layer)
    return doc


# The exact, inspectable form of the DXF (the CAM defaults differ: one file per sheet,
# exploded, simplified arc-fitted cut paths; tests/python/test_dxf_cam.py): one drawing,
# one block per panel, every outline point.
EXACT = dict(per_sheet=False, blocks=True, arcs=False, simplify_tolerance=0.0)


def check_dxf(path, r, flat, lay=None):
    doc = read_dxf(path)
    inserts = doc.modelspace().query("INSERT")
    names = [i.dxf.name for i in inserts]
    assert sorted(names) == sorted(r.panel_ids) and len(set(names)) == len(names)
    by_id = dict(zip(r.panel_ids, r.panels))
    from freecad_workbench.export import _arrange

    origins = _arrange.sheet_origins(lay) if lay else []  # sheets in a grid
    for ins in inserts:
        pid = ins.dxf.name
        p = r.vertices[list(by_id[pid])]
        block = doc.blocks[pid]
        cuts = [e for e in block if e.dxftype() == "LWPOLYLINE" and e.dxf.layer == "CUT"]
        assert len(cuts) == 1 and cuts[0].closed
        pts = np.array([(x, y) for x, y, *_ in cuts[0].get_points()])
        assert len(pts) == len(p)
        l3 = np.linalg.norm(np.roll(p, -1, axis=0) - p, axis=1)
        l2 = np.linalg.norm(np.roll(pts, -1, axis=0) - pts, axis=1)
        assert np.max(np.abs(l3 - l2)) < 1e-6, pid
        folds = [e for e in block if e.dxftype() == "LINE" and e.dxf.layer == "FOLD"]
        assert not [e for e in block if e.dxftype() == "TEXT" and e.dxf.layer == "FOLD"]
        texts = [e.dxf.text for e in block if e.dxftype() == "TEXT" and e.dxf.layer == "LABEL"]
        for line in folds:
            a, b = (int(v) for c, v in line.get_xdata("TESSELLA") if c == 1071)
            angle = [v for c, v in line.get_xdata("TESSELLA") if c == 1040][0]
            assert np.allclose([tuple(line.dxf.start)[:2], tuple(line.dxf.end)[:2]], [pts[a], pts[b]], atol=1e-9)
            assert abs(np.linalg.norm(pts[a] - pts[b]) - np.linalg.norm(p[a] - p[b])) < 1e-6
            if len(p) == 4:
                assert abs(abs(angle) - dihedral_quad(p, (a, b))) < 1e-6, pid
                assert f"{abs(angle):.4f}" in " ".join(texts)
        if len(p) == 4 and min(dihedral_quad(p, (0, 2)), dihedral_quad(p, (1, 3))) > tessella.fabrication.DEFAULT_FOLD_TOLERANCE:
            assert len(folds) == 1, pid
        labels = [t for t in texts if not re.match(r"^[VM] \d+\.\d{4}°$", t)]
        assert labels == [pid]
        assert any(e.dxftype() == "LINE" and e.dxf.layer == "LABEL" for e in block)  # mark
        if lay is not None:
            m = ins.matrix44()
            world = np.array([tuple(m.transform((x, y, 0)))[:2] for x, y in pts])
            sheet = lay.placements[r.panel_ids.index(pid)].sheet
            x0, y0 = origins[sheet]
            assert world[:, 0].min() >= x0 + lay.margin - 1e-6
            assert world[:, 0].max() <= x0 + lay.sheet_width - lay.margin + 1e-6
            assert world[:, 1].min() >= y0 + lay.margin - 1e-6
            assert world[:, 1].max() <= y0 + lay.sheet_height - lay.margin + 1e-6
    return doc


def test_dxf_reads_back_exactly_nested(tmp_path, freeform, layout):
    r, flat = freeform
    path = str(tmp_path / "panels.dxf")
    tessella.export_dxf(flat, path, layout=layout, kerf=0.0, **EXACT)
    doc = check_dxf(path, r, flat, layout)
    sheets = [e for e in doc.modelspace() if e.dxftype() == "LWPOLYLINE" and e.dxf.layer == "SHEET_REF"]
    assert len(sheets) == layout.sheet_count


def test_dxf_saddle_fold_angles(tmp_path, saddle):
    r, flat = saddle
    path = str(tmp_path / "saddle.dxf")
    tessella.export_dxf(flat, path, **EXACT)
    doc = check_dxf(path, r, flat)
    n_folds = sum(1 for e in doc.entitydb.values() if e.dxftype() == "LINE" and e.dxf.layer == "FOLD")
    assert n_folds == len(flat)


def test_dxf_kerf_offsets_the_cut(tmp_path, saddle):
    import ezdxf

    r, flat = saddle
    kerf = 0.4
    path = str(tmp_path / "kerf.dxf")
    lay = tessella.nest(flat, sheet_width=2500, sheet_height=1250, margin=10, spacing=6, kerf=kerf)
    check_layout(flat, lay, kerf)
    tessella.export_dxf(flat, path, layout=lay, cut_path="compensated", reference=True, **EXACT)
    doc = ezdxf.readfile(path)
    for f in flat:
        block = doc.blocks[f.id]
        cut = [e for e in block if e.dxftype() == "LWPOLYLINE" and e.dxf.layer == "CUT"][0]
        nominal = [e for e in block if e.dxftype() == "LWPOLYLINE" and e.dxf.layer == "REFERENCE"][0]
        wc = wire([(x, y) for x, y, *_ in cut.get_points()])
        wn = wire([(x, y) for x, y, *_ in nominal.get_points()])
        assert np.allclose([(x, y) for x, y, *_ in nominal.get_points()], f.outline, atol=1e-12)
        assert wc.distToShape(wn)[0] == pytest.approx(kerf / 2, abs=2e-4)
        assert Part.Face(wc).Area > Part.Face(wn).Area
    with pytest.raises(ValueError, match="kerf"):
        tessella.export_dxf(flat, path, kerf=-0.1)
    with pytest.raises(ValueError, match="differs"):  # cut paths nested at another kerf
        tessella.export_dxf(flat, path, layout=lay, kerf=0.5)
    with pytest.raises(ValueError, match="without kerf"):
        tessella.export_svg(flat, path, layout=tessella.nest(flat, 2500, 1250), kerf=0.5)


def test_svg(tmp_path, saddle):
    r, flat = saddle
    lay = tessella.nest(flat, sheet_width=2500, sheet_height=1250, margin=10, spacing=6)
    path = str(tmp_path / "panels.svg")
    tessella.export_svg(flat, path, layout=lay)
    root = ET.parse(path).getroot()
    ns = {"s": "http://www.w3.org/2000/svg"}
    groups = root.findall("s:g", ns)
    assert [g.get("id") for g in groups] == r.panel_ids
    for g, f in zip(groups, flat):
        poly = g.find("s:polygon", ns)
        pts = np.array([[float(v) for v in s.split(",")] for s in poly.get("points").split()])
        l2 = np.linalg.norm(np.roll(pts, -1, axis=0) - pts, axis=1)
        assert np.allclose(l2, f.edge_lengths, atol=1e-5)
        assert len(g.findall("s:line", ns)) == len(f.folds)
    assert len(root.findall("s:rect", ns)) == lay.sheet_count


# ---------------------------------------------------------------- curved patches

def test_flatten_cylinder_patch_is_developable():
    """A cylinder panel spanning 360/n degrees flattens to an R*2pi/n x h rectangle."""
    R, H, n, m = 3000.0, 2000.0, 12, 8
    face = Part.makeCylinder(R, H).Faces[0]
    r = tessella.panelize(face, method="iso_grid", u_count=n, v_count=2)
    patches = tessella.flatten(r, face, subdivisions=m)
    assert [p.id for p in patches] == r.panel_ids
    arc = m * 2 * R * math.sin(math.pi / n / m)  # the m chords of the subdivided arc
    for patch, panel in zip(patches, r.panels):
        assert patch.outline.shape == (4 * m, 2)
        assert patch.strain_max < 2e-3
        assert patch.area > 0 and patch.area == pytest.approx(patch.area_3d, rel=1e-9)
        # edge lengths: every outline segment keeps its 3D chord within the strain
        c = patch.corner_index
        for k in range(4):
            seg = patch.outline[c[k]:c[k] + m + 1] if k < 3 else np.vstack(
                [patch.outline[c[k]:], patch.outline[:1]])
            length = np.linalg.norm(np.diff(seg, axis=0), axis=1).sum()
            a, b = r.vertices[panel[k]], r.vertices[panel[(k + 1) % 4]]
            expect = H / 2 if abs(a[2] - b[2]) > 1 else arc
            assert length == pytest.approx(expect, rel=2e-3)


def test_flatten_sphere_reports_strain():
    face = Part.makeSphere(2000.0).Faces[0]
    r = tessella.panelize(face, method="iso_grid", u_count=12, v_count=8)
    patches = tessella.flatten(r, face, subdivisions=6)
    quads = [p for p, panel in zip(patches, r.panels) if len(panel) == 4]
    assert quads and all(1e-4 < p.strain_max < 0.2 for p in quads)
    assert all(p.area > 0 for p in patches)
    lay = tessella.nest(patches, sheet_width=3000, sheet_height=2000, margin=10, spacing=6)
    assert lay.ids == r.panel_ids and lay.sheet_count >= 1


def test_flatten_patches_to_dxf(tmp_path):
    import ezdxf

    R, H, n, m = 3000.0, 2000.0, 12, 4
    face = Part.makeCylinder(R, H).Faces[0]
    r = tessella.panelize(face, method="iso_grid", u_count=n, v_count=2)
    patches = tessella.flatten(r, face, subdivisions=m)
    lay = tessella.nest(patches, sheet_width=2500, sheet_height=1250, margin=10, spacing=6)
    path = str(tmp_path / "patches.dxf")
    tessella.export_dxf(patches, path, layout=lay, **EXACT)
    doc = ezdxf.readfile(path)
    for patch in patches:
        cut = [e for e in doc.blocks[patch.id] if e.dxftype() == "LWPOLYLINE" and e.dxf.layer == "CUT"][0]
        assert np.allclose([(x, y) for x, y, *_ in cut.get_points()], patch.outline, atol=1e-9)
        # the u direction of a cylinder runs around it: along the flat patch's hoop edges
        c = patch.corner_index
        hoop = [k for k in range(4) if abs(np.linalg.norm(
            patch.outline[c[(k + 1) % 4]] - patch.outline[c[k]]) - H / 2) > 1]
        e = patch.outline[c[(hoop[0] + 1) % 4]] - patch.outline[c[hoop[0]]]
        assert abs(abs(np.dot(e / np.linalg.norm(e), patch.u_direction)) - 1) < 1e-6
    with pytest.raises(ValueError, match="subdivisions"):
        tessella.flatten(r, face, subdivisions=0)
