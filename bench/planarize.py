"""Planarization (tessella.planarize) side by side: planarity reached against
distance from the surface, with the closeness goal on (a 20 mm band, hard) and
off (what libigl's planarize_quad_mesh does), on iso grids and boundary-driven
meshes and the curvature-line layout (method="curvature_lines") of two
surfaces of revolution and the bundled doubly curved examples.

    PYTHONPATH=/usr/lib/freecad-python3/lib:$PWD /usr/bin/python3 bench/planarize.py [--size 1500]

Prints one row per face, layout and mode: quads, planar within 1 mm before /
after, largest diagonal distance before / after (mm), largest node distance
from the surface after (mm), rounds, core seconds.
"""

import argparse
import math
import os
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.path.insert(0, ROOT)

import FreeCAD  # noqa: E402,F401  (before Part)
import Part  # noqa: E402
from FreeCAD import Vector as V  # noqa: E402

import freecad_workbench as tessella  # noqa: E402
from freecad_workbench import planarize  # noqa: E402


def funnel():
    pts = []
    for i in range(9):
        r = 800.0 + 4200.0 * (i / 8) ** 2.5
        pts.append([V(r * math.cos(math.pi * j / 12), r * math.sin(math.pi * j / 12), 750.0 * i)
                    for j in range(13)])
    s = Part.BSplineSurface()
    s.interpolate(pts)
    return s.toShape()


def vase():
    """A vase turned by 120 degrees: radius 3000 + 1500 sin(z / 2500), 12 m high."""
    pts = [[V((3000 + 1500 * math.sin(z / 2500.0)) * math.cos(math.radians(120) * j / 12),
              (3000 + 1500 * math.sin(z / 2500.0)) * math.sin(math.radians(120) * j / 12), z)
            for j in range(13)] for z in [1200.0 * i for i in range(11)]]
    s = Part.BSplineSurface()
    s.interpolate(pts)
    return s.toShape()


def example(name):
    s = Part.Shape()
    s.read(os.path.join(ROOT, "examples", name + ".brep"))
    return s.Faces[0]


def draw_classes(r, title, path):
    """Top view of the panels coloured by class (matplotlib, PNG)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.collections import PolyCollection
    from matplotlib.patches import Patch

    cls = tessella.panel_classes(r)
    colours = {0: "#d9ead3", 1: "#f6b26b", 2: "#cc0000"}
    fig, ax = plt.subplots(figsize=(7, 7))
    polys = [r.vertices[list(p)][:, :2] for p in r.panels]
    ax.add_collection(PolyCollection(polys, facecolors=[colours[int(c)] for c in cls.labels],
                                     edgecolors="k", linewidths=0.3))
    ax.autoscale()
    ax.set_aspect("equal")
    ax.set_axis_off()
    counts = cls.counts
    ax.set_title(f"{title}: curvature_lines + planarize, {len(r.panels)} panels")
    ax.legend(handles=[Patch(color=colours[k], label=f"{n}: {counts[n]}")
                       for k, n in enumerate(("flat", "cold-bent", "curved"))],
              loc="lower right", fontsize=8)
    os.makedirs(os.path.dirname(path) or ".", exist_ok=True)
    fig.savefig(path, dpi=80, bbox_inches="tight")
    plt.close(fig)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--size", type=float, default=1500.0)
    ap.add_argument("--pictures", metavar="DIR",
                    help="also draw each face's curvature-line panels after planarize, "
                         "coloured by class (flat / cold-bent / curved), top view, to DIR")
    args = ap.parse_args()
    faces = [("funnel (revolution)", funnel()),
             ("vase (revolution)", vase()),
             ("british_museum_roof", example("british_museum_roof")),
             ("chen_shan_dome", example("chen_shan_dome")),
             ("notched_shell", example("notched_shell"))]
    print(f"{'face':22s} {'layout':16s} {'closeness':9s} {'quads':>5s} {'planar 1mm':>13s} "
          f"{'max diag (mm)':>17s} {'node dev':>9s} {'rounds':>6s} {'s':>6s}")
    for name, face in faces:
        for layout in ("curvature_lines", "iso_grid", "boundary_driven"):
            try:
                r = tessella.panelize(face, method=layout, size=args.size)
            except (ValueError, RuntimeError) as exc:
                print(f"{name:22s} {layout:16s} refused: {exc}")
                continue
            for closeness in (0.1, 0.0):
                t = time.perf_counter()
                r2, rep = planarize(r, planarity_tolerance=1.0, max_deviation=20.0,
                                    closeness=closeness)
                if args.pictures and layout == "curvature_lines" and closeness:
                    draw_classes(r2, name, os.path.join(args.pictures,
                                                        f"planar_{name.split()[0]}.png"))
                dt = time.perf_counter() - t
                print(f"{name:22s} {layout:16s} {'on' if closeness else 'off':9s} "
                      f"{rep['quads']:5d} {rep['planar_before']:5d} -> {rep['planar_after']:5d} "
                      f"{rep['max_planarity_before']:7.1f} -> {rep['max_planarity_after']:6.1f} "
                      f"{rep['max_node_deviation_after']:9.1f} {rep['iterations']:6d} {dt:6.2f}",
                      flush=True)


if __name__ == "__main__":
    main()
