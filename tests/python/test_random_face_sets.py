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
    # boundary_driven with rods across a trim: a revolved profile and its
    # top, a side panel running along the rim and back over it (2,073 mm off
    # the surface at a size of 1,919 mm, T-junctions on the rim), and a box
    # fused with a cylinder, refused as "panels overlap in space" (stop 54).
    (747, "boundary_driven"), (714, "boundary_driven"), (964, "boundary_driven"),
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

