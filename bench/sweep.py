"""Every method on every non-planar face of every CAD file in a folder, at three sizes.

    PYTHONPATH=/usr/lib/freecad-python3/lib:$PWD /usr/bin/python3 bench/sweep.py corpus/ \
        [--methods iso_grid equal_size_grid walking_agent boundary_driven] \
        [--divisions 6 12 24] [--timeout 60] [--max-faces 0] [--remeasure 12] [--jobs 1] \
        [--csv out.csv] [--errors]

(bench/fetch_corpus.py gathers a public corpus from Debian's archive.) Files:
STEP / IGES / BRep / FCStd (top-level objects' shapes), also gzipped. A face is
taken when its surface is not a plane and its area is not negligible. Size per
face: sqrt(area) / divisions; walking_agent and gradient_descent get the
sagitta-like bound 0.002 x the face's diagonal x (12 / divisions)^2.

Each run is isolated: runs go to a worker process that reports one JSON line
per run; a worker that dies (a crash) or stays silent beyond --timeout (a
hang) is counted against the run it was on and replaced, and the sweep goes
on. Outcomes: ok, error (a ValueError / RuntimeError with a message: the
method refused, saying why), crash, timeout.

Quality figures of ok runs: panel count, the pipeline's own coverage (gap and
overlap fractions), flagged unreliable deviations, and an independent dense
re-measure (FreeCAD's Surface.parameter / value on a 21 x 21 grid of the
bilinear quad or the flat triangle, a compass search from the farthest
sample, the candidates checked by BRepExtrema) of --remeasure panels per run (the worst
reported, then a fixed-seed random choice) away from the trims (a trim-side
panel's model follows the trim, not its corners): the ratio reported /
re-measured, which must not fall below 0.99 (panels whose re-measured
distance is below 1e-6 mm are left out: there both figures are noise).

Prints one table per method and writes every run to --csv when given.
"""

import argparse
import csv
import json
import math
import os
import select
import statistics
import subprocess
import sys
import tempfile
import threading
import time

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(HERE)
FREECAD_LIB = "/usr/lib/freecad-python3/lib"

DEFAULT_METHODS = ("iso_grid", "equal_size_grid", "walking_agent", "boundary_driven")
BOUND_METHODS = ("walking_agent", "gradient_descent")
CAD_EXTENSIONS = (".step", ".stp", ".iges", ".igs", ".brep", ".brp", ".fcstd")
# Seconds of independent re-measure per run (env TESSELLA_REMEASURE_SECONDS:
# FreeCAD's projection takes ~20 ms a point on MAT.brep's 80 x 83 poles).
REMEASURE_BUDGET = float(os.environ.get("TESSELLA_REMEASURE_SECONDS", "10"))
MIN_AREA_FRACTION = 1e-4  # of the file's largest face: smaller faces are fillets and slivers


# ----------------------------------------------------------------- files
def cad_files(folder):
    out = []
    for root, _dirs, files in os.walk(folder):
        for name in sorted(files):
            low = name.lower()
            if low.endswith(".gz"):
                low = low[:-3]
            if low.endswith(CAD_EXTENSIONS):
                out.append(os.path.join(root, name))
    return sorted(out)


def load_shape(path):
    """The shape of a CAD file (a compound of the top-level objects for FCStd)."""
    import gzip

    import FreeCAD
    import Part

    from freecad_workbench.cli import top_level_shapes

    if path.lower().endswith(".gz"):
        tmp = tempfile.mkdtemp()
        plain = os.path.join(tmp, os.path.basename(path)[:-3])
        with gzip.open(path, "rb") as src, open(plain, "wb") as dst:
            dst.write(src.read())
        path = plain
    if path.lower().endswith(".fcstd"):
        doc = FreeCAD.openDocument(path)
        try:
            shapes = [s.copy() for s in top_level_shapes(doc)]
        finally:
            FreeCAD.closeDocument(doc.Name)
        return Part.makeCompound(shapes)
    shape = Part.Shape()
    shape.read(path)
    return shape


def sweep_faces(shape):
    """(index, face) of the faces worth panelizing: not planar, not negligible."""
    faces = shape.Faces
    if not faces:
        return []
    biggest = max(f.Area for f in faces)
    out = []
    for k, f in enumerate(faces):
        if type(f.Surface).__name__ == "Plane" or f.Area < MIN_AREA_FRACTION * biggest:
            continue
        out.append((k, f))
    return out


