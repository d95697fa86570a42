"""British Museum Great Court roof benchmark for the guide-line methods (seed 004, section 7).

    PYTHONPATH=/usr/lib/freecad-python3/lib:$PWD /usr/bin/python3 bench/british_museum.py

Runs the Guide Line Scaling Method on examples/british_museum_roof.brep (the
whole face, drum as a hole) with the west edge and then the south edge of the
court as the guide line, and 2G2VM with both edges as the two guide lines;
prints the rod-length mean and variance next to the paper's Table 3, the node
and member counts next to the built roof, the share of irregular cells and the
time per guide-line set next to the paper's 78-120 s, and writes a table and a
plan-view PNG of the grid into out/bench/.
"""

import argparse
import os
import sys
import time

import FreeCAD  # noqa: F401  (before Part)
import Part
import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.path.insert(0, ROOT)

import freecad_workbench as tessella  # noqa: E402
from freecad_workbench import core  # noqa: E402

ROOF = os.path.join(ROOT, "examples", "british_museum_roof.brep")

#: Seed 004 Table 3 (rod lengths, mm and mm^2) and the built roof (reference file).
PAPER = [
    ("Original mesh (triangular)", 2047.0, 207150.0),
    ("GSM (triangular), paper", 2032.0, 120136.0),
    ("2G2VM (quadrangular), paper", 2126.0, 464820.0),
]
BUILT_NODES, BUILT_MEMBERS = 1566, 4878
PAPER_SECONDS = (78.0, 120.0)


def load_roof():
    shape = Part.Shape()
    shape.importBrep(ROOF)
    return shape.Faces[0]


def edge_at(face, x=None, y=None):
    """The straight court edge at x = const or y = const."""
    for e in face.Edges:
        bb = e.BoundBox
        if x is not None and abs(bb.XMin - x) < 1 and abs(bb.XMax - x) < 1:
            return e
        if y is not None and abs(bb.YMin - y) < 1 and abs(bb.YMax - y) < 1:
            return e
    raise RuntimeError("court edge not found")


def plot(face, res, curves, path, title):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.collections import LineCollection

    fig, ax = plt.subplots(figsize=(7.5, 9.5))
    v = res.vertices / 1000.0
    segs = v[res.rods][:, :, :2]
    ax.add_collection(LineCollection(segs, colors="#223355", linewidths=0.5))
    bad = [i for i, flag in enumerate(res.irregular) if flag]
    for i in bad:
        poly = v[list(res.panels[i])][:, :2]
        ax.fill(poly[:, 0], poly[:, 1], color="#e07a5f", alpha=0.6, lw=0)
    for e in face.Edges:
        pts = np.array([[p.x, p.y] for p in e.discretize(100)]) / 1000.0
        ax.plot(pts[:, 0], pts[:, 1], color="k", lw=1.2)
    ax.set_aspect("equal")
    ax.set_title(title, fontsize=9)
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    fig.tight_layout()
    fig.savefig(path, dpi=130)
    plt.close(fig)


def plan_coverage(face, res, step=500.0):
    """Share of a plan grid of points on the face covered by at least one
    panel, and by more than one (overlap), panels projected to plan (the roof
    is a height field); the face's plan is the court rectangle minus the drum
    (centre at the origin, as examples/make_british_museum.py builds it),
    independent of the core's trim handling."""
    bb = face.BoundBox
    xs = np.arange(bb.XMin + step / 2, bb.XMax, step)
    ys = np.arange(bb.YMin + step / 2, bb.YMax, step)
    hits = np.zeros((len(xs), len(ys)), dtype=int)
    v = res.vertices
    for poly in res.panels:
        pts = v[list(poly)][:, :2]
        for k in range(1, len(pts) - 1):
            tri = pts[[0, k, k + 1]]
            i0, i1 = np.searchsorted(xs, [tri[:, 0].min(), tri[:, 0].max()])
            j0, j1 = np.searchsorted(ys, [tri[:, 1].min(), tri[:, 1].max()])
            if i1 <= i0 or j1 <= j0:
                continue
            X, Y = np.meshgrid(xs[i0:i1], ys[j0:j1], indexing="ij")
            a, b, c = tri
            d = (b[1] - c[1]) * (a[0] - c[0]) + (c[0] - b[0]) * (a[1] - c[1])
            if abs(d) < 1e-9:
                continue
            l1 = ((b[1] - c[1]) * (X - c[0]) + (c[0] - b[0]) * (Y - c[1])) / d
            l2 = ((c[1] - a[1]) * (X - c[0]) + (a[0] - c[0]) * (Y - c[1])) / d
            inside = (l1 >= 0) & (l2 >= 0) & (l1 + l2 <= 1)
            hits[i0:i1, j0:j1] += inside
    on_face = np.zeros_like(hits, dtype=bool)
    for i, x in enumerate(xs):
        for j, y in enumerate(ys):
            on_face[i, j] = (x * x + y * y) > 22245.0 ** 2  # outside the drum (r = 22.245 m)
    n = on_face.sum()
    return (hits[on_face] >= 1).sum() / n, (hits[on_face] >= 2).sum() / n


