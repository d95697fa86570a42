"""Family regularization (tessella.regularize_families): node moves that make
the panels of each family more nearly congruent, checked on a doubly curved
face built here: fewer families at the tighter tolerance (counted again with
the public clustering), every moved node within max_deviation of the surface
(FreeCAD's own distance), boundary nodes where they were, deterministic, bad
parameters refused."""

import math

import FreeCAD
import numpy as np
import Part
import pytest

import freecad_workbench as tessella
from freecad_workbench import regularize_families

V = FreeCAD.Vector


@pytest.fixture(scope="module")
def shell_face():
    """A 16 x 11 m shell, 1.4 m rise, leaning to one side (no symmetry)."""
    pts = [[V(16000.0 * i / 8, 11000.0 * j / 6,
              1400.0 * math.sin(math.pi * i / 8) * math.sin(math.pi * j / 6) + 250.0 * i / 8)
            for j in range(7)] for i in range(9)]
    s = Part.BSplineSurface()
    s.interpolate(pts)
    return s.toShape()


@pytest.fixture(scope="module")
def regularized(shell_face):
    r = tessella.panelize(shell_face, method="iso_grid", size=1000.0)
    r2, report = regularize_families(r, family_tolerance=4.0, tolerance=1.0, max_deviation=3.0)
    return r, r2, report


def test_fewer_families_at_the_tighter_tolerance(regularized):
    r, r2, report = regularized
    before = tessella.panel_families(r, family_tolerance=1.0)
    after = tessella.panel_families(r2, family_tolerance=1.0)
    assert len(before.templates) == report["families_before"]
    assert len(after.templates) == report["families_after"]
    assert report["families_after"] < report["families_before"]
    assert report["moved_nodes"] > 0 and report["max_move"] > 0


def test_nodes_stay_near_the_surface_and_on_the_boundary(shell_face, regularized):
    r, r2, report = regularized
    moved = np.linalg.norm(r2.vertices - r.vertices, axis=1)
    assert moved.max() == pytest.approx(report["max_move"])
    idx = np.nonzero(moved > 1e-9)[0]
    for v in idx[:: max(1, len(idx) // 40)]:
        d = shell_face.distToShape(Part.Vertex(V(*r2.vertices[v])))[0]
        assert d <= 3.0 + 1e-6
    # Nodes on the face's boundary did not move.
    tol = 1e-6 * shell_face.BoundBox.DiagonalLength
    boundary = [v for v in r.nodes
                if shell_face.OuterWire.distToShape(Part.Vertex(V(*r.vertices[v])))[0] <= tol]
    assert len(boundary) > 20
    assert np.all(moved[boundary] == 0)
    # The metrics are measured again on the moved nodes.
    assert r2.metrics["panel_deviation"].shape == r.metrics["panel_deviation"].shape
    assert not np.array_equal(r2.metrics["rod_length"], r.metrics["rod_length"])


def test_deterministic(regularized):
    r, r2, _ = regularized
    again, _ = regularize_families(r, family_tolerance=4.0, tolerance=1.0, max_deviation=3.0)
    assert np.array_equal(again.vertices, r2.vertices)


def test_bad_parameters(regularized):
    r, _, _ = regularized
    with pytest.raises(ValueError, match="tolerance"):
        regularize_families(r, family_tolerance=2.0, tolerance=3.0)
    with pytest.raises(ValueError, match="max_deviation"):
        regularize_families(r, family_tolerance=2.0, tolerance=0.5, max_deviation=-1.0)
