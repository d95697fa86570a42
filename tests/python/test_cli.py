"""The batch command line (python3 -m freecad_workbench.cli), run as a user runs
it: a STEP shell built here, a broken STEP file and a BRep face in; for each good
one a folder with the document, the schedules and the DXF, read back; a non-zero
exit status and no folder (nor a temporary one) for the broken file."""

import csv
import math
import os
import subprocess
import sys

import ezdxf
import FreeCAD
import pytest

from test_face_sets import split_bspline_shell

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def run_cli(*args):
    env = dict(os.environ)
    env["PYTHONPATH"] = os.pathsep.join(["/usr/lib/freecad-python3/lib", REPO])
    return subprocess.run([sys.executable, "-m", "freecad_workbench.cli", *args], env=env,
                          capture_output=True, text=True, timeout=600)


@pytest.fixture(scope="module")
def batch(tmp_path_factory):
    d = tmp_path_factory.mktemp("batch")
    shell = d / "shell.step"
    split_bspline_shell().exportStep(str(shell))
    broken = d / "broken.step"
    broken.write_text("ISO-10303-21; this is not a STEP file")
    face = os.path.join(REPO, "examples", "trimmed_bspline_holes.brep")
    out = d / "out"
    proc = run_cli(str(shell), str(broken), face, "--out", str(out), "--size", "1200",
                   "--param", "samples=6")
    return proc, out


def test_exit_status_and_progress(batch):
    proc, out = batch
    assert proc.returncode == 1, proc.stderr
    assert "FAILED" in proc.stderr and "broken.step" in proc.stderr
    assert "[1/3]" in proc.stderr and "2 of 3 input(s) done" in proc.stderr


def test_no_half_written_output(batch):
    _, out = batch
    assert sorted(os.listdir(out)) == ["shell", "trimmed_bspline_holes"]  # no temp, no broken


def test_outputs_read_back(batch):
    _, out = batch
    folder = out / "shell"
    assert sorted(os.listdir(folder)) == ["nodes.csv", "panels.csv", "panels.dxf", "rods.csv",
                                          "shell.FCStd"]
    with open(folder / "panels.csv", newline="") as f:
        panels = list(csv.DictReader(f))
    doc = FreeCAD.openDocument(str(folder / "shell.FCStd"))
    try:
        p = [o for o in doc.Objects if o.Name.startswith("Panelization")][0]
        p.touch()
        doc.recompute()
        assert p.isValid() and p.PanelCount == len(panels) > 0
        assert p.Proxy.result(p).result.face_count == 4  # the STEP shell as one envelope
    finally:
        FreeCAD.closeDocument(doc.Name)
    dxf = ezdxf.readfile(str(folder / "panels.dxf"))
    outlines = [e for e in dxf.modelspace() if e.dxftype() == "LWPOLYLINE"]
    assert len(outlines) >= len(panels)


def test_bad_arguments():
    proc = run_cli("x.step", "--out", "/tmp/never", "--param", "size")
    assert proc.returncode == 2 and "name=value" in proc.stderr


def test_a_document_s_shapes_are_those_no_other_shape_is_built_from(tmp_path):
    # A Cut of two boxes is one shape (not the boxes); a part that a FEM
    # constraint refers to is still a shape of its own (the constraint has
    # none). The old rule took only objects referred to by nothing, so a
    # document with a FEM analysis on its part had "no object with faces".
    from freecad_workbench.cli import load_shape

    doc = FreeCAD.newDocument("cli_top_level")
    try:
        a = doc.addObject("Part::Box", "A")
        b = doc.addObject("Part::Box", "B")
        b.Placement.Base = FreeCAD.Vector(5, 5, 5)
        cut = doc.addObject("Part::Cut", "Cut")
        cut.Base, cut.Tool = a, b
        held = doc.addObject("Part::Cylinder", "Held")
        held.Placement.Base = FreeCAD.Vector(100, 0, 0)
        doc.addObject("Fem::ConstraintFixed", "Fixed").References = [(held, "Face2")]
        doc.recompute()
        path = str(tmp_path / "parts.FCStd")
        doc.saveAs(path)
        expected = len(cut.Shape.Faces) + len(held.Shape.Faces)
    finally:
        FreeCAD.closeDocument(doc.Name)
    shape = load_shape(path)
    assert len(shape.Faces) == expected == 9 + 3
    assert abs(shape.Volume - (1000 - 125 + math.pi * 2 * 2 * 10)) < 1e-6


def test_the_report_view_s_warnings_are_printed(tmp_path):
    # A STEP part with a sliver between two faces: the set leaves it out and
    # says so in the Report view, which a batch run does not show; the CLI
    # prints the same warning.
    import Part
    from test_face_sets import slit_shell

    path = tmp_path / "slit.step"
    Part.Compound(slit_shell(1e-3)).exportStep(str(path))
    proc = run_cli(str(path), "--out", str(tmp_path / "out"), "--size", "1500")
    assert proc.returncode == 0, proc.stderr
    assert "slit: warning: 1 face(s) without area left out: face 2 (the face is a sliver" \
        in proc.stderr
