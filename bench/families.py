"""Panel families (issue 17): the closed-form case and families against tolerance.

    PYTHONPATH=/usr/lib/freecad-python3/lib:$PWD /usr/bin/python3 bench/families.py [--out FILE]

Prints four tables (Markdown):

1. Surfaces of revolution panelized along meridians and parallels (iso_grid
   with u_count x v_count on a sphere zone, a cone band and a torus band):
   the panels of a row are turned copies of each other, so the families are
   the rows (closed form), unless two rows are congruent themselves (the torus
   band is symmetric about its equator: with mirror those rows pair up).
   Rows are counted independently (corners' mean height).
2. The bundled examples (examples/*.brep) at about 1.5 m panels (iso_grid,
   size=1500): families against family_tolerance 1e-3 ("exact congruence"),
   0.5, 1, 2, 5 and 10 mm (mirror on), the reduction at 2 mm against 1e-3, and
   2 mm without mirror, and a lower bound of the families ANY grouping needs
   at 2 mm (packing_lower_bound: panels pairwise too different to share a
   template).
3. The three doubly curved examples (British Museum roof, Chen Shan dome, Sun
   Valley funnel) at 1.5 m in every quad layout (iso_grid, equal_size_grid,
   boundary_driven, curvature_lines, chebyshev_net): families at 1e-3 and 2 mm, the
   reduction, the lower bound at 2 mm (a layout whose bound exceeds half its
   exact count cannot reach 50% fewer with any grouping), and the fewest
   templates that cover every panel within 2 mm (the set cover solved exactly
   by SciPy's MILP, HiGHS; `make bench-deps` installs python3-scipy): how far
   the greedy cover is from the optimum for the same distance.
4. Time of tessella.panel_families on the examples at about 1 m panels
   (about 5,000 panels each), per tolerance, best of 3, with the family count
   and whether the coarse grouping ran (see docs/families.md).
"""

import argparse
import os
import sys
import time

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
for _p in ("/usr/lib/freecad-python3/lib", REPO):
    if _p not in sys.path:
        sys.path.append(_p)

import FreeCAD  # noqa: E402,F401  (before Part)
import Part  # noqa: E402
import numpy as np  # noqa: E402

import freecad_workbench as tessella  # noqa: E402
from freecad_workbench import families  # noqa: E402

V = FreeCAD.Vector
TOLERANCES = (1e-3, 0.5, 1.0, 2.0, 5.0, 10.0)
EXAMPLES = ("trimmed_bspline_holes", "bezier_patch", "british_museum_roof", "chen_shan_dome",
            "sun_valley_funnel", "cylinder_part", "plane")


def revolution_cases():
    line = Part.LineSegment(V(12000, 0, 0), V(5000, 0, 7000)).toBSpline()
    cone = Part.SurfaceOfRevolution(line, V(0, 0, 0), V(0, 0, 1)).toShape(
        0, 2.5, line.FirstParameter, line.LastParameter)
    return [
        ("sphere zone 10-70 deg, full turn", Part.makeSphere(10000, V(0, 0, 0), V(0, 0, 1), 10, 70,
                                                             360).Faces[0], 24, 8),
        ("sphere zone 10-70 deg, 150 deg", Part.makeSphere(10000, V(0, 0, 0), V(0, 0, 1), 10, 70,
                                                           150).Faces[0], 36, 12),
        ("cone band, 2.5 rad", cone, 20, 7),
        ("torus band -60..90 deg, 150 deg", Part.makeTorus(10000, 3000, V(0, 0, 0), V(0, 0, 1),
                                                           -60, 90, 150).Faces[0], 36, 10),
    ]


def rows_by_height(r):
    z = np.array([r.vertices[list(p)][:, 2].mean() for p in r.panels])
    return np.unique(np.round(z, 3), return_inverse=True)[1]


def same_partition(a, b):
    pairs = set(zip(np.asarray(a).tolist(), np.asarray(b).tolist()))
    return len(pairs) == len(set(a)) == len(set(b))


