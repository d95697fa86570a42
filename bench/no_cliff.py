"""No cliff on big surfaces: iso_grid panelize (metrics included) at the same
panel count on a smooth bicubic B-spline face with 10 x 10 poles (the
reference) and on big faces:

- the same surface with knots inserted to 312 x 323 poles (the same shape:
  what the surface's size alone costs);
- a terrain-like face with 312 x 323 poles whose hills are as fine as the
  poles carry (about two panels a hill: its panels are rougher than large);
- OCCT's public terrain test face (312 x 323 poles; from the occt-misc
  package, /usr/share/opencascade/data/occ/terrain.brep, if installed:
  `make bench-deps`), the face the target was set on.

Prints the time per panel of each, its ratio to the reference (target: under
3), the deviation measure alone on the same panels (core.measure_panels on
the result's mesh, checked to give the pipeline's figures bit for bit) per
panel and over the reference's whole time per panel, how many projections
needed the global search and the largest deviation.

    PYTHONPATH=/usr/lib/freecad-python3/lib:$PWD /usr/bin/python3 bench/no_cliff.py [--count 72] [--threads N]

The faces are built in code (bench/bench_faces.py) or read once; the time is
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

OCCT_TERRAIN = "/usr/share/opencascade/data/occ/terrain.brep"


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
    # The deviation measure alone on the same panels (the pipeline's figures
    # bit for bit): what the ratio cannot go below while the measure stays.
    measure = None
    for _ in range(repeat):
        t0 = time.perf_counter()
        m = core.measure_panels(sf, r.mesh, core.MetricsParams(), None)
        t = time.perf_counter() - t0
        measure = t if measure is None else min(measure, t)
    if list(m.deviation) != list(r.metrics.deviation):
        raise SystemExit("the measure alone differs from the pipeline's")
    return {"panels": n, "seconds": dt, "per_panel_us": 1e6 * dt / n,
            "measure_us": 1e6 * measure / n,
            "metrics_seconds": s.get("metrics_seconds"),
            "global": s.get("global_projections", "-"),
            "threads": s.get("metrics_threads", 1),
            "deviation_max": s["panel_deviation"]["max"]}


def faces():
    """(name, face) of the reference first, then the big faces."""
    small = bench_faces.terrain_face(10, 10)
    out = [("10 x 10 poles (reference)", small),
           ("same, knots to 312 x 323", bench_faces.refined_face(small, 312, 323)),
           ("312 x 323, fine hills", bench_faces.terrain_face(312, 323))]
    if os.path.exists(OCCT_TERRAIN):
        shape = Part.Shape()
        shape.read(OCCT_TERRAIN)
        face = max(shape.Faces, key=lambda f: f.Area)
        poles = f"{face.Surface.NbUPoles} x {face.Surface.NbVPoles}"
        out.append((f"OCCT terrain {poles}", face))
    else:
        print(f"({OCCT_TERRAIN} not installed: `make bench-deps` adds occt-misc)")
    return out


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--count", type=int, default=72, help="panels per side (72: 5,184 panels)")
    ap.add_argument("--threads", type=int, default=0, help="TESSELLA_THREADS (0: all cores)")
    ap.add_argument("--repeat", type=int, default=2)
    args = ap.parse_args(argv)
    if args.threads > 0:
        os.environ["TESSELLA_THREADS"] = str(args.threads)
    rows = []
    for name, face in faces():
        row = run(face, args.count, args.repeat)
        row["face"] = name
        rows.append(row)
    ref = rows[0]["per_panel_us"]
    print(f"{'face':<28}{'panels':>8}{'threads':>8}{'seconds':>10}{'us/panel':>10}"
          f"{'ratio':>8}{'measure us':>12}{'ratio':>7}{'global proj.':>14}{'max dev (mm)':>14}")
    for r in rows:
        print(f"{r['face']:<28}{r['panels']:>8}{r['threads']:>8}{r['seconds']:>10.3f}"
              f"{r['per_panel_us']:>10.1f}{r['per_panel_us'] / ref:>8.2f}"
              f"{r['measure_us']:>12.1f}{r['measure_us'] / ref:>7.2f}{str(r['global']):>14}"
              f"{r['deviation_max']:>14.2f}")
    print("ratio: time per panel over the reference's (target: under 3); measure: the deviation\n"
          "measure alone on the same panels per panel, and over the reference's whole time per\n"
          "panel (the ratio no faster method, merge or summary takes below)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
