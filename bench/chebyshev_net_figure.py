"""docs/chebyshev_net_dome.png: the Chen Shan dome at 1.5 m in equal_size_grid
and chebyshev_net, each panel coloured by the size of its 2 mm family.

    PYTHONPATH=/usr/lib/freecad-python3/lib:$PWD /usr/bin/python3 bench/chebyshev_net_figure.py
"""
import FreeCAD, Part
import numpy as np
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
from matplotlib.collections import PolyCollection
import freecad_workbench as tessella
face = Part.read("examples/chen_shan_dome.brep").Faces[0]
fig, axes = plt.subplots(1, 2, figsize=(14, 4.6))
for ax, method in zip(axes, ("equal_size_grid", "chebyshev_net")):
    r = tessella.panelize(face, method=method, size=1500.0)
    fam = tessella.panel_families(r, family_tolerance=2.0)
    exact = tessella.panel_families(r, family_tolerance=1e-3)
    xyz = np.asarray(r.vertices)
    polys = [xyz[list(p)][:, :2] / 1000 for p in r.panels]
    counts = fam.counts[fam.labels]
    pc = PolyCollection(polys, array=np.minimum(counts, 12), cmap="viridis", edgecolors="k", linewidths=0.2)
    pc.set_clim(1, 12)
    ax.add_collection(pc); ax.autoscale(); ax.set_aspect("equal")
    ax.set_title(f"{method}, 1.5 m: {len(r.panels)} panels, {exact.count} exact types, "
                 f"{fam.count} families at 2 mm", fontsize=9)
    ax.set_xlabel("x (m)")
    fig.colorbar(pc, ax=ax, shrink=0.8, label="panels in the family (12+)")
fig.tight_layout()
fig.savefig("docs/chebyshev_net_dome.png", dpi=90)
