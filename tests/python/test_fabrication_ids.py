"""Panel, rod and node IDs end to end (issue 12, part 3): the ID formats of a
result / Panelization reach unfold, nest, DXF, SVG, every schedule and the
structural export; a nesting layout is matched to its panels by ID; any ID a
user can type survives. The face is built here (not a bundled example): a
doubly curved B-spline patch trimmed by a circle, with a circular hole."""

import csv
import json
import re
import xml.etree.ElementTree as ET

import FreeCAD  # noqa: F401  (before Part)
import numpy as np
import Part
import pytest

import freecad_workbench as tessella
from conftest import make_round_trimmed_face
from freecad_workbench import api
from freecad_workbench.export import _arrange
from freecad_workbench.export import members as mx
from freecad_workbench.export import write_schedules

SVG = {"s": "http://www.w3.org/2000/svg"}
#: IDs with every character a DXF name, a file name or XML would choke on
AWKWARD = 'Dach/Süd:A*<1>?"|\\ ∑ é {:03d} ' + "x" * 120


@pytest.fixture(scope="module")
def face():
    return make_round_trimmed_face()


@pytest.fixture(scope="module")
def result(face):
    r = tessella.panelize(face, method="iso_grid", size=1200.0)
    r.panel_id_format = "ROOF-A-{:03d}"
    r.rod_id_format = "ROOF-R{:04d}"
    r.node_id_format = "ROOF-N{:04d}"
    return r


def expected(fmt, n):
    return [fmt.replace("{:03d}", f"{k:03d}").replace("{:04d}", f"{k:04d}")
            for k in range(1, n + 1)]


def read_csv(path):
    with open(path, newline="", encoding="utf-8") as f:
        return list(csv.reader(f))


# ------------------------------------------------------------ formats everywhere

def test_result_ids_follow_the_formats(result, tmp_path):
    r = result
    panels = expected("ROOF-A-{:03d}", len(r.panels))
    rods = expected("ROOF-R{:04d}", len(r.rods))
    nodes = expected("ROOF-N{:04d}", len(r.nodes))
    assert r.panel_ids == panels and r.rod_ids == rods and r.node_ids == nodes
    flat = tessella.unfold(r)
    assert [f.id for f in flat] == panels
    assert tessella.nest(flat, 4000, 2500).ids == panels
    # every schedule and the structural export
    paths = write_schedules(r, str(tmp_path), "roof")
    assert [row[0] for row in read_csv(paths["panels"])[1:]] == panels
    rod_rows = read_csv(paths["rods"])[1:]
    assert [row[0] for row in rod_rows] == rods
    assert {row[1] for row in rod_rows} | {row[2] for row in rod_rows} <= set(nodes)
    assert [row[0] for row in read_csv(paths["nodes"])[1:]] == nodes
    mx.write_panel_fabrication_schedule(r, flat, str(tmp_path / "fab.csv"))
    assert [row[0] for row in read_csv(tmp_path / "fab.csv")[1:]] == panels
    mx.write_rod_data(r, str(tmp_path / "rods.csv"))
    assert [row[0] for row in read_csv(tmp_path / "rods.csv")[1:]] == rods
    mx.write_cut_list(r, str(tmp_path / "cut.csv"))
    listed = sorted(i for row in read_csv(tmp_path / "cut.csv")[1:] for i in row[6].split(" "))
    assert listed == sorted(rods)
    mx.write_node_schedule(r, str(tmp_path / "hubs.csv"))
    hub_rows = read_csv(tmp_path / "hubs.csv")[1:]
    assert [row[0] for row in hub_rows] == nodes
    assert all(e.split("@")[0] in rods for row in hub_rows for e in row[9].split(" "))
    mx.write_structural_json(r, str(tmp_path / "frame.json"))
    frame = json.load(open(tmp_path / "frame.json", encoding="utf-8"))
    assert [n["id"] for n in frame["nodes"]] == nodes
    assert [e["id"] for e in frame["elements"]] == rods
    assert {i for e in frame["elements"] for i in e["nodes"]} <= set(nodes)
    s = tessella.buildability(r, flat=flat)
    assert s["panel_count"] == len(panels)


def test_panel_schedule_rows_are_found_by_id(result, tmp_path):
    flat = tessella.unfold(result)
    path = str(tmp_path / "fab.csv")
    mx.write_panel_fabrication_schedule(result, flat[::-1], path)
    rows = read_csv(path)[1:]
    area = dict(zip(result.panel_ids, result.metrics["panel_area"]))
    assert [row[0] for row in rows] == [f.id for f in flat[::-1]]
    for row in rows:  # the 3D area of the panel with that ID, not of the row's position
        assert float(row[5]) == float(area[row[0]])
    stranger = tessella.FlatPanel(id="NOT-A-PANEL", outline=flat[0].outline)
    with pytest.raises(ValueError, match="NOT-A-PANEL"):
        mx.write_panel_fabrication_schedule(result, [stranger], path)


