"""gui/task_form.py's parameter rows (plain data, checked headless): every row
names a real Panelization property, and the rows follow the method table."""
import FreeCAD
import pytest

from freecad_workbench import api, core
from freecad_workbench.features import panelization as feat
from freecad_workbench.gui import task_form


@pytest.fixture(scope="module")
def properties():
    doc = FreeCAD.newDocument("TaskForm")
    obj = doc.addObject("App::FeaturePython", "Panelization")
    feat.Panelization(obj)
    yield set(obj.PropertiesList)
    FreeCAD.closeDocument(doc.Name)


KINDS = {"bool": "bool", "int": "count", "choice": "choice", "int_list": "int_list",
         "uv_curves": "linked"}


@pytest.mark.parametrize("method", list(api.METHODS))
def test_rows_for_every_method(method, properties):
    rows = task_form.rows_for(method)
    spec = api.METHODS[method]
    names = [r.name for r in rows]
    assert len(set(names)) == len(names)
    # declaration order; nothing left out but the common rows and the picked guides
    assert names == [p.name for p in spec if p.name not in task_form.COMMON
                     and p.type != "curves"]
    for r in rows:
        p = spec.params[r.name]
        assert r.name not in task_form.COMMON
        assert r.prop == p.property and r.prop in properties, (method, r)
        assert (r.label, r.unit) == (p.label, p.unit)
        assert r.kind == KINDS.get(p.type, "number" if p.unit == "" else "quantity")
        assert r.prop in r.tooltip and p.doc in r.tooltip
        assert (r.minimum, r.maximum) == (p.minimum, p.maximum)


def test_common_rows(properties):
    rows = task_form.common_rows()
    assert [r.name for r in rows] == ["sliver_fraction", "min_angle", "max_panels"]
    assert [r.label for r in rows] == ["Sliver fraction", "Min angle", "Max panels"]
    assert all(r.prop in properties for r in rows)
    assert rows[1].maximum == 180.0 and rows[2].minimum == 1


def test_ranges_and_guides():
    def row(method, name):
        return next(r for r in task_form.rows_for(method) if r.name == name)

    by_name = {r.name: r for m in api.METHODS for r in task_form.rows_for(m)}
    assert row("iso_grid", "u_count").minimum == 0  # 0: use the size
    assert row("relaxed_grid", "u_count").minimum == 1
    assert by_name["boundary_divisions"].minimum == 0
    assert by_name["smoothing_iterations"].minimum == 0  # the core accepts no smoothing
    assert by_name["tolerance"].decimals == 6 and by_name["rho"].decimals == 4
    assert task_form.guides_needed("guide_line_scaling") == 1
    assert task_form.guides_needed("two_guide_lines") == 2
    assert task_form.guides_needed("iso_grid") == 0
    assert task_form.property_of("max_deviation") == "DeviationBound"
    assert task_form.default_of("boundary_driven", "rho") == pytest.approx(
        core.BoundaryDrivenParams().rho)
