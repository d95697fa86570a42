"""Face sets (tessella.panelize_faces) against one face, and on many threads.

    PYTHONPATH=/usr/lib/freecad-python3/lib:$PWD /usr/bin/python3 bench/face_sets.py [--size 1500]

Prints:
1. The British Museum roof (examples/british_museum_roof.brep) against the
   same roof split into four faces through the court's centre (along
   iso-lines of its surface; written to examples/face_sets/british_museum_roof_split.brep): panels,
   rods, rod length mean / variance, for iso_grid, equal_size_grid,
   boundary_driven and walking_agent; the share of shared-edge nodes whose rods on
   the two sides carry on within 20 degrees of one line (rows across the split).
   Then the roof split along its plan's diagonals, as seed 004 divides it
   (examples/face_sets/british_museum_roof_diagonals.brep), the same figures
   and, as a reference, the one face's rods cut where they cross the
   diagonals (the change a split makes by cutting alone); and chebyshev_net
   with the diagonals as its guides at 1000 / 1500 / 2200 mm (the cuts are
   rows of the net). Then the four faces each on a surface of its own (written to
   examples/face_sets/british_museum_roof_subsurfaces.brep) at 1000 / 1500 /
   2200 mm, boundary_driven and iso_grid, against the one face.
   With --sweep-walking-agent: walking_agent's panels on the three split
   roofs against the one face at 16 bounds from 12 to 65 mm (its own count
   jumps by up to 25% between neighbouring bounds on one face), with the
   median and range of the ratios; OVER marks a run beyond its bound.
2. A filleted box (26 trimmed faces: planes, cylinders, spheres) at about
   8,000 panels: seconds on 1 and 2 threads (best of --repeat), their ratio,
   the sum of the faces panelized one by one (the per-face overhead), and the
   peak memory of this process.
"""

import argparse
import math
import os
import resource
import sys
import time

import FreeCAD  # noqa: F401  (before Part, always)
import Part
import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.path.insert(0, ROOT)
sys.path.append("/usr/share/freecad/Mod/Part")  # BOPTools (FreeCAD's splitting tools)

import freecad_workbench as tessella  # noqa: E402

V = FreeCAD.Vector
ROOF = os.path.join(ROOT, "examples", "british_museum_roof.brep")
SPLIT = os.path.join(ROOT, "examples", "face_sets", "british_museum_roof_split.brep")
SUB = os.path.join(ROOT, "examples", "face_sets", "british_museum_roof_subsurfaces.brep")
DIAGONALS = os.path.join(ROOT, "examples", "face_sets", "british_museum_roof_diagonals.brep")


def split_roof(face):
    """The roof cut by the planes x = centre and y = centre: four faces sharing
    the cuts' edges (a compound from BOPTools' Split, edges shared)."""
    import BOPTools.SplitAPI as split_api

    bb = face.BoundBox
    c = bb.Center
    big = 2 * bb.DiagonalLength
    planes = [Part.Plane(c, V(1, 0, 0)).toShape(-big, big, -big, big),
              Part.Plane(c, V(0, 1, 0)).toShape(-big, big, -big, big)]
    return split_api.slice(face, planes, "Split")


def split_roof_diagonals(face):
    """The roof cut along the diagonals of its rectangular plan, as seed 004
    divides it into four sub-surfaces (section 5, Fig. 39): vertical planes
    through opposite corners of the plan; four faces sharing the cuts' edges."""
    import BOPTools.SplitAPI as split_api

    bb = face.BoundBox
    big = 2 * bb.DiagonalLength
    planes = []
    for x0, y0, x1, y1 in ((bb.XMin, bb.YMin, bb.XMax, bb.YMax),
                           (bb.XMin, bb.YMax, bb.XMax, bb.YMin)):
        normal = V(-(y1 - y0), x1 - x0, 0)
        normal.normalize()
        planes.append(Part.Plane(V(x0, y0, 0), normal).toShape(-big, big, -big, big))
    return split_api.slice(face, planes, "Split")


def plan_diagonal_guides(face):
    """The curves split_roof_diagonals cuts along, over the whole surface
    (through the drum): its vertical planes cut with the face's untrimmed
    surface, as edges (chebyshev_net's guides: the net's rows are the cuts)."""
    bb = face.BoundBox
    big = 2 * bb.DiagonalLength
    whole = face.Surface.toShape()
    guides = []
    for x0, y0, x1, y1 in ((bb.XMin, bb.YMin, bb.XMax, bb.YMax),
                           (bb.XMin, bb.YMax, bb.XMax, bb.YMin)):
        normal = V(-(y1 - y0), x1 - x0, 0)
        normal.normalize()
        plane = Part.Plane(V(x0, y0, 0), normal).toShape(-big, big, -big, big)
        guides.append(whole.section(plane).Edges[0])
    return guides


