"""Nesting: Tessella's nest() against FreeCAD's Arch Nest (ArchNesting.Nester) on
the same flat panels and the same sheet. Prints a table and writes it to
out/bench/nest_vs_arch.md.

    PYTHONPATH=/usr/lib/freecad-python3/lib:$PWD /usr/bin/python3 bench/nest_vs_arch.py

Arch Nest knows no margin or spacing: it gets the sheet shrunk by the margin and
spacing 0, Tessella gets margin and spacing (a harder problem). Arch runs in a
child process with a time limit (--arch-timeout, default 300 s).
"""

import argparse
import math
import multiprocessing as mp
import os
import sys
import time

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path[:0] = ["/usr/lib/freecad-python3/lib", REPO]

import FreeCAD  # noqa: E402  (before Part)
import Part  # noqa: E402

import freecad_workbench as tessella  # noqa: E402

MARGIN, SPACING = 10.0, 6.0


def cases():
    """(name, flat panels): planar cylinder quads and bent saddle quads."""
    out = []
    cyl = Part.makeCylinder(3000, 3000).Faces[0]
    r = tessella.panelize(cyl, method="iso_grid", u_count=24, v_count=3)
    out.append(("cylinder 24x3 (72 planar quads), 2500 x 1250", tessella.unfold(r), 2500.0, 1250.0))
    s = Part.BezierSurface()
    s.increase(1, 1)
    for i, x in enumerate((-2000, 2000)):
        for j, y in enumerate((-2000, 2000)):
            s.setPole(i + 1, j + 1, FreeCAD.Vector(x, y, x * y / 4000.0))
    r = tessella.panelize(s.toShape(), method="iso_grid", u_count=6, v_count=6)
    flat = tessella.unfold(r)
    out.append(("saddle 6x6 (36 bent quads), 2500 x 1250", flat, 2500.0, 1250.0))
    # Arch Nest opens no second sheet: a case that fits one sheet
    out.append(("saddle, first 12 bent quads, 4000 x 2500", flat[:12], 4000.0, 2500.0))
    return out


def arch_run(outlines, W, H, queue):
    import FreeCAD  # noqa: F401
    import Part

    sys.path += ["/usr/share/freecad/Mod/Arch", "/usr/share/freecad/Mod/Draft", "/usr/share/freecad/Mod", "/usr/share/freecad/Ext"]
    import ArchNesting

    faces = []
    for o in outlines:
        pts = [FreeCAD.Vector(x, y, 0) for x, y in o]
        faces.append(Part.Face(Part.makePolygon(pts + [pts[0]])))
    container = Part.makePlane(W - 2 * MARGIN, H - 2 * MARGIN)
    t = time.perf_counter()
    n = ArchNesting.Nester(container, faces)
    result = n.run()
    dt = time.perf_counter() - t
    if not result:
        queue.put((dt, None, None))
        return
    placed = sum(len(sheet) for sheet in result)
    queue.put((dt, len(result), placed))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--arch-timeout", type=float, default=300.0)
    args = ap.parse_args()
    rows = []
    for name, flat, W, H in cases():
        t = time.perf_counter()
        lay = tessella.nest(flat, sheet_width=W, sheet_height=H, margin=MARGIN, spacing=SPACING,
                            rotations=4)
        dt = time.perf_counter() - t
        rows.append((name, "Tessella nest (convex-hull NFP)", f"{dt:.3f}", lay.sheet_count,
                     len(flat), f"{100 * lay.utilization:.1f}%"))
        print(rows[-1], flush=True)
        q = mp.Queue()
        p = mp.Process(target=arch_run, args=([f.outline.tolist() for f in flat], W, H, q))
        p.start()
        p.join(args.arch_timeout)
        if p.is_alive():
            p.terminate()
            p.join()
            rows.append((name, "FreeCAD Arch Nest", f"> {args.arch_timeout:.0f} (stopped)", "-",
                         "-", "-"))
        else:
            dt, sheets, placed = q.get() if not q.empty() else (math.nan, None, None)
            area = sum(f.area for f in flat)
            util = f"{100 * area / (sheets * W * H):.1f}%" if sheets else "-"
            rows.append((name, "FreeCAD Arch Nest", f"{dt:.3f}",
                         sheets if sheets else "aborted (no room on the sheet)",
                         placed if placed is not None else "-", util))
        print(rows[-1], flush=True)
    header = ("panels", "nester", "time (s)", "sheets", "placed", "utilization")
    lines = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    lines += ["| " + " | ".join(str(c) for c in r) + " |" for r in rows]
    table = "\n".join(lines)
    print(table)
    os.makedirs(os.path.join(REPO, "out", "bench"), exist_ok=True)
    with open(os.path.join(REPO, "out", "bench", "nest_vs_arch.md"), "w") as f:
        f.write(f"Margin {MARGIN:g} mm, spacing {SPACING:g} mm (Tessella only), "
                "rotations 0/90/180/270.\n\n" + table + "\n")


if __name__ == "__main__":
    main()
