"""Histograms: counts agree with the metrics (recounted independently) and a
PNG is written."""
import numpy as np
import Part
import pytest

import freecad_workbench as tessella


@pytest.fixture(scope="module")
def result():
    face = Part.makeSphere(3000).Faces[0]
    return tessella.panelize(face, method="iso_grid", size=900.0)


def test_counts_add_up_and_match_an_independent_recount(result):
    data = tessella.histograms(result, bins=7)
    for key, factor in (("panel_deviation", 1.0), ("rod_length", 1.0), ("panel_area", 1e-6)):
        counts, edges, _unit = data[key]
        values = result.metrics[key] * factor
        assert counts.sum() == len(values)
        # Recount the first and last bins by hand (numpy's last bin is closed).
        assert counts[0] == np.sum((values >= edges[0]) & (values < edges[1]))
        assert counts[-1] == np.sum((values >= edges[-2]) & (values <= edges[-1]))


def test_png_is_written(result, tmp_path):
    path = tmp_path / "h.png"
    tessella.histograms(result, str(path))
    assert path.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert path.stat().st_size > 10_000


def test_bad_bins(result):
    with pytest.raises(ValueError, match="bins"):
        tessella.histograms(result, bins=0)
