"""PanelizeResult.panels_shape (the document's Panels, built in Python from the
core's face list) against panels_brep (the core's own BRep of the same faces):
same sub-shapes, faces, areas, normals and corners, on examples with flat,
bilinear, pieced and fanned panels."""
import math
import os

import FreeCAD  # noqa: F401  (before Part)
import Part
import pytest

import freecad_workbench as tessella

EXAMPLES = os.path.join(os.path.dirname(__file__), "..", "..", "examples")


@pytest.mark.parametrize("name,method", [
    ("trimmed_bspline_holes", "iso_grid"),      # bent quads, trimmed n-gons (pieces, fans)
    ("vault_openings", "boundary_driven"),
    ("plane", "iso_grid"),                      # flat faces around a hole
    ("full_cylinder", "iso_grid"),              # periodic seam
])
def test_panels_shape_matches_the_core_brep(name, method):
    face = Part.read(os.path.join(EXAMPLES, name + ".brep")).Faces[0]
    r = tessella.panelize(face, method=method, size=math.sqrt(face.Area / 300))
    ref = Part.Shape()
    ref.importBrepFromString(r.panels_brep(), False)
    got = r.panels_shape()
    assert got.isValid()
    a, b = ref.childShapes(), got.childShapes()
    assert len(a) == len(b) == len(r.panels)
    kinds = set()
    for x, y in zip(a, b):
        assert x.ShapeType == y.ShapeType and len(x.Faces) == len(y.Faces)
        for fx, fy in zip(x.Faces, y.Faces):
            kinds.add(type(fy.Surface).__name__)
            assert fy.Area == pytest.approx(fx.Area, rel=1e-9, abs=1e-6)
            ux, uy = fx.ParameterRange, fy.ParameterRange
            nx = fx.normalAt(0.5 * (ux[0] + ux[1]), 0.5 * (ux[2] + ux[3]))
            ny = fy.normalAt(0.5 * (uy[0] + uy[1]), 0.5 * (uy[2] + uy[3]))
            assert (nx - ny).Length < 1e-9
            assert len(fx.Vertexes) == len(fy.Vertexes)
            for v in fy.Vertexes:
                assert min((v.Point - w.Point).Length for w in fx.Vertexes) < 1e-6
    assert kinds <= {"Plane", "BezierSurface"}
