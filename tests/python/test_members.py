"""Rods, nodes, cut list, node types, buildability and structural export: closed
forms on a cylinder, file read-back, figures recomputed with plain Python."""

import csv
import json
import math
import statistics

import FreeCAD  # noqa: F401  (before Part)
import Part
import numpy as np
import pytest

import freecad_workbench as tessella
from freecad_workbench.export import members as mx

N_AROUND, N_UP, R, H = 24, 6, 5000.0, 6000.0


@pytest.fixture(scope="module")
def cyl():
    face = Part.makeCylinder(R, H).Faces[0]
    return tessella.panelize(face, method="iso_grid", u_count=N_AROUND, v_count=N_UP)


def is_hoop(r, k):
    a, b = r.rods[k]
    return abs(r.vertices[a][2] - r.vertices[b][2]) < 1e-6


def test_rod_cut_angles_closed_form(cyl):
    rd = tessella.rod_data(cyl)
    assert len(rd["id"]) == len(cyl.rods)
    for k in range(len(cyl.rods)):
        a, b = cyl.rods[k]
        assert rd["length"][k] == pytest.approx(math.dist(cyl.vertices[a], cyl.vertices[b]), rel=1e-12)
        if is_hoop(cyl, k):
            # a chord over 360/n degrees meets the radial node axis at 90 - 180/n
            expect = 180.0 / N_AROUND
            assert rd["length"][k] == pytest.approx(2 * R * math.sin(math.pi / N_AROUND), rel=1e-9)
        else:
            expect = 0.0
            assert rd["length"][k] == pytest.approx(H / N_UP, rel=1e-9)
        assert abs(rd["cut_angle_a"][k]) == pytest.approx(expect, abs=1e-6)
        assert abs(rd["cut_angle_b"][k]) == pytest.approx(expect, abs=1e-6)
        assert abs(rd["twist"][k]) < 1e-6


def test_cut_list_groups(cyl, tmp_path):
    types = tessella.cut_list(cyl, length_tol=0.5, angle_tol=0.1)
    assert len(types) == 2
    assert sum(t["count"] for t in types) == len(cyl.rods)
    hoops = sum(1 for k in range(len(cyl.rods)) if is_hoop(cyl, k))
    assert sorted(t["count"] for t in types) == sorted([hoops, len(cyl.rods) - hoops])
    path = str(tmp_path / "cut.csv")
    assert mx.write_cut_list(cyl, path, 0.5, 0.1) == 2
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    listed = [rid for row in rows for rid in row["rods"].split()]
    assert sorted(listed) == sorted(cyl.rod_ids)
    assert sum(int(row["count"]) for row in rows) == len(cyl.rods)
    # a tight length tolerance on a freeform face gives more types
    with pytest.raises(ValueError):
        tessella.cut_list(cyl, length_tol=-1)


def test_node_types_and_schedule(cyl, tmp_path):
    types, summary = tessella.node_types(cyl, angle_tol=0.1)
    # interior nodes (valence 4) are one type, boundary nodes (valence 3) another:
    # top and bottom nodes are the same hub turned 180 degrees about the axis
    assert len(summary) == 2
    assert sorted(t["valence"] for t in summary) == [3, 4]
    assert sum(t["count"] for t in summary) == len(cyl.vertices)
    path = str(tmp_path / "nodes.csv")
    assert mx.write_node_schedule(cyl, path, angle_tol=0.1) == len(cyl.vertices)
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    for row, val, p, n in zip(rows, cyl.metrics["node_valence"], cyl.vertices, cyl.normals):
        assert int(row["valence"]) == val
        assert [float(row[c]) for c in ("x", "y", "z")] == list(p)
        assert [float(row[c]) for c in ("axis_x", "axis_y", "axis_z")] == pytest.approx(list(n))
        rods = row["rods"].split()
        az = [float(s.split("@")[1].split("/")[0]) for s in rods]
        el = [float(s.split("/")[1]) for s in rods]
        assert az == sorted(az) and all(0 <= a < 360 for a in az)
        # on a cylinder with a radial axis, rods lie within 180/n of the tangent plane
        assert all(abs(e) <= 180.0 / N_AROUND + 1e-6 for e in el)


