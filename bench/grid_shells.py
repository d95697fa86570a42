"""Sun Valley funnel and Chen Shan dome benchmark for the guide-line methods
(seed 004, sections 5.2.1 and 6.2).

    PYTHONPATH=/usr/lib/freecad-python3/lib:$PWD /usr/bin/python3 examples/make_grid_shells.py
    PYTHONPATH=/usr/lib/freecad-python3/lib:$PWD /usr/bin/python3 bench/grid_shells.py

Faces: examples/sun_valley_funnel.brep and examples/chen_shan_dome.brep (see
examples/make_grid_shells.py for their geometry; this script takes the
mappings from there). Runs, through the console API tessella.panelize:

Sun Valley (half funnel, paper section 6.2.2)
  - 2G2VM (two_guide_lines) with two crossing oblique guides, quads and
    triangles. The guides run from the bottom semicircle to the top one with
    theta linear in the profile parameter: 56.25 -> 123.75 deg and back
    (90 -/+ 3/16 of the semicircle at the bottom, +/- at the top; they cross
    at theta = 90 deg, mid-height). boundary_divisions = 16: the paper divides
    the semicircles into 16 equal segments; the guides' feet sit on those
    divisions, so both families share the vertices on the boundary (the
    paper's vertex pairs, Fig. 31) and the cells along it are rhombi too.
  - 2G2VM with two crossing boundary guides, the top semicircle and the side
    edge at theta = 0 (x > 0; the paper's "left side" seen from the front),
    quads and triangles, boundary_divisions = 16.
  - guide_line_diamond with the two oblique guides, rod_length = the chord of
    the bottom semicircle divided in 16 (2 R sin(pi / 32) = 1,960 mm).
Chen Shan (bean-shaped dome, sections 5.2.1 and 6.2.1), rod_length = 2,000 mm
  - GSM (guide_line_scaling) with the paper's three kinds of initial guide:
    case 1 the bent spine Y = 0, case 2 the transverse line X = 0, case 3 an
    oblique line through the centre at 30 deg to the spine (in the bean
    coordinates (X, Y), which are orthogonal and unstretched on the spine).
  - guide_line_diamond with two oblique guides at +30 and -30 deg to the
    spine through the centre: rhombic cells along the spine (cases 1 + 2
    would give near-square cells aligned with the spine, not diamonds).
  - 2G2VM with the guides of cases 1 and 2, boundary_divisions = 48 (the
    paper's 48 equal chords).
Each guide is a Part.BSplineCurve interpolating 65 points of the surface.

For each run the table gives: nodes (len(res.vertices)), members
(len(res.rods)), cells (len(res.panels)), the rod-length mean and variance
(from res.vertices and res.rods), the share of irregular cells
(res.summary["irregular_count"] / cells), coverage = sum of the panel areas
(vector area of each polygon) / face.Area, the shares of a chart grid of
points on the face (plan for the dome; (theta, z) for the funnel, which is
vertical at its foot) under a cell (gaps) and under two or more (overlapping
cells), and the best of 3 wall times of
tessella.panelize next to the paper's time per guide-line set (Tables 1-2,
Chen Shan only; the paper gives none for Sun Valley). It writes the table to
<out>/grid_shells.txt and one plan + isometric PNG per run into <out>/.
A run that raises prints its message in the row and the others go on.
"""

import argparse
import math
import os
import sys
import time

import FreeCAD  # noqa: F401  (before Part)
import Part
import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.path.insert(0, ROOT)
sys.path.insert(0, os.path.join(ROOT, "examples"))

import freecad_workbench as tessella  # noqa: E402
import make_grid_shells as shells  # noqa: E402

FUNNEL = os.path.join(ROOT, "examples", "sun_valley_funnel.brep")
DOME = os.path.join(ROOT, "examples", "chen_shan_dome.brep")

#: Seed 004 Table 1 (GSM) and Table 2 (2G2VM): seconds per guide-line set, Chen Shan cases 1-3.
PAPER_GSM_SECONDS = (78.5, 112.7, 115.8)
PAPER_2G2VM_SECONDS = (102.0, 120.0, 117.0)
GUIDE_POINTS = 65
RUNS = 3
#: Sun Valley: 16 equal segments on each semicircle; rod length = the bottom chord.
SV_DIVISIONS = 16
SV_CHORD = 2.0 * shells.R_BOTTOM * 1000.0 * math.sin(math.pi / (2 * SV_DIVISIONS))
CS_DIVISIONS = 48
CS_ROD_LENGTH = 2000.0
CS_OBLIQUE_DEG = 30.0


