"""Buildable boundaries (issue 12): what a workshop gets along trims and openings,
per method and size, measured independently of the code that made the panels.

    PYTHONPATH=/usr/lib/freecad-python3/lib:$PWD /usr/bin/python3 bench/buildable_boundaries.py [--quick]

Faces: the bundled trimmed B-spline with holes and the freeform test face of
tests/python/conftest.py (not a bundled example). Columns:

- folds/panel: folds (unfolded at the default fold tolerance) of the worst quad
  (four-node panel) and of the worst panel of any kind; folds under 0.1 deg
  (share of all folds);
- rods: the shortest rod (mm, from the vertices);
- trim: the largest distance (mm) of a boundary node from the face's edges
  (Part distToShape), over the model size;
- area: total unfolded area / face area - 1;
- seg: cut-path segments per part (max / mean, export_dxf defaults; arcs count once);
- over: walking_agent panels over its bound.
"""

import argparse
import os
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
for _p in ("/usr/lib/freecad-python3/lib", ROOT, os.path.join(ROOT, "tests", "python")):
    if _p not in sys.path:
        sys.path.append(_p)

import FreeCAD  # noqa: E402,F401  (before Part)
import numpy as np  # noqa: E402
import Part  # noqa: E402

import freecad_workbench as tessella  # noqa: E402
from conftest import make_freeform_face  # noqa: E402


def bundled():
    s = Part.Shape()
    s.read(os.path.join(ROOT, "examples", "trimmed_bspline_holes.brep"))
    return s.Faces[0]


def runs(face, quick):
    size = float(np.sqrt(face.Area))
    sizes = [size / 8, size / 14] if quick else [size / 6, size / 10, size / 16]
    out = []
    for s in sizes:
        out += [("iso_grid", {"size": s}), ("equal_size_grid", {"size": s}),
                ("relaxed_grid", {"u_count": max(3, int(round(1.4 * size / s))),
                                  "v_count": max(3, int(round(1.4 * size / s)))}),
                ("boundary_driven", {"size": s})]
    for bound in ([40.0] if quick else [20.0, 60.0]):
        out.append(("walking_agent", {"max_deviation": bound}))
    # guide lines: iso-curves through the middle of the parameter range
    u0, u1, v0, v1 = face.ParameterRange
    gu = Part.Edge(face.Surface.uIso(0.5 * (u0 + u1)), v0, v1)
    gv = Part.Edge(face.Surface.vIso(0.5 * (v0 + v1)), u0, u1)
    s = sizes[len(sizes) // 2]
    out.append(("guide_line_scaling", {"rod_length": s, "guides": [gu]}))
    out.append(("two_guide_lines", {"rod_length": s, "guides": [gu, gv]}))
    return out


def boundary_node_trim_distance(face, r):
    """Largest distance of a node on the face boundary (within 1e-3 of it) from the
    face's edges, measured with OCCT; nodes off the boundary are skipped."""
    edges = Part.Compound(face.Edges)
    worst = 0.0
    xyz = np.asarray(r.vertices)
    for v in r.nodes:
        p = FreeCAD.Vector(*map(float, xyz[v]))
        d = edges.distToShape(Part.Vertex(p))[0]
        if d < 1.0:  # on (or within a millimetre of) the trim: a boundary node
            worst = max(worst, d)
    return worst


def row(name, face, method, params):
    t0 = time.perf_counter()
    r = tessella.panelize(face, method=method, **params)
    seconds = time.perf_counter() - t0
    flat = tessella.unfold(r)
    nodes = set(int(v) for v in r.nodes)
    quad_folds = [len(f.folds) for f, p in zip(flat, r.panels)
                  if len(p) == 4 and all(int(v) in nodes for v in p)]
    all_folds = [len(f.folds) for f in flat]
    angles = np.array([abs(a) for f in flat for _, _, a in f.folds])
    xyz = np.asarray(r.vertices)
    rods = np.asarray(r.rods).reshape(-1, 2)
    shortest = float(np.min(np.linalg.norm(xyz[rods[:, 0]] - xyz[rods[:, 1]], axis=1)))
    area = sum(f.area for f in flat) / face.Area - 1.0
    trim = boundary_node_trim_distance(face, r) / r.summary["model_size"]
    with tempfile.TemporaryDirectory() as tmp:
        s = tessella.export_dxf(flat, os.path.join(tmp, "p.dxf"))
    seg = s.get("segments_per_part") or {}
    over = ""
    if method == "walking_agent":
        dev = np.asarray(r.metrics["panel_deviation"])
        over = str(int(np.sum(dev > params["max_deviation"] * (1 + 1e-9))))
    small = float(np.mean(angles < 0.1)) if len(angles) else 0.0
    label = ", ".join(f"{k}={v:.0f}" if isinstance(v, float) else f"{k}={v}"
                      for k, v in params.items() if k != "guides")
    return (f"| {name} | {method} {label} | {len(r.panels)} | {max(quad_folds, default=0)} / "
            f"{max(all_folds, default=0)} | {100 * small:.0f}% | {r.summary.get('bend_count', '-')} | "
            f"{shortest:.1f} | {trim:.1e} | {100 * area:+.3f}% | "
            f"{seg.get('max', '-')} / {seg.get('mean', 0):.1f} | {over} | {seconds:.2f} |")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--quick", action="store_true")
    args = ap.parse_args()
    print("| face | method | panels | folds/panel quad / any | folds < 0.1° | bends | "
          "shortest rod mm | trim / size | area | seg max / mean | over | s |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|")
    for name, face in (("bundled", bundled()), ("freeform", make_freeform_face())):
        for method, params in runs(face, args.quick):
            try:
                print(row(name, face, method, params), flush=True)
            except Exception as e:  # a method that refuses a size says why
                print(f"| {name} | {method} {params} | failed: {e} |", flush=True)


if __name__ == "__main__":
    main()