@pytest.mark.parametrize("fmt, match", [
    ("ROOF", "same ID 'ROOF'"),                 # no number: every panel the same ID
    ("{:.0e}", "same ID '1e\\+01'"),            # 10 and 11 print alike
    ("{:d", "not a format"),
    ("{name}", "not a format"),
    ("A\n{:d}", "control character"),
    ("", "must be a text"),
])
def test_formats_that_cannot_name_every_panel_are_refused(result, fmt, match):
    r = tessella.panelize(make_round_trimmed_face(), method="iso_grid", size=1200.0)
    r.panel_id_format = fmt
    with pytest.raises(ValueError, match=match):
        r.panel_ids
    with pytest.raises(ValueError, match=match):
        tessella.unfold(r)
    with pytest.raises(ValueError, match="RodIdFormat"):
        api.format_ids("R", 3, "rod")


def test_duplicate_flat_ids_are_refused(result):
    flat = tessella.unfold(result)
    twin = flat + [tessella.FlatPanel(id=flat[2].id, outline=flat[5].outline)]
    with pytest.raises(ValueError, match=f"{flat[2].id}' is given twice"):
        tessella.nest(twin, 4000, 2500)
    with pytest.raises(ValueError, match="given twice"):
        tessella.export_svg(twin, "/tmp/never.svg", layout=tessella.nest(flat, 4000, 2500))


# ------------------------------------------------------------ layouts by ID

FOLD_TEXT = re.compile(r"^[VM] \d+\.\d{4}°$")


def world_cut_polylines(path):
    """Every closed CUT polyline of a DXF in drawing coordinates (block inserts
    decomposed), and every LABEL text."""
    import ezdxf
    from ezdxf import disassemble

    doc = ezdxf.readfile(path)
    polys, texts = [], []
    for e in disassemble.recursive_decompose(doc.modelspace()):
        if e.dxftype() == "LWPOLYLINE" and e.dxf.layer == "CUT":
            m = e.ocs()
            polys.append(np.array([tuple(m.to_wcs((x, y, 0)))[:2] for x, y, *_ in e.get_points()]))
        elif e.dxftype() in ("TEXT", "MTEXT") and e.dxf.layer in ("LABEL", "ENGRAVE"):
            # fold texts and sheet captions share LABEL
            if not FOLD_TEXT.match(e.dxf.text) and not e.dxf.text.startswith("Sheet "):
                texts.append(e.plain_text())
    return doc, polys, texts


def expected_world(lay, pid):
    j = lay.index(pid)
    x0, y0 = _arrange.sheet_origins(lay)[lay.placements[j].sheet]
    return lay.placed_outline(j) + np.array([x0, y0])


def find_outline(polys, want):
    for p in polys:
        if p.shape == want.shape and np.allclose(p, want, atol=1e-6):
            return True
    return False


def inside_sheet(pts, lay, s, origin=(0.0, 0.0)):
    w, h = lay.sheet_size(s)
    x0, y0 = origin
    m = lay.margin - 1e-6
    return (pts[:, 0].min() >= x0 + m and pts[:, 0].max() <= x0 + w - m
            and pts[:, 1].min() >= y0 + m and pts[:, 1].max() <= y0 + h - m)


def test_dxf_places_every_part_where_the_layout_put_its_id(result, tmp_path):
    flat = tessella.unfold(result)
    lay = tessella.nest(flat, sheet_width=3000, sheet_height=2000)
    assert lay.sheet_count >= 2
    path = str(tmp_path / "reversed.dxf")
    tessella.export_dxf(flat[::-1], path, layout=lay, per_sheet=False, arcs=False, simplify_tolerance=0)
    _doc, polys, texts = world_cut_polylines(path)
    assert len(polys) == len(flat)
    origins = _arrange.sheet_origins(lay)
    for f in flat:
        want = expected_world(lay, f.id)
        assert find_outline(polys, want), f.id
        s = lay.placements[lay.index(f.id)].sheet
        assert inside_sheet(want, lay, s, origins[s]), f.id
        # the outline there is this panel's (its edge lengths), not another's
        l2 = np.linalg.norm(np.roll(want, -1, axis=0) - want, axis=1)
        assert np.allclose(l2, f.edge_lengths, atol=1e-6)
    assert sorted(texts) == sorted(f.id for f in flat)


