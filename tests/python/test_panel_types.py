"""Panel types on the Panels object: congruent flat panels share a type
(turned allowed, mirror images differ), checked on cases known by hand."""
import FreeCAD
import Part
import pytest

import freecad_workbench as tessella
from freecad_workbench.features.panelization import children_of


def panels_of(shape, **params):
    doc = FreeCAD.newDocument("Types")
    src = doc.addObject("Part::Feature", "Src")
    src.Shape = shape
    doc.recompute()
    p = tessella.make_panelization((src, "Face1"), **params)
    return doc, p, children_of(p)[0]


def test_cylinder_panels_are_one_type():
    doc, p, panels = panels_of(Part.makeCylinder(5000, 4000), u_count=24, v_count=4)
    try:
        assert panels.TypeCount == 1 and set(panels.PanelType) == {0}
    finally:
        FreeCAD.closeDocument(doc.Name)


def test_sphere_has_one_type_per_latitude_pair():
    # 6 rows: the panels of a row are congruent, and row k matches row 5-k
    # (turned upside down): 3 types.
    doc, p, panels = panels_of(Part.makeSphere(3000), u_count=12, v_count=6)
    try:
        assert panels.TypeCount == 3
        rows = [panels.PanelType[12 * r:12 * (r + 1)] for r in range(6)]
        assert all(len(set(row)) == 1 for row in rows)
        assert rows[0] == rows[5] and rows[1] == rows[4] and rows[2] == rows[3]
    finally:
        FreeCAD.closeDocument(doc.Name)


def test_tolerance_groups_near_equal_panels():
    # An equal_size grid on a plate: every panel the same within 1 mm.
    doc, p, panels = panels_of(Part.makePlane(3000, 2000), method="equal_size_grid", size=500.0)
    try:
        assert panels.TypeCount == 1
        panels.TypeTolerance = 0.001
        doc.recompute()
        assert panels.TypeCount == 1  # exact squares are still one type
    finally:
        FreeCAD.closeDocument(doc.Name)
