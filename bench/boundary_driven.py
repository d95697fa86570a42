"""Boundary-driven meshing (seed 001) against the clipped iso grid at the same size.

    PYTHONPATH=/usr/lib/freecad-python3/lib:. /usr/bin/python3 bench/boundary_driven.py

For each trimmed example (openings and notches) both methods run at the same
nominal panel size; the script prints a table and writes
out/bench/boundary_driven.{md,json} and one picture per run,
out/bench/boundary_driven_<example>_<size>.png (the two meshes side by side,
irregular panels in red).

Every figure is measured here from the returned arrays, with one definition for
both methods:
- irregular: not a quad, or a corner angle under 30 deg, or an area under 25% of
  size^2 (the nominal panel);
- boundary-node-on-trim: largest distance (FreeCAD's distToShape against the
  face's edges) from a node on a boundary rod (a rod used by one panel) to the
  trim curves, divided by the model size; trim_tolerance is the largest edge
  tolerance of the face / model size (how far OCCT lets an edge's 3D curve
  stray from its curve on the surface, which our nodes follow);
- coverage: sum of the panel areas / the face area;
- edge-length CV: standard deviation / mean of all rod lengths;
- core time: best of 3 of the core call alone (no metrics), seconds.
"""

import json
import math
import os
import sys

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
for _p in ("/usr/lib/freecad-python3/lib", REPO):
    if _p not in sys.path:
        sys.path.append(_p)

import FreeCAD  # noqa: E402,F401  (before Part)
import Part  # noqa: E402
import numpy as np  # noqa: E402

import freecad_workbench as tessella  # noqa: E402
from freecad_workbench import api, core  # noqa: E402

#: (example, nominal size in mm)
RUNS = tuple(
    (name, size)
    for name in ("cone_facade", "notched_shell", "vault_openings", "trimmed_bspline_holes")
    for size in (600.0, 900.0, 1200.0)
)
#: a larger run for the timing target (a few thousand panels)
TIMING_RUN = ("cone_facade", 220.0)
METHODS = ("iso_grid", "boundary_driven")


def load(name):
    shape = Part.Shape()
    shape.read(os.path.join(REPO, "examples", name + ".brep"))
    return shape.Faces[0]


def corner_angles(xyz, panel):
    n = len(panel)
    out = []
    for i in range(n):
        a = xyz[panel[i - 1]] - xyz[panel[i]]
        b = xyz[panel[(i + 1) % n]] - xyz[panel[i]]
        c = np.dot(a, b) / (np.linalg.norm(a) * np.linalg.norm(b))
        out.append(math.degrees(math.acos(max(-1.0, min(1.0, c)))))
    return out


def boundary_nodes(panels):
    uses = {}
    for p in panels:
        for i in range(len(p)):
            e = tuple(sorted((p[i], p[(i + 1) % len(p)])))
            uses[e] = uses.get(e, 0) + 1
    return sorted({v for e, n in uses.items() if n == 1 for v in e})


def core_time(face, method, size):
    """Fastest of 3 method stages of the C++ pipeline (no metrics), seconds."""
    surface = core.SurfaceFace.from_brep_string(api.face_to_brep(face))
    values = api.core_values(method, {"size": size}, surface)
    best = float("inf")
    for _ in range(3):
        r = core.panelize(surface, method, values)
        best = min(best, r.summary["core_seconds"])
    return best, r.summary["panel_count"]


def measure(face, method, size):
    r = tessella.panelize(face, method=method, size=size)
    xyz = r.vertices
    nominal = size * size
    angles = [corner_angles(xyz, p) for p in r.panels]
    min_angle = np.array([min(a) for a in angles])
    area = r.metrics["panel_area"]
    quad = np.array([len(p) == 4 for p in r.panels])
    irregular = (~quad) | (min_angle < 30.0) | (area < 0.25 * nominal)
    edges = face.Edges
    trim = Part.Compound(edges)
    model = r.summary["model_size"]
    dist = [trim.distToShape(Part.Vertex(FreeCAD.Vector(*xyz[v])))[0] for v in boundary_nodes(r.panels)]
    rods = r.metrics["rod_length"]
    t, n = core_time(face, method, size)
    return r, {
        "panels": len(r.panels),
        "irregular": int(irregular.sum()),
        "quad_share": float(quad.mean()),
        "min_angle_deg": float(min_angle.min()),
        "panels_under_15deg": int((min_angle < 15.0).sum()),
        "boundary_node_on_trim": float(max(dist) / model),
        "trim_tolerance": float(max(e.Tolerance for e in edges) / model),
        "coverage": float(area.sum() / face.Area),
        "edge_cv": float(rods.std() / rods.mean()),
        "max_deviation_mm": float(r.metrics["panel_deviation"].max()),
        "core_time_s": t,
    }, irregular