def svg_parts(path):
    """{data-id: polygon points in its sheet's frame (y up, origin at the sheet's
    lower left corner)}, the sheet rectangles, and the root."""
    root = ET.parse(path).getroot()
    rects = [(float(r.get("x")), float(r.get("y")), float(r.get("width")), float(r.get("height")))
             for r in root.findall("s:rect", SVG)]
    parts = {}
    for g in root.findall("s:g", SVG):
        pts = np.array([[float(v) for v in p.split(",")]
                        for p in g.find("s:polygon", SVG).get("points").split()])
        parts[g.get("data-id")] = (g, pts)
    return root, rects, parts


def to_sheet(pts, rect):
    x, y, w, h = rect
    return np.column_stack([pts[:, 0] - x, (y + h) - pts[:, 1]])


def test_svg_places_every_part_where_the_layout_put_its_id(result, tmp_path):
    flat = tessella.unfold(result)
    lay = tessella.nest(flat, sheet_width=3000, sheet_height=2000)
    path = str(tmp_path / "reversed.svg")
    tessella.export_svg(flat[::-1], path, layout=lay)
    _root, rects, parts = svg_parts(path)
    assert len(rects) == lay.sheet_count and sorted(parts) == sorted(lay.ids)
    for pid, (g, pts) in parts.items():
        j = lay.index(pid)
        s = lay.placements[j].sheet
        local = to_sheet(pts, rects[s])
        assert np.allclose(local, lay.placed_outline(j), atol=1e-5), pid
        assert inside_sheet(local, lay, s), pid
        assert g.find("s:title", SVG).text == pid


@pytest.mark.parametrize("export", ["export_dxf", "export_svg"])
def test_a_layout_of_other_panels_is_refused_naming_the_first_mismatch(result, tmp_path, export):
    write = getattr(tessella, export)
    flat = tessella.unfold(result)
    lay = tessella.nest(flat, 4000, 2500)
    path = str(tmp_path / ("x." + export[-3:]))
    with pytest.raises(ValueError, match=f"layout holds panel '{flat[0].id}'"):
        write(flat[1:], path, layout=lay)                     # one panel fewer
    with pytest.raises(ValueError, match=f"panel '{flat[0].id}' is not in the layout"):
        write(flat, path, layout=tessella.nest(flat[1:], 4000, 2500))  # one more
    with pytest.raises(ValueError, match=f"'{flat[3].id}' is given twice"):
        write(flat[:-1] + [flat[3]], path, layout=lay)        # same count, one twice
    renamed = [tessella.FlatPanel(id=f.id.replace("ROOF", "WALL"), outline=f.outline)
               for f in flat]
    with pytest.raises(ValueError, match="'WALL-A-001' is not in the layout"):
        write(renamed, path, layout=lay)
    swapped = list(flat)
    swapped[0] = tessella.FlatPanel(id=flat[0].id, outline=flat[1].outline)
    with pytest.raises(ValueError, match=f"'{flat[0].id}' is not the panel the layout nested"):
        write(swapped, path, layout=lay)


# ------------------------------------------------------------ any ID a user types

@pytest.fixture(scope="module")
def awkward(face):
    r = tessella.panelize(face, method="iso_grid", size=1200.0)
    r.panel_id_format = AWKWARD
    r.rod_id_format = "R/{:d}:*"
    r.node_id_format = 'N "{:d}", \\'
    return r


def test_awkward_ids_survive_svg_csv_json(awkward, tmp_path):
    r = awkward
    ids = [AWKWARD.replace("{:03d}", f"{k:03d}") for k in range(1, len(r.panels) + 1)]
    assert r.panel_ids == ids and len(ids[0]) > 140
    flat = tessella.unfold(r)
    lay = tessella.nest(flat, 4000, 2500)
    path = str(tmp_path / "awkward.svg")
    tessella.export_svg(flat[::-1], path, layout=lay)
    root, rects, parts = svg_parts(path)
    assert sorted(parts) == sorted(ids)  # data-id: the ID as typed
    svg_ids = [g.get("id") for g, _ in parts.values()]
    assert len(set(svg_ids)) == len(svg_ids)
    assert all(" " not in i and "/" not in i for i in svg_ids)
    texts = sorted(g.findall("s:text", SVG)[-1].text for g, _ in parts.values())
    assert texts == sorted(ids)
    for pid, (g, pts) in parts.items():
        j = lay.index(pid)
        assert np.allclose(to_sheet(pts, rects[lay.placements[j].sheet]), lay.placed_outline(j),
                           atol=1e-5)
    paths = write_schedules(r, str(tmp_path), "awkward")
    assert [row[0] for row in read_csv(paths["panels"])[1:]] == ids
    assert [row[0] for row in read_csv(paths["rods"])[1:]] == [f"R/{k}:*" for k in
                                                              range(1, len(r.rods) + 1)]
    assert [row[0] for row in read_csv(paths["nodes"])[1:]] == [f'N "{k}", \\' for k in
                                                               range(1, len(r.nodes) + 1)]
    mx.write_structural_json(r, str(tmp_path / "frame.json"))
    frame = json.load(open(tmp_path / "frame.json", encoding="utf-8"))
    assert frame["nodes"][0]["id"] == 'N "1", \\'


