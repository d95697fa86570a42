"""The core's panel types (members.panel_types) against an independent
brute-force check of the greedy rule, on real panelizations of every bundled
example, and on a cone whose answer is known in closed form (types = rows)."""
import glob
import math
import os

import FreeCAD  # noqa: F401  (before Part)
import numpy as np
import Part
import pytest

import freecad_workbench as tessella
from freecad_workbench.fabrication import unfold
from freecad_workbench.members import panel_types

EXAMPLES = sorted(glob.glob(os.path.join(os.path.dirname(__file__), "..", "..", "examples",
                                         "*.brep")))


def signature(outline):
    """(edge lengths, turning angles in degrees), corner by corner."""
    p = np.asarray(outline, dtype=float)
    nxt = np.concatenate([p[1:], p[:1]])
    prv = np.concatenate([p[-1:], p[:-1]])
    edge, before = nxt - p, p - prv
    lengths = np.hypot(edge[:, 0], edge[:, 1])
    turn = np.degrees(np.arctan2(before[:, 0] * edge[:, 1] - before[:, 1] * edge[:, 0],
                                 before[:, 0] * edge[:, 0] + before[:, 1] * edge[:, 1]))
    return lengths, turn


def matching(sigs, folds, i, others, lt, at, slack=0.0):
    """Which of `others` panel i matches: same corner count, folds within at,
    and some cyclic shift with every length within lt and angle within at.
    slack widens (> 0) or narrows (< 0) the tolerances, to stay clear of
    rounding at the boundary."""
    li, ai = sigs[i]
    k = len(li)
    out = np.zeros(len(others), dtype=bool)
    for n, j in enumerate(others):
        lj, aj = sigs[j]
        if len(lj) != k or k == 0 or abs(folds[i] - folds[j]) > at + slack:
            continue
        for shift in range(k):
            if (np.all(np.abs(li - np.roll(lj, -shift)) <= lt + slack)
                    and np.all(np.abs(ai - np.roll(aj, -shift)) <= at + slack)):
                out[n] = True
                break
    return out


def check_greedy(flat, types, count, lt, at):
    """The greedy rule, checked pair by pair (margins of 1e-9 keep the check
    off the tolerance boundary, where rounding could decide either way)."""
    sigs = [signature(f.outline) for f in flat]
    folds = [f.fold_angle for f in flat]
    types = list(types)
    assert len(types) == len(flat)
    # numbered by first appearance: 0, then each new type one above the largest so far
    first = {}
    for i, t in enumerate(types):
        if t not in first:
            assert t == len(first), f"panel {i} starts type {t}, expected {len(first)}"
            first[t] = i
    assert len(first) == count
    reps = [first[t] for t in range(count)]
    for i, t in enumerate(types):
        # every panel is within tolerance of its type's first panel ...
        assert matching(sigs, folds, i, [reps[t]], lt, at, slack=1e-9)[0], (i, t)
        # ... and of no earlier type's first panel (else it would have joined it)
        earlier = matching(sigs, folds, i, reps[:t], lt, at, slack=-1e-9)
        assert not earlier.any(), (i, t, np.nonzero(earlier)[0])


@pytest.mark.parametrize("path", EXAMPLES, ids=[os.path.basename(p) for p in EXAMPLES])
def test_types_follow_the_greedy_rule_on_the_examples(path):
    face = Part.read(path).Faces[0]
    r = tessella.panelize(face, method="iso_grid", size=math.sqrt(face.Area / 250))
    flat = unfold(r)
    for lt, at in ((1.0, 0.5), (40.0, 3.0)):
        types, count = panel_types(flat, lt, at)
        check_greedy(flat, types, count, lt, at)


def test_types_of_an_equal_size_grid_follow_the_greedy_rule():
    face = Part.read(EXAMPLES[-1]).Faces[0]  # the vault with openings
    r = tessella.panelize(face, method="equal_size_grid", size=math.sqrt(face.Area / 200))
    flat = unfold(r)
    types, count = panel_types(flat, 5.0, 1.0)
    check_greedy(flat, types, count, 5.0, 1.0)


def test_cone_rows_are_the_types():
    """A cone frustum cut by an iso grid of n x m: every panel is a planar
    isosceles trapezoid whose parallel sides are 2 r sin(pi/n) at the radii of
    its row's two parallels, so the panels of a row are congruent and the
    rows differ (by far more than the tolerance): m types, one per row."""
    n, m, r1, r2, h = 24, 6, 5000.0, 2000.0, 6000.0
    face = Part.makeCone(r1, r2, h).Faces[0]
    r = tessella.panelize(face, method="iso_grid", u_count=n, v_count=m)
    assert len(r.panels) == n * m
    flat = unfold(r)
    types, count = panel_types(flat)
    assert count == m
    z = np.array([np.mean(r.vertices[list(p), 2]) for p in r.panels])
    row = np.floor(z / (h / m)).astype(int)
    for t in range(count):
        members = {int(k) for k in row[np.asarray(types) == t]}
        assert len(members) == 1, (t, members)  # one row per type ...
    assert len({int(t) for t in types}) == len(set(row.tolist())) == m  # ... and a type per row
    # the closed form of each type's parallel sides
    slant = math.hypot(h / m, (r1 - r2) / m)
    for t in range(count):
        i = types.index(t)
        lengths = sorted(flat[i].edge_lengths)
        j = int(row[i])
        ra, rb = r1 - (r1 - r2) * j / m, r1 - (r1 - r2) * (j + 1) / m
        expect = sorted([2 * ra * math.sin(math.pi / n), 2 * rb * math.sin(math.pi / n),
                         slant, slant])
        assert lengths == pytest.approx(expect, rel=1e-9)


def test_coarse_tolerance_merges_neighbouring_rows_greedily():
    """The same cone with a tolerance above one row's step in parallel side
    (2 (r1 - r2)/m sin(pi/n) = 130.5 mm) but under two: rows pair up from
    whichever row the panel order meets first, and the result still follows
    the greedy rule."""
    n, m = 24, 6
    face = Part.makeCone(5000.0, 2000.0, 6000.0).Faces[0]
    r = tessella.panelize(face, method="iso_grid", u_count=n, v_count=m)
    flat = unfold(r)
    types, count = panel_types(flat, length_tol=200.0, angle_tol=10.0)
    check_greedy(flat, types, count, 200.0, 10.0)
    assert count == m // 2


def test_bad_tolerance_is_refused():
    face = Part.makePlane(1000, 1000).Faces[0]
    flat = unfold(tessella.panelize(face, u_count=2, v_count=2))
    with pytest.raises(ValueError, match="length_tol"):
        panel_types(flat, length_tol=-1.0)