def polygon_area(v, poly):
    """Area of a planar-ish polygon (vector area), for triangles, quads and the
    n-gons along the trim alike."""
    pts = v[list(poly)]
    return 0.5 * np.linalg.norm(np.cross(pts, np.roll(pts, -1, axis=0)).sum(axis=0))


def rod_lengths(res):
    """Rod lengths from the returned coordinates (not the core's metrics)."""
    rods = np.asarray(res.rods)
    return np.linalg.norm(res.vertices[rods[:, 0]] - res.vertices[rods[:, 1]], axis=1)


def run_gsm(face, guide_edge, rod_length, advance):
    t = time.perf_counter()
    res = tessella.panelize(face, method="guide_line_scaling", guides=[guide_edge],
                            rod_length=rod_length, advance=advance)
    seconds = time.perf_counter() - t
    # The curves alone (the "guide-line set" the paper times).
    sf = core.SurfaceFace.from_brep_string(face.exportBrepToString())
    p = core.GuideLineScalingParams()
    p.guide = tessella.api.edge_polyline(guide_edge)
    p.rod_length, p.advance = rod_length, advance
    t = time.perf_counter()
    _, curves = core.guide_line_scaling_curves(sf, p)
    core_seconds = time.perf_counter() - t
    return res, curves, seconds, core_seconds


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--rod-length", type=float, default=2000.0)
    ap.add_argument("--advance", type=float, default=0.0, help="0 = rod_length * sqrt(3)/2")
    ap.add_argument("--out", default=os.path.join(ROOT, "out", "bench"))
    args = ap.parse_args(argv)
    os.makedirs(args.out, exist_ok=True)
    face = load_roof()
    print(f"British Museum roof: {face.Area / 1e6:,.1f} m2 (published glazing ~6,100 m2)")
    rows = []
    bb = face.BoundBox
    pngs = []
    for label, key, where in (("west edge", "west", dict(x=bb.XMin)), ("south edge", "south", dict(y=bb.YMin))):
        guide = edge_at(face, **where)
        res, curves, seconds, core_seconds = run_gsm(face, guide, args.rod_length, args.advance)
        rl = rod_lengths(res)
        s = res.summary
        covered = sum(polygon_area(res.vertices, q) for q in res.panels) / face.Area
        rows.append((f"GSM, Tessella, guide = {label}", rl.mean(), rl.var(), s["node_count"], s["rod_count"],
                     s["irregular_count"] / max(1, s["panel_count"]), core_seconds, seconds, len(curves),
                     covered, plan_coverage(face, res)))
        png = os.path.join(args.out, f"british_museum_gsm_{key}.png")
        plot(face, res, curves, png,
             f"GSM on the British Museum roof: guide = {label}, L1 = {args.rod_length:.0f} mm\n"
             f"{s['node_count']} nodes, {s['rod_count']} rods, rod length {rl.mean():.0f} mm "
             f"(variance {rl.var():,.0f} mm2); irregular cells shaded")
        pngs.append(png)

    # 2G2VM: the west edge and the south edge as the two guide lines; and the
    # diamond grid of the two GSM sets (seed 004 Fig. 19) from the same edges.
    guides = [edge_at(face, x=bb.XMin), edge_at(face, y=bb.YMin)]
    sf = core.SurfaceFace.from_brep_string(face.exportBrepToString())
    for label, key, method in (("2G2VM (quads), Tessella, west + south", "2g2vm", "two_guide_lines"),
                               ("GSM diamond, Tessella, west + south", "diamond", "guide_line_diamond")):
        kw = dict(guides=guides, rod_length=args.rod_length)
        if method == "guide_line_diamond" and args.advance > 0:
            kw["advance"] = args.advance
        t = time.perf_counter()
        res = tessella.panelize(face, method=method, **kw)
        seconds = time.perf_counter() - t
        if method == "two_guide_lines":
            p = core.TwoGuideLinesParams()
            p.guides = [tessella.api.edge_polyline(g) for g in guides]
            p.rod_length = args.rod_length
            t = time.perf_counter()
            _, curves_a, curves_b = core.two_guide_lines_curves(sf, p)
            core_seconds = time.perf_counter() - t
            ncurves = len(curves_a) + len(curves_b)
        else:  # the pipeline's method stage: two GSM sets and their crossings
            core_seconds = res.summary["core_seconds"] / 2  # per guide-line set
            ncurves = 0
        rl = rod_lengths(res)
        s = res.summary
        covered = sum(polygon_area(res.vertices, q) for q in res.panels) / face.Area
        rows.append((label, rl.mean(), rl.var(), s["node_count"], s["rod_count"],
                     s["irregular_count"] / max(1, s["panel_count"]), core_seconds, seconds,
                     ncurves, covered, plan_coverage(face, res)))
        png = os.path.join(args.out, f"british_museum_{key}.png")
        plot(face, res, None, png,
             f"{label.split(',')[0]} on the British Museum roof: guides = west and south edges, "
             f"L1 = {args.rod_length:.0f} mm\n"
             f"{s['node_count']} nodes, {s['rod_count']} rods, rod length {rl.mean():.0f} mm "
             f"(variance {rl.var():,.0f} mm2); irregular cells shaded")
        pngs.append(png)

    lines = []
    lines.append(f"{'grid':40s} {'mean (mm)':>10s} {'var (mm2)':>11s} {'nodes':>6s} {'members':>8s} "
                 f"{'irregular':>9s} {'curves (s)':>10s} {'total (s)':>9s}")
    for name, mean, var in PAPER:
        extra = f"{BUILT_NODES:6d} {BUILT_MEMBERS:8d}" if name.startswith("Original") else f"{'-':>6s} {'-':>8s}"
        t = f"{'78-120':>10s}" if "paper" in name else f"{'-':>10s}"
        lines.append(f"{name:40s} {mean:10.0f} {var:11,.0f} {extra} {'-':>9s} {t} {'-':>9s}")
    for name, mean, var, nodes, members, irr, cs, ts, nc, cov, _ in rows:
        lines.append(f"{name:40s} {mean:10.0f} {var:11,.0f} {nodes:6d} {members:8d} {100 * irr:8.1f}% "
                     f"{cs:10.3f} {ts:9.3f}")
    for name, mean, var, nodes, members, irr, cs, ts, nc, cov, (plan, twice) in rows:
        lines.append(f"{name}: {nc} curves, panel area = {100 * cov:.1f}% of the face; plan grid (0.5 m): "
                     f"{100 * plan:.1f}% covered, {100 * twice:.1f}% covered twice (overlap)")
    lines.append(f"paper: {PAPER_SECONDS[0]:.0f}-{PAPER_SECONDS[1]:.0f} s per guide-line set "
                 "(Tables 1-2, Chen Shan); 'curves (s)' = our guide-line set (core), "
                 "'total (s)' = panelize() with metrics")
    text = "\n".join(lines)
    print(text)
    with open(os.path.join(args.out, "british_museum.txt"), "w") as f:
        f.write(text + "\n")
    for png in pngs:
        print(f"wrote {png}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
