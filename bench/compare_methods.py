"""The thesis' comparison (seed 000, section 5), redone and measured:
walking_agent vs gradient_descent vs relaxed_grid vs iso_grid on five surfaces
at the same deviation bound.

    PYTHONPATH=/usr/lib/freecad-python3/lib:$PWD /usr/bin/python3 bench/compare_methods.py

Writes out/bench/compare_methods.md, .json and compare_methods_*.png and prints
the table. Options: --bound MM (default 20), --out DIR, --quick (fewer search
steps for the coarsest iso_grid).

Every deviation here is the foundation's measure (api.panelize: sampled panel
model projected onto the surface), not a method's own estimate; for
walking_agent the worst panels are also re-measured with FreeCAD's
Surface.parameter ("independent max").

Rows per surface:
- walking_agent (max_deviation = bound)
- gradient_descent (max_deviation = bound as its target)
- relaxed_grid with the same number of grid lines as walking_agent (same node
  budget, fixed topology: the thesis' comparison)
- iso_grid, the coarsest (u_count, v_count) whose panels all meet the bound
  (searched along the frontier of feasible counts)
"""

import argparse
import json
import math
import os
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.path.insert(0, ROOT)

import FreeCAD  # noqa: E402,F401  (before Part)
import numpy as np  # noqa: E402
import Part  # noqa: E402
from FreeCAD import Vector  # noqa: E402

import freecad_workbench as tessella  # noqa: E402
from freecad_workbench import core  # noqa: E402


# ----------------------------------------------------------------- surfaces
def _interpolated(fn, x0, x1, y0, y1, n=25, m=17):
    pts = [[Vector(x, y, fn(x, y)) for y in np.linspace(y0, y1, m)] for x in np.linspace(x0, x1, n)]
    s = Part.BSplineSurface()
    s.interpolate(pts)
    return s.toShape().Faces[0]


def gentle():
    """12 x 8 m shallow dome, 400 mm rise."""
    return _interpolated(lambda x, y: 400 * (1 - (x / 6000) ** 2) * (1 - (y / 4000) ** 2),
                         -6000, 6000, -4000, 4000)


def varying_curvature():
    """12 x 8 m: nearly flat, with a tight ridge (1.2 m high, 0.8 m wide) near
    one end and a gentle slope elsewhere: curvature varies by two orders."""
    return _interpolated(
        lambda x, y: 1200 * math.exp(-(((x + 3500) / 800) ** 2)) + 0.02 * x + 50 * (y / 4000) ** 2,
        -6000, 6000, -4000, 4000, n=49, m=9)


def trimmed_with_hole():
    """The bundled example: trimmed B-spline face with holes."""
    shape = Part.Shape()
    shape.read(os.path.join(ROOT, "examples", "trimmed_bspline_holes.brep"))
    return shape.Faces[0]


def revolution():
    """A half vase: profile r(z) = 3000 + 700 sin(z / 1200), z in [0, 7000] mm,
    revolved by 180 degrees."""
    zs = np.linspace(0, 7000, 15)
    profile = Part.BSplineCurve()
    profile.interpolate([Vector(3000 + 700 * math.sin(z / 1200), 0, z) for z in zs])
    face = profile.toShape().revolve(Vector(0, 0, 0), Vector(0, 0, 1), 180)
    return face.Faces[0]


def saddle():
    """Hyperbolic paraboloid z = (x^2 - y^2) / (2 * 8000) over 10 x 10 m."""
    return _interpolated(lambda x, y: (x * x - y * y) / 16000, -5000, 5000, -5000, 5000, 17, 17)


SURFACES = {
    "gentle": gentle,
    "varying_curvature": varying_curvature,
    "trimmed_with_hole": trimmed_with_hole,
    "revolution": revolution,
    "saddle": saddle,
}


# ----------------------------------------------------------------- measures
def row(result, bound, seconds=None):
    s = result.summary
    dev = result.metrics["panel_deviation"]
    rods = result.metrics["rod_length"]
    return {
        "panels": s["panel_count"],
        "over_bound_share": float(np.mean(dev > bound)) if len(dev) else 0.0,
        "max_deviation": float(dev.max()),
        "mean_deviation": float(dev.mean()),
        "min_edge": float(rods.min()),
        "max_edge": float(rods.max()),
        "quad_share": float(s["quad_share"]),
        "folds": int(s["fold_count"]),
        "surface_evaluations": int(s["surface_evaluations"]),
        "core_ms": 1e3 * float(s["core_seconds"] if seconds is None else seconds),
    }


def best_core_seconds(face, method, repeats=3, **params):
    """Fastest of `repeats` method calls (no metrics), seconds: the C++
    pipeline's own timing of its method stage."""
    surface = core.SurfaceFace.from_brep_string(tessella.api.face_to_brep(face))
    values = tessella.api.core_values(method, params, surface)
    best = math.inf
    for _ in range(repeats):
        best = min(best, core.panelize(surface, method, values).summary["core_seconds"])
    return best