def test_buildability(cyl):
    flat = tessella.unfold(cyl)
    lay = tessella.nest(flat, sheet_width=2500, sheet_height=1250, margin=10, spacing=6)
    s = tessella.buildability(cyl, flat=flat, layout=lay, length_tol=0.5, angle_tol=0.1)
    lengths = [math.dist(cyl.vertices[a], cyl.vertices[b]) for a, b in cyl.rods]
    assert s["rod_length_similarity"] == pytest.approx(
        1 + statistics.pstdev(lengths) / statistics.mean(lengths), rel=1e-9)
    assert s["total_rod_length"] == pytest.approx(sum(lengths), rel=1e-12)
    assert s["panel_types"] == 1  # congruent planar rectangles
    assert s["rod_types"] == 2 and s["node_types"] == 2
    assert s["planarity_freegrid"] == pytest.approx(1.0, abs=1e-12)  # cylinder grid quads are planar
    assert s["folded_panels"] == 0
    assert s["nesting_utilization"] == lay.utilization
    assert s["flat_area"] == pytest.approx(
        N_AROUND * N_UP * 2 * R * math.sin(math.pi / N_AROUND) * H / N_UP, rel=1e-9)


def test_freegrid_planarity_bent_quad():
    """One quad with corner 2 lifted by h: best-fit plane distances are h/4 at
    every corner (the twist splits evenly), half perimeter ~ 2 s."""
    import types

    s, h = 1000.0, 10.0
    v = np.array([[0, 0, 0], [s, 0, 0], [s, s, h], [0, s, 0]], float)
    r = types.SimpleNamespace(vertices=v, panels=[(0, 1, 2, 3)])
    half = 0.5 * (s + s + 2 * math.hypot(s, h))
    assert tessella.freegrid_planarity(r) == pytest.approx(1 + (h / 4) / half, rel=1e-6)


def test_structural_json_and_abaqus(cyl, tmp_path):
    jp = str(tmp_path / "frame.json")
    mx.write_structural_json(cyl, jp)
    with open(jp) as f:
        model = json.load(f)
    assert [n["id"] for n in model["nodes"]] == cyl.node_ids
    assert np.allclose([n["xyz"] for n in model["nodes"]], cyl.vertices, atol=0)
    ids = {nid: i for i, nid in enumerate(cyl.node_ids)}
    assert [[ids[a], ids[b]] for a, b in (e["nodes"] for e in model["elements"])] == cyl.rods.tolist()

    ip = str(tmp_path / "frame.inp")
    mx.write_abaqus_inp(cyl, ip, profile=("rect", 60.0, 120.0))
    nodes, elements, section = {}, [], None
    block = None
    with open(ip) as f:
        lines = [ln.strip() for ln in f]
    for i, ln in enumerate(lines):
        if ln.startswith("*"):
            block = ln.split(",")[0].upper()
            if block == "*ELEMENT":
                assert "TYPE=B31" in ln.replace(" ", "")
            if block == "*BEAM SECTION":
                section = ln, lines[i + 1]
            continue
        if block == "*NODE":
            k, x, y, z = ln.split(",")
            nodes[int(k)] = (float(x), float(y), float(z))
        elif block == "*ELEMENT":
            elements.append([int(t) for t in ln.split(",")])
    assert len(elements) == len(cyl.rods)
    for (e, a, b, o), (ra, rb) in zip(elements, cyl.rods):
        assert (a, b) == (ra + 1, rb + 1)
        assert nodes[a] == tuple(cyl.vertices[ra]) and nodes[b] == tuple(cyl.vertices[rb])
        # orientation node: from the midpoint, along the (radial) surface normal
        mid = 0.5 * (np.array(nodes[a]) + np.array(nodes[b]))
        d = np.array(nodes[o]) - mid
        radial = np.array([mid[0], mid[1], 0.0])
        assert np.dot(d, radial) / (np.linalg.norm(d) * np.linalg.norm(radial)) == pytest.approx(1.0, abs=1e-9)
    assert "SECTION=RECT" in section[0] and section[1] == "60.0, 120.0"
    with pytest.raises(ValueError):
        mx.write_abaqus_inp(cyl, ip, profile=("pipe", 10.0, 20.0))
    with pytest.raises(ValueError):
        mx.write_abaqus_inp(cyl, ip, profile=("rect", -1.0, 2.0))


