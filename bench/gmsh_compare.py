"""Tessella against Gmsh and FreeCAD's MeshPart on trimmed doubly curved faces
that are not the bundled examples (built in code: bench/bench_faces.py): a dome
with an opening, a saddle trimmed by a curve, a British-Museum-like roof with a
drum hole, each at a target size giving about 2,000 panels.

    PYTHONPATH=/usr/lib/freecad-python3/lib:$PWD /usr/bin/python3 bench/gmsh_compare.py [--panels 2000]

Timed (best of --repeat):
- Tessella: the core pipeline on the parsed face (core.panelize: method,
  short rods, metrics on every core, boundary pieces, nodes) for iso_grid,
  equal_size_grid and boundary_driven at `size`, and walking_agent with
  max_size = size and max_deviation = 0.002 x the face's diagonal;
- Gmsh (python3-gmsh, a benchmark-only dependency: `make bench-deps`):
  mesh.generate(2) of the same face (BREP import not timed, in a child
  process), Frontal-Delaunay (algorithm 6; 8, frontal for quads, crashes in
  Debian's Gmsh 4.8.4) with Blossom recombination, element size = size;
- MeshPart: MeshPart.meshFromShape(face, MaxLength=size) (Mefisto, triangles).
Prints one table per face: elements, seconds, microseconds per element and
the ratio of Gmsh's time per element to each row's (above 1: faster than Gmsh).
Under each Tessella row, the deviation measure alone on its panels
(core.measure_panels on the result's mesh, checked to give the pipeline's
figures bit for bit): its ratio is the most these panels reach while the
measure stays as it is, whatever the method, the short-rod merge, the
boundary pieces and the summary cost. The closing summary also gives the
ratio of the rest (panelize's time less the measure's: the method, the
short-rod merge, the boundary pieces and the summary).
"""

import argparse
import math
import os
import sys
import subprocess
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)

import FreeCAD  # noqa: E402,F401  (before Part, always)
import Part  # noqa: E402,F401

import bench_faces  # noqa: E402
from freecad_workbench import core  # noqa: E402


def best_of(repeat, fn):
    best = None
    for _ in range(repeat):
        t0 = time.perf_counter()
        out = fn()
        dt = time.perf_counter() - t0
        if best is None or dt < best[0]:
            best = (dt, out)
    return best


def tessella_rows(face, size, repeat):
    sf = core.SurfaceFace.from_brep_string(face.exportBrepToString())
    cases = [
        ("iso_grid", {"size": size}),
        ("equal_size_grid", {"size": size}),
        ("boundary_driven", {"size": size}),
        ("walking_agent", {"max_size": size,
                           "max_deviation": 0.002 * face.BoundBox.DiagonalLength}),
    ]
    rows = []
    for method, values in cases:
        dt, r = best_of(repeat, lambda: core.panelize(sf, method, values, None))
        n = r.summary["panel_count"]
        quads = int(round(r.summary["quad_share"] * n))
        rows.append((f"tessella {method}", n, quads, dt))
        rows.append(measure_alone_row(sf, r, method, repeat))
    return rows


def measure_alone_row(sf, r, method, repeat):
    """The deviation measure alone: every panel of the result measured again
    (core.measure_panels on its mesh, all cores), the same figures bit for
    bit as the pipeline's. Its ratio to Gmsh bounds the pipeline's from
    above while the measure stays as it is (the method, the short-rod merge,
    the boundary pieces and the summary cost nothing in it)."""
    dt, m = best_of(repeat, lambda: core.measure_panels(sf, r.mesh, core.MetricsParams(), None))
    if list(m.deviation) != list(r.metrics.deviation):
        raise SystemExit(f"{method}: the measure alone differs from the pipeline's")
    return (f"  measure alone ({method})", r.summary["panel_count"], 0, dt)


GMSH_ALGORITHM = 6  # Frontal-Delaunay (8, frontal for quads, crashes in Debian's 4.8.4)


