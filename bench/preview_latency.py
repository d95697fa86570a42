"""Responsiveness: time from a parameter change to an updated preview, i.e. what
the task panel runs after its debounce (panelize with preview sampling + the
rod line index for the 3D view), for a few hundred to a few thousand panels.

    PYTHONPATH=/usr/lib/freecad-python3/lib:. /usr/bin/python3 bench/preview_latency.py

Target (issue 7): under 200 ms for 1,000 panels. The debounce delay itself
(250 ms, freecad_workbench/gui/preview.py) is not included.
"""
import math
import os
import statistics
import sys
import time

import FreeCAD  # noqa: F401  (before Part)
import Part

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
import freecad_workbench as tessella  # noqa: E402
from freecad_workbench.gui.task_panel import PREVIEW_SAMPLES  # noqa: E402


def preview(face, size):
    r = tessella.panelize(face, method="iso_grid", size=size, samples=PREVIEW_SAMPLES)
    index = []
    for a, b in r.rods:
        index += [int(a), int(b), -1]
    return r


def main():
    shape = Part.Shape()
    shape.read(os.path.join(os.path.dirname(__file__), "..", "examples", "trimmed_bspline_holes.brep"))
    face = shape.Faces[0]
    print(f"{'target panels':>13} {'panels':>7} {'median ms':>10} {'min ms':>8}")
    for target in (300, 1000, 3000):
        size = math.sqrt(face.Area / target)
        times = []
        for _ in range(5):
            t0 = time.perf_counter()
            r = preview(face, size)
            times.append((time.perf_counter() - t0) * 1000)
        print(f"{target:>13} {len(r.panels):>7} {statistics.median(times):>10.1f} {min(times):>8.1f}")


if __name__ == "__main__":
    main()