def sub_surfaces(pieces):
    """The split roof's four faces, each on a B-spline surface of its own (its
    piece of the roof's surface, `segment`ed to the face's range, the face's
    wire projected onto it): the roof as a modeller or a STEP file gives it in
    sub-surfaces, with no common (u,v)."""
    faces = []
    for f in pieces.Faces:
        s = f.Surface.copy()
        u0, u1, v0, v1 = f.ParameterRange
        s.segment(u0, u1, v0, v1)
        face = Part.Face(s, f.OuterWire)
        face.fix(1e-7, 1e-7, 1e-3)
        faces.append(face)
    return Part.Compound(faces)


def stats(r):
    lengths = r.metrics["rod_length"]
    return len(r.panels), len(r.rods), float(lengths.mean()), float(lengths.var())


def carried_rows(shape, r, angle=20.0):
    """Share of nodes on shared edges where a rod of each face, the two leaving
    the edge, lie within `angle` of one line."""
    from collections import defaultdict

    edges = []
    all_faces = shape.Faces
    for e in shape.Edges:
        owners = [i for i, f in enumerate(all_faces) if any(e.isSame(g) for g in f.Edges)]
        if len(owners) == 2:
            edges.append(e)
    tol = 1e-6 * shape.BoundBox.DiagonalLength
    on_edge = set()
    for v in r.nodes:
        p = Part.Vertex(V(*r.vertices[v]))
        if any(e.distToShape(p)[0] <= 10 * tol for e in edges):
            on_edge.add(int(v))
    rods_at = defaultdict(list)
    for k, (a, b) in enumerate(r.rods):
        rods_at[int(a)].append((int(b), int(r.rod_face[k])))
        rods_at[int(b)].append((int(a), int(r.rod_face[k])))
    cos = math.cos(math.radians(angle))
    carried = 0
    for v in on_edge:
        leaving = [(w, f) for w, f in rods_at[v] if w not in on_edge]
        dirs = {}
        for w, f in leaving:
            d = r.vertices[w] - r.vertices[v]
            dirs.setdefault(f, []).append(d / np.linalg.norm(d))
        faces = list(dirs)
        ok = False
        if len(faces) >= 2:
            for d1 in dirs[faces[0]]:
                for d2 in dirs[faces[1]]:
                    ok = ok or float(-d1 @ d2) >= cos
        carried += ok
    return carried / max(1, len(on_edge)), len(on_edge)


def against_one(one, r, shape, label):
    """The set's panel count and rod statistics against the one face's, and
    the rows carried across its shared edges."""
    a, b = stats(one), stats(r)
    share, count = carried_rows(shape, r)
    return (f"one {a[0]:5d} {label} {b[0]:5d} {100 * (b[0] - a[0]) / a[0]:+5.1f}%  "
            f"mean {100 * (b[2] / a[2] - 1):+5.1f}%  var {100 * (b[3] / a[3] - 1):+6.1f}%  "
            f"rows {100 * share:3.0f}% of {count}")


def cut_only(one, roof):
    """The one face's rod count and length statistics if its rods were only cut
    where they cross the plan's diagonals (a lower bound of what a split
    must change: every rod crossing a cut becomes two)."""
    bb = roof.BoundBox
    lengths = []
    cuts = []
    for x0, y0, x1, y1 in ((bb.XMin, bb.YMin, bb.XMax, bb.YMax),
                           (bb.XMin, bb.YMax, bb.XMax, bb.YMin)):
        a = np.array([x0, y0])
        t = np.array([x1 - x0, y1 - y0])
        cuts.append((a, np.array([-t[1], t[0]]) / np.linalg.norm(t)))
    for a_i, b_i in one.rods:
        p, q = one.vertices[a_i], one.vertices[b_i]
        ts = []
        for a, n in cuts:
            sp, sq = (p[:2] - a) @ n, (q[:2] - a) @ n
            if sp * sq < 0:
                ts.append(sp / (sp - sq))
        ts = [0.0] + sorted(ts) + [1.0]
        for t0, t1 in zip(ts, ts[1:]):
            lengths.append((t1 - t0) * float(np.linalg.norm(q - p)))
    base = stats(one)
    lengths = np.array(lengths)
    return (f"rods {100 * (len(lengths) / base[1] - 1):+5.1f}%  mean "
            f"{100 * (lengths.mean() / base[2] - 1):+5.1f}%  var {100 * (lengths.var() / base[3] - 1):+6.1f}%")


def filleted_box():
    box = Part.makeBox(6000, 4500, 3000)
    return Part.Shell(box.makeFillet(600, box.Edges).Faces)


