"""Rod cut list, node schedule (CSV) and structural export (JSON, Abaqus .inp).

    from freecad_workbench.export import members
    members.write_cut_list(r, "cutlist.csv", length_tol=1.0, angle_tol=0.5)
    members.write_node_schedule(r, "nodes.csv")
    members.write_structural_json(r, "frame.json")
    members.write_abaqus_inp(r, "frame.inp", profile=("pipe", 60.0, 4.0))

Numbers are written with repr precision (read back exactly). No FreeCAD import.
"""

import csv
import json

import numpy as np

from .. import members as m

CUT_LIST_COLUMNS = ("type", "count", "length_mm", "cut_angle_1_deg", "cut_angle_2_deg",
                    "max_length_diff_mm", "rods")
ROD_DATA_COLUMNS = ("id", "node_a", "node_b", "length_mm", "cut_angle_a_deg", "cut_angle_b_deg",
                    "twist_deg", "type")
NODE_SCHEDULE_COLUMNS = ("id", "type", "x", "y", "z", "axis_x", "axis_y", "axis_z", "valence",
                         "rods")


PANEL_FAB_COLUMNS = ("id", "type", "vertex_count", "flat_width_mm", "flat_height_mm", "area_mm2",
                     "flat_area_mm2", "perimeter_mm", "deviation_mm", "planarity", "fold",
                     "fold_angle_deg", "fold_valley", "folds", "warp_mm", "class")


def _open(path):
    return open(path, "w", newline="", encoding="utf-8")


def write_cut_list(result, path, length_tol=1.0, angle_tol=0.5):
    """One row per rod type; returns the number of types."""
    rows = m.cut_list(result, length_tol, angle_tol)
    with _open(path) as f:
        w = csv.writer(f)
        w.writerow(CUT_LIST_COLUMNS)
        for r in rows:
            w.writerow([r["type"], r["count"], repr(r["length"]), repr(r["cut_angle_1"]),
                        repr(r["cut_angle_2"]), repr(r["max_length_diff"]), " ".join(r["rods"])])
    return len(rows)


def write_rod_data(result, path, length_tol=1.0, angle_tol=0.5):
    """One row per rod (rod order) with its type; returns the row count."""
    rd = m.rod_data(result)
    types = {}
    for t in m.cut_list(result, length_tol, angle_tol):
        for rid in t["rods"]:
            types[rid] = t["type"]
    node_id = result.node_id_by_vertex  # a property that builds the map: read it once
    with _open(path) as f:
        w = csv.writer(f)
        w.writerow(ROD_DATA_COLUMNS)
        for k, rid in enumerate(rd["id"]):
            w.writerow([rid, node_id[int(rd["node_a"][k])], node_id[int(rd["node_b"][k])],
                        repr(float(rd["length"][k])), repr(float(rd["cut_angle_a"][k])),
                        repr(float(rd["cut_angle_b"][k])), repr(float(rd["twist"][k])), types[rid]])
    return len(rd["id"])


def write_node_schedule(result, path, angle_tol=0.5):
    """One row per node: type, point, axis, and incident rods as
    'R-0001@azimuth/elevation' (deg, in the node's frame). Returns the row count."""
    frames = m.node_frames(result)
    types, summary = m.node_types(result, angle_tol, frames)
    with _open(path) as f:
        w = csv.writer(f)
        w.writerow(NODE_SCHEDULE_COLUMNS)
        for fr, t in zip(frames, types):
            rods = " ".join(f"{e['rod']}@{e['azimuth']!r}/{e['elevation']!r}" for e in fr["rods"])
            w.writerow([fr["id"], summary[t]["type"], *(repr(float(v)) for v in fr["point"]),
                        *(repr(float(v)) for v in fr["axis"]), len(fr["rods"]), rods])
    return len(frames)


def structural_model(result):
    rd = m.rod_data(result)
    node_id = result.node_id_by_vertex
    nodes = np.asarray(result.nodes, dtype=np.int64)
    return {
        "units": {"length": "mm"},
        "nodes": [{"id": nid, "xyz": [float(v) for v in p], "normal": [float(v) for v in n]}
                  for nid, p, n in zip(result.node_ids, np.asarray(result.vertices)[nodes],
                                       np.asarray(result.normals)[nodes])],
        "elements": [{"id": rid, "nodes": [node_id[int(a)], node_id[int(b)]],
                      "length": float(length)}
                     for rid, a, b, length in zip(rd["id"], rd["node_a"], rd["node_b"], rd["length"])],
    }


def write_structural_json(result, path):
    with open(path, "w", encoding="utf-8") as f:
        json.dump(structural_model(result), f, indent=1)
    return path


PROFILES = ("pipe", "rect", "circ")


