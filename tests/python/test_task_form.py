"""gui/task_form.py's parameter rows (plain data, checked headless): every row
names a real Panelization property, and the rows follow the method table."""
import FreeCAD
import pytest

from freecad_workbench import api
from freecad_workbench.features import panelization as feat
from freecad_workbench.gui import task_form


@pytest.fixture(scope="module")
def properties():
    doc = FreeCAD.newDocument("TaskForm")
    obj = doc.addObject("App::FeaturePython", "Panelization")
    feat.Panelization(obj)
    yield set(obj.PropertiesList)
    FreeCAD.closeDocument(doc.Name)


KINDS = {bool: "bool", None: "count", "": "number", "mm": "quantity", "deg": "quantity"}


@pytest.mark.parametrize("method", list(api.METHODS))
def test_rows_for_every_method(method, properties):
    rows = task_form.rows_for(method)
    spec = api.METHODS[method]
    names = [r.name for r in rows]
    assert len(set(names)) == len(names)
    # declaration order, only the method's own numeric / yes-no parameters
    assert names == [n for n in spec.params if n in names]
    for r in rows:
        assert spec.params[r.name] in (int, float, bool)
        assert r.name not in task_form.COMMON
        assert r.prop in properties, (method, r)
        assert (r.label, r.unit) == api.PARAM_INFO.get(r.name, (r.name, ""))
        assert r.kind == KINDS[r.unit]
        assert r.prop in r.tooltip and r.minimum <= r.maximum
    # nothing typed is left out: every stored numeric parameter has a row
    from freecad_workbench.make import _PARAM_TO_PROPERTY

    typed = [n for n, k in spec.params.items() if k in (int, float, bool)
             and n in _PARAM_TO_PROPERTY and n not in ("trim_deflection", "samples")
             and n not in task_form.COMMON]
    assert names == typed


def test_common_rows(properties):
    rows = task_form.common_rows()
    assert [r.name for r in rows] == ["sliver_fraction", "min_angle", "max_panels"]
    assert [r.label for r in rows] == ["Sliver fraction", "Min angle", "Max panels"]
    assert all(r.prop in properties for r in rows)
    assert rows[1].maximum == 180.0 and rows[2].minimum == 1


def test_ranges_and_guides():
    by_name = {r.name: r for m in api.METHODS for r in task_form.rows_for(m)}
    assert by_name["u_count"].minimum == 0 and by_name["boundary_divisions"].minimum == 0
    assert by_name["smoothing_iterations"].minimum == 1
    assert by_name["tolerance"].decimals == 6 and by_name["rho"].decimals == 4
    assert task_form.guides_needed("guide_line_scaling") == 1
    assert task_form.guides_needed("two_guide_lines") == 2
    assert task_form.guides_needed("iso_grid") == 0
    assert task_form.property_of("max_deviation") == "DeviationBound"
    assert task_form.default_of("boundary_driven", "rho") == pytest.approx(
        api.METHODS["boundary_driven"].make_params().rho)
