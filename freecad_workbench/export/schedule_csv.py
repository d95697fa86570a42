"""CSV schedules of panels, rods and nodes from a PanelizeResult.

One row per item, in the result's order, so row k has the ID `result.panel_ids[k]`
(and likewise for rods and nodes). Lengths in mm, areas in mm^2, angles in degrees.
Numbers are written with `repr` precision: reading a file back gives the same floats.
No FreeCAD import: works on any object with the PanelizeResult attributes.
"""

import csv
import os

import numpy as np

PANEL_COLUMNS = (
    "id",
    "vertex_count",
    "area_mm2",
    "perimeter_mm",
    "deviation_mm",
    "planarity",
    "min_angle_deg",
    "max_angle_deg",
    "irregular",
    "centroid_x",
    "centroid_y",
    "centroid_z",
    "warp_mm",
    "class",
)
ROD_COLUMNS = ("id", "node_a", "node_b", "length_mm")
#: The family schedule (freecad_workbench.families): one row per family; members
#: are the panel IDs separated by spaces.
FAMILY_COLUMNS = ("family", "template", "count", "max_error_mm", "members")
NODE_COLUMNS = ("id", "x", "y", "z", "nx", "ny", "nz", "valence")


def panel_perimeters(result):
    """Perimeter of every panel (mm): the sum of its 3D edge lengths, closing edge included."""
    xyz = np.asarray(result.vertices, dtype=float)
    out = np.empty(len(result.panels))
    for k, panel in enumerate(result.panels):
        ring = xyz[list(panel)]
        out[k] = float(np.linalg.norm(np.roll(ring, -1, axis=0) - ring, axis=1).sum())
    return out


def _metric(result, name, count):
    values = np.asarray(result.metrics[name], dtype=float)
    if values.shape != (count,):
        raise ValueError(f"metric {name!r} has {values.shape[0]} values, expected {count}")
    return values


def _num(value):
    return repr(float(value))


def _open(path):
    path = os.fspath(path)
    folder = os.path.dirname(path)
    if folder:
        os.makedirs(folder, exist_ok=True)
    # newline="" as the csv module asks; UTF-8 so any spreadsheet reads it.
    return open(path, "w", newline="", encoding="utf-8")


def _class_columns(result, classes, n):
    """(warp mm, class name) per panel: of `classes` (a panel_classes.PanelClasses
    of the result) or, without, the result's own at the defaults."""
    from ..panel_classes import panel_classes

    if classes is None:
        classes = panel_classes(result)
    if len(classes.labels) != n:
        raise ValueError("the panel classes are not of this result's panels")
    return classes.warp, classes.names


def write_panel_schedule(result, path, families=None, classes=None):
    """Writes one row per panel (columns PANEL_COLUMNS, then "family" when
    `families`, a families.PanelFamilies of the result, is given; the warp and
    class of `classes`, a panel_classes.PanelClasses, or the defaults').
    Returns the number of rows."""
    n = len(result.panels)
    xyz = np.asarray(result.vertices, dtype=float)
    area = _metric(result, "panel_area", n)
    deviation = _metric(result, "panel_deviation", n)
    planarity = _metric(result, "panel_planarity", n)
    min_angle = _metric(result, "panel_min_angle", n)
    max_angle = _metric(result, "panel_max_angle", n)
    irregular = np.asarray(result.irregular, dtype=bool)
    if irregular.shape != (n,):
        raise ValueError(f"irregular has {irregular.shape[0]} flags, expected {n}")
    perimeter = panel_perimeters(result)
    ids = result.panel_ids
    names = _family_names(families, n)
    warp, class_names = _class_columns(result, classes, n)
    with _open(path) as f:
        w = csv.writer(f)
        w.writerow(PANEL_COLUMNS + (("family",) if names is not None else ()))
        for k, panel in enumerate(result.panels):
            c = xyz[list(panel)].mean(axis=0)
            w.writerow(
                (
                    ids[k],
                    len(panel),
                    _num(area[k]),
                    _num(perimeter[k]),
                    _num(deviation[k]),
                    _num(planarity[k]),
                    _num(min_angle[k]),
                    _num(max_angle[k]),
                    int(irregular[k]),
                    _num(c[0]),
                    _num(c[1]),
                    _num(c[2]),
                    _num(warp[k]),
                    class_names[k],
                )
                + ((names[k],) if names is not None else ())
            )
    return n


def _family_names(families, count):
    """Family name per panel (PF-001, ...), None without families."""
    if families is None:
        return None
    if len(families.labels) != count:
        raise ValueError(f"the families have {len(families.labels)} panels, the result {count}: "
                         "compute them from the result you write")
    return families.names()


def write_family_schedule(result, families, path):
    """Writes one row per family (columns FAMILY_COLUMNS): its name, its
    template's panel ID, the number of panels, the largest corner distance of
    a member to the template (mm) and the members' panel IDs. Returns the
    number of rows."""
    from ..families import family_rows

    _family_names(families, len(result.panels))
    rows = family_rows(result, families)
    with _open(path) as f:
        w = csv.writer(f)
        w.writerow(FAMILY_COLUMNS)
        for row in rows:
            w.writerow((row["family"], row["template"], row["count"], _num(row["max_error_mm"]),
                        " ".join(row["members"])))
    return len(rows)


def write_rod_schedule(result, path):
    """Writes one row per rod (columns ROD_COLUMNS); node_a/node_b are node IDs."""
    rods = np.asarray(result.rods, dtype=np.int64).reshape(-1, 2)
    length = _metric(result, "rod_length", len(rods))
    ids = result.rod_ids
    node_id = result.node_id_by_vertex  # rods end at nodes
    with _open(path) as f:
        w = csv.writer(f)
        w.writerow(ROD_COLUMNS)
        for k, (a, b) in enumerate(rods):
            w.writerow((ids[k], node_id[int(a)], node_id[int(b)], _num(length[k])))
    return len(rods)


def write_node_schedule(result, path):
    """Writes one row per node (columns NODE_COLUMNS): position, face normal, valence."""
    nodes = np.asarray(result.nodes, dtype=np.int64).reshape(-1)
    xyz = np.asarray(result.vertices, dtype=float).reshape(-1, 3)[nodes]
    normals = np.asarray(result.normals, dtype=float).reshape(-1, 3)[nodes]
    valence = np.asarray(result.metrics["node_valence"]).reshape(-1)
    if valence.shape[0] != len(xyz):
        raise ValueError("node_valence does not match the node count")
    ids = result.node_ids
    with _open(path) as f:
        w = csv.writer(f)
        w.writerow(NODE_COLUMNS)
        for k in range(len(xyz)):
            p, nrm = xyz[k], normals[k]
            w.writerow(
                (ids[k], _num(p[0]), _num(p[1]), _num(p[2]),
                 _num(nrm[0]), _num(nrm[1]), _num(nrm[2]), int(valence[k]))
            )
    return len(xyz)


def write_schedules(result, folder, name, families=None):
    """Writes panels_<name>.csv, rods_<name>.csv and nodes_<name>.csv into `folder`
    (and families_<name>.csv, with the panels' family column, when `families`
    is given).

    Returns {"panels": path, "rods": path, "nodes": path[, "families": path]}.
    """
    kinds = ("panels", "rods", "nodes") + (("families",) if families is not None else ())
    paths = {kind: os.path.join(folder, f"{kind}_{name}.csv") for kind in kinds}
    write_panel_schedule(result, paths["panels"], families)
    write_rod_schedule(result, paths["rods"])
    write_node_schedule(result, paths["nodes"])
    if families is not None:
        write_family_schedule(result, families, paths["families"])
    return paths
