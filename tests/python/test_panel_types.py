"""Panel types against cases whose answer is known without the code."""
import types

import numpy as np
import Part
import pytest

import freecad_workbench as tessella
from freecad_workbench.panel_types import panel_types


def fake(vertices, panels):
    return types.SimpleNamespace(vertices=np.asarray(vertices, float), panels=panels)


def test_rotated_mirrored_and_relabelled_quads_are_one_type():
    square = [(0, 0, 0), (1000, 0, 0), (1000, 1000, 0), (0, 1000, 0)]
    kite = [(0, 0, 0), (1000, 0, 0), (1200, 900, 0), (0, 1000, 0)]
    mirrored_kite = [(-x, y, z) for x, y, z in kite]
    c, s = np.cos(0.7), np.sin(0.7)
    moved_kite = [(c * x - s * y + 5000, s * x + c * y, 300.0) for x, y, z in kite]
    verts = square + kite + mirrored_kite + moved_kite
    panels = [(0, 1, 2, 3), (4, 5, 6, 7), (11, 10, 9, 8), (13, 14, 15, 12), (14, 15, 12, 13)]
    t = panel_types(fake(verts, panels))
    assert t.tolist() == [0, 1, 1, 1, 1]


def test_a_2_mm_difference_is_another_type_at_1_mm():
    a = [(0, 0, 0), (1000, 0, 0), (1000, 1000, 0), (0, 1000, 0)]
    b = [(0, 0, 0), (1002, 0, 0), (1002, 1000, 0), (0, 1000, 0)]
    t = panel_types(fake(a + b, [(0, 1, 2, 3), (4, 5, 6, 7)]), tolerance=1.0)
    assert t.tolist() == [0, 1]
    assert panel_types(fake(a + b, [(0, 1, 2, 3), (4, 5, 6, 7)]), tolerance=50.0).tolist() == [0, 0]


def test_cylinder_rings_give_one_type_per_ring():
    # All panels of a cylinder iso grid are congruent rectangles: one type.
    r = tessella.panelize(Part.makeCylinder(5000, 4000).Faces[0], u_count=24, v_count=4)
    assert set(panel_types(r, 0.01).tolist()) == {0}
    # A sphere's panels differ by latitude: one type per ring (the two
    # hemispheres mirror each other), so rows/2 types.
    s = tessella.panelize(Part.makeSphere(3000).Faces[0], u_count=12, v_count=6)
    assert len(set(panel_types(s, 0.01).tolist())) == 3


def test_bad_tolerance():
    with pytest.raises(ValueError, match="tolerance"):
        panel_types(fake([], []), tolerance=0)
