"""CSV schedules (freecad_workbench.export.schedule_csv): read back and check against
the result they came from, with figures recomputed here independently."""

import csv
import math
import os
import sys
import types

import pytest

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
for _p in ("/usr/lib/freecad-python3/lib", REPO):
    if _p not in sys.path:
        sys.path.append(_p)

import FreeCAD  # noqa: E402,F401  (before Part)
import Part  # noqa: E402
import numpy as np  # noqa: E402

from freecad_workbench.export import (  # noqa: E402
    NODE_COLUMNS,
    PANEL_COLUMNS,
    ROD_COLUMNS,
    write_node_schedule,
    write_panel_schedule,
    write_rod_schedule,
    write_schedules,
)

EXAMPLES = os.path.join(REPO, "examples")


def read_csv(path):
    with open(path, newline="", encoding="utf-8") as f:
        rows = list(csv.reader(f))
    return rows[0], [dict(zip(rows[0], r)) for r in rows[1:]]


def load_face(name):
    shape = Part.Shape()
    shape.read(os.path.join(EXAMPLES, name + ".brep"))
    return shape.Faces[0]


@pytest.fixture(scope="module", params=[("trimmed_bspline_holes", "equal_size_grid", 1500.0),
                                        ("plane", "iso_grid", 700.0)],
                ids=lambda p: f"{p[0]}-{p[1]}")
def result(request):
    import freecad_workbench as tessella

    name, method, size = request.param
    return tessella.panelize(load_face(name), method=method, size=size)


def fake_result():
    """A hand-made result (two quads), no compiled core needed."""
    vertices = np.array([[0, 0, 0], [1000, 0, 0], [2000, 0, 100], [0, 1000, 0],
                         [1000, 1000, 50], [2000, 1000, 0]], dtype=float)
    panels = [(0, 1, 4, 3), (1, 2, 5, 4)]
    rods = np.array([[0, 1], [0, 3], [1, 2], [1, 4], [2, 5], [3, 4], [4, 5]])
    n, e = len(panels), len(rods)
    r = types.SimpleNamespace(
        vertices=vertices,
        uv=vertices[:, :2] / 1000.0,
        normals=np.tile([0.0, 0.0, 1.0], (len(vertices), 1)),
        panels=panels,
        rods=rods,
        metrics={
            "panel_deviation": np.array([0.5, 1.25]),
            "panel_planarity": np.array([0.01, 0.02]),
            "panel_area": np.array([1.0e6, 1.01e6]),
            "panel_min_angle": np.array([88.0, 85.0]),
            "panel_max_angle": np.array([92.0, 95.0]),
            "rod_length": np.linalg.norm(vertices[rods[:, 0]] - vertices[rods[:, 1]], axis=1),
            "node_valence": np.array([2, 3, 2, 2, 3, 2]),
        },
        irregular=np.array([False, True]),
        nodes=np.arange(len(vertices)),
        panel_ids=[f"P-{i + 1:04d}" for i in range(n)],
        rod_ids=[f"R-{i + 1:04d}" for i in range(e)],
        node_ids=[f"N-{i + 1:04d}" for i in range(len(vertices))],
        node_id_by_vertex={i: f"N-{i + 1:04d}" for i in range(len(vertices))},
    )
    return r


def perimeter(vertices, panel):
    """Independent of the writer: plain Python over the corner list."""
    pts = [tuple(map(float, vertices[i])) for i in panel]
    return sum(math.dist(pts[k], pts[(k + 1) % len(pts)]) for k in range(len(pts)))


def check_ids(ids, prefix):
    assert len(set(ids)) == len(ids)
    assert ids == [f"{prefix}-{k + 1:04d}" for k in range(len(ids))]


def check_panel_schedule(r, path):
    assert write_panel_schedule(r, path) == len(r.panels)
    header, rows = read_csv(path)
    assert tuple(header) == PANEL_COLUMNS
    assert len(rows) == len(r.panels)
    check_ids([row["id"] for row in rows], "P")
    assert [row["id"] for row in rows] == list(r.panel_ids)
    for k, (row, panel) in enumerate(zip(rows, r.panels)):
        assert int(row["vertex_count"]) == len(panel)
        assert float(row["perimeter_mm"]) == pytest.approx(perimeter(r.vertices, panel), rel=1e-12)
        assert float(row["area_mm2"]) == r.metrics["panel_area"][k]  # exact round trip
        assert float(row["deviation_mm"]) == r.metrics["panel_deviation"][k]
        assert float(row["min_angle_deg"]) <= float(row["max_angle_deg"])
        assert int(row["irregular"]) == int(bool(r.irregular[k]))
        c = [float(row[f"centroid_{a}"]) for a in "xyz"]
        expect = np.mean([r.vertices[i] for i in panel], axis=0)
        assert c == pytest.approx(expect.tolist(), abs=1e-9)
    return rows


