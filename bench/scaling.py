"""How panelize scales: iso_grid on one trimmed doubly curved face (the dome
with an opening of bench/bench_faces.py) from about 1,000 to about 128,000
panels, each size in its own process. Prints panels, seconds (the core
pipeline call on the parsed face, metrics included, best of --repeat), time per
panel, the metrics' share, and the peak memory of the process (ru_maxrss; the
doubling sizes and 10,000 and 100,000 panels), then
the exponents fitted to time ~ panels^k and to the memory above the process's
footprint before the call.

    PYTHONPATH=/usr/lib/freecad-python3/lib:$PWD /usr/bin/python3 bench/scaling.py [--max 128000]
"""

import argparse
import json
import math
import os
import resource
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))


def child(panels, repeat):
    sys.path.insert(0, HERE)
    import FreeCAD  # noqa: F401  (before Part, always)
    import Part  # noqa: F401

    import bench_faces
    from freecad_workbench import core

    face = bench_faces.dome_with_opening()
    sf = core.SurfaceFace.from_brep_string(face.exportBrepToString())
    size = math.sqrt(face.Area / panels)
    before = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
    best = None
    for _ in range(repeat):
        t0 = time.perf_counter()
        r = core.panelize(sf, "iso_grid", {"size": size}, None)
        dt = time.perf_counter() - t0
        if best is None or dt < best[0]:
            best = (dt, r.summary)
        del r
    peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
    dt, s = best
    print(json.dumps({"panels": s["panel_count"], "seconds": dt,
                      "metrics_seconds": s.get("metrics_seconds", float("nan")),
                      "threads": s.get("metrics_threads", 1),
                      "global": s.get("global_projections", -1),
                      "peak_mb": peak / 1024.0, "base_mb": before / 1024.0}))


def fit(xs, ys):
    lx = [math.log(x) for x in xs]
    ly = [math.log(y) for y in ys]
    mx, my = sum(lx) / len(lx), sum(ly) / len(ly)
    sxx = sum((a - mx) ** 2 for a in lx)
    return sum((a - mx) * (b - my) for a, b in zip(lx, ly)) / sxx if sxx > 0 else float("nan")


def main(argv=None):
    argv = sys.argv[1:] if argv is None else argv
    if argv[:1] == ["--child"]:
        child(int(argv[1]), int(argv[2]))
        return 0
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--min", type=int, default=1000)
    ap.add_argument("--max", type=int, default=128000)
    ap.add_argument("--repeat", type=int, default=2)
    args = ap.parse_args(argv)
    targets = []
    n = args.min
    while n <= args.max:
        targets.append(n)
        n *= 2
    # The issue's own sizes for the peak memory: 10,000 and 100,000 panels.
    targets = sorted(set(targets) | {t for t in (10000, 100000) if args.min <= t <= args.max})
    rows = []
    print(f"{'panels':>8}{'seconds':>10}{'us/panel':>10}{'metrics':>9}{'threads':>8}"
          f"{'global':>8}{'peak MB':>9}{'+MB':>8}", flush=True)
    for target in targets:
        out = subprocess.run([sys.executable, os.path.abspath(__file__), "--child", str(target),
                              str(args.repeat)], capture_output=True, text=True)
        if out.returncode != 0:
            print(f"{target:>8} failed: {out.stderr.strip().splitlines()[-1:]}")
            continue
        r = json.loads(out.stdout.strip().splitlines()[-1])
        rows.append(r)
        share = r["metrics_seconds"] / r["seconds"]
        print(f"{r['panels']:>8}{r['seconds']:>10.3f}{1e6 * r['seconds'] / r['panels']:>10.1f}"
              f"{share:>9.0%}{r['threads']:>8}{r['global']:>8}{r['peak_mb']:>9.0f}"
              f"{r['peak_mb'] - r['base_mb']:>8.0f}", flush=True)
    if len(rows) >= 2:
        k_time = fit([r["panels"] for r in rows], [r["seconds"] for r in rows])
        grown = [(r["panels"], r["peak_mb"] - r["base_mb"]) for r in rows
                 if r["peak_mb"] - r["base_mb"] > 1]
        k_mem = fit(*zip(*grown)) if len(grown) >= 2 else float("nan")
        print(f"fitted exponent: time ~ panels^{k_time:.2f}, memory above the footprint "
              f"~ panels^{k_mem:.2f} (1.00 = linear)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
