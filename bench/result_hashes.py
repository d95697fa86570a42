"""Fingerprints of every method on every bundled example: one line per case.

Captures the exact results of `tessella.panelize` (public console API only) so a
restructuring can be shown to change nothing:

    PYTHONPATH=/usr/lib/freecad-python3/lib:$PWD /usr/bin/python3 bench/result_hashes.py \
        --out bench/result_hashes_before.txt
    PYTHONPATH=/usr/lib/freecad-python3/lib:$PWD /usr/bin/python3 bench/result_hashes.py \
        --compare bench/result_hashes_before.txt      # exit 1 if any line differs

The package is imported from PYTHONPATH as it stands (this script does not add
the repository to sys.path), so the same script can fingerprint a frozen copy.

One line per (example, method):

    <example> <method> panels=<n> rods=<n> nodes=<n> sha=<sha256>
    <example> <method> error: <first line of the ValueError/RuntimeError message>
    <example> <method> skipped: slow            (the SKIP set below; fixed, not timed)

The sha256 is over, in this order: r.vertices, r.uv, the panels flattened with
their lengths ([len, i0, i1, ...] per panel), r.rods, r.nodes, r.folds,
r.irregular, then every array of r.metrics in sorted key order. Each array
enters as a C-contiguous float64 (floating) or int64 (integer / bool) copy,
preceded by a small header (its name, dtype and shape) so arrays cannot
shift into one another. Timings (summary["core_seconds"]) are not hashed.

Parameters are fixed functions of each face (no randomness):
- grid-like methods (iso_grid, equal_size_grid, boundary_driven, chebyshev_net):
  size = sqrt(area)/12
- guide-line methods: rod_length = sqrt(area)/12; guides are iso-curves of the
  face's surface through the middle of its (u, v) parameter range, trimmed to
  that range: the u-iso (a curve along v) for guide_line_scaling, the u-iso and
  the v-iso (crossing) for two_guide_lines and guide_line_diamond
- walking_agent, gradient_descent: max_deviation = 0.002 * the face's bounding
  box diagonal
- relaxed_grid: u_count = v_count = 8
"""

import argparse
import glob
import hashlib
import math
import os
import sys
import time

import FreeCAD  # noqa: F401  (first, always: Part segfaults otherwise)
import Part  # noqa: E402
import numpy as np  # noqa: E402

import freecad_workbench as tessella  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
EXAMPLES = os.path.join(os.path.dirname(HERE), "examples")

#: Fixed so the list of cases does not depend on where the package declares them.
METHOD_NAMES = (
    "iso_grid",
    "equal_size_grid",
    "boundary_driven",
    "guide_line_scaling",
    "guide_line_diamond",
    "two_guide_lines",
    "walking_agent",
    "gradient_descent",
    "relaxed_grid",
    "chebyshev_net",  # stop 55: 11 cases more (110)
)

#: (example, method) pairs not run (recorded as "skipped: slow"). Fixed here, never
#: decided by a clock, so the output stays deterministic.
SKIP = frozenset()

DIVISIONS = 12.0
DEVIATION_FRACTION = 0.002
RELAXED_COUNT = 8


def example_faces(directory=EXAMPLES):
    """[(name, face)] for every face of every examples/*.brep, sorted by file name.
    A file with several faces gives name#1, name#2, ..."""
    out = []
    for path in sorted(glob.glob(os.path.join(directory, "*.brep"))):
        shape = Part.Shape()
        shape.read(path)
        stem = os.path.splitext(os.path.basename(path))[0]
        faces = shape.Faces
        if len(faces) == 1:
            out.append((stem, faces[0]))
        else:
            out.extend((f"{stem}#{k + 1}", f) for k, f in enumerate(faces))
    return out


def iso_guides(face):
    """(u-iso edge, v-iso edge) through the middle of the face's parameter range."""
    u0, u1, v0, v1 = face.ParameterRange
    um, vm = 0.5 * (u0 + u1), 0.5 * (v0 + v1)
    surf = face.Surface
    along_v = Part.Edge(surf.uIso(um), v0, v1)  # u fixed: runs along v
    along_u = Part.Edge(surf.vIso(vm), u0, u1)  # v fixed: runs along u
    return along_v, along_u