# ---------------------------------------------------------------- worker
def params_for(method, face, divisions):
    if method in BOUND_METHODS:
        return {"max_deviation": 0.002 * face.BoundBox.DiagonalLength * (12.0 / divisions) ** 2}
    if method == "relaxed_grid":
        n = max(2, int(round(divisions)))
        return {"u_count": n, "v_count": n}
    return {"size": math.sqrt(face.Area) / divisions}


def _dense(face, pts3, deadline=math.inf):
    """Largest distance of the points to the face's surface (FreeCAD's
    projection); None when the deadline (perf_counter) passes first."""
    import FreeCAD

    surf = face.Surface
    worst = 0.0
    for x in pts3:
        if time.perf_counter() > deadline:
            return None
        u, v = surf.parameter(FreeCAD.Vector(*x))
        q = surf.value(u, v)
        worst = max(worst, math.dist((q.x, q.y, q.z), x))
    return worst


def _dense_panel(face, p, deadline=math.inf):
    """Largest distance from the panel (bilinear quad or flat triangle with
    corners p) to the face's surface: a 21 x 21 grid of its parameters, then
    a pattern search from the three farthest samples (eight directions,
    halving steps down to 1/10000 of the panel), so a peak between the
    samples is not missed (on
    OCCT's wavy MAT.brep the grid alone read up to 4% under the top of a
    wave). None when the deadline passes first."""
    import numpy as np

    quad = len(p) == 4

    def point(a, b):
        if quad:
            return (1 - a) * (1 - b) * p[0] + a * (1 - b) * p[1] + a * b * p[2] + (1 - a) * b * p[3]
        return (1 - a - b) * p[0] + a * p[1] + b * p[2]

    def valid(a, b):
        return 0.0 <= a <= 1.0 and 0.0 <= b <= 1.0 and (quad or a + b <= 1.0 + 1e-12)

    s = np.linspace(0.0, 1.0, 21)
    params = [(a, b) for a in s for b in s if valid(a, b)]
    dists = []
    for a, b in params:
        d = _dense(face, [point(a, b)], deadline)
        if d is None:
            return None
        dists.append(d)
    # FreeCAD's projection (OCCT's extrema) at times stops at a local
    # minimum, a distance too large; a search for the largest distance is
    # drawn to exactly those points. So the candidates are checked by a
    # second projection (BRepExtrema, distToShape on the untrimmed surface
    # over the face's parameter range) and each keeps the smaller of the
    # two: both are distances to real surface points, upper bounds of the
    # true one.
    import FreeCAD
    import Part

    try:
        sheet = face.Surface.toShape(*face.ParameterRange)
    except Exception:  # an unbounded surface OCC cannot make a sheet of
        sheet = None

    def checked(a, b, d):
        if sheet is None:
            return d
        x = point(a, b)
        try:
            return min(d, sheet.distToShape(Part.Vertex(FreeCAD.Vector(*x)))[0])
        except Exception:
            return d

    order = np.argsort(dists)[::-1]
    worst = max(checked(*params[k], dists[k]) for k in order[:3])
    # From the three farthest samples, along the edges and the diagonals (a
    # crease of the distance can run diagonally: on MAT.brep one climb from
    # the farthest sample along s and t read 2.7% under the top).
    for k in order[:3]:
        a, b = params[k]
        best, step = dists[k], 0.05
        while step > 1e-4:
            moved = False
            for da, db in ((step, 0), (-step, 0), (0, step), (0, -step),
                           (step, step), (-step, -step), (step, -step), (-step, step)):
                if not valid(a + da, b + db):
                    continue
                d = _dense(face, [point(a + da, b + db)], deadline)
                if d is None:
                    return None
                if d > best:
                    best, a, b, moved = d, a + da, b + db, True
                    break
            if not moved:
                step *= 0.5
        worst = max(worst, checked(a, b, best))
    return worst


def dented_corner(uv):
    """The corner of a quad whose (u,v) outline turns the other way than the
    rest (the core's dented_quad), or None for a convex quad."""
    import numpy as np

    uv = np.asarray(uv, dtype=float)
    turn = []
    for i in range(4):
        a, b = uv[(i + 1) % 4] - uv[i], uv[(i + 2) % 4] - uv[(i + 1) % 4]
        turn.append(a[0] * b[1] - a[1] * b[0])
    tol = 1e-12 * max(abs(t) for t in turn)
    left = [i for i, t in enumerate(turn) if t > tol]
    right = [i for i, t in enumerate(turn) if t < -tol]
    if not left or not right:
        return None
    minority = left if len(left) < len(right) else right
    return (minority[0] + 1) % 4  # turn i is taken at corner i + 1