def write_abaqus_inp(result, path, profile=("pipe", 60.0, 4.0), young=210000.0, poisson=0.3,
                     density=7.85e-9):
    """Abaqus input: nodes (1-based, mm), B31 beam elements (one per rod) with an
    orientation node each (along the mean node normal from the rod's midpoint, so
    the section's n1 axis follows the surface normal), one beam section and an
    elastic material (N, mm, MPa; default steel). Profile: ("pipe", radius,
    thickness), ("rect", width, height) or ("circ", radius)."""
    kind = profile[0]
    if kind not in PROFILES:
        raise ValueError(f"profile must start with one of {PROFILES}, got {kind!r}")
    dims = [float(v) for v in profile[1:]]
    need = {"pipe": 2, "rect": 2, "circ": 1}[kind]
    if len(dims) != need or any(not v > 0 for v in dims):
        raise ValueError(f"profile {kind!r} needs {need} positive dimension(s) (mm), got {dims}")
    if kind == "pipe" and dims[1] >= dims[0]:
        raise ValueError("pipe thickness must be less than its radius")
    # Abaqus node k+1 is result.nodes[k] (rod ends only; outline points are not
    # structural).
    nodes = np.asarray(result.nodes, dtype=np.int64)
    number = {int(v): k + 1 for k, v in enumerate(nodes)}
    xyz_all = np.asarray(result.vertices, dtype=float)
    nrm_all = np.asarray(result.normals, dtype=float)
    rods_v = np.asarray(result.rods, dtype=np.int64).reshape(-1, 2)
    xyz, nrm = xyz_all, nrm_all
    n_nodes = len(nodes)
    lines = ["*HEADING", "Tessella grid shell: nodes and B31 beams (mm, N, MPa)", "*NODE"]
    for i, p in enumerate(xyz_all[nodes]):
        lines.append(f"{i + 1}, {p[0]!r}, {p[1]!r}, {p[2]!r}")
    rods = rods_v
    lines.append("*NODE, NSET=ORIENTATION")
    for k, (a, b) in enumerate(rods):
        n = nrm[a] + nrm[b]
        n = n / (np.linalg.norm(n) or 1.0)
        length = np.linalg.norm(xyz[b] - xyz[a])
        p = 0.5 * (xyz[a] + xyz[b]) + length * n
        lines.append(f"{n_nodes + k + 1}, {p[0]!r}, {p[1]!r}, {p[2]!r}")
    lines.append("*ELEMENT, TYPE=B31, ELSET=RODS")
    for k, (a, b) in enumerate(rods):
        lines.append(f"{k + 1}, {number[int(a)]}, {number[int(b)]}, {n_nodes + k + 1}")
    section = {"pipe": "PIPE", "rect": "RECT", "circ": "CIRC"}[kind]
    lines.append(f"*BEAM SECTION, ELSET=RODS, MATERIAL=MAT1, SECTION={section}")
    lines.append(", ".join(repr(v) for v in dims))
    lines += ["*MATERIAL, NAME=MAT1", "*ELASTIC", f"{young!r}, {poisson!r}", "*DENSITY", f"{density!r}"]
    with open(path, "w", encoding="utf-8") as f:
        f.write("\n".join(lines) + "\n")
    return path


def write_panel_fabrication_schedule(result, flat, path, length_tol=1.0, angle_tol=0.5,
                                     families=None, classes=None):
    """One row per panel: type (congruent flat panels), flat size (bounding box of
    the outline as unfolded), 3D model area and flat area, perimeter, deviation,
    planarity, fold diagonal ("a-b", corner indices) and angle; with `families`
    (a families.PanelFamilies of the result) a last column "family" (PF-001,
    ...). The warp (mm) and class (flat / cold-bent / curved) of `classes` (a
    panel_classes.PanelClasses of the result) or the result's at the defaults.
    Returns the row count."""
    from .schedule_csv import _class_columns, panel_perimeters

    from ..fabrication import unique_ids

    flat = list(flat)
    types, _ = m.panel_types(flat, length_tol, angle_tol)
    per = panel_perimeters(result)
    index = {pid: k for k, pid in enumerate(result.panel_ids)}
    rows = []  # the result's panel of each flat panel, found by ID
    for pid in unique_ids(flat):
        if pid not in index:
            raise ValueError(f"flat panel {pid!r} is not a panel of this result: unfold "
                             "the result you write")
        rows.append(index[pid])
    warp, class_names = _class_columns(result, classes, len(result.panels))
    with _open(path) as f:
        w = csv.writer(f)
        names = None
        if families is not None:
            if len(families.labels) != len(result.panels):
                raise ValueError("the families are not of this result's panels")
            names = families.names()
        w.writerow(PANEL_FAB_COLUMNS + (("family",) if names is not None else ()))
        for t, fp, k in zip(types, flat, rows):
            size = fp.outline.max(axis=0) - fp.outline.min(axis=0)
            w.writerow([fp.id, f"PT-{t + 1:03d}", len(fp.outline), repr(float(size[0])),
                        repr(float(size[1])), repr(float(result.metrics["panel_area"][k])),
                        repr(float(fp.area)), repr(float(per[k])),
                        repr(float(result.metrics["panel_deviation"][k])),
                        repr(float(result.metrics["panel_planarity"][k])),
                        f"{fp.fold[0]}-{fp.fold[1]}" if fp.fold else "",
                        repr(float(fp.fold_angle)), int(fp.fold_valley), len(fp.folds),
                        repr(float(warp[k])), class_names[k]]
                       + ([names[k]] if names is not None else []))
    return len(flat)
