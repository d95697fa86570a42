"""A document saved by an earlier Tessella version still opens and recomputes to
the same results: tests/fixtures/panelizations_v0.FCStd (one Panelization per
method and one Unfold, written by tests/fixtures/make_v0_document.py with the
version of that time) against the counts it recorded in panelizations_v0.json.

The package under test is whatever PYTHONPATH provides (this module adds
nothing to sys.path); test_package_comes_from_pythonpath checks that.
"""

import json
import os
import shutil

import FreeCAD  # noqa: F401  (before Part)
import Part  # noqa: F401
import pytest

import freecad_workbench
from freecad_workbench.features import panelization as pfeat
from freecad_workbench.features import unfold as ufeat

HERE = os.path.dirname(os.path.abspath(__file__))
FIXTURES = os.path.join(os.path.dirname(HERE), "fixtures")
FCSTD = os.path.join(FIXTURES, "panelizations_v0.FCStd")
JSON = os.path.join(FIXTURES, "panelizations_v0.json")

ALL_METHODS = {
    "iso_grid", "equal_size_grid", "boundary_driven", "guide_line_scaling",
    "guide_line_diamond", "two_guide_lines", "walking_agent", "gradient_descent",
    "relaxed_grid",
}
SUMMARY_INTS = ("PanelCount", "RodCount", "NodeCount", "MergedSlivers", "IrregularPanels", "Folds")


@pytest.fixture(scope="module")
def expected():
    with open(JSON, encoding="utf-8") as f:
        return json.load(f)


@pytest.fixture
def saved_doc(tmp_path):
    path = str(tmp_path / os.path.basename(FCSTD))
    shutil.copyfile(FCSTD, path)  # never touch the fixture itself
    doc = FreeCAD.openDocument(path)
    name = doc.Name
    yield doc
    if name in FreeCAD.listDocuments():
        FreeCAD.closeDocument(name)


def _by_label(doc, label):
    found = doc.getObjectsByLabel(label)
    assert len(found) == 1, f"{label!r}: {len(found)} objects with that label"
    return found[0]


def _child_counts(p):
    kids = {k.Role: k for k in pfeat.children_of(p)}
    assert sorted(kids) == sorted(pfeat.ROLES), f"{p.Label}: children {sorted(kids)}"
    return {
        "Panels": len(kids["Panels"].Shape.childShapes()),
        "PanelIds": len(kids["Panels"].PanelIds),
        "TypeCount": int(kids["Panels"].TypeCount),
        "Rods": len(kids["Rods"].Shape.childShapes()),
        "RodIds": len(kids["Rods"].RodIds),
        "Nodes": len(kids["Nodes"].Shape.childShapes()),
        "NodeIds": len(kids["Nodes"].NodeIds),
    }


def _unfold_counts(u):
    return {
        "Panels": len(u.Shape.childShapes()),
        "PanelIds": len(u.PanelIds),
        "FoldAngles": len(u.FoldAngles),
        "FoldedPanels": int(u.FoldedPanels),
        "SheetCount": int(u.SheetCount),
    }


def _summary(p):
    return {k: int(getattr(p, k)) for k in SUMMARY_INTS}


def test_package_comes_from_pythonpath():
    """The first PYTHONPATH entry holding a freecad_workbench package is the one imported."""
    entries = [e for e in os.environ.get("PYTHONPATH", "").split(os.pathsep) if e]
    roots = [e for e in entries if os.path.isdir(os.path.join(e, "freecad_workbench"))]
    if not roots:
        pytest.skip("no freecad_workbench package on PYTHONPATH")
    imported = os.path.realpath(os.path.dirname(freecad_workbench.__file__))
    assert imported == os.path.realpath(os.path.join(roots[0], "freecad_workbench")), (
        f"imported {imported}, but PYTHONPATH names {roots[0]} first: `python -m pytest` "
        "puts the current directory first on sys.path; run from elsewhere or with python3 -P"
    )
    assert os.path.realpath(os.path.dirname(pfeat.__file__)).startswith(imported)


def test_fixture_covers_every_method(expected):
    methods = {e["method"] for e in expected["panelizations"].values()}
    assert methods == ALL_METHODS
    assert len(expected["unfolds"]) == 1


def test_proxies_are_the_current_classes(saved_doc, expected):
    pans = [o for o in saved_doc.Objects if pfeat.is_panelization(o)]
    assert sorted(o.Label for o in pans) == sorted(expected["panelizations"])
    for label, e in expected["panelizations"].items():
        p = _by_label(saved_doc, label)
        assert type(p.Proxy) is pfeat.Panelization, (label, type(p.Proxy))
        assert type(p.Proxy).__module__ == "freecad_workbench.features.panelization"
        assert p.Method == e["method"]
        for child in pfeat.children_of(p):
            assert type(child.Proxy) is pfeat.PanelizationPart
    for label in expected["unfolds"]:
        u = _by_label(saved_doc, label)
        assert type(u.Proxy) is ufeat.Unfold
        assert type(u.Proxy).__module__ == "freecad_workbench.features.unfold"


def test_saved_values_restore(saved_doc, expected):
    """Before any recompute: the stored summaries and shapes read back as saved."""
    for label, e in expected["panelizations"].items():
        p = _by_label(saved_doc, label)
        assert _summary(p) == {k: e[k] for k in SUMMARY_INTS}, label
        assert _child_counts(p) == e["children"], label
    for label, e in expected["unfolds"].items():
        u = _by_label(saved_doc, label)
        assert u.Base.Label == e["base"]
        assert _unfold_counts(u) == {k: v for k, v in e.items() if k != "base"}, label


def test_recompute_matches_the_console_with_the_saved_settings(saved_doc, expected):
    """Recomputed, every saved Panelization gives what the console API gives for
    its settings today (the counts the old version saved differ where a method
    changed on purpose since, e.g. boundary pieces split by a new rod), and its
    children and the Unfold follow it."""
    for o in saved_doc.Objects:
        o.touch()
    saved_doc.recompute()
    bad = [f"{o.Label} ({', '.join(o.State)})" for o in saved_doc.Objects
           if not o.isValid() or "Touched" in o.State]
    assert not bad, "objects did not recompute: " + ", ".join(bad)
    source = _by_label(saved_doc, "Surface").Shape.Faces[0]
    for label, e in expected["panelizations"].items():
        p = _by_label(saved_doc, label)
        assert p.Proxy.result(p).result.method == e["method"]
        method, params = p.Proxy.parameters(p)
        fresh = freecad_workbench.panelize(source, method=method, **params)
        assert (p.PanelCount, p.RodCount, p.NodeCount) == (
            fresh.summary["panel_count"], fresh.summary["rod_count"],
            fresh.summary["node_count"]), label
        kids = _child_counts(p)
        assert kids["Panels"] == kids["PanelIds"] == p.PanelCount, label
        assert kids["Rods"] == kids["RodIds"] == p.RodCount, label
    for label, e in expected["unfolds"].items():
        u = _by_label(saved_doc, label)
        got = _unfold_counts(u)
        assert got["Panels"] == got["PanelIds"] == got["FoldAngles"] == u.Base.PanelCount, label
        assert got["SheetCount"] > 0, label