def test_panel_fabrication_schedule(tmp_path):
    """Saddle quads: the schedule's fold angle equals the dihedral recomputed from
    the 3D corners; mirror-symmetric panels of the saddle share types."""
    pts = [[FreeCAD.Vector(x, y, x * y / 4000.0) for y in (-2000, 2000)] for x in (-2000, 2000)]
    s = Part.BezierSurface()
    s.increase(1, 1)
    for i in range(2):
        for j in range(2):
            s.setPole(i + 1, j + 1, pts[i][j])
    r = tessella.panelize(s.toShape(), method="iso_grid", u_count=4, v_count=4)
    flat = tessella.unfold(r)
    path = str(tmp_path / "panels_fab.csv")
    assert mx.write_panel_fabrication_schedule(r, flat, path) == 16
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    for row, panel in zip(rows, r.panels):
        p = r.vertices[list(panel)]
        a, b = (int(t) for t in row["fold"].split("-"))
        c, d = [i for i in range(4) if i not in (a, b)]
        n1 = np.cross(p[b] - p[a], p[c] - p[a])
        n2 = np.cross(p[b] - p[a], p[d] - p[a])
        dihedral = 180 - math.degrees(math.acos(np.dot(n1, n2) / np.linalg.norm(n1) / np.linalg.norm(n2)))
        assert float(row["fold_angle_deg"]) == pytest.approx(dihedral, abs=1e-7)
        assert float(row["flat_area_mm2"]) > 0
    types = {row["type"] for row in rows}
    # z = xy/4000 on a 4x4 grid: a panel and its 180-degree-turned partner match
    assert 1 < len(types) < 16


def test_rod_and_hub_solids(cyl):
    lengths = [math.dist(cyl.vertices[a], cyl.vertices[b]) for a, b in cyl.rods]
    rect = tessella.rod_solids(cyl, profile=("rect", 60.0, 160.0))
    assert len(rect.Solids) == len(cyl.rods)
    for s, length, (a, b) in zip(rect.Solids, lengths, cyl.rods):
        assert s.isValid()
        assert s.Volume == pytest.approx(60.0 * 160.0 * length, rel=1e-9)
        # the 160 mm side follows the (radial) surface normal: the solid's extent
        # along the normal at the rod's midpoint is 160
        mid = 0.5 * (cyl.vertices[a] + cyl.vertices[b])
        radial = FreeCAD.Vector(mid[0], mid[1], 0).normalize()
        ext = [v.Point.dot(radial) for v in s.Vertexes]
        assert max(ext) - min(ext) == pytest.approx(160.0, abs=1e-6 + 60 * math.sin(math.pi / N_AROUND))
    pipe = tessella.rod_solids(cyl, profile=("pipe", 30.0, 3.0))
    total = sum(lengths) * math.pi * (30.0 ** 2 - 27.0 ** 2)
    assert pipe.Volume == pytest.approx(total, rel=1e-6)
    hubs = tessella.hub_solids(cyl, radius=50.0, height=100.0)
    assert len(hubs.Solids) == len(cyl.vertices)
    for h, p in zip(hubs.Solids, cyl.vertices):
        c = h.CenterOfMass
        assert math.dist((c.x, c.y, c.z), p) < 1e-6
    with pytest.raises(ValueError):
        tessella.rod_solids(cyl, profile=("rect", 0.0, 1.0))
    with pytest.raises(ValueError):
        tessella.hub_solids(cyl, radius=-1)


def test_panel_solids(cyl):
    t = 10.0
    flat = tessella.unfold(cyl)
    back = tessella.panel_solids(cyl, thickness=t, side="back", flat=flat)
    front = tessella.panel_solids(cyl, thickness=t, side="front", flat=flat)
    assert len(back.Solids) == len(cyl.panels) == len(front.Solids)
    w = 2 * R * math.sin(math.pi / N_AROUND)  # chord width of a panel
    h = H / N_UP
    for sb, sf, panel in zip(back.Solids, front.Solids, cyl.panels):
        assert sb.isValid() and sf.isValid()
        # a planar chord panel offset along the radial node normals: a prism whose
        # cross-section is a trapezoid with parallel sides w and w(1 -+ t/R), the
        # chords t cos(pi/n) apart -> volume = h t cos(pi/n) w (1 -+ t/(2R))
        k = t / R
        c = math.cos(math.pi / N_AROUND)
        n0 = np.asarray(cyl.normals[panel[0]])
        outward = np.dot(n0, [cyl.vertices[panel[0]][0], cyl.vertices[panel[0]][1], 0]) > 0
        v_in = h * t * c * w * (1 - k / 2)
        v_out = h * t * c * w * (1 + k / 2)
        assert sb.Volume == pytest.approx(v_in if outward else v_out, rel=1e-6)
        assert sf.Volume == pytest.approx(v_out if outward else v_in, rel=1e-6)
        # the panel's own corners lie on the solid
        for v in panel:
            p = FreeCAD.Vector(*map(float, cyl.vertices[v]))
            assert sb.distToShape(Part.Vertex(p))[0] < 1e-6
    with pytest.raises(ValueError):
        tessella.panel_solids(cyl, thickness=0)
    with pytest.raises(ValueError):
        tessella.panel_solids(cyl, side="up")
