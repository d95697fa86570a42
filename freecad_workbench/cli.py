"""Batch panelization from the command line: many files in, for each a document,
schedules and DXF out.

    PYTHONPATH=/usr/lib/freecad-python3/lib:$PWD /usr/bin/python3 -m freecad_workbench.cli \\
        roof.step facade.iges variant_*.brep --out out/batch --method iso_grid --size 1500

Each input (STEP, IGES, BRep, or an FCStd document: its final shapes, those no
other object uses) is panelized as one envelope: all its faces, joined along
their shared edges (one face: the single-face pipeline). For each input
`<out>/<name>/` receives `<name>.FCStd` (the source shape and a parametric
Panelization), `panels.csv`, `rods.csv`, `nodes.csv` and `panels.dxf` (the
unfolded panels). The folder is written under a temporary name and renamed
when complete, so a failed or interrupted run never leaves a half-written one
(an existing folder of that name is replaced only on success).

Progress goes to stderr, one line per input and stage, with the warnings a
Panelization gives in the Report view (faces left out or meshed finer, a
coverage warning); the exit status is 0
when every input succeeded, 1 when any failed (the others still run), 2 for
bad arguments.
"""

import argparse
import os
import shutil
import sys
import tempfile
import time


def _parse_params(pairs):
    """--param name=value pairs as numbers where they read as numbers."""
    params = {}
    for pair in pairs or []:
        if "=" not in pair:
            raise ValueError(f"--param takes name=value, got {pair!r}")
        name, value = pair.split("=", 1)
        try:
            number = float(value)
            value = int(number) if number.is_integer() and "." not in value else number
        except ValueError:
            if value.lower() in ("true", "false"):
                value = value.lower() == "true"
        params[name.strip()] = value
    return params


def _has_faces(obj):
    shape = getattr(obj, "Shape", None)
    return shape is not None and not shape.isNull() and bool(shape.Faces)


def top_level_shapes(doc):
    """The shapes of a document's objects with faces that no other shape is
    built from: a Cut, not the boxes it cuts. An object that only refers to
    one without a shape of its own (a group, a FEM analysis or constraint)
    does not hide it."""
    return [o.Shape for o in doc.Objects
            if _has_faces(o) and not o.TypeId.startswith("App::FeaturePython")
            and not any(_has_faces(user) for user in o.InList)]


def load_shape(path):
    """The shape to panelize from a STEP/IGES/BRep file or an FCStd document."""
    import FreeCAD
    import Part

    ext = os.path.splitext(path)[1].lower()
    if ext in (".step", ".stp", ".iges", ".igs", ".brep", ".brp"):
        shape = Part.read(path)
    elif ext == ".fcstd":
        doc = FreeCAD.openDocument(path, True)  # hidden
        try:
            shapes = top_level_shapes(doc)
        finally:
            FreeCAD.closeDocument(doc.Name)
        if not shapes:
            raise ValueError("the document has no object with faces")
        shape = shapes[0] if len(shapes) == 1 else Part.Compound(shapes)
    else:
        raise ValueError(f"unknown file type {ext!r} (STEP, IGES, BRep or FCStd)")
    if shape.isNull() or not shape.Faces:
        raise ValueError("the file holds no faces")
    return shape


def run_one(path, out_dir, method, params, log):
    """Panelize one file into out_dir/<name>/ (complete or not at all)."""
    import FreeCAD

    import freecad_workbench as tessella
    from freecad_workbench.export import schedule_csv
    from freecad_workbench.features.panelization import result_warnings

    name = os.path.splitext(os.path.basename(path))[0]
    final = os.path.join(out_dir, name)
    started = time.perf_counter()
    log(f"{name}: reading {path}")
    shape = load_shape(path)
    log(f"{name}: {len(shape.Faces)} face(s), panelizing ({method})")
    work = tempfile.mkdtemp(prefix=f".{name}.", dir=out_dir)
    doc = None
    try:
        doc = FreeCAD.newDocument(f"Batch_{name}".replace("-", "_").replace(" ", "_"))
        source = doc.addObject("Part::Feature", "Source")
        source.Shape = shape
        doc.recompute()
        p = tessella.make_panelization(source if len(shape.Faces) > 1 else (source, "Face1"),
                                       method=method, **params)
        res = p.Proxy.result(p).result
        # The Report view's warnings, which a headless run does not show.
        for warning in result_warnings(res.summary):
            log(f"{name}: warning: {warning}")
        log(f"{name}: {len(res.panels)} panels, {len(res.rods)} rods, {len(res.nodes)} nodes; "
            "writing schedules and DXF")
        schedule_csv.write_panel_schedule(res, os.path.join(work, "panels.csv"))
        schedule_csv.write_rod_schedule(res, os.path.join(work, "rods.csv"))
        schedule_csv.write_node_schedule(res, os.path.join(work, "nodes.csv"))
        flat = tessella.unfold(res)
        tessella.export_dxf(flat, os.path.join(work, "panels.dxf"))
        doc.saveAs(os.path.join(work, f"{name}.FCStd"))
        FreeCAD.closeDocument(doc.Name)
        doc = None
        if os.path.isdir(final):
            shutil.rmtree(final)
        os.chmod(work, 0o755)  # mkdtemp's 0700 is for while it is incomplete
        os.replace(work, final)
        log(f"{name}: done in {time.perf_counter() - started:.1f} s -> {final}")
        return len(res.panels)
    finally:
        if doc is not None:
            FreeCAD.closeDocument(doc.Name)
        if os.path.isdir(work):
            shutil.rmtree(work, ignore_errors=True)


def main(argv=None):
    ap = argparse.ArgumentParser(prog="python3 -m freecad_workbench.cli",
                                 description=__doc__.split("\n\n")[0])
    ap.add_argument("inputs", nargs="+", help="STEP, IGES, BRep or FCStd files")
    ap.add_argument("--out", required=True, help="output folder (one subfolder per input)")
    ap.add_argument("--method", default="iso_grid")
    ap.add_argument("--size", type=float, help="panel size (mm), for the methods that take one")
    ap.add_argument("--param", action="append", metavar="NAME=VALUE",
                    help="any other method parameter (repeatable), e.g. --param max_deviation=20")
    try:
        args = ap.parse_args(argv)
        params = _parse_params(args.param)
    except SystemExit as exc:
        return 2 if exc.code else 0
    except ValueError as exc:
        print(f"error: {exc}", file=sys.stderr)
        return 2
    if args.size is not None:
        params["size"] = args.size
    os.makedirs(args.out, exist_ok=True)

    import FreeCAD  # noqa: F401  (before Part, always)

    def log(text):
        print(text, file=sys.stderr, flush=True)

    failed = []
    for k, path in enumerate(args.inputs, 1):
        log(f"[{k}/{len(args.inputs)}] {path}")
        try:
            run_one(path, args.out, args.method, params, log)
        except Exception as exc:  # noqa: BLE001  (report, go on with the next file)
            failed.append(path)
            log(f"FAILED {path}: {exc}")
    log(f"{len(args.inputs) - len(failed)} of {len(args.inputs)} input(s) done"
        + (f"; failed: {', '.join(failed)}" if failed else ""))
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
