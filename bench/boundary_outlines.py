"""The outlines a workshop cuts, per method: every bundled example and the
freeform test face (tests/python/conftest.py, not a bundled example) at 600,
900, 1200, 1400 and 1500 mm, measured independently of the code that made
the panels (the panels' own vertices; FreeCAD-free geometry in numpy).

    PYTHONPATH=/usr/lib/freecad-python3/lib:$PWD /usr/bin/python3 bench/boundary_outlines.py [--methods boundary_driven,iso_grid]

Per method, summed over the runs:

- runs: results made / sizes refused by the method (a refusal says why);
- crossing: panels whose whole outline (trim points included) crosses itself
  in (u,v): not a piece anyone can cut;
- unfold failed: results whose unfold raised an error;
- spikes: panels with an outline corner under 5 deg (3D, from the vertices);
  the sharpest corner;
- micro sides: panels with an outline side under 0.01 mm; the shortest;
- fans: panels unfolded with more folds than their model allows (one for a
  quad of four nodes, two otherwise) or a fold not between two nodes (a
  boundary piece left curved).

The worst runs are listed below the table.
"""

import argparse
import math
import os
import sys
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

SIZES = (600.0, 900.0, 1200.0, 1400.0, 1500.0)
MAX_PANELS = 5000  # sizes giving more panels than this are skipped (time)


def faces():
    out = []
    folder = os.path.join(ROOT, "examples")
    for name in sorted(f[:-5] for f in os.listdir(folder) if f.endswith(".brep")):
        shape = Part.Shape()
        shape.read(os.path.join(folder, name + ".brep"))
        out.append((name, shape.Faces[0]))
    out.append(("freeform", make_freeform_face()))
    return out


def params(method, size):
    if method == "walking_agent":
        return {"max_size": size, "max_deviation": 0.01 * size}
    return {"size": size}


def _orient(a, b, c):
    return (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])


def crosses_itself(uv):
    """Whether two non-adjacent sides of the closed outline cross (properly)."""
    n = len(uv)
    uv = uv - uv.min(axis=0)
    lo = np.minimum(uv, np.roll(uv, -1, axis=0))
    hi = np.maximum(uv, np.roll(uv, -1, axis=0))
    for i in range(n):
        # only sides whose boxes meet side i's
        near = np.nonzero((lo[:, 0] <= hi[i, 0]) & (hi[:, 0] >= lo[i, 0]) &
                          (lo[:, 1] <= hi[i, 1]) & (hi[:, 1] >= lo[i, 1]))[0]
        p, q = uv[i], uv[(i + 1) % n]
        for j in near:
            if j <= i + 1 or (i == 0 and j == n - 1):
                continue
            r, s = uv[j], uv[(j + 1) % n]
            if _orient(p, q, r) * _orient(p, q, s) < 0 and _orient(r, s, p) * _orient(r, s, q) < 0:
                return True
    return False


def unwrapped(uv, periods):
    """A panel's (u,v) corners made continuous across a periodic face's seam
    (each within half a period of the one before)."""
    uv = uv.copy()
    for k, period in enumerate(periods):
        if period:
            step = np.diff(uv[:, k])
            uv[1:, k] -= period * np.cumsum(np.round(step / period))
    return uv


def corners_and_sides(xyz):
    """Outline corner angles (deg) and side lengths (mm) of one panel, 3D."""
    a = np.roll(xyz, 1, axis=0) - xyz
    b = np.roll(xyz, -1, axis=0) - xyz
    la, lb = np.linalg.norm(a, axis=1), np.linalg.norm(b, axis=1)
    cos = np.einsum("ij,ij->i", a, b) / np.maximum(la * lb, 1e-300)
    return np.degrees(np.arccos(np.clip(cos, -1, 1))), lb


def fans(r, flat):
    nodes = set(int(v) for v in r.nodes)
    n = 0
    for p, f in zip(r.panels, flat):
        quad = len(p) == 4 and all(int(v) in nodes for v in p)
        if len(f.folds) > (1 if quad else 2) or any(
                int(p[a]) not in nodes or int(p[b]) not in nodes for a, b, _ in f.folds):
            n += 1
    return n


def survey(method, face_list):
    t = dict(made=0, refused=0, panels=0, crossing=0, unfold_failed=0, spikes=0,
             sharpest=180.0, micro=0, shortest=math.inf, fans=0)
    worst = []
    for name, face in face_list:
        for size in SIZES:
            if face.Area / size ** 2 > MAX_PANELS:
                continue
            try:
                r = tessella.panelize(face, method=method, **params(method, size))
            except Exception:  # a refusal names its reason; counted only
                t["refused"] += 1
                continue
            t["made"] += 1
            t["panels"] += len(r.panels)
            uv, xyz = np.asarray(r.uv), np.asarray(r.vertices)
            surf = face.Surface
            periods = (surf.UPeriod() if surf.isUPeriodic() else 0.0,
                       surf.VPeriod() if surf.isVPeriodic() else 0.0)
            crossing = spikes = micro = 0
            for p in r.panels:
                idx = list(p)
                crossing += crosses_itself(unwrapped(uv[idx], periods))
                angles, sides = corners_and_sides(xyz[idx])
                spikes += bool(angles.min() < 5.0)
                micro += bool(sides.min() < 0.01)
                t["sharpest"] = min(t["sharpest"], float(angles.min()))
                t["shortest"] = min(t["shortest"], float(sides.min()))
            try:
                fan = fans(r, tessella.unfold(r))
            except Exception:
                t["unfold_failed"] += 1
                fan = 0
            t["crossing"] += crossing
            t["spikes"] += spikes
            t["micro"] += micro
            t["fans"] += fan
            if crossing or spikes or micro or fan:
                worst.append(f"{method} {name} {size:.0f} mm: {len(r.panels)} panels, "
                             f"{crossing} crossing, {spikes} spikes, {micro} micro sides, {fan} fans")
    return t, worst


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--methods", default="iso_grid,equal_size_grid,boundary_driven,walking_agent")
    args = ap.parse_args()
    face_list = faces()
    print("| method | runs made / refused | panels | crossing | unfold failed | "
          "spikes (< 5°) | sharpest ° | micro sides (< 0.01 mm) | shortest mm | fans | s |")
    print("|---|---|---|---|---|---|---|---|---|---|---|")
    notes = []
    for method in args.methods.split(","):
        t0 = time.perf_counter()
        t, worst = survey(method, face_list)
        notes += worst
        print(f"| {method} | {t['made']} / {t['refused']} | {t['panels']} | {t['crossing']} | "
              f"{t['unfold_failed']} | {t['spikes']} | {t['sharpest']:.2f} | {t['micro']} | "
              f"{t['shortest']:.2g} | {t['fans']} | {time.perf_counter() - t0:.0f} |", flush=True)
    print()
    for line in notes:
        print("-", line)


if __name__ == "__main__":
    main()