def case_params(method, face):
    area = face.Area
    step = math.sqrt(area) / DIVISIONS
    if method in ("iso_grid", "equal_size_grid", "boundary_driven", "chebyshev_net"):
        return {"size": step}
    if method == "guide_line_scaling":
        return {"rod_length": step, "guides": [iso_guides(face)[0]]}
    if method in ("two_guide_lines", "guide_line_diamond"):
        return {"rod_length": step, "guides": list(iso_guides(face))}
    if method in ("walking_agent", "gradient_descent"):
        return {"max_deviation": DEVIATION_FRACTION * face.BoundBox.DiagonalLength}
    if method == "relaxed_grid":
        return {"u_count": RELAXED_COUNT, "v_count": RELAXED_COUNT}
    raise KeyError(method)


def _feed(h, name, arr):
    a = np.asarray(arr)
    if a.dtype.kind == "f":
        a = np.ascontiguousarray(a, dtype=np.float64)
    elif a.dtype.kind in "iub":
        a = np.ascontiguousarray(a, dtype=np.int64)
    else:
        raise TypeError(f"{name}: unexpected dtype {a.dtype}")
    h.update(f"{name}:{a.dtype.str}:{a.shape};".encode())
    h.update(a.tobytes())


def result_sha(r):
    h = hashlib.sha256()
    _feed(h, "vertices", np.asarray(r.vertices, dtype=np.float64))
    _feed(h, "uv", np.asarray(r.uv, dtype=np.float64))
    flat = []
    for p in r.panels:
        flat.append(len(p))
        flat.extend(int(i) for i in p)
    _feed(h, "panels", np.asarray(flat, dtype=np.int64))
    _feed(h, "rods", np.asarray(r.rods, dtype=np.int64))
    _feed(h, "nodes", np.asarray(r.nodes, dtype=np.int64))
    _feed(h, "folds", np.asarray(r.folds, dtype=np.int64))
    _feed(h, "irregular", np.asarray(r.irregular, dtype=np.int64))
    for key in sorted(r.metrics):
        m = np.asarray(r.metrics[key])
        if m.dtype.kind not in "f":
            m = m.astype(np.int64)
        _feed(h, "metrics." + key, m)
    return h.hexdigest()


def result_arrays(r):
    """Every hashed array by name (for --dump / --compare-dump)."""
    out = {
        "vertices": np.asarray(r.vertices, dtype=np.float64),
        "uv": np.asarray(r.uv, dtype=np.float64),
        "panels": np.asarray([x for p in r.panels for x in (len(p), *p)], dtype=np.int64),
        "rods": np.asarray(r.rods, dtype=np.int64),
        "nodes": np.asarray(r.nodes, dtype=np.int64),
        "folds": np.asarray(r.folds, dtype=np.int64),
        "irregular": np.asarray(r.irregular, dtype=np.int64),
    }
    for key in sorted(r.metrics):
        out["metrics." + key] = np.asarray(r.metrics[key])
    return out


def run_case(method, face, dump=None):
    try:
        params = case_params(method, face)
        r = tessella.panelize(face, method=method, **params)
    except (ValueError, RuntimeError) as exc:
        msg = (str(exc).strip().splitlines() or [""])[0]
        return f"error: {msg}"
    if dump is not None:
        dump(result_arrays(r))
    return (f"panels={len(r.panels)} rods={len(r.rods)} nodes={len(r.nodes)} "
            f"sha={result_sha(r)}")


def run_all(verbose=True, echo=True, dump_dir=None):
    methods = getattr(tessella, "METHODS", None)
    if methods is not None:
        extra = sorted(set(methods) - set(METHOD_NAMES))
        missing = sorted(set(METHOD_NAMES) - set(methods))
        if extra or missing:
            print(f"note: tessella.METHODS extra {extra}, missing {missing}", file=sys.stderr)
    lines = []
    started = time.perf_counter()
    for name, face in example_faces():
        for method in METHOD_NAMES:
            t0 = time.perf_counter()
            if (name, method) in SKIP:
                outcome = "skipped: slow"
            else:
                dump = None
                if dump_dir:
                    path = os.path.join(dump_dir, f"{name}__{method}.npz")
                    dump = lambda arrays, path=path: np.savez(path, **arrays)  # noqa: E731
                outcome = run_case(method, face, dump)
            line = f"{name} {method} {outcome}"
            lines.append(line)
            if echo:
                print(line, flush=True)
            if verbose:
                print(f"  [{time.perf_counter() - t0:.2f} s]", file=sys.stderr, flush=True)
    print(f"{len(lines)} cases in {time.perf_counter() - started:.1f} s", file=sys.stderr)
    return lines