def test_fake_result_schedules(tmp_path):
    r = fake_result()
    rows = check_panel_schedule(r, tmp_path / "p.csv")
    assert float(rows[0]["perimeter_mm"]) == pytest.approx(2000 + 2 * math.hypot(1000, 50))
    assert write_rod_schedule(r, tmp_path / "r.csv") == 7
    header, rods = read_csv(tmp_path / "r.csv")
    assert tuple(header) == ROD_COLUMNS
    assert (rods[2]["node_a"], rods[2]["node_b"]) == ("N-0002", "N-0003")
    assert float(rods[2]["length_mm"]) == pytest.approx(math.hypot(1000, 100))
    assert write_node_schedule(r, tmp_path / "n.csv") == 6
    header, nodes = read_csv(tmp_path / "n.csv")
    assert tuple(header) == NODE_COLUMNS
    assert [int(n["valence"]) for n in nodes] == [2, 3, 2, 2, 3, 2]


def test_mismatched_metric_is_refused(tmp_path):
    r = fake_result()
    r.metrics["panel_area"] = np.array([1.0])
    with pytest.raises(ValueError, match="panel_area"):
        write_panel_schedule(r, tmp_path / "p.csv")


def test_panel_schedule(result, tmp_path):
    rows = check_panel_schedule(result, tmp_path / "panels.csv")
    total = sum(float(row["area_mm2"]) for row in rows)
    stats = result.summary["panel_area"]
    assert stats["count"] == len(rows)
    assert total == pytest.approx(stats["mean"] * stats["count"], rel=1e-9)
    assert total == pytest.approx(float(np.sum(result.metrics["panel_area"])), rel=1e-12)
    assert sum(int(row["irregular"]) for row in rows) == result.summary["irregular_count"]


def test_rod_schedule(result, tmp_path):
    path = tmp_path / "rods.csv"
    assert write_rod_schedule(result, path) == len(result.rods)
    header, rows = read_csv(path)
    assert tuple(header) == ROD_COLUMNS
    assert len(rows) == len(result.rods) == result.summary["rod_count"]
    check_ids([row["id"] for row in rows], "R")
    node_ids = result.node_ids  # a property that builds the list: call it once
    known = set(node_ids)
    position = {int(v): k for k, v in enumerate(result.nodes)}
    for row, (a, b) in zip(rows, result.rods):
        assert row["node_a"] in known and row["node_b"] in known
        assert (row["node_a"], row["node_b"]) == (node_ids[position[a]], node_ids[position[b]])
        length = math.dist(result.vertices[a], result.vertices[b])
        assert float(row["length_mm"]) == pytest.approx(length, rel=1e-9, abs=1e-6)


def test_node_schedule(result, tmp_path):
    path = tmp_path / "nodes.csv"
    assert write_node_schedule(result, path) == len(result.nodes)
    header, rows = read_csv(path)
    assert tuple(header) == NODE_COLUMNS
    assert len(rows) == len(result.nodes) == result.summary["node_count"]
    check_ids([row["id"] for row in rows], "N")
    # Valence recomputed from the rods.
    valence = np.bincount(np.asarray(result.rods).ravel(), minlength=len(result.vertices))
    for k, row in enumerate(rows):
        v = result.nodes[k]
        assert [float(row[a]) for a in "xyz"] == result.vertices[v].tolist()
        n = [float(row[a]) for a in ("nx", "ny", "nz")]
        assert math.hypot(*n) == pytest.approx(1.0, abs=1e-9)
        assert int(row["valence"]) == valence[v]


def test_write_schedules_names(result, tmp_path):
    paths = write_schedules(result, tmp_path / "sub", "ex_iso")
    assert {os.path.basename(p) for p in paths.values()} == {
        "panels_ex_iso.csv", "rods_ex_iso.csv", "nodes_ex_iso.csv"}
    assert all(os.path.getsize(p) > 0 for p in paths.values())
