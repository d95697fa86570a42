"""Random multi-face shapes (bench_faces.random_face_set: B-spline faces split
by random planes, boxes with random fillets, revolved profiles with a planar
top, extruded closed curves with caps, a box fused with a cylinder) with the
four face-set methods: how many runs conform, how many are refused with a
clear error, and how many break an invariant of the face-set tests
(tests/python/test_face_sets.py: check_conforming: two nodes in one place, a
node off the shape, a panel with a corner twice, a shared-edge segment
without its rod or without a panel of each face), and how many results
carry the product's own warning of that (summary "join_warning"; a
result that conforms but is warned is reported as broken, by
check_conforming). Coverage is the
pipeline's own check (each face refused beyond 0.1% uncovered or covered
twice, the strips between a curved shared edge and its chords allowed).

    PYTHONPATH=/usr/lib/freecad-python3/lib:$PWD /usr/bin/python3 bench/random_face_sets.py [--first 0] [--count 40] [--threads-check]

--threads-check also runs each case on one thread and on two and compares
the results bit for bit. Against another build: put that build's repository
first on PYTHONPATH.
"""

import argparse
import os
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
# The face-set tests' own invariants.
sys.path.insert(0, os.path.join(os.path.dirname(HERE), "tests", "python"))

import FreeCAD  # noqa: E402,F401  (before Part, always)
import Part  # noqa: E402,F401

import bench_faces  # noqa: E402
import freecad_workbench as tessella  # noqa: E402
from face_set_sweep import first_difference  # noqa: E402  (the sweep's own comparison)
from test_face_sets import check_conforming  # noqa: E402

METHODS = ("iso_grid", "equal_size_grid", "boundary_driven", "walking_agent")
# Also taken (--methods): gradient_descent, relaxed_grid.


def method_kw(method, size):
    """The parameters for about `size` panels: walking_agent's largest panel
    and a bound of 1% of it; gradient_descent that bound (it sizes its
    panels from it); relaxed_grid 6 x 6 per face; the others the size."""
    if method == "walking_agent":
        return {"max_size": size, "max_deviation": 0.01 * size}
    if method == "gradient_descent":
        return {"max_deviation": 0.01 * size}
    if method == "relaxed_grid":
        return {"u_count": 6, "v_count": 6}
    return {"size": size}


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--first", type=int, default=0, help="first seed")
    ap.add_argument("--count", type=int, default=40, help="shapes")
    ap.add_argument("--methods", nargs="+", default=list(METHODS))
    ap.add_argument("--threads-check", action="store_true")
    args = ap.parse_args(argv)
    tally = {m: {"ok": 0, "refused": 0, "broken": 0, "warned": 0, "threads": 0}
             for m in args.methods}
    t0 = time.perf_counter()
    for seed in range(args.first, args.first + args.count):
        kind, shape, size = bench_faces.random_face_set(seed)
        for method in args.methods:
            kw = method_kw(method, size)
            try:
                r = tessella.panelize_faces(shape, method=method, **kw)
            except (ValueError, RuntimeError) as e:
                tally[method]["refused"] += 1
                print(f"seed {seed} {kind} {method}: refused: {str(e)[:150]}", flush=True)
                continue
            # The product's own check of the joined result (summary
            # "join_warning"); check_conforming below is the independent one.
            warning = r.summary.get("join_warning", "")
            tally[method]["warned"] += 1 if warning else 0
            said = " (warned)" if warning else " (not warned)"
            try:
                check_conforming(shape, r)
            except AssertionError as e:
                tally[method]["broken"] += 1
                print(f"seed {seed} {kind} {method}: BROKEN{said} {str(e)[:150]}", flush=True)
                continue
            tally[method]["ok"] += 1
            if args.threads_check:
                one = tessella.panelize_faces(shape, method=method, threads=1, **kw)
                two = tessella.panelize_faces(shape, method=method, threads=2, **kw)
                if first_difference(one, two) is not None:
                    tally[method]["threads"] += 1
                    print(f"seed {seed} {kind} {method}: 1 AND 2 THREADS DIFFER", flush=True)
    print(f"\n{args.count} shapes (seeds {args.first}..{args.first + args.count - 1}), "
          f"{time.perf_counter() - t0:.0f} s:")
    head = f"  {'method':<18}{'ok':>5}{'refused':>9}{'broken':>8}{'warned':>8}"
    print(head + (f"{'1 vs 2 threads differ':>23}" if args.threads_check else ""))
    for method in args.methods:
        t = tally[method]
        line = f"  {method:<18}{t['ok']:>5}{t['refused']:>9}{t['broken']:>8}{t['warned']:>8}"
        print(line + (f"{t['threads']:>23}" if args.threads_check else ""))
    return 0


if __name__ == "__main__":
    sys.exit(main())