def test_dxf_text_shows_percent_signs_as_typed(tmp_path):
    import ezdxf

    doc = ezdxf.new("R2010")
    for pid in ("50%%d", "P-0001", "a%b"):
        doc.modelspace().add_text(_arrange.dxf_text(pid), dxfattribs={"layer": "LABEL"})
    path = str(tmp_path / "names.dxf")
    doc.saveas(path)
    raw = [e.dxf.text for e in ezdxf.readfile(path).modelspace()]
    # DXF reads %%% as one '%' (and %%d as a degree sign): escaped only where %% occurs.
    assert raw == ["50%%%%%%d", "P-0001", "a%b"]


def test_awkward_ids_survive_the_dxf(awkward, tmp_path):
    flat = tessella.unfold(awkward)
    lay = tessella.nest(flat, 4000, 2500)
    path = str(tmp_path / "awkward.dxf")
    tessella.export_dxf(flat[::-1], path, layout=lay, per_sheet=False, arcs=False, simplify_tolerance=0)
    _doc, polys, texts = world_cut_polylines(path)
    assert sorted(texts) == sorted(f.id for f in flat)
    for f in flat:
        assert find_outline(polys, expected_world(lay, f.id)), f.id


# ------------------------------------------------------------ the document

def test_document_formats_reach_unfold_schedules_and_files(face, tmp_path):
    import ezdxf

    doc = FreeCAD.newDocument("TessellaIds")
    try:
        src = doc.addObject("Part::Feature", "Roof")
        src.Shape = face
        doc.recompute()
        p = tessella.make_panelization((src, "Face1"), method="iso_grid", size=1200.0)
        p.PanelIdFormat = "ROOF-A-{:03d}"
        p.RodIdFormat = "ROOF-R{:04d}"
        p.NodeIdFormat = "ROOF-N{:04d}"
        doc.recompute()
        kids = {c.Role: c for c in tessella.features.panelization.children_of(p)}
        n = p.PanelCount
        panels = expected("ROOF-A-{:03d}", n)
        assert list(kids["Panels"].PanelIds) == panels
        assert list(kids["Rods"].RodIds) == expected("ROOF-R{:04d}", p.RodCount)
        assert list(kids["Nodes"].NodeIds) == expected("ROOF-N{:04d}", p.NodeCount)
        u = tessella.make_unfold(p, nest=True, sheet_width=4000.0, sheet_height=2500.0)
        assert list(u.PanelIds) == panels and u.Status == "OK"
        sheets = tessella.make_schedules(p)
        panel_sheet, rod_sheet, node_sheet = sheets
        assert panel_sheet.get("A2") == panels[0] and panel_sheet.get(f"A{n + 1}") == panels[-1]
        assert rod_sheet.get("A2") == "ROOF-R0001" and node_sheet.get("A2") == "ROOF-N0001"
        tessella.export_unfold(u, str(tmp_path / "u.dxf"), per_sheet=False, arcs=False,
                               simplify_tolerance=0)
        _d, polys, texts = world_cut_polylines(str(tmp_path / "u.dxf"))
        assert sorted(texts) == panels
        tessella.export_unfold(u, str(tmp_path / "u.svg"))
        assert sorted(svg_parts(str(tmp_path / "u.svg"))[2]) == panels
        # a new format re-labels everything on recompute
        p.PanelIdFormat = "WALL {:d}"
        doc.recompute()
        assert list(u.PanelIds) == [f"WALL {k}" for k in range(1, n + 1)]
        assert list(kids["Panels"].PanelIds) == list(u.PanelIds)
        # a format that names two panels alike: Panels invalid, Unfold says why
        p.PanelIdFormat = "WALL"
        doc.recompute()
        assert not kids["Panels"].isValid()
        assert "same ID 'WALL'" in u.Status and u.isValid()
        assert ezdxf  # imported for the reader above
    finally:
        FreeCAD.closeDocument(doc.Name)
