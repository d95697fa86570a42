"""features/base.py: the helpers every proxy shares (and their old import paths)."""
import json

import FreeCAD
import pytest

from freecad_workbench.features import base, curve_network, panelization, unfold


def test_helpers_are_still_importable_from_panelization():
    for name in ("add_property", "value_of", "_StateMixin", "_upgrade_enumeration",
                 "_PROP_READONLY", "_PROP_OUTPUT", "_READONLY_OUTPUT", "SCHEMA_VERSION"):
        assert getattr(panelization, name) is getattr(base, name), name


@pytest.mark.parametrize("cls", [panelization.Panelization, panelization.PanelizationPart,
                                 unfold.Unfold, curve_network.CurveNetwork])
def test_every_proxy_persists_json_safe_state(cls):
    assert issubclass(cls, base._StateMixin)
    proxy = cls.__new__(cls)
    proxy._restore(None)
    for state in (proxy.dumps(), proxy.__getstate__()):
        assert json.loads(json.dumps(state)) == {"schema": base.SCHEMA_VERSION}
    other = cls.__new__(cls)
    other.__setstate__(json.loads(json.dumps(proxy.__getstate__())))
    assert other.schema == base.SCHEMA_VERSION and other._cache is None
    other = cls.__new__(cls)
    assert other.loads(None) is None and other.schema == base.SCHEMA_VERSION


def test_add_property_and_enumeration_upgrade():
    doc = FreeCAD.newDocument("FeatBase")
    try:
        obj = doc.addObject("App::FeaturePython", "X")
        assert base.add_property(obj, "App::PropertyLength", "L", "G", "doc", default=5.0)
        assert not base.add_property(obj, "App::PropertyLength", "L", "G", "doc", default=7.0)
        assert base.value_of(obj.L) == 5.0 and base.value_of(3) == 3.0
        ro = base.READONLY_OUTPUT
        base.add_property(obj, "App::PropertyInteger", "N", "G", "doc", attr=ro)
        assert sorted(obj.getTypeOfProperty("N")) == ["Output", "ReadOnly"]
        base.add_property(obj, "App::PropertyEnumeration", "E", "G", "doc", default="b",
                          enum=["a", "b"])
        base._upgrade_enumeration(obj, "E", ["a", "b", "c"])
        assert list(obj.getEnumerationsOfProperty("E")) == ["a", "b", "c"] and obj.E == "b"
    finally:
        FreeCAD.closeDocument(doc.Name)