def load(path):
    shape = Part.Shape()
    shape.importBrep(path)
    return shape.Faces[0]


def curve_through(points):
    curve = Part.BSplineCurve()
    curve.interpolate(points)
    return curve.toShape()


def funnel_guide(theta_bottom_deg, theta_top_deg):
    """Surface curve from the bottom semicircle to the top one, theta linear in height."""
    pts = []
    for k in range(GUIDE_POINTS):
        t = k / (GUIDE_POINTS - 1)
        theta = math.radians(theta_bottom_deg + (theta_top_deg - theta_bottom_deg) * t)
        pts.append(shells.funnel_point(theta, shells.HEIGHT * t))
    return curve_through(pts)


def funnel_edges(face):
    """The top semicircle and the side edge at theta = 0 (x > 0)."""
    top = [e for e in face.Edges if e.BoundBox.ZLength < 1e-6 and e.BoundBox.ZMin > 1.0]
    side = [e for e in face.Edges if e.BoundBox.YLength < 1e-6 and e.BoundBox.XMin > 0.0]
    if len(top) != 1 or len(side) != 1:
        raise RuntimeError("funnel boundary edges not found")
    return top[0], side[0]


def dome_guide(face, angle_deg):
    """Straight line through the centre in bean coordinates (X, Y) at angle_deg
    to the spine, from outline to outline, mapped to plan and lifted onto the
    face's surface (its parameters are plan x, y in mm)."""
    c, s = math.cos(math.radians(angle_deg)), math.sin(math.radians(angle_deg))
    reach = 1.0 / math.hypot(c / shells.A, s / shells.B)  # where the line meets the ellipse
    pts = []
    for k in range(GUIDE_POINTS):
        q = reach * (2.0 * k / (GUIDE_POINTS - 1) - 1.0)
        x, y = shells.to_plan(q * c, q * s)
        pts.append(face.Surface.value(x * 1000.0, y * 1000.0))
    return curve_through(pts)


def funnel_chart(xyz):
    """(theta * R_TOP, z) in mm: one-to-one on the half funnel, not flattened at its foot."""
    return np.column_stack([np.arctan2(np.abs(xyz[:, 1]), xyz[:, 0]) * shells.R_TOP * 1000.0, xyz[:, 2]])


def funnel_on_face(pts):
    return np.ones(len(pts), dtype=bool)


def dome_chart(xyz):
    return xyz[:, :2].copy()


def dome_on_face(pts):
    inside = np.empty(len(pts), dtype=bool)
    for k, (x, y) in enumerate(pts / 1000.0):
        X, Y = shells.to_bean(x, y)
        inside[k] = (X / shells.A) ** 2 + (Y / shells.B) ** 2 <= 1.0
    return inside


def chart_overlap(res, chart, on_face, step):
    """Share of a chart grid of points on the face under at least one cell and
    under two or more (overlapping cells); cells as polygons in the chart."""
    from matplotlib.path import Path

    v2 = chart(res.vertices)
    lo, hi = v2.min(axis=0), v2.max(axis=0)
    # Offsets off the grid of the rods (which often run at round coordinates).
    xs = np.arange(lo[0] + 0.37 * step, hi[0], step)
    ys = np.arange(lo[1] + 0.61 * step, hi[1], step)
    X, Y = np.meshgrid(xs, ys, indexing="ij")
    pts = np.column_stack([X.ravel(), Y.ravel()])
    hits = np.zeros(len(pts), dtype=int)
    for poly in res.panels:
        p = v2[list(poly)]
        (x0, y0), (x1, y1) = p.min(axis=0), p.max(axis=0)
        sel = np.nonzero((pts[:, 0] >= x0) & (pts[:, 0] <= x1) & (pts[:, 1] >= y0) & (pts[:, 1] <= y1))[0]
        if len(sel):
            hits[sel] += Path(p).contains_points(pts[sel])
    face_pts = on_face(pts)
    n = max(1, face_pts.sum())
    return (hits[face_pts] >= 1).sum() / n, (hits[face_pts] >= 2).sum() / n