def table_revolution(out):
    out("## 1. Surfaces of revolution along meridians and parallels (family_tolerance = 2 mm)\n")
    out("| surface | panels (u x v) | rows | families, mirror | families, no mirror | "
        "families == rows | largest error (mm) |")
    out("|---|---|---|---|---|---|---|")
    for label, face, u, v in revolution_cases():
        r = tessella.panelize(face, method="iso_grid", u_count=u, v_count=v)
        rows = rows_by_height(r)
        fm = tessella.panel_families(r, 2.0, mirror=True)
        fn = tessella.panel_families(r, 2.0, mirror=False)
        ok = "yes" if same_partition(fn.labels, rows) and fn.count == rows.max() + 1 else "no"
        okm = "yes" if same_partition(fm.labels, rows) else "no (congruent rows pair up)"
        out(f"| {label} | {len(r.panels)} ({u} x {v}) | {rows.max() + 1} | {fm.count} ({okm}) | "
            f"{fn.count} | {ok} | {max(fm.error.max(), fn.error.max()):.2e} |")
    out("")


def packing_lower_bound(corners, tol):
    """A lower bound of the families any grouping needs at `tol`: panels pairwise
    more than 2 x tol apart can share no template (two members of one family
    are within 2 x tol of each other under some rigid motion). "Apart" is
    measured by a lower bound of the least largest corner distance (over rigid
    motions, mirror images and corner correspondences): half the largest change
    of a corner-to-corner distance. Greedy in panel order (a maximal packing,
    not necessarily the largest)."""
    picked = {}  # corner count -> list of (k,k) distance tables
    count = 0
    for c in corners:
        c = np.asarray(c, dtype=float)
        k = len(c)
        d = np.linalg.norm(c[:, None, :] - c[None, :, :], axis=2)
        mine = picked.setdefault(k, [])
        if mine:
            tables = np.asarray(mine)  # (m,k,k)
            best = np.full(len(mine), np.inf)
            for order in (np.arange(k), np.arange(k)[::-1]):
                for s in range(k):
                    perm = np.roll(order, -s)
                    change = np.abs(tables - d[np.ix_(perm, perm)][None]).max(axis=(1, 2)) / 2
                    best = np.minimum(best, change)
            if best.min() <= 2 * tol:
                continue
        mine.append(d)
        count += 1
    return count


def table_examples(out, size=1500.0):
    out(f"## 2. Families against tolerance, bundled examples (iso_grid, size = {size:g} mm)\n")
    head = " | ".join(f"{t:g} mm" for t in TOLERANCES)
    out(f"| example | panels | {head} | fewer at 2 mm vs 1e-3 | 2 mm, no mirror | "
        "2 mm, lower bound (any grouping) |")
    out("|---|---|" + "---|" * len(TOLERANCES) + "---|---|---|")
    for name in EXAMPLES:
        face = Part.read(os.path.join(REPO, "examples", f"{name}.brep")).Faces[0]
        r = tessella.panelize(face, method="iso_grid", size=size)
        corners = families.panel_corners(r)
        counts = [families.families_of_corners(corners, t).count for t in TOLERANCES]
        exact, at2 = counts[0], counts[TOLERANCES.index(2.0)]
        no_mirror = families.families_of_corners(corners, 2.0, mirror=False).count
        cells = " | ".join(str(c) for c in counts)
        bound = packing_lower_bound(corners, 2.0)
        out(f"| {name} | {len(r.panels)} | {cells} | {100.0 * (exact - at2) / exact:.0f}% | "
            f"{no_mirror} | {bound} |")
    out("")


