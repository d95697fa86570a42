"""panel_deviation is an upper bound of the true distance from the panel model
to the surface, within 1%: checked against an independent dense re-measure with
FreeCAD's own projection (Surface.parameter + Surface.value) of 41 x 41 points
of each quad's bilinear patch, on the freeform face (not a bundled example)."""


import FreeCAD  # noqa: F401  (before Part)
import numpy as np
import pytest

import freecad_workbench as tessella
from conftest import dense_quad_deviation

DENSE = 40


def dense_deviation(surface, p):
    """Largest distance of the bilinear patch of the quad p (4 x 3) to the surface."""
    return dense_quad_deviation(surface, p, DENSE)


def quads_to_check(result, worst=15, others=15):
    dev = result.metrics["panel_deviation"]
    quads = [k for k, p in enumerate(result.panels) if len(p) == 4]
    quads.sort(key=lambda k: -dev[k])
    chosen = quads[:worst]
    rest = quads[worst:]
    if rest:
        rng = np.random.default_rng(11)
        chosen += [int(k) for k in rng.choice(rest, size=min(others, len(rest)), replace=False)]
    return chosen


@pytest.mark.parametrize(
    "method,params",
    [("iso_grid", {"size": 1500.0}), ("walking_agent", {"max_deviation": 30.0})],
)
def test_deviation_is_a_tight_upper_bound(freeform_face, method, params):
    r = tessella.panelize(freeform_face, method=method, **params)
    assert r.summary["unreliable_deviation"] == 0
    dev = r.metrics["panel_deviation"]
    surface = freeform_face.Surface
    checked = quads_to_check(r)
    assert len(checked) >= 20
    for k in checked:
        dense = dense_deviation(surface, r.vertices[list(r.panels[k])])
        assert dev[k] >= dense * (1 - 0.01), (k, dev[k], dense)
        assert dev[k] <= dense * 1.01 + 1e-6, (k, dev[k], dense)


def test_summary_counts_unreliable_panels(freeform_face):
    r = tessella.panelize(freeform_face, method="iso_grid", size=2500.0)
    flags = r._core.metrics.deviation_unreliable
    assert len(flags) == len(r.panels)
    assert r.summary["unreliable_deviation"] == sum(bool(f) for f in flags)
