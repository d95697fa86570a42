"""Random multi-face shapes that broke a face-set invariant or were refused
wrongly (bench/random_face_sets.py runs them by seed; bench/bench_faces.py:
random_face_set builds them, deterministic per seed). Each case is checked
with the face-set tests' own invariants (test_face_sets.check_conforming)."""

import os
import sys

import pytest

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
for _p in ("/usr/lib/freecad-python3/lib", REPO, os.path.join(REPO, "bench")):
    if _p not in sys.path:
        sys.path.append(_p)

import FreeCAD  # noqa: E402,F401  (before Part)
import Part  # noqa: E402,F401

import freecad_workbench as tessella  # noqa: E402
from bench_faces import random_face_set  # noqa: E402  (bench/: the benchmark's shapes)
from test_face_sets import check_conforming  # noqa: E402


@pytest.mark.parametrize("seed, method", [
    # Small faces cut out of a B-spline face by three planes: their shared
    # edges bend more in (u,v) than in space, and the strips between them
    # and the panels' sides were allowed for by their 3D sagitta only (a
    # triangle of 0.26 m2 refused by every method, 0.10-0.53% uncovered).
    (175, "iso_grid"), (175, "equal_size_grid"), (175, "boundary_driven"),
    (175, "walking_agent"), (140, "walking_agent"),
    # An extruded closed curve: OCCT's adaptive area of the side was 7.7%
    # off, and walking_agent refused as overlapping.
    (38, "walking_agent"),
    # Two cut planes crossing on a B-spline face: a node 0.1 mm from the
    # four faces' common vertex stayed a node of its own (a 0.096 mm rod).
    (220, "walking_agent"),
    # A revolved profile with its top: nodes on the side's seam (FreeCAD's
    # distToShape reads one of them 159 mm off; the check looks again a
    # hair off the seam).
    (232, "boundary_driven"),
    # A box fused with a cylinder through it, a box with filleted edges: a
    # curved face's node joined onto a planar face's along their edge bent
    # its panel over walking_agent's bound on every retry.
    (154, "walking_agent"), (211, "walking_agent"),
    # A B-spline face with holes, split: a boundary panel's centre (its
    # corners' middle) lay 25.9 mm inside a hole, an interior node there.
    (1058, "boundary_driven"),
    # A sphere cut by planes 0.8 mm and 23 mm from its poles: near a pole
    # the nearest point in (u,v) is not the nearest in space, and a side
    # along the cut looks like a chord across the face there; the faces did
    # not meet node to node (2 to 9 segments).
    (1113, "iso_grid"), (1113, "walking_agent"), (1332, "equal_size_grid"),
    # Three planes crossing near one point of a B-spline face: a triangle
    # of 12 to 16 mm (80 mm2) read as a sliver 0.01 mm wide (its area over
    # its whole surface's box) and was left out, a hole in the set.
    (430, "iso_grid"), (430, "boundary_driven"), (710, "walking_agent"),
    # A revolved profile and its top at about 60 panels: boundary_driven's
    # top row ran along the rim and back over it (see below).
    (747, "boundary_driven"),
])
def test_random_face_set(seed, method):
    kind, shape, size = random_face_set(seed)
    kw = ({"max_size": size, "max_deviation": 0.01 * size} if method == "walking_agent"
          else {"size": size})
    r = tessella.panelize_faces(shape, method=method, **kw)
    assert check_conforming(shape, r) > 0
    assert set(r.panel_face.tolist()) == set(range(len(shape.Faces)))
    # No rod of a fraction of a millimetre (a few may stay under the
    # minimum where no merge keeps the panels valid; summary short_rods).
    # Where the shape itself has them, the shape's: cuts 0.8 and 23 mm from
    # the pole of a sphere (the pole node and the cut's nodes beside it: 0.7
    # and 9.3 mm, left open), the edges of 12 to 16 mm of a small face cut
    # out by three planes.
    if seed not in SHORT_BY_THE_SHAPE:
        assert r.metrics["rod_length"].min() > 0.1 * r.summary["min_rod_length"]


SHORT_BY_THE_SHAPE = {1113, 1332, 430}


def _folds(q):
    """Whether outline q (u,v) runs back over itself: a side doubling back
    along the one before, or two sides on one line overlapping."""
    def orient(a, b, c):
        d = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])
        return (d > 0) - (d < 0)
    n = len(q)
    for i in range(n):
        a, b, c = q[i - 1], q[i], q[(i + 1) % n]
        if orient(a, b, c) == 0 and (a[0] - b[0]) * (c[0] - b[0]) + (a[1] - b[1]) * (c[1] - b[1]) > 0:
            return True
    for i in range(n):
        for j in range(i + 2, n):
            if i == 0 and j == n - 1:
                continue
            a, b, c, d = q[i], q[(i + 1) % n], q[j], q[(j + 1) % n]
            if orient(a, b, c) or orient(a, b, d):
                continue
            k = 0 if abs(b[0] - a[0]) >= abs(b[1] - a[1]) else 1
            if min(max(a[k], b[k]), max(c[k], d[k])) > max(min(a[k], b[k]), min(c[k], d[k])):
                return True
    return False


def test_no_boundary_driven_panel_runs_back_along_a_closed_rim():
    # The revolved side of random_face_set(747) alone: its top row had a
    # panel running along the rim and back over it to a corner 130 degrees
    # round (zero area in (u,v), unseen by the coverage), its sides chords
    # across the rim circle: 2,073 mm off the surface at a size of 1,919 mm.
    kind, shape, size = random_face_set(747)
    r = tessella.panelize(shape.Faces[0], method="boundary_driven", size=size)
    corner_uv = r._mesh.corner_uv
    for k, panel in enumerate(r.panels):
        q = [tuple(map(float, x)) for x in (corner_uv[k] if len(corner_uv) else r.uv[panel])]
        assert not _folds(q), k
    assert r.metrics["panel_deviation"].max() < size