def optimal_cover(corners, tol, mirror=True):
    """The fewest templates covering every panel within `tol` (the distance
    of tessella's clustering, core.panel_distance): the set cover solved
    exactly by HiGHS (scipy.optimize.milp). Candidate pairs by the same
    necessary condition as the core (sorted corner-to-corner distances within
    2 x tol, here with a k-d tree). None without SciPy or when HiGHS does not
    prove the optimum within a minute."""
    try:
        from scipy.optimize import Bounds, LinearConstraint, milp
        from scipy.sparse import csr_matrix
        from scipy.spatial import cKDTree
    except ImportError:
        return None
    from freecad_workbench import core

    n = len(corners)
    rows, cols = list(range(n)), list(range(n))
    by_count = {}
    for i, c in enumerate(corners):
        by_count.setdefault(len(c), []).append(i)
    for k, members in by_count.items():
        upper = np.triu_indices(k, 1)
        keys = [np.sort(np.linalg.norm(np.asarray(corners[i])[:, None] - np.asarray(corners[i])[None],
                                       axis=2)[upper]) for i in members]
        for a, b in cKDTree(np.array(keys)).query_pairs(2 * tol, p=np.inf):
            i, j = members[a], members[b]
            if core.panel_distance(np.asarray(corners[i], dtype=float),
                                   np.asarray(corners[j], dtype=float), mirror) <= tol:
                rows += [i, j]
                cols += [j, i]
    cover = csr_matrix((np.ones(len(rows)), (rows, cols)), shape=(n, n))
    res = milp(c=np.ones(n), constraints=LinearConstraint(cover, lb=1, ub=np.inf),
               integrality=np.ones(n), bounds=Bounds(0, 1), options={"time_limit": 60})
    return int(round(res.fun)) if res.status == 0 else None


DOUBLY_CURVED = ["british_museum_roof", "chen_shan_dome", "sun_valley_funnel"]
LAYOUTS = ["iso_grid", "equal_size_grid", "boundary_driven", "curvature_lines", "chebyshev_net"]


def table_layouts(out, size=1500.0):
    out(f"## 3. Families by layout, doubly curved examples (size = {size:g} mm, mirror on)\n")
    out("| example | layout | panels | families at 1e-3 mm | at 2 mm | fewer | "
        "lower bound at 2 mm | bound allows 50% | optimal cover at 2 mm |")
    out("|---|---|---|---|---|---|---|---|---|")
    for name in DOUBLY_CURVED:
        face = Part.read(os.path.join(REPO, "examples", f"{name}.brep")).Faces[0]
        for method in LAYOUTS:
            r = tessella.panelize(face, method=method, size=size)
            corners = families.panel_corners(r)
            exact = families.families_of_corners(corners, 1e-3).count
            at2 = families.families_of_corners(corners, 2.0).count
            bound = packing_lower_bound(corners, 2.0)
            best = optimal_cover(corners, 2.0)
            out(f"| {name} | {method} | {len(r.panels)} | {exact} | {at2} | "
                f"{100.0 * (exact - at2) / exact:.0f}% | {bound} | "
                f"{'yes' if bound <= exact / 2 else 'no'} | "
                f"{'n/a' if best is None else best} |")
    out("")


def table_timing(out, size=1000.0):
    out(f"## 4. Time, about 5,000 panels (iso_grid, size = {size:g} mm; best of 3)\n")
    out("| example | panels | " + " | ".join(f"{t:g} mm" for t in (2.0, 10.0, 50.0)) + " |")
    out("|---|---|---|---|---|")
    for name in ("british_museum_roof", "chen_shan_dome", "sun_valley_funnel"):
        face = Part.read(os.path.join(REPO, "examples", f"{name}.brep")).Faces[0]
        r = tessella.panelize(face, method="iso_grid", size=size)
        corners = families.panel_corners(r)
        cells = []
        for tol in (2.0, 10.0, 50.0):
            best = np.inf
            for _ in range(3):
                t0 = time.perf_counter()
                f = families.families_of_corners(corners, tol)
                best = min(best, time.perf_counter() - t0)
            coarse = ", coarse" if f.summary()["coarse"] else ""
            cells.append(f"{1000 * best:.0f} ms ({f.count} families{coarse})")
        out(f"| {name} | {len(r.panels)} | " + " | ".join(cells) + " |")
    out("")


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--out", help="also write the tables to this file")
    ap.add_argument("--tables", default="1234", help="which tables, e.g. 3 (default: all)")
    args = ap.parse_args()
    lines = []

    def out(text):
        print(text, flush=True)
        lines.append(text)

    for key, table in zip("1234", (table_revolution, table_examples, table_layouts, table_timing)):
        if key in args.tables:
            table(out)
    if args.out:
        with open(args.out, "w", encoding="utf-8") as f:
            f.write("\n".join(lines) + "\n")


if __name__ == "__main__":
    main()