def _key(line):
    parts = line.split(" ", 2)
    return (parts[0], parts[1]), (parts[2] if len(parts) > 2 else "")


def compare(lines, path):
    with open(path, encoding="utf-8") as f:
        before = dict(_key(l.rstrip("\n")) for l in f if l.strip())
    now = dict(_key(l) for l in lines)
    differs = 0
    for key in list(before) + [k for k in now if k not in before]:
        label = f"{key[0]} {key[1]}"
        if key not in now:
            print(f"{label}: missing now (was: {before[key]})")
            differs += 1
        elif key not in before:
            print(f"{label}: new (now: {now[key]})")
            differs += 1
        elif before[key] == now[key]:
            print(f"{label}: identical")
        else:
            print(f"{label}: different\n    before: {before[key]}\n    now:    {now[key]}")
            differs += 1
    print(f"{len(before)} before, {len(now)} now: {differs} differ")
    return differs


def compare_dumps(before_dir, after_dir, rtol):
    """Arrays of two --dump runs: integer arrays equal, float arrays bit for bit or
    within rtol relative (of the array's largest magnitude). Returns the count of
    cases that differ beyond rtol; prints the largest relative difference."""
    differs = 0
    worst_all = 0.0
    for path in sorted(glob.glob(os.path.join(before_dir, "*.npz"))):
        name = os.path.basename(path)
        other = os.path.join(after_dir, name)
        if not os.path.exists(other):
            print(f"{name}: missing now")
            differs += 1
            continue
        a, b = np.load(path), np.load(other)
        bad, worst, exact = [], 0.0, True
        for key in a.files:
            x, y = a[key], b[key] if key in b.files else None
            if y is None or x.shape != y.shape:
                bad.append(f"{key} shape")
                continue
            if x.dtype.kind != "f":
                if not np.array_equal(x, y):
                    bad.append(key)
                continue
            same = np.array_equal(x, y, equal_nan=True)
            exact = exact and same
            if same:
                continue
            fin = np.isfinite(x)
            if not np.array_equal(fin, np.isfinite(y)):
                bad.append(f"{key} nan")
                continue
            scale = max(np.abs(x[fin]).max(initial=0.0), 1e-300)
            rel = float(np.abs(x[fin] - y[fin]).max(initial=0.0) / scale)
            worst = max(worst, rel)
            if rel > rtol:
                bad.append(f"{key} rel {rel:.2e}")
        worst_all = max(worst_all, worst)
        state = "bit-identical" if exact and not bad else (f"max rel {worst:.2e}" if not bad else "DIFFERS: " + ", ".join(bad))
        print(f"{name}: {state}")
        differs += 1 if bad else 0
    print(f"largest relative difference {worst_all:.3e}; {differs} cases beyond {rtol:g}")
    return differs


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--out", help="also write the lines to this file")
    ap.add_argument("--compare", help="compare with the lines of this file; exit 1 if any differs")
    ap.add_argument("--quiet", action="store_true", help="no per-case timings on stderr")
    # With --compare, stdout holds only the per-line report (identical / different).
    ap.add_argument("--dump", help="also save every case's arrays to DIR/<example>__<method>.npz")
    ap.add_argument("--compare-dump", nargs=2, metavar=("BEFORE", "AFTER"),
                    help="only compare two --dump folders (exit 1 beyond --rtol)")
    ap.add_argument("--rtol", type=float, default=1e-9)
    args = ap.parse_args(argv)
    if args.compare_dump:
        return 1 if compare_dumps(*args.compare_dump, args.rtol) else 0
    if args.dump:
        os.makedirs(args.dump, exist_ok=True)
    lines = run_all(verbose=not args.quiet, echo=not args.compare, dump_dir=args.dump)
    if args.out:
        with open(args.out, "w", encoding="utf-8") as f:
            f.write("\n".join(lines) + "\n")
    if args.compare:
        return 1 if compare(lines, args.compare) else 0
    return 0


if __name__ == "__main__":
    sys.exit(main())
