"""Histograms of the distributions fabricators and engineers look at: panel
deviation, rod length and panel area.

    import freecad_workbench as tessella
    r = tessella.panelize(face, size=1500.0)
    data = tessella.histograms(r, "histograms.png")   # also returns the counts
"""

import numpy as np

PLOTS = (
    ("panel_deviation", "Panel deviation", "mm", 1.0),
    ("rod_length", "Rod length", "mm", 1.0),
    ("panel_area", "Panel area", "m²", 1e-6),
)


def histogram_data(result, bins=20):
    """{metric: (counts, bin_edges, unit)} computed with numpy.histogram."""
    out = {}
    for key, _title, unit, factor in PLOTS:
        values = np.asarray(result.metrics[key], dtype=float) * factor
        counts, edges = np.histogram(values, bins=bins)
        out[key] = (counts, edges, unit)
    return out


def histograms(result, path=None, bins=20, title=None):
    """Histogram data for a PanelizeResult (or a Panelization document object);
    with `path`, also a PNG of the three histograms side by side."""
    if not hasattr(result, "metrics"):
        result = result.Proxy.result(result).result  # a Panelization object
    if not isinstance(bins, int) or bins < 1:
        raise ValueError(f"bins must be an integer >= 1, got {bins!r}")
    data = histogram_data(result, bins)
    if path is not None:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt

        fig, axes = plt.subplots(1, len(PLOTS), figsize=(13, 3.6))
        for ax, (key, name, unit, _f) in zip(axes, PLOTS):
            counts, edges, _u = data[key]
            ax.bar(edges[:-1], counts, width=np.diff(edges), align="edge",
                   color="#3b528b", edgecolor="white")
            ax.set_xlabel(f"{name} ({unit})")
            ax.set_ylabel("count")
            ax.set_title(f"{name}: n={int(counts.sum())}")
        fig.suptitle(title or f"{result.method}: {len(result.panels)} panels, "
                     f"{len(result.rods)} rods")
        fig.tight_layout()
        fig.savefig(path, dpi=110)
        plt.close(fig)
    return data