def remeasure(face, r, count, size):
    """(reported / re-measured) per sampled interior quad or triangle."""
    import random

    import numpy as np

    if count <= 0 or len(r.panels) == 0:
        return []
    dev = np.asarray(r.metrics["panel_deviation"])
    folds = {frozenset(map(int, f)) for f in np.asarray(r.folds).reshape(-1, 2)}
    # Trim-side corners: within 1% of the size of the boundary, measured
    # against the edges discretized to size/50 (segments, vectorized).
    segs = []
    for e in face.Edges:
        if getattr(e, "Degenerated", False) or e.Length <= 0:
            continue  # a pole or a seam point: no segment
        try:
            pts = np.array([tuple(q) for q in e.discretize(Distance=max(size / 50.0, 1e-9))])
        except Exception:  # OCC cannot discretize it: its end points only
            pts = np.array([tuple(v.Point) for v in e.Vertexes])
        if len(pts) >= 2:
            segs.append(np.stack([pts[:-1], pts[1:]], axis=1))
    segs = np.concatenate(segs) if segs else np.zeros((0, 2, 3))
    near = 0.01 * size

    def trim_side(corners):
        if len(segs) == 0:
            return False
        a, b = segs[:, 0], segs[:, 1]
        ab = b - a
        den = np.maximum((ab * ab).sum(axis=1), 1e-300)
        for c in corners:
            t = np.clip(((c - a) * ab).sum(axis=1) / den, 0.0, 1.0)
            d = np.linalg.norm(a + t[:, None] * ab - c, axis=1).min()
            if d < near:
                return True
        return False
    order = list(np.argsort(-dev, kind="stable"))
    rng = random.Random(1)
    pool = order[count:]
    rng.shuffle(pool)
    out = []
    # FreeCAD's projection rebuilds its search on every call: on a surface of
    # thousands of poles 441 projections take seconds. The re-measure stops
    # after REMEASURE_BUDGET seconds (the run reports how many it did).
    started = time.perf_counter()
    for k in (order[: max(1, count // 2)] + pool)[: 10 * count]:  # a bounded search
        if len(out) >= count or time.perf_counter() - started > REMEASURE_BUDGET:
            break
        p = r.vertices[list(r.panels[k])]
        corners = [int(i) for i in r.panels[k]]
        if len(p) not in (3, 4) or any(frozenset((a, b)) in folds for a in corners
                                       for b in corners if a < b):
            continue  # a bent panel: its model is its flat pieces
        if trim_side(p):
            continue  # a trim-side panel: its model follows the trim
        reflex = dented_corner(r.uv[list(r.panels[k])]) if len(p) == 4 else None
        if reflex is None:
            dense = _dense_panel(face, p, started + REMEASURE_BUDGET)
        else:
            # A dented quad is modelled as two flat triangles bent along the
            # diagonal from its dented corner (mesh/panel_model.h), not as
            # its bilinear patch (which reads up to 25% more on Ball.brep).
            i = reflex
            parts = [_dense_panel(face, p[[i, (i + 1) % 4, (i + 2) % 4]],
                                  started + REMEASURE_BUDGET),
                     _dense_panel(face, p[[i, (i + 2) % 4, (i + 3) % 4]],
                                  started + REMEASURE_BUDGET)]
            dense = None if None in parts else max(parts)
        if dense is None:
            break
        if dense > 1e-6:  # below the kernel's confusion (1e-7 mm) a ratio is noise
            out.append(float(dev[k]) / dense)
    return out


def run_one(job, shapes, remeasure_count):
    import freecad_workbench as tessella

    path, index, method, divisions = job
    if path not in shapes:
        shapes.clear()  # one file at a time in memory
        shapes[path] = load_shape(path)
    face = shapes[path].Faces[index]
    params = params_for(method, face, divisions)
    t0 = time.perf_counter()
    try:
        r = tessella.panelize(face, method=method, **params)
    except (ValueError, RuntimeError) as exc:
        return {"status": "error", "message": str(exc).splitlines()[0][:300],
                "seconds": time.perf_counter() - t0}
    seconds = time.perf_counter() - t0
    s = r.summary
    size = params.get("size", math.sqrt(face.Area) / divisions)
    ratios = remeasure(face, r, remeasure_count, size)
    return {"status": "ok", "seconds": seconds, "panels": int(s["panel_count"]),
            "gap": float(s.get("gap_fraction", 0.0)), "overlap": float(s.get("overlap_fraction", 0.0)),
            "unreliable": int(s.get("unreliable_deviation", 0)),
            "zero_area": int(s.get("zero_area_panels", 0)),
            "ratio_min": min(ratios) if ratios else None,
            "ratio_max": max(ratios) if ratios else None, "remeasured": len(ratios)}


def worker(remeasure_count):
    """Reads jobs (JSON lines) on stdin, answers one JSON line per job."""
    for p in (FREECAD_LIB, REPO):
        if p not in sys.path:
            sys.path.append(p)
    import FreeCAD  # noqa: F401  (before Part)

    shapes = {}
    for line in sys.stdin:
        job = json.loads(line)
        try:
            out = run_one(job, shapes, remeasure_count)
        except Exception as exc:  # a bug of ours (not a refusal): reported, not a crash
            out = {"status": "error", "message": f"{type(exc).__name__}: {exc}"[:300],
                   "seconds": 0.0, "internal": True}
        sys.stdout.write(json.dumps(out) + "\n")
        sys.stdout.flush()


# ---------------------------------------------------------------- parent
class Worker:
    def __init__(self, remeasure_count):
        env = dict(os.environ, PYTHONPATH=f"{FREECAD_LIB}:{REPO}")
        self.proc = subprocess.Popen([sys.executable, os.path.abspath(__file__), "--worker",
                                      "--remeasure", str(remeasure_count)],
                                     stdin=subprocess.PIPE, stdout=subprocess.PIPE,
                                     stderr=subprocess.DEVNULL, text=True, env=env, bufsize=1)

    def run(self, job, timeout):
        """The job's result dict, or {"status": "crash"|"timeout"} (the worker is then dead)."""
        try:
            self.proc.stdin.write(json.dumps(job) + "\n")
            self.proc.stdin.flush()
        except (BrokenPipeError, OSError):
            return {"status": "crash"}
        ready, _, _ = select.select([self.proc.stdout], [], [], timeout)
        if not ready:
            self.kill()
            return {"status": "timeout", "seconds": timeout}
        line = self.proc.stdout.readline()
        if not line:
            self.kill()
            return {"status": "crash", "code": self.proc.returncode}
        return json.loads(line)

    def kill(self):
        try:
            self.proc.kill()
            self.proc.wait(5)
        except Exception:
            pass

    def alive(self):
        return self.proc.poll() is None


def list_jobs(files, methods, divisions, max_faces):
    """[(path, face index, method, divisions)] and {path: faces taken}."""
    for p in (FREECAD_LIB, REPO):
        if p not in sys.path:
            sys.path.append(p)
    import FreeCAD  # noqa: F401

    jobs, taken = [], {}
    for path in files:
        try:
            faces = sweep_faces(load_shape(path))
        except Exception as exc:
            print(f"skipped {path}: {exc}", file=sys.stderr)
            continue
        if max_faces:
            faces = sorted(faces, key=lambda kf: -kf[1].Area)[:max_faces]
            faces.sort(key=lambda kf: kf[0])
        taken[path] = len(faces)
        for k, _f in faces:
            for d in divisions:
                for m in methods:
                    jobs.append((path, k, m, d))
    return jobs, taken


def table(rows, methods):
    grid_ok = {(r["file"], r["face"], r["divisions"]) for r in rows
               if r["method"] in ("iso_grid", "equal_size_grid") and r["status"] == "ok"}
    print("| method | runs | ok | error (a bug of ours) | crash | timeout | ok where grids ok | median panels "
          "| worst gap % | worst overlap % | reported / dense min | max | unreliable | median s |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    for m in methods:
        mine = [r for r in rows if r["method"] == m]
        if not mine:
            continue
        count = {k: sum(1 for r in mine if r["status"] == k)
                 for k in ("ok", "error", "crash", "timeout")}
        count["error"] = "%d (%d ours)" % (count["error"], sum(1 for r in mine if r.get("internal")))
        ok = [r for r in mine if r["status"] == "ok"]
        on_grid = [r for r in mine if (r["file"], r["face"], r["divisions"]) in grid_ok]
        share = (sum(1 for r in on_grid if r["status"] == "ok") / len(on_grid)) if on_grid else 0.0
        lo = [r["ratio_min"] for r in ok if r.get("ratio_min") is not None]
        hi = [r["ratio_max"] for r in ok if r.get("ratio_max") is not None]
        print(f"| {m} | {len(mine)} | {count['ok']} | {count['error']} | {count['crash']} | "
              f"{count['timeout']} | {100 * share:.1f}% | "
              f"{statistics.median([r['panels'] for r in ok]) if ok else 0:.0f} | "
              f"{100 * max((r['gap'] for r in ok), default=0):.3f} | "
              f"{100 * max((r['overlap'] for r in ok), default=0):.3f} | "
              f"{min(lo) if lo else float('nan'):.4f} | {max(hi) if hi else float('nan'):.4f} | "
              f"{sum(r['unreliable'] for r in ok)} | "
              f"{statistics.median([r['seconds'] for r in ok]) if ok else 0:.3f} |")


def run_jobs(jobs, folder, lanes_count=1, timeout=60.0, remeasure_count=12):
    """Run the jobs in `lanes_count` worker lanes; one result dict per job, in order."""
    t0 = time.perf_counter()
    results = [None] * len(jobs)
    done = [0]
    lock = threading.Lock()

    def lane(first):
        # Worker `first` takes every --jobs-th run: files stay grouped per lane.
        w = None
        for n in range(first, len(jobs), lanes_count):
            if w is None or not w.alive():
                w = Worker(remeasure_count)
            path, k, m, d = jobs[n]
            out = w.run(list(jobs[n]), timeout)
            results[n] = dict(out, file=os.path.relpath(path, folder), face=k, method=m,
                              divisions=d)
            with lock:
                done[0] += 1
                if out["status"] in ("crash", "timeout"):
                    print(f"  {out['status']}: {os.path.basename(path)} Face{k + 1} {m} /{d:g}",
                          flush=True)
                if done[0] % 200 == 0:
                    print(f"  {done[0]}/{len(jobs)} runs, {time.perf_counter() - t0:.0f} s",
                          flush=True)
        if w is not None:
            w.kill()

    lanes = [threading.Thread(target=lane, args=(j,)) for j in range(max(1, lanes_count))]
    for t in lanes:
        t.start()
    for t in lanes:
        t.join()
    return results


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("folder", nargs="?")
    ap.add_argument("--methods", nargs="*", default=list(DEFAULT_METHODS))
    ap.add_argument("--divisions", nargs="*", type=float, default=[6.0, 12.0, 24.0])
    ap.add_argument("--timeout", type=float, default=60.0, help="seconds per run")
    ap.add_argument("--max-faces", type=int, default=0, help="largest N faces per file (0: all)")
    ap.add_argument("--remeasure", type=int, default=12, help="panels re-measured per ok run")
    ap.add_argument("--jobs", type=int, default=1, help="runs in parallel (worker processes)")
    ap.add_argument("--csv", help="write every run here")
    ap.add_argument("--errors", action="store_true", help="list every refusal message")
    ap.add_argument("--worker", action="store_true", help=argparse.SUPPRESS)
    args = ap.parse_args(argv)
    if args.worker:
        worker(args.remeasure)
        return 0
    if not args.folder:
        ap.error("give the folder of CAD files (bench/fetch_corpus.py makes one)")
    files = cad_files(args.folder)
    jobs, taken = list_jobs(files, args.methods, args.divisions, args.max_faces)
    print(f"{len(files)} files, {sum(taken.values())} faces, {len(jobs)} runs "
          f"(methods {', '.join(args.methods)}; divisions {args.divisions})", flush=True)
    t0 = time.perf_counter()
    rows = run_jobs(jobs, args.folder, args.jobs, args.timeout, args.remeasure)
    print(f"\n{len(rows)} runs in {time.perf_counter() - t0:.0f} s\n")
    table(rows, args.methods)
    if args.errors:
        for r in rows:
            if r["status"] != "ok":
                print(f"{r['file']} Face{r['face'] + 1} {r['method']} /{r['divisions']:g}: "
                      f"{r['status']} {r.get('message', '')}")
    if args.csv:
        keys = sorted({k for r in rows for k in r})
        with open(args.csv, "w", newline="", encoding="utf-8") as f:
            wr = csv.DictWriter(f, fieldnames=keys)
            wr.writeheader()
            wr.writerows(rows)
    return 0


if __name__ == "__main__":
    sys.exit(main())
