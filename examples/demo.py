"""Tessella demo: panelizes the bundled example faces and writes what a workshop gets.

    make demo
    # or: PYTHONPATH=/usr/lib/freecad-python3/lib:. /usr/bin/python3 examples/demo.py --out out

Writes into the output folder:
    tessella_demo.FCStd                  one source face and one Panelization per run, side
                                         by side; the first run's schedules (spreadsheets)
    panels_<example>_<method>.csv        panel schedule (rods_*.csv, nodes_*.csv too)
    tessella_demo.png                    panels coloured by deviation, one view per run
and prints a summary table. Headless, reads no stdin.
"""

import argparse
import os
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(HERE)
FREECAD_LIB = "/usr/lib/freecad-python3/lib"
for _p in (FREECAD_LIB, REPO):
    if _p not in sys.path:
        sys.path.append(_p)

import FreeCAD  # noqa: E402  (before Part, see DESIGN.md)
import Part  # noqa: E402

import freecad_workbench as tessella  # noqa: E402
from freecad_workbench.export import write_schedules  # noqa: E402

#: (example file stem, method, parameters). Sizes give a few hundred panels each.
RUNS = (
    ("trimmed_bspline_holes", "iso_grid", {"size": 800.0}),
    ("trimmed_bspline_holes", "equal_size_grid", {"size": 800.0}),
    ("bezier_patch", "iso_grid", {"size": 550.0}),
    ("cylinder_part", "iso_grid", {"size": 500.0}),
    ("plane", "iso_grid", {"size": 250.0}),
    ("full_cylinder", "iso_grid", {"size": 600.0}),
)


def load_face(name, folder=HERE):
    shape = Part.Shape()
    shape.read(os.path.join(folder, name + ".brep"))
    faces = shape.Faces
    if len(faces) != 1:
        raise RuntimeError(f"{name}.brep holds {len(faces)} faces, expected 1")
    return faces[0]


def run_all(runs=RUNS, folder=HERE):
    """Panelizes every run with the console API. Returns [(example, method, params, result, seconds)]."""
    out = []
    for name, method, params in runs:
        face = load_face(name, folder)
        t0 = time.perf_counter()
        result = tessella.panelize(face, method=method, **params)
        out.append((name, method, params, result, time.perf_counter() - t0))
    return out


def grid_layout(boxes, columns=3):
    """Offsets (FreeCAD.Vector) that lay the boxes out in rows of `columns`,
    a tenth of the largest size apart: a picture that fills a wide view."""
    gap = 0.1 * max(max(b.XLength, b.YLength) for b in boxes)
    out, x, y, row_depth = [], 0.0, 0.0, 0.0
    for k, b in enumerate(boxes):
        if k and k % columns == 0:
            x, y, row_depth = 0.0, y - row_depth - gap, 0.0
        out.append(FreeCAD.Vector(x - b.XMin, y - b.YMax, 0.0))
        x += b.XLength + gap
        row_depth = max(row_depth, b.YLength)
    return out


def build_document(runs, path, folder=HERE):
    """A FreeCAD document: one Part::Feature per source face, one Panelization per run."""
    try:
        from freecad_workbench import make  # noqa: F401
    except ImportError as exc:
        make = None
        print(
            f"WARNING: freecad_workbench.make is not available ({exc}); the document gets "
            "plain Part::Feature compounds instead of parametric Panelization objects.",
            file=sys.stderr,
        )
    doc = FreeCAD.newDocument("tessella_demo")
    try:
        faces = [load_face(name, folder) for name, *_ in runs]
        places = grid_layout([f.BoundBox for f in faces])
        for (name, method, params, result, _), face, place in zip(runs, faces, places):
            # One source per run, laid out side by side so no two runs overlap.
            feature = doc.addObject("Part::Feature", name)
            feature.Label = f"{name}_{method}_source"
            feature.Shape = face
            feature.Placement = FreeCAD.Placement(place, FreeCAD.Rotation())
            if make is not None:
                parent = tessella.make_panelization(
                    (feature, "Face1"), method=method, doc=doc, **params
                )
                parent.Label = f"Panelization_{name}_{method}"
                from freecad_workbench.features.panelization import children_of

                for child in children_of(parent):  # the legend names the run
                    child.Label = f"{child.Role} {name} {method}"
                # The document's objects and the console run must agree.
                got = (parent.PanelCount, parent.RodCount, parent.NodeCount)
                want = (len(result.panels), len(result.rods), len(result.nodes))
                if got != want:
                    raise RuntimeError(
                        f"{parent.Label}: document has panels/rods/nodes {got}, "
                        f"console API gave {want}"
                    )
            else:
                panels = Part.Shape()
                panels.importBrepFromString(result.panels_brep())
                fallback = doc.addObject("Part::Feature", f"Panels_{name}_{method}")
                fallback.Shape = panels
        doc.recompute()
        if make is not None:  # the schedules of the first run, as the Schedules command makes them
            first = [o for o in doc.Objects if o.Label.startswith("Panelization_")][0]
            tessella.make_schedules(first)
        broken = [o.Label for o in doc.Objects if "Invalid" in o.State or "Error" in o.State]
        if broken:
            raise RuntimeError(f"objects failed to recompute: {', '.join(broken)}")
        if os.path.exists(path):
            os.remove(path)
        doc.saveAs(path)
        return len(doc.Objects)
    finally:
        FreeCAD.closeDocument(doc.Name)