def plot(name, size, results, path):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.collections import PolyCollection

    # project onto the best-fit plane of the face (principal axes of its nodes)
    allxyz = np.vstack([r.vertices for r, _, _ in results.values()])
    centre = allxyz.mean(axis=0)
    _, _, vt = np.linalg.svd(allxyz - centre, full_matrices=False)
    axes = vt[:2].T
    fig, axs = plt.subplots(1, 2, figsize=(14, 6.5))
    for ax, (method, (r, m, irregular)) in zip(axs, results.items()):
        xy = (r.vertices - centre) @ axes
        polys = [xy[list(p)] for p in r.panels]
        colors = ["#e05050" if irr else "#cfe3f5" for irr in irregular]
        ax.add_collection(PolyCollection(polys, facecolors=colors, edgecolors="#203040", linewidths=0.5))
        ax.autoscale()
        ax.set_aspect("equal")
        ax.set_axis_off()
        ax.set_title(f"{method}: {m['panels']} panels, {m['irregular']} irregular (red), "
                     f"quads {100 * m['quad_share']:.0f}%", fontsize=10)
    fig.suptitle(f"{name}, size {size:.0f} mm")
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


COLUMNS = (
    ("panels", "{:d}"),
    ("irregular", "{:d}"),
    ("quad_share", "{:.3f}"),
    ("min_angle_deg", "{:.1f}"),
    ("panels_under_15deg", "{:d}"),
    ("boundary_node_on_trim", "{:.1e}"),
    ("trim_tolerance", "{:.1e}"),
    ("coverage", "{:.4f}"),
    ("edge_cv", "{:.3f}"),
    ("max_deviation_mm", "{:.1f}"),
    ("core_time_s", "{:.3f}"),
)


def main(out_dir=os.path.join(REPO, "out", "bench")):
    os.makedirs(out_dir, exist_ok=True)
    rows = []
    for name, size in RUNS:
        face = load(name)
        results = {}
        for method in METHODS:
            r, m, irregular = measure(face, method, size)
            results[method] = (r, m, irregular)
            rows.append({"example": name, "size_mm": size, "method": method, **m})
        plot(name, size, results, os.path.join(out_dir, f"boundary_driven_{name}_{size:.0f}.png"))
        iso, bd = results["iso_grid"][1], results["boundary_driven"][1]
        fewer = 1.0 - bd["irregular"] / iso["irregular"] if iso["irregular"] else float("nan")
        rows[-1]["irregular_reduction"] = fewer
    name, size = TIMING_RUN
    face = load(name)
    timing = {}
    for method in METHODS:
        t, n = core_time(face, method, size)
        timing[method] = {"example": name, "size_mm": size, "panels": n, "core_time_s": t}

    header = "| example | size | method | " + " | ".join(c for c, _ in COLUMNS) + " | irregular reduction |"
    lines = [header, "|" + "---|" * (len(COLUMNS) + 4)]
    for row in rows:
        cells = [row["example"], f"{row['size_mm']:.0f}", row["method"]]
        cells += [fmt.format(row[c]) for c, fmt in COLUMNS]
        red = row.get("irregular_reduction")
        cells.append(f"{100 * red:.0f}%" if red is not None else "")
        lines.append("| " + " | ".join(cells) + " |")
    lines.append("")
    lines.append("| timing run | size | method | panels | core time (s) |")
    lines.append("|---|---|---|---|---|")
    for method, t in timing.items():
        lines.append(f"| {t['example']} | {t['size_mm']:.0f} | {method} | {t['panels']} | "
                     f"{t['core_time_s']:.3f} |")
    table = "\n".join(lines)
    print(table)
    with open(os.path.join(out_dir, "boundary_driven.md"), "w") as f:
        f.write("# Boundary-driven vs clipped iso grid\n\n" + table + "\n")
    with open(os.path.join(out_dir, "boundary_driven.json"), "w") as f:
        json.dump({"runs": rows, "timing": timing}, f, indent=2)
    return 0


if __name__ == "__main__":
    sys.exit(main())