def panel_area(vertices, poly):
    """Vector area of a (possibly non-planar) polygon, mm2."""
    p = vertices[list(poly)]
    return 0.5 * np.linalg.norm(np.cross(p, np.roll(p, -1, axis=0)).sum(axis=0))


def isometric(xyz, azimuth_deg, elevation_deg):
    """Axonometric projection seen from (azimuth, elevation)."""
    a, e = math.radians(azimuth_deg), math.radians(elevation_deg)
    right = np.array([-math.sin(a), math.cos(a), 0.0])
    up = np.array([-math.sin(e) * math.cos(a), -math.sin(e) * math.sin(a), math.cos(e)])
    return np.column_stack([xyz @ right, xyz @ up])


def plot(face, res, guides, view, path, title):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.collections import LineCollection

    fig, axes = plt.subplots(1, 2, figsize=(13, 6.5))
    outline = [np.array([[p.x, p.y, p.z] for p in e.discretize(200)]) / 1000.0 for e in face.Edges]
    guide_pts = [np.array([[p.x, p.y, p.z] for p in g.discretize(200)]) / 1000.0 for g in guides]
    v = res.vertices / 1000.0
    for ax, project, name in ((axes[0], lambda p: p[:, :2], "plan"),
                              (axes[1], lambda p: isometric(p, *view), "isometric")):
        segs = project(v)[res.rods]
        ax.add_collection(LineCollection(segs, colors="#223355", linewidths=0.5))
        for i in np.nonzero(res.irregular)[0]:
            poly = project(v[list(res.panels[i])])
            ax.fill(poly[:, 0], poly[:, 1], color="#e07a5f", alpha=0.5, lw=0)
        for pts in outline:
            q = project(pts)
            ax.plot(q[:, 0], q[:, 1], color="k", lw=1.2)
        for pts in guide_pts:
            q = project(pts)
            ax.plot(q[:, 0], q[:, 1], color="red", lw=1.8)
        ax.set_aspect("equal")
        ax.autoscale_view()
        ax.set_title(name, fontsize=9)
        if name == "plan":
            ax.set_xlabel("x (m)")
            ax.set_ylabel("y (m)")
        else:
            ax.set_axis_off()
    fig.suptitle(title, fontsize=9)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def run(face, params, chart, on_face, chart_step):
    """panelize best of RUNS, and the figures of one table row."""
    seconds = []
    for _ in range(RUNS):
        t = time.perf_counter()
        res = tessella.panelize(face, **params)
        seconds.append(time.perf_counter() - t)
    v = res.vertices
    rods = np.linalg.norm(v[res.rods[:, 1]] - v[res.rods[:, 0]], axis=1)
    cells = len(res.panels)
    area = sum(panel_area(v, p) for p in res.panels)
    covered, twice = chart_overlap(res, chart, on_face, chart_step)
    row = dict(nodes=len(v), members=len(res.rods), cells=cells, mean=rods.mean(), var=rods.var(),
               irregular=res.summary["irregular_count"] / max(1, cells), coverage=area / face.Area,
               covered=covered, twice=twice, seconds=min(seconds))
    return res, row


