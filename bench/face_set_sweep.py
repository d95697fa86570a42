"""Face sets on real shapes: every CAD file of a folder panelized as one set
(tessella.panelize_faces) on one thread and on two, the two compared.

    PYTHONPATH=/usr/lib/freecad-python3/lib:$PWD /usr/bin/python3 bench/face_set_sweep.py corpus/ \
        [--methods iso_grid boundary_driven walking_agent] [--max-faces 150] [--timeout 300] \
        [--jsonl out.jsonl]

(bench/fetch_corpus.py gathers a public corpus.) Files: STEP / IGES / BRep /
FCStd (the top-level objects' shapes). A file with 2 to --max-faces faces is
taken whole (planar faces too), at size sqrt(total area / 1500) (walking_agent:
that as its largest panel, and 0.002 x the shape's diagonal as its bound).

Each file runs in a process of its own (a crash or a hang is counted against
it, and the sweep goes on). Outcomes per file and method:
- identical: both runs give the same vertices, panels, rods, metrics and
  coverage figures, bit for bit;
- same error: both refuse, with the same message (a refused face is named,
  the same one on any thread count);
- DIFFERENT / error mismatch: the thread count changed the result or the
  message (a defect);
- crash / timeout.
Prints a line per mismatch and the counts. For every result also the
invariants the face-set tests assert on built shapes: pairs of nodes within
1e-6 of the shape's diagonal (one position taken twice) and panels with a
corner twice; files with any are listed.
"""

import argparse
import json
import math
import os
import subprocess
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
EXTENSIONS = (".step", ".stp", ".iges", ".igs", ".brep", ".brp", ".fcstd")


def load(path):
    import FreeCAD
    import Part

    if path.lower().endswith(".fcstd"):
        from freecad_workbench.cli import top_level_shapes

        doc = FreeCAD.openDocument(path)
        shapes = top_level_shapes(doc)
        return Part.Compound(shapes) if shapes else None
    shape = Part.Shape()
    shape.read(path)
    return shape


def first_difference(a, b):
    """The first part in which two results differ (vertices, panels, rods, a
    metric, a coverage figure), or None where they are the same bit for bit."""
    import numpy as np

    if not np.array_equal(a.vertices, b.vertices):
        return "vertices"
    if a.panels != b.panels:
        return "panels"
    if not np.array_equal(a.rods, b.rods):
        return "rods"
    for k in a.metrics:
        if not np.array_equal(a.metrics[k], b.metrics[k], equal_nan=True):
            return f"metrics.{k}"
    for k in ("gap_fraction", "overlap_fraction", "model_area_ratio"):
        if a.summary[k] != b.summary[k]:
            return f"summary.{k}"
    return None


def worker(path, methods, max_faces):
    """One file, in this process: a JSON line per method (or one for the file)."""
    import FreeCAD  # noqa: F401  (before Part)

    import freecad_workbench as tessella

    # The face-set tests' own check of one position taken twice.
    sys.path.insert(0, os.path.join(ROOT, "tests", "python"))
    from conftest import close_node_pairs

    try:
        shape = load(path)
    except Exception as e:  # noqa: BLE001  (any reader failure: the file is unreadable)
        print(json.dumps({"file": path, "outcome": "unreadable", "message": str(e)[:200]}))
        return
    faces = 0 if shape is None else len(shape.Faces)
    if not 2 <= faces <= max_faces:
        print(json.dumps({"file": path, "outcome": "skipped", "faces": faces}))
        return
    size = math.sqrt(sum(f.Area for f in shape.Faces) / 1500)
    for method in methods:
        kw = ({"max_size": size, "max_deviation": 0.002 * shape.BoundBox.DiagonalLength}
              if method == "walking_agent" else {"size": size})
        runs = []
        for threads in (1, 2):
            start = time.perf_counter()
            try:
                runs.append(tessella.panelize_faces(shape, method=method, threads=threads, **kw))
            except (ValueError, RuntimeError) as e:
                runs.append(f"{type(e).__name__}: {e}")
            runs.append(time.perf_counter() - start)
        a, _, b, _ = runs
        out = {"file": path, "method": method, "faces": faces,
               "seconds": [round(runs[1], 3), round(runs[3], 3)]}
        if isinstance(a, str) or isinstance(b, str):
            out["outcome"] = "same error" if a == b else "error mismatch"
            out["message"] = [x if isinstance(x, str) else "ok" for x in (a, b)]
        else:
            differs = first_difference(a, b)
            out["outcome"] = "identical" if differs is None else "DIFFERENT"
            if differs:
                out["differs"] = differs
            out["panels"] = len(a.panels)
            out["duplicate_nodes"] = len(
                close_node_pairs(a.vertices[a.nodes], 1e-6 * shape.BoundBox.DiagonalLength))
            out["repeated_corners"] = sum(len(set(map(int, p))) < len(p) for p in a.panels)
        print(json.dumps(out), flush=True)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("folder")
    ap.add_argument("--methods", nargs="+", default=["iso_grid", "boundary_driven", "walking_agent"])
    ap.add_argument("--max-faces", type=int, default=150)
    ap.add_argument("--timeout", type=float, default=300)
    ap.add_argument("--jsonl", help="write every outcome here")
    ap.add_argument("--worker", action="store_true", help=argparse.SUPPRESS)
    args = ap.parse_args(argv)
    if args.worker:
        worker(args.folder, args.methods, args.max_faces)
        return 0
    files = sorted(os.path.join(d, f) for d, _, fs in os.walk(args.folder) for f in fs
                   if f.lower().endswith(EXTENSIONS))
    env = dict(os.environ, PYTHONPATH=os.pathsep.join(
        p for p in ("/usr/lib/freecad-python3/lib", ROOT, os.environ.get("PYTHONPATH")) if p))
    results = []
    for path in files:
        cmd = [sys.executable, os.path.abspath(__file__), path, "--worker", "--max-faces",
               str(args.max_faces), "--methods", *args.methods]
        try:
            done = subprocess.run(cmd, capture_output=True, text=True, timeout=args.timeout, env=env)
            lines = [json.loads(x) for x in done.stdout.splitlines() if x.startswith("{")]
            if done.returncode != 0:
                lines.append({"file": path, "outcome": f"crash (exit {done.returncode})"})
        except subprocess.TimeoutExpired:
            lines = [{"file": path, "outcome": "timeout"}]
        for line in lines:
            results.append(line)
            if line["outcome"] not in ("identical", "same error", "skipped"):
                print(f"{os.path.relpath(line['file'], args.folder)} {line.get('method', '')}: "
                      f"{line['outcome']} {line.get('differs', '')}{line.get('message', '')}",
                      flush=True)
    if args.jsonl:
        with open(args.jsonl, "w") as out:
            for line in results:
                out.write(json.dumps(line) + "\n")
    counts = {}
    for line in results:
        counts[line["outcome"]] = counts.get(line["outcome"], 0) + 1
    print(f"{len(files)} files: " + ", ".join(f"{n} {k}" for k, n in sorted(counts.items())))
    flawed = [x for x in results if x.get("duplicate_nodes") or x.get("repeated_corners")]
    for x in flawed:
        print(f"  {os.path.relpath(x['file'], args.folder)} {x['method']}: "
              f"{x['duplicate_nodes']} node pair(s) within 1e-6 of the size, "
              f"{x['repeated_corners']} panel(s) with a corner twice")
    print(f"{len(flawed)} result(s) with nodes at one position or a corner twice")
    bad = sum(n for k, n in counts.items() if k not in ("identical", "same error", "skipped",
                                                          "unreadable"))
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
