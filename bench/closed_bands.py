"""Bands closed on themselves (bench_faces.closed_band: random B-spline bands
interpolated round a closed section, not periodic, some to an apex, some
closed along v) with every tiling method: how many runs conform, how many are
refused with a clear error, and how many break an invariant (two nodes in one
place, or more than 0.1% of the face uncovered or covered twice).

    PYTHONPATH=/usr/lib/freecad-python3/lib:$PWD /usr/bin/python3 bench/closed_bands.py [--first 100] [--count 40]

Against another build: put that build's repository first on PYTHONPATH.
"""

import argparse
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
# The tests' own check of one position taken twice.
sys.path.insert(0, os.path.join(os.path.dirname(HERE), "tests", "python"))

import FreeCAD  # noqa: E402,F401  (before Part, always)
import Part  # noqa: E402,F401
import numpy as np  # noqa: E402

import bench_faces  # noqa: E402
import freecad_workbench as tessella  # noqa: E402
from conftest import close_node_pairs  # noqa: E402

METHODS = ("iso_grid", "equal_size_grid", "boundary_driven", "walking_agent")


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--first", type=int, default=100, help="first seed")
    ap.add_argument("--count", type=int, default=40, help="bands")
    args = ap.parse_args(argv)
    tally = {m: {"ok": 0, "refused": 0, "broken": 0} for m in METHODS}
    for seed in range(args.first, args.first + args.count):
        face, size = bench_faces.closed_band(seed)
        model = face.BoundBox.DiagonalLength
        for method in METHODS:
            kw = ({"max_size": size, "max_deviation": 0.01 * size} if method == "walking_agent"
                  else {"size": size})
            try:
                r = tessella.panelize(face, method=method, **kw)
            except (ValueError, RuntimeError) as e:
                tally[method]["refused"] += 1
                print(f"seed {seed} {method}: refused: {str(e)[:110]}")
                continue
            s = r.summary
            if (close_node_pairs(np.asarray(r.vertices[r.nodes]), 1e-6 * model)
                    or s["gap_fraction"] > 1e-3 or s["overlap_fraction"] > 1e-3):
                tally[method]["broken"] += 1
                print(f"seed {seed} {method}: BROKEN gap {s['gap_fraction']:.3g} "
                      f"overlap {s['overlap_fraction']:.3g}")
                continue
            tally[method]["ok"] += 1
    print(f"\n{args.count} bands (seeds {args.first}..{args.first + args.count - 1}):")
    print(f"  {'method':<18}{'ok':>5}{'refused':>9}{'broken':>8}")
    for method in METHODS:
        t = tally[method]
        print(f"  {method:<18}{t['ok']:>5}{t['refused']:>9}{t['broken']:>8}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