def best(repeat, fn):
    t = float("inf")
    out = None
    for _ in range(repeat):
        start = time.perf_counter()
        out = fn()
        t = min(t, time.perf_counter() - start)
    return t, out


def best_cpu(repeat, fn):
    """Least CPU time of this process over `repeat` calls: on one thread the
    work done, steadier than wall time on a machine other jobs share."""
    t = float("inf")
    for _ in range(repeat):
        start = time.process_time()
        fn()
        t = min(t, time.process_time() - start)
    return t


def sweep_walking_agent():
    """walking_agent's panels on the split roofs against the one face, bound by bound."""
    import statistics

    roof = Part.read(ROOF).Faces[0]
    shapes = {"centre": Part.read(SPLIT), "diagonals": Part.read(DIAGONALS),
              "sub-surfaces": Part.read(SUB)}
    ratios = {k: [] for k in shapes}
    print("walking_agent: panels, one face against the split roofs")
    for bound in (12, 14, 16, 17, 19, 20, 21, 23, 26, 28, 30, 33, 36, 40, 50, 65):
        one = len(tessella.panelize(roof, method="walking_agent", max_deviation=float(bound)).panels)
        row = [f"{bound:3d} mm  one {one:5d}"]
        for name, shape in shapes.items():
            r = tessella.panelize_faces(shape, method="walking_agent", max_deviation=float(bound))
            n = len(r.panels)
            worst = float(r.metrics["panel_deviation"].max())
            ratios[name].append(n / one)
            row.append(f"{name} {n:5d} ({100 * (n / one - 1):+5.1f}%{'' if worst <= bound else ' OVER'})")
        print("  ".join(row), flush=True)
    for name, r in ratios.items():
        print(f"{name:13s} median {100 * (statistics.median(r) - 1):+5.1f}%, "
              f"range {100 * (min(r) - 1):+5.1f} .. {100 * (max(r) - 1):+5.1f}%")


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--size", type=float, default=1500.0, help="panel size on the roof (mm)")
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--sweep-walking-agent", action="store_true",
                    help="walking_agent on the split roofs at 16 bounds (about 3 minutes)")
    args = ap.parse_args(argv)
    if args.sweep_walking_agent:
        sweep_walking_agent()
        return 0

    roof = Part.read(ROOF).Faces[0]
    pieces = split_roof(roof)
    if not os.path.exists(SPLIT):
        pieces.exportBrep(SPLIT)
    print(f"British Museum roof: one face vs {len(pieces.Faces)} sub-surfaces "
          f"(size {args.size:.0f} mm)")
    print(f"{'method':18s} {'':6s} {'panels':>7s} {'rods':>6s} {'rod mean':>9s} "
          f"{'rod var':>10s} {'diff':>6s} {'rows 20deg':>10s}")
    # The four tiling methods at the roof's size (walking_agent at its bound).
    methods = [("iso_grid", {"size": args.size}), ("equal_size_grid", {"size": args.size}),
               ("boundary_driven", {"size": args.size}), ("walking_agent", {"max_deviation": 30.0})]
    for method, params in methods:
        one = tessella.panelize(roof, method=method, **params)
        split = tessella.panelize_faces(pieces, method=method, **params)
        a, b = stats(one), stats(split)
        share, count = carried_rows(pieces, split)
        print(f"{method:18s} {'one':6s} {a[0]:7d} {a[1]:6d} {a[2]:9.1f} {a[3]:10.0f}")
        print(f"{'':18s} {'split':6s} {b[0]:7d} {b[1]:6d} {b[2]:9.1f} {b[3]:10.0f} "
              f"{100 * (b[0] - a[0]) / a[0]:+5.1f}% {100 * share:8.0f}% of {count}")

    if not os.path.exists(DIAGONALS):
        split_roof_diagonals(roof).exportBrep(DIAGONALS)
    diagonals = Part.read(DIAGONALS)
    print(f"\nThe roof split along its plan's diagonals, as seed 004 splits it "
          f"({len(diagonals.Faces)} faces):")
    for method, params in methods:
        one = tessella.panelize(roof, method=method, **params)
        r = tessella.panelize_faces(diagonals, method=method, **params)
        print(f"  {method:16s} {against_one(one, r, diagonals, 'diagonals')}")
        print(f"  {'':16s} the one face's rods cut at the diagonals (no other change): "
              f"{cut_only(one, roof)}")
    # A net whose generators are the diagonals: the cuts are rows of it.
    guides = plan_diagonal_guides(roof)
    print("  chebyshev_net with the diagonals as guides, by size (the cuts rows of the net):")
    for size in (1000.0, 1500.0, 2200.0):
        one = tessella.panelize(roof, method="chebyshev_net", size=size, guides=guides)
        r = tessella.panelize_faces(diagonals, method="chebyshev_net", size=size, guides=guides)
        print(f"  {size:16.0f} {against_one(one, r, diagonals, 'diagonals')}  "
              f"unmatched segments {r.summary['unmatched_shared_segments']}")

    print("\nwalking_agent on the split roof (its lines walked on the faces' union):")
    for bound in (15.0, 60.0, 100.0):
        one = tessella.panelize(roof, method="walking_agent", max_deviation=bound)
        r = tessella.panelize_faces(pieces, method="walking_agent", max_deviation=bound)
        print(f"  max_deviation {bound:5.0f} mm: {against_one(one, r, pieces, 'split')}  "
              f"on the union {r.summary['faces_traced_across']}")

    print("\nboundary_driven on the split roof at other sizes (traced on the faces' union):")
    for size in (1000.0, 2200.0):
        one = tessella.panelize(roof, method="boundary_driven", size=size)
        r = tessella.panelize_faces(pieces, method="boundary_driven", size=size)
        print(f"  size {size:5.0f} mm: {against_one(one, r, pieces, 'split')}")

    if not os.path.exists(SUB):
        sub_surfaces(pieces).exportBrep(SUB)
    sub = Part.read(SUB)
    print(f"\nThe same roof in {len(sub.Faces)} sub-surfaces of their own "
          f"(boundary_driven traces across them):")
    for size in (1000.0, 1500.0, 2200.0):
        for method, params in [("boundary_driven", {"size": size}),
                               ("iso_grid", {"size": size})]:
            one = tessella.panelize(roof, method=method, **params)
            r = tessella.panelize_faces(sub, method=method, **params)
            print(f"{method:16s} {size:5.0f} {against_one(one, r, sub, 'sub')}  "
                  f"traced across {r.summary['faces_traced_across_surfaces']}")

    # The per-face overhead on sub-surfaces (ShapeFix's approximated pcurves).
    saved = os.environ.get("TESSELLA_THREADS")
    os.environ["TESSELLA_THREADS"] = "1"
    for method in ("iso_grid", "boundary_driven"):
        ts, _ = best(args.repeat, lambda: tessella.panelize_faces(sub, method=method,
                                                                  size=args.size, threads=1))
        tf, _ = best(args.repeat, lambda: [tessella.panelize(f, method=method, size=args.size)
                                           for f in sub.Faces])
        cs = best_cpu(args.repeat, lambda: tessella.panelize_faces(sub, method=method,
                                                                   size=args.size, threads=1))
        cf = best_cpu(args.repeat, lambda: [tessella.panelize(f, method=method, size=args.size)
                                            for f in sub.Faces])
        print(f"  {method}: the set on 1 thread {ts:.3f} s, the faces one by one {tf:.3f} s: "
              f"{ts / tf:.2f}; CPU time {cs:.3f} / {cf:.3f} s: {cs / cf:.2f}")
    if saved is None:
        del os.environ["TESSELLA_THREADS"]
    else:
        os.environ["TESSELLA_THREADS"] = saved

    shape = filleted_box()
    size = math.sqrt(shape.Area / 8000)
    print(f"\nFilleted box: {len(shape.Faces)} faces, size {size:.0f} mm")
    t1, r1 = best(args.repeat, lambda: tessella.panelize_faces(shape, size=size, threads=1))
    t2, r2 = best(args.repeat, lambda: tessella.panelize_faces(shape, size=size, threads=2))
    same = (np.array_equal(r1.vertices, r2.vertices) and r1.panels == r2.panels)
    faces = shape.Faces
    saved = os.environ.get("TESSELLA_THREADS")
    os.environ["TESSELLA_THREADS"] = "1"  # as the set on one thread
    tf, _ = best(args.repeat, lambda: [tessella.panelize(f, size=size) for f in faces])
    cs = best_cpu(args.repeat, lambda: tessella.panelize_faces(shape, size=size, threads=1))
    cf = best_cpu(args.repeat, lambda: [tessella.panelize(f, size=size) for f in faces])
    if saved is None:
        del os.environ["TESSELLA_THREADS"]
    else:
        os.environ["TESSELLA_THREADS"] = saved
    print(f"  panels {len(r1.panels)}, shared-edge nodes {r1.summary['shared_edge_nodes']}")
    print(f"  1 thread {t1:.3f} s, 2 threads {t2:.3f} s: ratio {t2 / t1:.2f} "
          f"(same result: {same})")
    print(f"  faces one by one {tf:.3f} s (one call each, one thread); "
          f"set on 1 thread / sum of faces: {t1 / tf:.2f}; CPU time {cs:.3f} / {cf:.3f} s: "
          f"{cs / cf:.2f}")
    peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024
    print(f"  peak memory of this process: {peak:.0f} MB")


if __name__ == "__main__":
    main()
