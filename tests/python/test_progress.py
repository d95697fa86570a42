"""Progress reporting and cancellation through the core (headless)."""
import FreeCAD
import Part
import pytest

import freecad_workbench as tessella


@pytest.fixture(scope="module")
def face():
    return Part.makeSphere(20000).Faces[0]  # about 7,000 panels at 500 mm


def test_progress_is_reported_and_result_unchanged(face):
    calls = []

    def progress(fraction, stage):
        calls.append((fraction, stage))
        return True

    r = tessella.panelize(face, size=500.0, progress=progress)
    plain = tessella.panelize(face, size=500.0)
    assert calls, "a job of this size reports at least once (every 50 ms)"
    assert all(0.0 <= f <= 1.0 for f, _ in calls)
    assert {s for _, s in calls} <= {"cutting the grid by the trim", "merging short rods",
                                     "measuring panels", "modelling boundary pieces",
                                     "checking coverage", "tightening max_deviation"}
    assert r.panels == plain.panels
    assert (r.metrics["panel_deviation"] == plain.metrics["panel_deviation"]).all()


def test_returning_false_cancels(face):
    with pytest.raises(tessella.Cancelled, match="cancelled"):
        tessella.panelize(face, size=500.0, progress=lambda f, s: False)


def test_an_error_in_the_callback_cancels(face):
    def broken(fraction, stage):
        raise ZeroDivisionError

    with pytest.raises(tessella.Cancelled):
        tessella.panelize(face, size=500.0, progress=broken)


def test_cancelled_make_panelization_leaves_nothing(face):
    doc = FreeCAD.newDocument("Cancel")
    try:
        src = doc.addObject("Part::Feature", "Sphere")
        src.Shape = Part.makeSphere(20000)
        doc.recompute()
        before = [o.Name for o in doc.Objects]
        with pytest.raises(tessella.Cancelled):
            tessella.make_panelization((src, "Face1"), size=500.0, progress=lambda f, s: False)
        assert [o.Name for o in doc.Objects] == before
        # Without cancelling, the object is built once and its counts match.
        obj = tessella.make_panelization((src, "Face1"), size=2000.0, progress=lambda f, s: True)
        assert obj.PanelCount == len(tessella.panelize(src.Shape.Faces[0], size=2000.0).panels)
    finally:
        FreeCAD.closeDocument(doc.Name)
