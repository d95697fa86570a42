"""chebyshev_net against the grids on the bundled examples: how many rods
inside the face are exactly `size` long (within 1e-6 of it, measured from the
result's vertices), the rod-length spread of all rods, the panel families at
2 mm against exact congruence (1e-3 mm), the largest deviation and the time.

    PYTHONPATH=/usr/lib/freecad-python3/lib:$PWD /usr/bin/python3 bench/chebyshev_net.py [--size 1500] [--methods chebyshev_net,equal_size_grid]

Prints one Markdown table (docs/chebyshev_net.md).
"""

import argparse
import os
import sys
import time
from collections import Counter

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
for _p in ("/usr/lib/freecad-python3/lib", REPO):
    if _p not in sys.path:
        sys.path.append(_p)

import FreeCAD  # noqa: E402,F401  (before Part)
import Part  # noqa: E402
import numpy as np  # noqa: E402

import freecad_workbench as tessella  # noqa: E402
from freecad_workbench import families  # noqa: E402

EXAMPLES = ["british_museum_roof", "chen_shan_dome", "sun_valley_funnel", "notched_shell",
            "trimmed_bspline_holes", "vault_openings", "cone_facade", "bezier_patch"]
# The small examples at a size that gives a few hundred panels.
SMALL_SIZE = {"notched_shell": 400.0, "trimmed_bspline_holes": 400.0, "vault_openings": 400.0,
              "cone_facade": 400.0, "bezier_patch": 400.0}


def rod_figures(r, size):
    """(rods inside the face, share of them within 1e-6 of size, CV of all rods)."""
    xyz = np.asarray(r.vertices, dtype=float).reshape(-1, 3)
    sides = Counter()
    for p in r.panels:
        for a, b in zip(p, list(p[1:]) + [p[0]]):
            sides[(min(a, b), max(a, b))] += 1
    rim = {v for side, n in sides.items() if n == 1 for v in side}
    rods = np.asarray(r.rods)
    lengths = np.linalg.norm(xyz[rods[:, 0]] - xyz[rods[:, 1]], axis=1)
    inside = np.array([a not in rim and b not in rim for a, b in rods])
    equal = np.abs(lengths[inside] - size) <= 1e-6 * size
    return int(inside.sum()), float(equal.mean()) if inside.any() else 0.0, \
        float(lengths.std() / lengths.mean())


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--size", type=float, default=1500.0, help="size of the big examples (mm)")
    ap.add_argument("--methods", default="chebyshev_net,equal_size_grid,iso_grid")
    args = ap.parse_args()
    methods = args.methods.split(",")
    print("| example | method | size mm | panels | rods inside | of them exactly `size` | "
          "rod CV (all) | families 1e-3 mm | 2 mm | fewer | largest deviation mm | s |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|")
    for name in EXAMPLES:
        face = Part.read(os.path.join(REPO, "examples", f"{name}.brep")).Faces[0]
        size = SMALL_SIZE.get(name, args.size)
        for method in methods:
            t0 = time.perf_counter()
            try:
                r = tessella.panelize(face, method=method, size=size)
            except Exception as e:  # noqa: BLE001  (a refusal is a figure too)
                print(f"| {name} | {method} | {size:g} | refused: {e} |")
                continue
            seconds = time.perf_counter() - t0
            inside, share, cv = rod_figures(r, size)
            corners = families.panel_corners(r)
            exact = families.families_of_corners(corners, 1e-3).count
            at2 = families.families_of_corners(corners, 2.0).count
            dev = float(np.max(r.metrics["panel_deviation"]))
            print(f"| {name} | {method} | {size:g} | {len(r.panels)} | {inside} | "
                  f"{100 * share:.1f}% | {cv:.3f} | {exact} | {at2} | "
                  f"{100 * (exact - at2) / exact:.0f}% | {dev:.1f} | {seconds:.2f} |", flush=True)


if __name__ == "__main__":
    main()
