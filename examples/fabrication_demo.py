"""Fabrication demo: the bundled trimmed B-spline face with holes, panelized,
unfolded, nested, exported (DXF, SVG, CSV, JSON, Abaqus .inp) and summarized.
The CAM files are cam/panels_sheetNN.dxf (one per sheet); panels.dxf holds every
sheet in one drawing for review.

    PYTHONPATH=/usr/lib/freecad-python3/lib:. /usr/bin/python3 examples/fabrication_demo.py --out out/fabrication

Also draws docs/fabrication.png (with --figure) from the nested layout.
"""

import argparse
import json
import os
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(HERE)
sys.path[:0] = ["/usr/lib/freecad-python3/lib", REPO]

import FreeCAD  # noqa: E402  (before Part)
import Part  # noqa: E402

import freecad_workbench as tessella  # noqa: E402
from freecad_workbench.export import members as mx  # noqa: E402


def figure(r, flat, layout, path):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import numpy as np

    sheets = min(layout.sheet_count, 3)
    fig, axes = plt.subplots(1, sheets + 1, figsize=(5 * (sheets + 1), 3.6))
    # left: one bent panel unfolded, with its fold
    f = max(flat, key=lambda x: (len(x.outline) == 4, x.fold_angle))
    ax = axes[0]
    o = np.vstack([f.outline, f.outline[:1]])
    ax.plot(o[:, 0], o[:, 1], "r-", lw=1.5)
    if f.fold:
        a, b = f.fold
        ax.plot(*zip(f.outline[a], f.outline[b]), "b--", lw=1.2)
        mid = 0.5 * (f.outline[a] + f.outline[b])
        ax.text(mid[0], mid[1], f"{'V' if f.fold_valley else 'M'} {f.fold_angle:.3f}°", color="b",
                ha="center", va="bottom", fontsize=8)
    c = f.outline.mean(axis=0)
    ax.text(c[0], c[1], f.id, ha="center", va="top", fontsize=9)
    ax.set_title(f"{f.id} unfolded (fold {f.fold_angle:.2f}°)", fontsize=9)
    ax.set_aspect("equal")
    ax.axis("off")
    for s in range(sheets):
        ax = axes[s + 1]
        ax.add_patch(plt.Rectangle((0, 0), layout.sheet_width, layout.sheet_height, fill=False,
                                   ec="0.5"))
        for i in layout.on_sheet(s):
            p = layout.placed_outline(i)
            p = np.vstack([p, p[:1]])
            ax.fill(p[:, 0], p[:, 1], fc=(0.95, 0.85, 0.6), ec="r", lw=0.6)
            for a, b, _ in flat[i].folds[:1] if len(flat[i].outline) == 4 else []:
                q = layout.placed_outline(i, flat[i].outline[[a, b]])
                ax.plot(q[:, 0], q[:, 1], "b--", lw=0.5)
        ax.set_title(f"sheet {s + 1}/{layout.sheet_count}: "
                     f"{100 * layout.sheet_utilization[s]:.0f}% used", fontsize=9)
        ax.set_aspect("equal")
        ax.axis("off")
    fig.tight_layout()
    fig.savefig(path, dpi=110)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--out", default=os.path.join(REPO, "out", "fabrication"))
    ap.add_argument("--size", type=float, default=900.0)
    ap.add_argument("--figure", action="store_true", help="also write docs/fabrication.png")
    args = ap.parse_args()
    os.makedirs(args.out, exist_ok=True)
    shape = Part.Shape()
    shape.read(os.path.join(HERE, "trimmed_bspline_holes.brep"))
    r = tessella.panelize(shape.Faces[0], method="equal_size_grid", size=args.size)
    t = time.perf_counter()
    flat = tessella.unfold(r)
    t_unfold = time.perf_counter() - t
    t = time.perf_counter()
    layout = tessella.nest(flat, sheet_width=3000.0, sheet_height=1500.0, margin=10.0,
                           spacing=6.0, rotations=4, kerf=0.2)
    t_nest = time.perf_counter() - t
    out = lambda name: os.path.join(args.out, name)  # noqa: E731
    # For the CAM: one file per sheet (origin at the sheet corner) in cam/; for
    # review: every sheet in one drawing.
    os.makedirs(out("cam"), exist_ok=True)
    for old in os.listdir(out("cam")):  # files of an earlier run with more sheets
        if old.endswith(".dxf"):
            os.remove(os.path.join(out("cam"), old))
    tessella.export_dxf(flat, os.path.join(out("cam"), "panels.dxf"), layout=layout)
    tessella.export_dxf(flat, out("panels.dxf"), layout=layout, per_sheet=False)
    tessella.export_svg(flat, out("panels.svg"), layout=layout)
    mx.write_panel_fabrication_schedule(r, flat, out("panels_fabrication.csv"))
    mx.write_cut_list(r, out("cut_list.csv"))
    mx.write_rod_data(r, out("rods.csv"))
    mx.write_node_schedule(r, out("nodes.csv"))
    mx.write_structural_json(r, out("frame.json"))
    mx.write_abaqus_inp(r, out("frame.inp"), profile=("rect", 60.0, 160.0))
    summary = tessella.buildability(r, flat=flat, layout=layout)
    summary["unfold_seconds"] = t_unfold
    summary["nest_seconds"] = t_nest
    with open(out("buildability.json"), "w") as f:
        json.dump(summary, f, indent=1)
    for k, v in summary.items():
        print(f"{k:24s} {v:.6g}" if isinstance(v, float) else f"{k:24s} {v}")
    if args.figure:
        figure(r, flat, layout, os.path.join(REPO, "docs", "fabrication.png"))


if __name__ == "__main__":
    main()