def independent_max(face, result, count=20):
    """FreeCAD's Surface.parameter on sample points of the worst panels' models."""
    surf = face.Surface
    dev = result.metrics["panel_deviation"]
    worst = 0.0
    for k in np.argsort(-dev)[:count]:
        p = result.vertices[list(result.panels[k])]
        s = np.linspace(0, 1, 7)
        if len(p) == 4:
            pts = [(1 - a) * (1 - b) * p[0] + a * (1 - b) * p[1] + a * b * p[2] + (1 - a) * b * p[3]
                   for a in s for b in s]
        elif len(p) == 3:
            pts = [(1 - a - b) * p[0] + a * p[1] + b * p[2] for a in s for b in s if a + b <= 1]
        else:  # n-gon: its edges (any triangulation contains them)
            pts = [(1 - a) * p[i] + a * p[(i + 1) % len(p)] for i in range(len(p)) for a in s]
        for x in pts:
            u, v = surf.parameter(Vector(*x))
            q = surf.value(u, v)
            worst = max(worst, math.dist((q.x, q.y, q.z), x))
    return worst


def coarsest_iso_grid(face, bound, quick=False, cap=40000):
    """(u_count, v_count) with the fewest panels whose max deviation <= bound.
    Feasibility is monotone in each count (denser -> smaller deviation), so the
    frontier is walked as a staircase: for growing u_count, the smallest
    feasible v_count can only shrink."""
    surface = core.SurfaceFace.from_brep_string(tessella.api.face_to_brep(face))
    mp = core.MetricsParams()
    mp.samples = 6
    cache = {}

    def feasible(nu, nv):
        if (nu, nv) not in cache:
            if nu * nv > cap:
                cache[(nu, nv)] = True  # assume (never chosen: too many panels)
                return True
            p = core.IsoGridParams()
            p.u_count, p.v_count = nu, nv
            mesh = core.iso_grid(surface, p)
            cache[(nu, nv)] = max(core.measure_panels(surface, mesh, mp).deviation) <= bound
        return cache[(nu, nv)]

    n = 2
    while not feasible(n, n):
        n *= 2
        if n * n > cap:
            raise RuntimeError("no iso_grid under the panel cap meets the bound")
    top = 4 * n

    def smallest(pred, lo, hi):
        """Smallest k in [lo, hi] with pred(k) (pred monotone, pred(hi) true)."""
        while lo < hi:
            mid = (lo + hi) // 2
            if pred(mid):
                hi = mid
            else:
                lo = mid + 1
        return lo

    # Fewest lines each direction needs with the other one dense.
    nu_min = smallest(lambda k: feasible(k, top), 1, top)
    nv_min = smallest(lambda k: feasible(top, k), 1, top)
    best = (n, n)
    nv_hi = top
    stride = 2 if quick else 1
    nu = nu_min
    while nu <= top and nu * nv_min < best[0] * best[1]:
        if feasible(nu, nv_hi):
            nv_hi = smallest(lambda k: feasible(nu, k), nv_min, nv_hi)
            if nu * nv_hi < best[0] * best[1]:
                best = (nu, nv_hi)
        nu += stride
    return best, len(cache)


# ----------------------------------------------------------------- main
def run(bound, out_dir, quick):
    os.makedirs(out_dir, exist_ok=True)
    table = {}
    for name, make in SURFACES.items():
        face = make()
        print(f"\n== {name}: area {face.Area / 1e6:.1f} m^2", flush=True)
        rows = {}
        wa = tessella.panelize(face, method="walking_agent", max_deviation=bound)
        rows["walking_agent"] = row(wa, bound, best_core_seconds(face, "walking_agent",
                                                                 max_deviation=bound))
        rows["walking_agent"]["independent_max"] = independent_max(face, wa)
        gd = tessella.panelize(face, method="gradient_descent", max_deviation=bound)
        rows["gradient_descent"] = row(gd, bound, best_core_seconds(face, "gradient_descent",
                                                                    max_deviation=bound))
        nu_lines = len(np.unique(np.round(wa.uv[:, 0], 9)))
        nv_lines = len(np.unique(np.round(wa.uv[:, 1], 9)))
        # Same node budget as the walking agent: its number of lines per direction
        # (on a trimmed face the count of distinct (u,v) values overcounts; cap it).
        uc = max(1, min(nu_lines - 1, 200))
        vc = max(1, min(nv_lines - 1, 200))
        if name == "trimmed_with_hole":
            # Boundary nodes sit on the trim, not on lines: use the full-cell layout.
            n_eq = max(2, int(round(math.sqrt(wa.summary["panel_count"]))))
            uc = vc = n_eq
        rg = tessella.panelize(face, method="relaxed_grid", u_count=uc, v_count=vc)
        rows["relaxed_grid"] = row(rg, bound, best_core_seconds(face, "relaxed_grid", repeats=1,
                                                                u_count=uc, v_count=vc))
        rows["relaxed_grid"]["counts"] = [uc, vc]
        t = time.perf_counter()
        (nu, nv), tried = coarsest_iso_grid(face, bound, quick)
        search_s = time.perf_counter() - t
        iso = tessella.panelize(face, method="iso_grid", u_count=nu, v_count=nv)
        rows["iso_grid"] = row(iso, bound, best_core_seconds(face, "iso_grid", u_count=nu,
                                                             v_count=nv))
        rows["iso_grid"]["counts"] = [nu, nv]
        rows["iso_grid"]["search"] = {"grids_tried": tried, "seconds": search_s}
        saving = 1 - rows["walking_agent"]["panels"] / rows["iso_grid"]["panels"]
        table[name] = {"rows": rows, "walking_agent_vs_iso_grid_saving": saving}
        for method, r in rows.items():
            print(f"  {method:17s} panels {r['panels']:6d}  over {100 * r['over_bound_share']:5.1f}%"
                  f"  max {r['max_deviation']:8.2f}  mean {r['mean_deviation']:7.2f}"
                  f"  edges {r['min_edge']:7.1f}..{r['max_edge']:7.1f}  quads {r['quad_share']:.2f}"
                  f"  evals {r['surface_evaluations']:8d}  {r['core_ms']:8.1f} ms", flush=True)
        print(f"  walking_agent vs coarsest iso_grid {nu}x{nv}: {100 * saving:.0f}% fewer panels")
    write_outputs(table, bound, out_dir)
    return table