def gmsh_child(path, size, repeat):
    """In a child process (a crash of Gmsh's mesher must not end the bench):
    mesh the face, print 'elements quads seconds'."""
    import gmsh
    best = None
    for _ in range(repeat):
        gmsh.initialize()
        try:
            gmsh.option.setNumber("General.Terminal", 0)
            gmsh.option.setNumber("General.AbortOnError", 0)  # raise, do not exit
            gmsh.option.setNumber("General.NumThreads", 1)
            gmsh.model.add("face")
            gmsh.model.occ.importShapes(path)
            gmsh.model.occ.synchronize()
            gmsh.option.setNumber("Mesh.MeshSizeMin", size)
            gmsh.option.setNumber("Mesh.MeshSizeMax", size)
            gmsh.option.setNumber("Mesh.MeshSizeFromCurvature", 0)
            gmsh.option.setNumber("Mesh.Algorithm", GMSH_ALGORITHM)
            gmsh.option.setNumber("Mesh.RecombineAll", 1)
            gmsh.option.setNumber("Mesh.RecombinationAlgorithm", 1)  # Blossom
            t0 = time.perf_counter()
            gmsh.model.mesh.generate(2)
            dt = time.perf_counter() - t0
            types, tags, _ = gmsh.model.mesh.getElements(2)
            count = {t: len(x) for t, x in zip(types, tags)}
        finally:
            gmsh.finalize()
        if best is None or dt < best[2]:
            best = (count.get(3, 0) + count.get(2, 0), count.get(3, 0), dt)
    print(*best)


def gmsh_row(face, size, repeat):
    label = "gmsh frontal + Blossom"
    try:
        import gmsh  # noqa: F401
    except ImportError:
        return ("gmsh (missing: make bench-deps)", 0, 0, float("nan"))
    with tempfile.TemporaryDirectory() as tmp:
        path = os.path.join(tmp, "face.brep")
        face.exportBrep(path)
        done = subprocess.run([sys.executable, os.path.abspath(__file__), "--gmsh-child", path,
                               repr(size), str(repeat)], capture_output=True, text=True)
        try:
            n, quads, dt = done.stdout.split()[-3:]
            return (label, int(n), int(quads), float(dt))
        except ValueError:
            return (f"gmsh failed (exit {done.returncode})", 0, 0, float("nan"))


def meshpart_row(face, size, repeat):
    import MeshPart
    dt, mesh = best_of(repeat, lambda: MeshPart.meshFromShape(Shape=face, MaxLength=size))
    return ("FreeCAD MeshPart (Mefisto)", mesh.CountFacets, 0, dt)


def main(argv=None):
    argv = sys.argv[1:] if argv is None else argv
    if argv[:1] == ["--gmsh-child"]:
        gmsh_child(argv[1], float(argv[2]), int(argv[3]))
        return 0
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--panels", type=int, default=2000, help="target panel count per face")
    ap.add_argument("--repeat", type=int, default=2)
    args = ap.parse_args(argv)
    threads = os.environ.get("TESSELLA_THREADS", "all cores")
    print(f"Tessella metrics threads: {threads}; Gmsh on 1 thread; times are best of {args.repeat}")
    summary = []
    for name, build in bench_faces.TRIMMED.items():
        face = build()
        size = math.sqrt(face.Area / args.panels)
        rows = tessella_rows(face, size, args.repeat)
        g = gmsh_row(face, size, args.repeat)
        rows.append(g)
        rows.append(meshpart_row(face, size, args.repeat))
        g_per = g[3] / g[1] if g[1] else float("nan")
        print(f"\n{name}: area {face.Area / 1e6:.0f} m2, size {size:.0f} mm")
        print(f"  {'':<32}{'elements':>9}{'quads':>7}{'seconds':>9}{'us/elem':>9}"
              f"{'gmsh/this':>11}")
        for label, n, quads, dt in rows:
            per = dt / n if n else float("nan")
            ratio = g_per / per if n else float("nan")
            print(f"  {label:<32}{n:>9}{quads:>7}{dt:>9.3f}{1e6 * per:>9.1f}{ratio:>11.2f}")
            summary.append((name, label, ratio))
    print("\nratio of Gmsh's time per element to Tessella's (above 1: Tessella faster); "
          "'measure': to the deviation measure alone on the same panels (the most they reach "
          "with it); 'rest': to panelize less the measure alone (the method, the short-rod "
          "merge, the boundary pieces and the summary; from two timings, so rougher):")
    print(f"  {'':<20}{'':<18}{'whole':>6}{'measure':>9}{'rest':>7}")
    alone = {(name, label.split("(")[1].rstrip(")")): ratio for name, label, ratio in summary
             if label.strip().startswith("measure alone")}
    for name, label, ratio in summary:
        if label.startswith("tessella"):
            measure = alone.get((name, label[9:]), float("nan"))
            # Times per element add: 1 / rest = 1 / whole - 1 / measure.
            # (No Gmsh: every ratio is nan, and so is the rest.)
            rest = float("nan")
            if ratio > 0 and measure > 0:
                rest_inverse = 1 / ratio - 1 / measure
                rest = 1 / rest_inverse if rest_inverse > 0 else float("inf")
            print(f"  {name:<20}{label[9:]:<18}{ratio:>6.2f}{measure:>9.2f}{rest:>7.2f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