def plot(runs, path):
    """One 3D view per run, panels coloured by deviation, with a colour bar each."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import numpy as np
    from mpl_toolkits.mplot3d.art3d import Poly3DCollection

    cols = 3
    rows = (len(runs) + cols - 1) // cols
    fig = plt.figure(figsize=(6.0 * cols, 5.2 * rows))
    cmap = plt.get_cmap("viridis")
    for k, (name, method, params, r, _) in enumerate(runs):
        ax = fig.add_subplot(rows, cols, k + 1, projection="3d")
        xyz = r.vertices / 1000.0  # m
        dev = np.asarray(r.metrics["panel_deviation"])
        vmax = max(float(dev.max()) if len(dev) else 0.0, 1e-3)
        norm = matplotlib.colors.Normalize(vmin=0.0, vmax=vmax)
        polys = [xyz[list(p)] for p in r.panels]
        coll = Poly3DCollection(polys, facecolors=cmap(norm(dev)), edgecolors="k", linewidths=0.3)
        ax.add_collection3d(coll)
        lo, hi = xyz.min(axis=0), xyz.max(axis=0)
        pad = np.maximum(0.02 * (hi - lo).max() - (hi - lo), 0.0) / 2.0  # flat axes get a little depth
        lo, hi = lo - pad, hi + pad
        ax.set_xlim(lo[0], hi[0])
        ax.set_ylim(lo[1], hi[1])
        ax.set_zlim(lo[2], hi[2])
        ax.set_box_aspect(hi - lo)
        ax.set_xlabel("x (m)")
        ax.set_ylabel("y (m)")
        ax.set_zlabel("z (m)")
        ax.tick_params(labelsize=7)
        if (hi - lo)[2] <= 0.05 * (hi - lo).max():  # flat or nearly: z ticks only clutter
            ax.set_zticks([])
            ax.set_zlabel("")
        else:
            ax.locator_params(axis="z", nbins=4)
        s = r.summary
        ax.set_title(
            f"{name} / {method} (size {params.get('size', 0):g} mm)\n"
            f"{s['panel_count']} panels, {s['rod_count']} rods, {s['node_count']} nodes, "
            f"{s['irregular_count']} irregular",
            fontsize=9,
        )
        sm = matplotlib.cm.ScalarMappable(norm=norm, cmap=cmap)
        sm.set_array([])
        fig.colorbar(sm, ax=ax, shrink=0.6, pad=0.14, label="deviation (mm)")
    fig.suptitle("Tessella: panels coloured by deviation from the surface", fontsize=12)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def _stat(stats, key):
    """A field of a summarize() result (a dict, or an object with attributes)."""
    return stats[key] if isinstance(stats, dict) else getattr(stats, key)


def summary_table(runs):
    head = f"{'example':24s} {'method':16s} {'panels':>6s} {'rods':>6s} {'nodes':>6s} " \
           f"{'max dev mm':>10s} {'irregular':>9s} {'time s':>6s}"
    lines = [head, "-" * len(head)]
    for name, method, _, r, seconds in runs:
        s = r.summary
        lines.append(
            f"{name:24s} {method:16s} {s['panel_count']:6d} {s['rod_count']:6d} "
            f"{s['node_count']:6d} {s['panel_deviation']['max']:10.2f} {s['irregular_count']:9d} "
            f"{seconds:6.2f}"
        )
    return "\n".join(lines)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", default="out", help="output folder (created)")
    parser.add_argument("--no-document", action="store_true", help="skip the .FCStd")
    parser.add_argument("--no-plot", action="store_true", help="skip the .png")
    args = parser.parse_args(argv)
    out = os.path.abspath(args.out)
    os.makedirs(out, exist_ok=True)

    t0 = time.perf_counter()
    runs = run_all()
    for name, method, _, r, _ in runs:
        write_schedules(r, out, f"{name}_{method}")
    print(summary_table(runs))
    written = [f"panels_/rods_/nodes_<example>_<method>.csv ({3 * len(runs)} files)"]
    if not args.no_document:
        path = os.path.join(out, "tessella_demo.FCStd")
        count = build_document(runs, path)
        written.append(f"tessella_demo.FCStd ({count} objects)")
    if not args.no_plot:
        plot(runs, os.path.join(out, "tessella_demo.png"))
        written.append("tessella_demo.png")
    print(f"\nwrote into {out}: " + ", ".join(written))
    print(f"total {time.perf_counter() - t0:.1f} s")
    return 0


if __name__ == "__main__":
    sys.exit(main())