def write_outputs(table, bound, out_dir):
    with open(os.path.join(out_dir, "compare_methods.json"), "w") as fh:
        json.dump({"bound_mm": bound, "surfaces": table}, fh, indent=2)
    cols = [
        ("panels", "panels", "{:d}"),
        ("over_bound_share", "over bound", "{:.1%}"),
        ("max_deviation", "max dev (mm)", "{:.2f}"),
        ("mean_deviation", "mean dev (mm)", "{:.2f}"),
        ("min_edge", "min edge (mm)", "{:.0f}"),
        ("max_edge", "max edge (mm)", "{:.0f}"),
        ("quad_share", "quads", "{:.2f}"),
        ("surface_evaluations", "surface evals", "{:d}"),
        ("core_ms", "core ms", "{:.1f}"),
    ]
    lines = [f"# Method comparison at a deviation bound of {bound:g} mm", "",
             "Generated by `bench/compare_methods.py`. Deviation: the foundation's measure "
             "(sampled panel model projected onto the surface).", ""]
    for name, entry in table.items():
        rows = entry["rows"]
        lines += [f"## {name}", "",
                  "| method | " + " | ".join(c[1] for c in cols) + " |",
                  "|---|" + "---|" * len(cols)]
        for method, r in rows.items():
            label = method
            if "counts" in r:
                label += f" ({r['counts'][0]}x{r['counts'][1]})"
            lines.append(f"| {label} | " + " | ".join(f.format(r[k]) for k, _, f in cols) + " |")
        wa = rows["walking_agent"]
        lines += ["", f"walking_agent: {wa['folds']} folds; independent max deviation of its 20 "
                  f"worst panels (FreeCAD Surface.parameter): {wa['independent_max']:.2f} mm. "
                  f"Panels vs the coarsest iso_grid meeting the bound: "
                  f"{100 * entry['walking_agent_vs_iso_grid_saving']:.0f}% fewer.", ""]
    with open(os.path.join(out_dir, "compare_methods.md"), "w") as fh:
        fh.write("\n".join(lines) + "\n")
    plot(table, bound, out_dir)


def plot(table, bound, out_dir):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    names = list(table)
    methods = list(next(iter(table.values()))["rows"])
    x = np.arange(len(names))
    w = 0.8 / len(methods)
    for key, title, fname, log in (
        ("panels", "Panels at the same bound", "compare_methods_panels.png", True),
        ("max_deviation", f"Max panel deviation (bound {bound:g} mm)",
         "compare_methods_deviation.png", True),
        ("over_bound_share", "Share of panels over the bound", "compare_methods_over.png", False),
        ("surface_evaluations", "Surface evaluations (method call)",
         "compare_methods_evaluations.png", True),
    ):
        fig, ax = plt.subplots(figsize=(9, 4))
        for i, m in enumerate(methods):
            vals = [table[n]["rows"][m][key] for n in names]
            ax.bar(x + (i - (len(methods) - 1) / 2) * w, vals, w, label=m)
        if key == "max_deviation":
            ax.axhline(bound, color="k", lw=1, ls="--", label="bound")
        if log:
            ax.set_yscale("log")
        ax.set_xticks(x)
        ax.set_xticklabels(names, rotation=15)
        ax.set_title(title)
        ax.legend(fontsize=8)
        fig.tight_layout()
        fig.savefig(os.path.join(out_dir, fname), dpi=110)
        plt.close(fig)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--bound", type=float, default=20.0, help="deviation bound, mm")
    ap.add_argument("--out", default=os.path.join(ROOT, "out", "bench"))
    ap.add_argument("--quick", action="store_true")
    args = ap.parse_args(argv)
    run(args.bound, args.out, args.quick)


if __name__ == "__main__":
    main()
