"""No cliff on big surfaces: iso_grid panelize (metrics included) on a smooth
terrain-like bicubic B-spline face with 312 x 323 poles against the same kind
of face with 10 x 10 poles, at the same panel count. Prints the time per panel
of each, their ratio (target: under 3) and how many projections needed the
global search.

    PYTHONPATH=/usr/lib/freecad-python3/lib:$PWD /usr/bin/python3 bench/no_cliff.py [--count 72] [--threads N]

The faces are built in code (bench/bench_faces.py), parsed once; the time is
the core pipeline call alone (core.panelize on the parsed face), best of
--repeat runs. Also runs against another build: put that build's repository
first on PYTHONPATH.
"""

import argparse
import os
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)

import FreeCAD  # noqa: E402,F401  (before Part, always)
import Part  # noqa: E402,F401

import bench_faces  # noqa: E402
from freecad_workbench import core  # noqa: E402


def run(face, count, repeat):
    sf = core.SurfaceFace.from_brep_string(face.exportBrepToString())
    values = {"u_count": count, "v_count": count}
    best = None
    for _ in range(repeat):
        t0 = time.perf_counter()
        r = core.panelize(sf, "iso_grid", values, None)
        dt = time.perf_counter() - t0
        if best is None or dt < best[0]:
            best = (dt, r)
    dt, r = best
    s = r.summary
    n = s["panel_count"]
    return {"panels": n, "seconds": dt, "per_panel_us": 1e6 * dt / n,
            "metrics_seconds": s.get("metrics_seconds"),
            "global": s.get("global_projections", "-"),
            "threads": s.get("metrics_threads", 1),
            "deviation_max": s["panel_deviation"]["max"]}


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--count", type=int, default=72, help="panels per side (72: 5,184 panels)")
    ap.add_argument("--threads", type=int, default=0, help="TESSELLA_THREADS (0: all cores)")
    ap.add_argument("--repeat", type=int, default=2)
    args = ap.parse_args(argv)
    if args.threads > 0:
        os.environ["TESSELLA_THREADS"] = str(args.threads)
    rows = []
    for nu, nv in ((10, 10), (312, 323)):
        face = bench_faces.terrain_face(nu, nv)
        row = run(face, args.count, args.repeat)
        row["face"] = f"{nu} x {nv} poles"
        rows.append(row)
    print(f"{'face':<18}{'panels':>8}{'threads':>8}{'seconds':>10}{'us/panel':>10}"
          f"{'global proj.':>14}{'max dev (mm)':>14}")
    for r in rows:
        print(f"{r['face']:<18}{r['panels']:>8}{r['threads']:>8}{r['seconds']:>10.3f}"
              f"{r['per_panel_us']:>10.1f}{str(r['global']):>14}{r['deviation_max']:>14.2f}")
    ratio = rows[1]["per_panel_us"] / rows[0]["per_panel_us"]
    print(f"time per panel, 312 x 323 over 10 x 10: {ratio:.2f} (target: under 3)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
