"""Document speed (issue 13): a Panelization in a FreeCAD document at about
2k, 5k, 10k and 20k panels, before (main's document code) and after.

    PYTHONPATH=/usr/lib/freecad-python3/lib:$PWD /usr/bin/python3 bench/document_speed.py
    ... document_speed.py --panels 2000 5000 --modes after     # a subset

Per size and mode it prints (seconds): panelize (api.panelize alone),
make (make_panelization: parent + Panels/Rods/Nodes with shapes, IDs and
types, recomputed), param (recompute after a Size change), touch (recompute
after a bare touch of the parent), save, reopen, and types (panel typing of
the result as the document runs it: before, unfold + members.panel_types in
Python; after, the core's grouping).

"before" runs main's document code - features/panelization.py, the Python
typing of members.py and api.format_ids - loaded from git (`git show
main:<file>`) over the current package, for comparison only; the compiled core
(panelize, the shape compounds) is today's in both modes. Every mode runs in
its own interpreter. The sample face is
examples/trimmed_bspline_holes.brep, iso_grid, size = sqrt(area / panels).
"""
import argparse
import json
import math
import os
import subprocess
import sys
import tempfile
import time
import types

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
EXAMPLE = os.path.join(ROOT, "examples", "trimmed_bspline_holes.brep")
OLD_REF = "main"  # where "before" comes from


def _git_show(path):
    return subprocess.run(["git", "-C", ROOT, "show", f"{OLD_REF}:{path}"], check=True,
                          capture_output=True, text=True).stdout


def _load_old(path, name, package):
    """Main's version of a package module, executed beside the current one."""
    mod = types.ModuleType(name)
    mod.__package__ = package
    mod.__file__ = os.path.join(ROOT, path)
    sys.modules[name] = mod
    exec(compile(_git_show(path), f"{OLD_REF}:{path}", "exec"), mod.__dict__)
    return mod


def _timed(fn):
    t0 = time.perf_counter()
    out = fn()
    return time.perf_counter() - t0, out


def run(mode, target):
    import FreeCAD
    import Part

    if mode == "before":
        # Main's class bodies, fetched before today's are patched over.
        import freecad_workbench.features.panelization as feat

        old_feat = _load_old("freecad_workbench/features/panelization.py",
                             "freecad_workbench.features._panelization_before",
                             "freecad_workbench.features")
        old_members = _load_old("freecad_workbench/members.py",
                                "freecad_workbench._members_before", "freecad_workbench")
        old_api = _load_old("freecad_workbench/api.py", "freecad_workbench._api_before",
                            "freecad_workbench")
        import freecad_workbench.api as api
        import freecad_workbench.members as members

        members.panel_types = old_members.panel_types
        api.format_ids = old_api.format_ids
        for cls_name in ("Panelization", "PanelizationPart"):
            old_cls, cls = getattr(old_feat, cls_name), getattr(feat, cls_name)
            for name, value in vars(old_cls).items():
                if callable(value) or isinstance(value, (staticmethod, classmethod)):
                    setattr(cls, name, value)
        old_feat.Panelization, old_feat.PanelizationPart = feat.Panelization, feat.PanelizationPart

    import freecad_workbench as tessella
    from freecad_workbench import core
    from freecad_workbench.fabrication import unfold
    from freecad_workbench.features.panelization import children_of

    face = Part.read(EXAMPLE).Faces[0]
    size = math.sqrt(face.Area / target)
    out = {"mode": mode, "target": target}
    out["panelize"], r = _timed(lambda: tessella.panelize(face, method="iso_grid", size=size))
    out["panels"] = len(r.panels)
    if mode == "before":
        import freecad_workbench.members as members

        out["types"], _ = _timed(lambda: members.panel_types(unfold(r), length_tol=1.0))
    else:
        def core_types():
            p = core.PanelTypeParams()
            p.length_tol = 1.0
            return core.mesh_panel_types(r._mesh, core.UnfoldParams(), p)

        out["types"], _ = _timed(core_types)

    doc = FreeCAD.newDocument("DocSpeed")
    src = doc.addObject("Part::Feature", "Surface")
    src.Shape = face
    doc.recompute()
    out["make"], p = _timed(lambda: tessella.make_panelization((src, "Face1"), method="iso_grid",
                                                               size=size))
    p.Size = size * 1.02
    out["param"], _ = _timed(doc.recompute)
    p.touch()
    out["touch"], _ = _timed(doc.recompute)
    kids = children_of(p)
    assert all(o.isValid() for o in [p] + kids), [o.State for o in [p] + kids]
    panels = kids[0]
    out["types_count"] = panels.TypeCount
    out["panels_after_param"] = len(panels.PanelIds)
    with tempfile.TemporaryDirectory() as tmp:
        path = os.path.join(tmp, "docspeed.FCStd")
        out["save"], _ = _timed(lambda: doc.saveAs(path))
        out["file_mb"] = os.path.getsize(path) / 1e6
        FreeCAD.closeDocument(doc.Name)
        out["reopen"], doc2 = _timed(lambda: FreeCAD.openDocument(path))
        restored = [o for o in doc2.Objects if o.Label.startswith("Panels")]
        assert restored and len(restored[0].Shape.childShapes()) == out["panels_after_param"]
        FreeCAD.closeDocument(doc2.Name)
    return out


COLUMNS = ("panels", "panelize", "make", "param", "touch", "save", "reopen", "types",
           "types_count", "file_mb")


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--panels", type=int, nargs="+", default=[2000, 5000, 10000, 20000])
    ap.add_argument("--modes", nargs="+", default=["before", "after"],
                    choices=["before", "after"])
    ap.add_argument("--one", nargs=2, metavar=("MODE", "PANELS"), help=argparse.SUPPRESS)
    args = ap.parse_args()
    if args.one:
        print(json.dumps(run(args.one[0], int(args.one[1]))))
        return
    env = dict(os.environ)
    env["PYTHONPATH"] = os.pathsep.join(
        [p for p in ("/usr/lib/freecad-python3/lib", ROOT, env.get("PYTHONPATH")) if p])
    print(f"{'mode':>6} {'target':>6} " + " ".join(f"{c:>11}" for c in COLUMNS), flush=True)
    for target in args.panels:
        for mode in args.modes:
            proc = subprocess.run([sys.executable, os.path.abspath(__file__), "--one", mode,
                                   str(target)], env=env, capture_output=True, text=True)
            lines = [ln for ln in proc.stdout.splitlines() if ln.startswith("{")]
            if proc.returncode != 0 or not lines:
                print(f"{mode:>6} {target:>6} failed: {proc.stderr.strip()[-400:]}", flush=True)
                continue
            row = json.loads(lines[-1])
            cells = []
            for c in COLUMNS:
                v = row[c]
                cells.append(f"{v:>11d}" if isinstance(v, int) else f"{v:>11.3f}")
            print(f"{mode:>6} {target:>6} " + " ".join(cells), flush=True)


if __name__ == "__main__":
    main()