def scenarios(funnel, dome):
    """The runs: (case, method label, guides, panelize params, (face, chart,
    on_face, chart step, isometric view), paper seconds, PNG name)."""
    sv_oblique = [funnel_guide(56.25, 123.75), funnel_guide(123.75, 56.25)]
    sv_boundary = list(funnel_edges(funnel))
    cs = {case: dome_guide(dome, angle) for case, angle in ((1, 0.0), (2, 90.0), (3, CS_OBLIQUE_DEG))}
    cs_diamond = [dome_guide(dome, CS_OBLIQUE_DEG), dome_guide(dome, -CS_OBLIQUE_DEG)]
    sv = (funnel, funnel_chart, funnel_on_face, 500.0, (-60.0, 20.0))
    dm = (dome, dome_chart, dome_on_face, 500.0, (-60.0, 35.0))
    paper_gsm = dict(zip((1, 2, 3), PAPER_GSM_SECONDS))
    paper_2g = " / ".join(f"{s:.0f}" for s in PAPER_2G2VM_SECONDS) + " (cases 1-3)"
    out = []
    for label, guides, key in (("oblique guides", sv_oblique, "oblique"),
                               ("boundary guides", sv_boundary, "boundary")):
        for tri in (False, True):
            kind = "triangles" if tri else "quads"
            out.append((f"Sun Valley, {label}", f"2G2VM {kind}", guides,
                        dict(method="two_guide_lines", rod_length=SV_CHORD, boundary_divisions=SV_DIVISIONS,
                             triangulate=tri), sv, "-", f"sun_valley_2g2vm_{key}_{kind}"))
    out.append(("Sun Valley, oblique guides", "diamond (2 x GSM)", sv_oblique,
                dict(method="guide_line_diamond", rod_length=SV_CHORD), sv, "-", "sun_valley_diamond"))
    for case, label in ((1, "spine"), (2, "transverse"), (3, f"oblique {CS_OBLIQUE_DEG:.0f} deg")):
        out.append((f"Chen Shan case {case}, {label}", "GSM", [cs[case]],
                    dict(method="guide_line_scaling", rod_length=CS_ROD_LENGTH), dm,
                    f"{paper_gsm[case]:.1f}", f"chen_shan_gsm_case{case}"))
    out.append((f"Chen Shan, oblique +/-{CS_OBLIQUE_DEG:.0f} deg", "diamond (2 x GSM)", cs_diamond,
                dict(method="guide_line_diamond", rod_length=CS_ROD_LENGTH), dm, "-", "chen_shan_diamond"))
    out.append(("Chen Shan, cases 1 + 2", "2G2VM quads", [cs[1], cs[2]],
                dict(method="two_guide_lines", rod_length=CS_ROD_LENGTH, boundary_divisions=CS_DIVISIONS),
                dm, paper_2g, "chen_shan_2g2vm"))
    return out


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--out", default=os.path.join(ROOT, "out", "bench"))
    args = ap.parse_args(argv)
    os.makedirs(args.out, exist_ok=True)
    funnel, dome = load(FUNNEL), load(DOME)
    header = (f"{'case':34s} {'method':18s} {'nodes':>6s} {'members':>7s} {'cells':>6s} {'mean (mm)':>9s} "
              f"{'var (mm2)':>11s} {'irreg':>6s} {'cover':>6s} {'grid':>6s} {'2x':>6s} {'best (s)':>8s}  paper (s)")
    lines = [f"Sun Valley funnel {funnel.Area / 1e6:,.1f} m2, Chen Shan dome {dome.Area / 1e6:,.1f} m2 (face.Area); "
             f"best of {RUNS} runs of tessella.panelize", header]
    print("\n".join(lines))
    pngs = []
    for case, label, guides, params, (face, chart, on_face, step, view), paper, key in scenarios(funnel, dome):
        try:
            res, r = run(face, dict(params, guides=guides), chart, on_face, step)
        except Exception as exc:  # a failed run is reported in its row
            line = f"{case:34s} {label:18s} FAILED: {type(exc).__name__}: {exc}"
        else:
            line = (f"{case:34s} {label:18s} {r['nodes']:6d} {r['members']:7d} {r['cells']:6d} {r['mean']:9.0f} "
                    f"{r['var']:11,.0f} {100 * r['irregular']:5.1f}% {100 * r['coverage']:5.1f}% "
                    f"{100 * r['covered']:5.1f}% {100 * r['twice']:5.1f}% {r['seconds']:8.3f}  {paper}")
            png = os.path.join(args.out, f"{key}.png")
            plot(face, res, guides, view, png,
                 f"{case}: {label}, {params['method']}, rod_length {params['rod_length']:.0f} mm\n"
                 f"{r['nodes']} nodes, {r['members']} rods, {r['cells']} cells, rod length {r['mean']:.0f} mm "
                 f"(variance {r['var']:,.0f} mm2), coverage {100 * r['coverage']:.1f}%; "
                 "guides red, irregular cells shaded")
            pngs.append(png)
        print(line)
        lines.append(line)
    lines.append("cover = sum of panel areas / face.Area; grid, 2x = share of a 0.5 m chart grid on the face "
                 "under one or more cells, under two or more (plan for the dome, (theta * 45 m, z) for the "
                 "funnel); paper = seconds per guide-line set (Tables 1-2, Chen Shan)")
    with open(os.path.join(args.out, "grid_shells.txt"), "w") as f:
        f.write("\n".join(lines) + "\n")
    print(lines[-1])
    for png in pngs:
        print(f"wrote {png}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
