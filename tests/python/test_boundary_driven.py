"""method="boundary_driven" (seed 001) on real trimmed OCCT faces, checked with
FreeCAD's own geometry (distToShape, isInside, Surface.parameter) and numpy,
never with the core's own figures alone."""

import math
import os
import sys

import pytest

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
for _p in ("/usr/lib/freecad-python3/lib", REPO):
    if _p not in sys.path:
        sys.path.append(_p)

import FreeCAD  # noqa: E402  (before Part)
import Part  # noqa: E402
import numpy as np  # noqa: E402

import freecad_workbench as tessella  # noqa: E402
from freecad_workbench import core  # noqa: E402
from conftest import close_node_pairs, independent_coverage, widest_turn_round_z  # noqa: E402

SIZE = 900.0


def _load(name):
    shape = Part.Shape()
    shape.read(os.path.join(REPO, "examples", name + ".brep"))
    return shape.Faces[0]


_cache = {}


def run(face_key, face, **kw):
    key = (face_key, tuple(sorted((k, str(v)) for k, v in kw.items())))
    if key not in _cache:
        _cache[key] = tessella.panelize(face, **kw)
    return _cache[key]


def corner_angles(xyz, panel):
    out = []
    n = len(panel)
    for i in range(n):
        a = xyz[panel[i - 1]] - xyz[panel[i]]
        b = xyz[panel[(i + 1) % n]] - xyz[panel[i]]
        out.append(math.degrees(math.acos(np.clip(np.dot(a, b) / np.linalg.norm(a) / np.linalg.norm(b), -1, 1))))
    return out


def node_panels(r):
    """Each panel as its node polygon: the outline points a boundary panel
    carries along a curved trim are not corners (rods run node to node)."""
    nodes = set(int(v) for v in r.nodes)
    return [tuple(v for v in p if v in nodes) for p in r.panels]


def boundary_rods(panels):
    uses = {}
    for p in panels:
        for i in range(len(p)):
            e = tuple(sorted((p[i], p[(i + 1) % len(p)])))
            uses[e] = uses.get(e, 0) + 1
    return [e for e, n in uses.items() if n == 1]


@pytest.fixture(scope="module")
def freeform(freeform_face):
    return freeform_face


def test_freeform_face_all_quads_nodes_on_surface_and_inside(freeform):
    r = run("freeform", freeform, method="boundary_driven", size=SIZE)
    assert len(r.panels) > 50
    assert all(len(p) == 4 for p in node_panels(r))
    model = r.summary["model_size"]
    surface = freeform.Surface
    # every node on the surface (FreeCAD's own projection)
    nodes = r.vertices[r.nodes]  # outline points sit on their boundary pieces' planes
    for x in nodes[:: max(1, len(nodes) // 150)]:
        v = FreeCAD.Vector(*x)
        u, w = surface.parameter(v)
        assert (surface.value(u, w) - v).Length < 1e-6 * model
    # panel centres (mean of corners, projected) lie on the trimmed face: no panel
    # covers a hole or reaches outside
    for p in node_panels(r):
        c = FreeCAD.Vector(*r.vertices[list(p)].mean(axis=0))
        u, w = surface.parameter(c)
        assert freeform.isInside(surface.value(u, w), 1e-3 * SIZE, True), p


def test_freeform_boundary_nodes_on_trim_and_boundary_closed(freeform):
    r = run("freeform", freeform, method="boundary_driven", size=SIZE)
    model = r.summary["model_size"]
    tol = max(e.Tolerance for e in freeform.Edges) + 1e-6 * model
    edges = Part.Compound(freeform.Edges)
    rods = boundary_rods(node_panels(r))
    nodes = sorted({v for e in rods for v in e})
    assert len(nodes) > 20
    for v in nodes:
        assert edges.distToShape(Part.Vertex(FreeCAD.Vector(*r.vertices[v])))[0] < tol
    # the boundary rods form closed loops (every boundary node meets exactly two):
    # the trim is covered with no gap
    count = {}
    for a, b in rods:
        count[a] = count.get(a, 0) + 1
        count[b] = count.get(b, 0) + 1
    assert set(count.values()) == {2}
    # one loop per wire: walk the boundary graph
    adj = {}
    for a, b in rods:
        adj.setdefault(a, []).append(b)
        adj.setdefault(b, []).append(a)
    seen, loops = set(), 0
    for start in adj:
        if start in seen:
            continue
        loops += 1
        stack = [start]
        while stack:
            v = stack.pop()
            if v not in seen:
                seen.add(v)
                stack.extend(adj[v])
    assert loops == len(freeform.Wires)
    # and the chords add up to the perimeter (within the chord sagitta)
    length = sum(np.linalg.norm(r.vertices[a] - r.vertices[b]) for a, b in rods)
    perimeter = sum(e.Length for e in freeform.Edges)
    assert 0.97 * perimeter < length <= perimeter * (1 + 1e-9)


def test_freeform_area_and_fewer_irregular_than_clipped_iso_grid(freeform):
    bd = run("freeform", freeform, method="boundary_driven", size=SIZE)
    iso = run("freeform", freeform, method="iso_grid", size=SIZE)
    # area of the panel models adds up to the face area (no gap, no overlap)
    assert bd.metrics["panel_area"].sum() == pytest.approx(freeform.Area, rel=0.02)

    def irregular(r):
        count = 0
        for p, area in zip(node_panels(r), r.metrics["panel_area"]):
            if len(p) != 4 or min(corner_angles(r.vertices, p)) < 30 or area < 0.25 * SIZE**2:
                count += 1
        return count

    assert irregular(bd) < 0.5 * irregular(iso)
    lengths_bd = np.linalg.norm(bd.vertices[bd.rods[:, 0]] - bd.vertices[bd.rods[:, 1]], axis=1)
    lengths_iso = np.linalg.norm(iso.vertices[iso.rods[:, 0]] - iso.vertices[iso.rods[:, 1]], axis=1)
    assert lengths_bd.std() / lengths_bd.mean() < lengths_iso.std() / lengths_iso.mean()
    # panels come out near the nominal size
    assert 0.5 * SIZE < np.median(lengths_bd) < 1.5 * SIZE


#: Issue 18 part 3: where an opening comes closer to the outer trim than a
#: panel, the curve network puts panels inside the opening (0.13-0.29% of the
#: face). These runs used to return those panels; the coverage check now
#: refuses them. Strict: the day the network is fixed, these pass and must
#: be un-marked.
#: Refused until stop 54 (panels reaching into an opening near the outer
#: trim); since no rod crosses a trim the mesh is made, but its rods scatter
#: more than the clipped grid's, as at 600 mm.
NARROW_PASSAGE = pytest.mark.xfail(
    strict=True, raises=AssertionError,
    reason="issue 18 part 3: CV above iso_grid's where an opening nears the outer trim")


#: Since stop 52 (a quad's centre that lay in the opening is moved onto the
#: face) cone_facade at 900 mm is no longer refused: it covers the face
#: (0.07% overlap), every corner at 15 degrees or more, but two of its 209
#: panels by the narrow passage are triangles.
TWO_TRIANGLES_AT_THE_PASSAGE = pytest.mark.xfail(
    strict=True, raises=AssertionError,
    reason="issue 18 part 3: two triangles where the opening nears the outer trim")


@pytest.mark.parametrize("name", [pytest.param("cone_facade", marks=TWO_TRIANGLES_AT_THE_PASSAGE),
                                  "notched_shell", "vault_openings"])
def test_examples_quad_mesh_covering_the_face(name):
    face = _load(name)
    r = run(name, face, method="boundary_driven", size=SIZE)
    assert all(len(p) == 4 for p in node_panels(r))
    assert r.metrics["panel_area"].sum() == pytest.approx(face.Area, rel=0.03)
    worst = min(min(corner_angles(r.vertices, p)) for p in node_panels(r))
    assert worst >= 15.0  # issue 4: no corner under 15 deg


@pytest.mark.parametrize(
    "name, size, sharp_without",
    [("vault_openings", 1200.0, True), ("cone_facade", 900.0, True),
     # Its 6.4 deg corner came from a diagonal across a hole's rim; since the
     # quadrangulation cuts no panel across a trim (stop 54) it has no sharp
     # corner even without the relocation.
     ("trimmed_bspline_holes", 1200.0, False)],
)
def test_no_corner_under_15_deg_where_trims_are_closer_than_a_panel(name, size, sharp_without):
    # The worst cases of the benchmark (4.2, 6.6 and 6.4 deg before the
    # angle-aware relocation): an opening closer to the outer trim than a panel.
    face = _load(name)
    without = run(name, face, method="boundary_driven", size=size, angle_target=0.0)
    worst_without = min(min(corner_angles(without.vertices, p)) for p in node_panels(without))
    assert (worst_without < 15.0) == sharp_without, worst_without
    r = run(name, face, method="boundary_driven", size=size)
    angles = [min(corner_angles(r.vertices, p)) for p in node_panels(r)]
    assert min(angles) >= 15.0
    assert sum(len(p) == 4 for p in node_panels(r)) >= 0.95 * len(r.panels)
    assert r.metrics["panel_area"].sum() == pytest.approx(face.Area, rel=0.02)
    # the relocated boundary nodes are still on the trim curves
    nodes = sorted({v for e in boundary_rods(node_panels(r)) for v in e})
    ms = face.BoundBox.DiagonalLength
    worst = max(
        min(e.distToShape(Part.Vertex(FreeCAD.Vector(*r.vertices[v])))[0]
                                    for e in face.Edges)
        for v in nodes
    )
    assert worst < 1e-6 * ms


def _segments_cross(p, q, r, s):
    """Whether segments pq and rs (2D) cross at a point inside both."""
    def orient(a, b, c):
        return (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])
    return (orient(p, q, r) * orient(p, q, s) < 0) and (orient(r, s, p) * orient(r, s, q) < 0)


def self_crossing(outline):
    """The first pair of non-adjacent sides of a closed (u,v) outline that
    cross, or None."""
    n = len(outline)
    lo = outline.min(axis=0) if n else None
    for i in range(n):
        p, q = outline[i], outline[(i + 1) % n]
        for j in range(i + 2, n):
            if i == 0 and j == n - 1:
                continue
            r, s = outline[j], outline[(j + 1) % n]
            if max(p[0], q[0]) < min(r[0], s[0]) or max(r[0], s[0]) < min(p[0], q[0]):
                continue
            if _segments_cross(p - lo, q - lo, r - lo, s - lo):
                return i, j
    return None


# Boundary panels as a workshop cuts them: the whole outline, trim points
# included. Before stop 54 each of these had a panel whose outline crossed
# itself: a rod across a hole's rim (cone_facade at 600 and 900 mm: a
# 336-corner panel folded over the rim; trimmed_bspline_holes at 1200 mm),
# or a trim point 0.2 um from a trim corner (notched_shell at every size, a
# 1 deg spike). And cone_facade at 1200 mm and vault_openings at 1500 mm
# were refused (panels reaching over an opening).
@pytest.mark.parametrize(
    "name, size",
    [("cone_facade", 600.0), ("cone_facade", 900.0), ("cone_facade", 1200.0),
     ("trimmed_bspline_holes", 1200.0), ("notched_shell", 600.0), ("notched_shell", 1500.0),
     ("vault_openings", 1500.0)],
)
def test_boundary_panel_outlines_do_not_cross_themselves_spike_or_repeat_a_point(name, size):
    face = _load(name)
    r = run(name, face, method="boundary_driven", size=size)
    crossing = [(k, c) for k, p in enumerate(r.panels)
                if (c := self_crossing(np.asarray(r.uv)[list(p)])) is not None]
    assert crossing == []
    sides = [np.linalg.norm(r.vertices[list(p)] - r.vertices[list(p[1:]) + [p[0]]], axis=1).min()
             for p in r.panels]
    assert min(sides) > 1e-2  # mm: no side too short to cut
    assert min(min(corner_angles(r.vertices, p)) for p in r.panels) > 5.0
    gap, extra = independent_coverage(face, r)  # the moves left no gap or overlap
    # 3000 samples: a share p is seen within ~3 sqrt(p / 3000); 0.1% reads as < 0.4%.
    assert gap < 4e-3 and extra < 4e-3, (gap, extra)


def _rod_lengths(r):
    xyz = np.asarray(r.vertices)
    return np.array([np.linalg.norm(xyz[a] - xyz[b]) for a, b in r.rods])


@pytest.mark.parametrize("name,size", [
    # Measured on the rods (node to node) rather than on the panel outlines,
    # whose trim segments made the clipped grid's lengths look scattered: at
    # 600 mm the claim does not hold (CV 0.187 against 0.173; issue 18 part 3).
    pytest.param("cone_facade", 600.0, marks=pytest.mark.xfail(
        strict=True, raises=AssertionError, reason="issue 18 part 3: CV above iso_grid's")),
    pytest.param("cone_facade", 1200.0, marks=NARROW_PASSAGE),
    pytest.param("vault_openings", 1200.0, marks=pytest.mark.xfail(
        strict=True, raises=AssertionError, reason="issue 18 part 3: CV above iso_grid's"))])
def test_edge_length_cv_lower_than_clipped_iso_grid(name, size):
    # the runs where big n-gons / long network edges of the coarse curve
    # network used to give rods up to 3.2 x the mean (CV above the iso grid's)
    face = _load(name)
    cv = {}
    for method in ("iso_grid", "boundary_driven"):
        rods = _rod_lengths(run(name, face, method=method, size=size))
        cv[method] = rods.std() / rods.mean()
    assert cv["boundary_driven"] < cv["iso_grid"], cv
    rods = _rod_lengths(run(name, face, method="boundary_driven", size=size))
    assert rods.max() < 3.0 * rods.mean()


def test_stages_curves_stay_inside_and_end_on_the_trim(freeform):
    surface = core.SurfaceFace.from_brep_string(freeform.exportBrepToString())
    p = core.BoundaryDrivenParams()
    p.size = SIZE
    d = core.boundary_driven_stages(surface, p)
    assert len(d["curves_uv"]) > 10
    fs = freeform.Surface
    model = surface.model_size()
    edges = Part.Compound(freeform.Edges)
    tol = max(e.Tolerance for e in freeform.Edges) + 1e-6 * model
    for uv, xyz in zip(d["curves_uv"], d["curves_xyz"]):
        for (u, v), x in zip(uv[:: max(1, len(uv) // 6)], xyz[:: max(1, len(uv) // 6)]):
            assert freeform.isInside(fs.value(u, v), 1e-6 * model, True)
            assert (fs.value(u, v) - FreeCAD.Vector(*x)).Length < 1e-9 * model
    # network nodes flagged as on a trim loop are on the face's edges
    on_loop = [x for x, loop in zip(d["network_xyz"], d["network_loop"]) if loop >= 0]
    for x in on_loop[:: max(1, len(on_loop) // 40)]:
        assert edges.distToShape(Part.Vertex(FreeCAD.Vector(*x)))[0] < tol
    assert len(d["network_panels"]) > 5


def test_source_selection_changes_the_field(freeform):
    all_loops = run("freeform", freeform, method="boundary_driven", size=SIZE)
    outer_only = run("freeform", freeform, method="boundary_driven", size=SIZE, source_loops=[0])
    assert len(outer_only.panels) > 0
    assert len(outer_only.panels) != len(all_loops.panels) or not np.allclose(
        outer_only.vertices, all_loops.vertices)
    # an extra source curve (paper Figure 20): a diagonal line across the face
    surface = core.SurfaceFace.from_brep_string(freeform.exportBrepToString())
    u0, u1, v0, v1 = surface.bounds()
    t = np.linspace(0.35, 0.65, 5)
    curve = np.column_stack([u0 + t * (u1 - u0), v0 + t * (v1 - v0)])
    curve = np.array([c for c in curve if surface.is_inside(*c)])
    extra = tessella.panelize(freeform, method="boundary_driven", size=SIZE, source_loops=[0],
                              extra_curves=[curve])
    assert not np.allclose(extra.vertices[: 20], outer_only.vertices[: 20]) or len(
        extra.panels) != len(outer_only.panels)


@pytest.mark.parametrize(
    "kw, words",
    [
        ({"size": -1.0}, "size"),
        ({"size": SIZE, "rho": 0.0}, "rho"),
        ({"size": SIZE, "skew_ratio": 2.0}, "skew_ratio"),
        ({"size": SIZE, "smoothing_iterations": -3}, "smoothing_iterations"),
        ({"size": SIZE, "angle_target": 100.0}, "angle_target"),
        ({"size": SIZE, "source_loops": [7]}, "source loop index"),
        ({"size": SIZE, "extra_curves": [[[1e9, 1e9], [2e9, 2e9]]]}, "not inside the face"),
        ({"size": SIZE, "extra_curves": [[[0.5, 0.5]]]}, "at least 2"),
        ({"size": 200.0, "max_panels": 100}, "max_panels"),
        ({}, "size"),
    ],
)
def test_bad_parameters_raise_value_error_naming_them(freeform, kw, words):
    with pytest.raises(ValueError, match=words):
        tessella.panelize(freeform, method="boundary_driven", **kw)


def test_cylinder_side_face_with_seam_does_not_crash():
    face = Part.makeCylinder(3000, 6000).Faces[0]
    r = tessella.panelize(face, method="boundary_driven", size=1500.0)
    assert len(r.panels) > 0
    assert r.metrics["panel_area"].sum() == pytest.approx(face.Area, rel=0.05)


def _round_positions(r):
    """How many distinct angles round the z axis the panels' centres take."""
    c = np.array([r.vertices[list(p)].mean(axis=0) for p in r.panels])
    a = np.sort(np.mod(np.arctan2(c[:, 1], c[:, 0]), 2 * math.pi))
    steps = np.diff(np.append(a, a[0] + 2 * math.pi))
    return max(1, int(np.sum(steps > 1e-6)))


def _no_two_panels_in_one_place(r):
    c = np.array([r.vertices[list(p)].mean(axis=0) for p in r.panels])
    d = np.linalg.norm(c[:, None] - c[None], axis=2) + np.eye(len(c)) * 1e9
    return d.min() > 1e-6


@pytest.mark.parametrize("quadrangulate", [True, False])
def test_a_column_at_a_size_beyond_a_third_of_its_girth(quadrangulate):
    # A 300 mm column 3 m high at 500-1500 mm: too few curves went round it,
    # so it was 89-100% unmeshed ("too coarse"), or (not quadrangulated, at
    # 500 mm) two flat panels through its axis in each row, the same in
    # space. Round a closed direction the curves now go at most a half (every
    # cell split in two round it) or a third of a rim apart: four or three
    # panels round, flat rectangles of an inscribed prism.
    radius, height = 150.0, 3000.0
    face = Part.makeCylinder(radius, height).Faces[0]
    for size in (300.0, 500.0, 1500.0):
        r = tessella.panelize(face, method="boundary_driven", size=size,
                              quadrangulate=quadrangulate)
        n = _round_positions(r)
        assert n == (4 if quadrangulate else 3)
        assert all(len(p) == 4 for p in r.panels) and _no_two_panels_in_one_place(r)
        # No panel half way round (corners across a diameter): at 300 mm,
        # quadrangulated, some rows were two such panels.
        assert widest_turn_round_z(r) < 0.99 * math.pi
        # n sides round, each a chord 2 R sin(pi / n) wide, the full height.
        prism = n * 2 * radius * math.sin(math.pi / n) * height
        assert r.metrics["panel_area"].sum() == pytest.approx(prism, rel=1e-6)
        assert r.summary["gap_fraction"] < 1e-6 and r.summary["overlap_fraction"] < 1e-6


@pytest.mark.parametrize("solid, quadrangulate, size", [
    (lambda: Part.makeCone(400, 100, 2000), False, 800.0),  # its smaller rim: 628 mm
    # A ring panel round the top, split across the seam by the boundary
    # pieces: 11.8% uncovered, refused after the method had returned.
    (lambda: Part.makeCone(400, 100, 2000), True, 300.0),
    (lambda: Part.makeSphere(500, FreeCAD.Vector(), FreeCAD.Vector(0, 0, 1), 0, 90),
     True, 800.0),  # a dome: two curves round met at the apex in one line
])
def test_closed_faces_coarser_than_their_rims(solid, quadrangulate, size):
    face = solid().Faces[0]
    r = tessella.panelize(face, method="boundary_driven", size=size,
                          quadrangulate=quadrangulate)
    assert r.summary["gap_fraction"] < 1e-3 and r.summary["overlap_fraction"] < 1e-3
    assert _round_positions(r) >= 3 and _no_two_panels_in_one_place(r)
    assert widest_turn_round_z(r) < 0.99 * math.pi  # no panel half way round
    worst = max(face.distToShape(Part.Vertex(FreeCAD.Vector(*p)))[0] for p in r.vertices)
    assert worst < 1e-6 * face.BoundBox.DiagonalLength
    # Flat panels on the convex face: less area than it, but not much less.
    assert 0.75 < r.metrics["panel_area"].sum() / face.Area < 1.0


def _seam_nodes_on_both_sides(r, on_seam, across):
    """Every node on the seam is a corner of panels on both of its sides
    (`across`: the coordinate whose sign tells them apart): no T-junction,
    the other side's nodes are in each panel side along it."""
    seam = [int(k) for k in r.nodes if on_seam(r.vertices[k])]
    for k in seam:
        sides = [float(np.mean(r.vertices[list(map(int, p))][:, across]))
                 for p in r.panels if k in p]
        assert min(sides) < 0 < max(sides), (k, r.vertices[k])
    return seam


@pytest.mark.parametrize("method", ["boundary_driven", "iso_grid"])
def test_a_band_closed_on_itself_but_not_periodic(method):
    # A B-spline band interpolated round a circle, its last row the first
    # (closed, not periodic: OCCT's Pump_TopCover has such a face): its
    # seam edge is met from both sides, and boundary_driven put each side's
    # node at each crossing (three pairs 1e-13 mm apart) and left the other
    # side's between them out of its panel sides. Joined as a periodic
    # face's seam is.
    from FreeCAD import Vector
    rows = []
    for k in range(13):
        a = 2 * math.pi * (k % 12) / 12
        rows.append([Vector(1000 * math.cos(a), 1000 * math.sin(a), z)
                     for z in (0, 500, 1000, 1500)])
    surface = Part.BSplineSurface()
    surface.interpolate(rows)
    assert surface.isUClosed() and not surface.isUPeriodic()
    face = Part.Face(surface)
    r = tessella.panelize(face, method=method, size=400.0)
    assert not close_node_pairs(r.vertices[r.nodes], 1e-6 * face.BoundBox.DiagonalLength)
    seam = _seam_nodes_on_both_sides(r, lambda x: abs(x[1]) < 1e-6 and x[0] > 999.999, 1)
    assert len(seam) >= 3
    # Flat panels on a band of radius 1000 at 400 mm: a little under the area.
    assert r.metrics["panel_area"].sum() / face.Area == pytest.approx(0.995, abs=0.005)
    assert r.summary["gap_fraction"] < 1e-6 and r.summary["overlap_fraction"] < 1e-6


@pytest.mark.parametrize("method", ["boundary_driven", "iso_grid"])
def test_a_face_on_a_trimmed_periodic_surface_keeps_its_seam(method):
    # A face whose surface is a rectangular trim of a cone, one whole turn
    # (a face set sews OCCT's CrankArm.brep into such faces): the same points
    # at the same (u,v), but OCCT calls the trim not periodic, so the seam
    # was read as two sides of the face (in the set, boundary_driven's nodes
    # twice along it). Its basis is periodic, and so is the face.
    cone = Part.Cone(FreeCAD.Vector(0, 0, 0), FreeCAD.Vector(0, 0, 1500), 1200, 800)
    slant = math.hypot(1500, 400)  # v runs along the cone's lines
    face = Part.Face(Part.RectangularTrimmedSurface(cone, 0, 2 * math.pi, 0, slant))
    # The B-rep keeps the trim (surface type 10 in OCCT's BRep format).
    brep = face.exportBrepToString()
    surfaces = brep.split("Surfaces", 1)[1].splitlines()[1:3]
    assert surfaces[0].startswith("10 "), surfaces
    assert core.SurfaceFace.from_brep_string(brep).u_periodic
    r = tessella.panelize(face, method=method, size=300.0)
    assert not close_node_pairs(r.vertices[r.nodes], 1e-6 * face.BoundBox.DiagonalLength)
    # The seam is the cone's line at u = 0 (x = 0, y < 0).
    seam0 = cone.value(0, 0)
    seam = _seam_nodes_on_both_sides(
        r, lambda x: abs(x[0] - seam0.x) < 1e-6 and x[1] < -700, 0)
    assert len(seam) >= 3
    assert r.summary["gap_fraction"] < 1e-6 and r.summary["overlap_fraction"] < 1e-6


def _closed_band_with_an_apex(kind):
    """A surface round the z axis up to an apex, closed on itself along u
    (its last row of poles its first) and not periodic, its two sides
    meeting at a crease: an interpolated B-spline (read as periodic, the
    crease inside the face) or a Bezier surface (no periodic form: its seam
    is joined after the method)."""
    from FreeCAD import Vector
    radii = ((1000, 0), (700, 500), (350, 1000), (0, 1500))
    if kind in ("bspline", "pointed"):
        # A teardrop section, pointed at the seam (a crease of 5 or 35 deg).
        point = 0.1 if kind == "bspline" else 0.4
        rows = [[Vector(r * (1 - point + point * abs(math.sin(a / 2))) * math.cos(a),
                        r * (1 - point + point * abs(math.sin(a / 2))) * math.sin(a), z)
                 for r, z in radii]
                for a in (2 * math.pi * (k % 12) / 12 for k in range(13))]
        surface = Part.BSplineSurface()
        surface.interpolate(rows)
    else:
        surface = Part.BezierSurface()
        surface.increase(8, len(radii) - 1)
        for i in range(9):
            a = 2 * math.pi * (i % 8) / 8
            for j, (r, z) in enumerate(radii):
                surface.setPole(i + 1, j + 1, Vector(r * math.cos(a), r * math.sin(a), z))
    assert surface.isUClosed() and not surface.isUPeriodic()
    return Part.Face(surface)


@pytest.mark.parametrize("kind", ["bspline", "pointed", "bezier"])
@pytest.mark.parametrize("method", ["boundary_driven", "iso_grid"])
def test_a_band_closed_on_itself_up_to_an_apex(method, kind):
    # boundary_driven left T-junctions along the seam of such a face (nodes
    # of one side missing from the other side's panel sides): the join of
    # the two sides was kept from faces with a pole at an end of the seam.
    # A B-spline is now read as periodic (the same points at the same
    # (u,v)); a Bezier surface's seam is joined, pole and all. Before, the
    # grids also left 0.24% of the pointed one uncovered (refused).
    face = _closed_band_with_an_apex(kind)
    surface = face.Surface
    u0, u1, v0, v1 = surface.bounds()
    assert surface.normal(u0, 0.5 * (v0 + v1)).getAngle(
        surface.normal(u1, 0.5 * (v0 + v1))) > 0.05  # a crease (3 degrees)
    assert core.SurfaceFace.from_brep_string(face.exportBrepToString()).u_periodic() == (
        kind != "bezier")
    for size in (150.0, 300.0):
        r = tessella.panelize(face, method=method, size=size)
        assert not close_node_pairs(r.vertices[r.nodes], 1e-6 * face.BoundBox.DiagonalLength)
        seam = _seam_nodes_on_both_sides(
            r, lambda x: abs(x[1]) < 1e-6 and x[0] > 1e-3, 1)
        assert len(seam) >= 4
        assert r.summary["gap_fraction"] < 1e-3 and r.summary["overlap_fraction"] < 1e-3
        # Flat panels on a convex face: a little under its area.
        assert 0.95 < r.metrics["panel_area"].sum() / face.Area < 1.0


@pytest.mark.parametrize("method", ["boundary_driven", "iso_grid", "walking_agent"])
def test_a_closed_bspline_not_marked_periodic_meshes_as_its_periodic_twin(method):
    # The same NURBS surface of revolution, periodic and not (setUNotPeriodic
    # keeps its points: its last row of poles repeats its first). Read as
    # periodic, the second gives the first's panels. Before, boundary_driven
    # traced curves from its seam (two sides of the face) and the grids put
    # a node on each side.
    from FreeCAD import Vector
    profile = Part.BSplineCurve()
    profile.interpolate([Vector(r, 0, z) for r, z in ((1000, 0), (700, 500), (350, 1000),
                                                      (0, 1500))])
    revolution = Part.SurfaceOfRevolution(profile, Vector(0, 0, 0), Vector(0, 0, 1))
    periodic = revolution.toShape().toNurbs().Faces[0].Surface
    assert periodic.isUPeriodic()
    closed = periodic.copy()
    closed.setUNotPeriodic()
    assert closed.isUClosed() and not closed.isUPeriodic()
    assert core.SurfaceFace.from_brep_string(Part.Face(closed).exportBrepToString()).u_periodic()
    kw = {"max_size": 300.0, "max_deviation": 10.0} if method == "walking_agent" else {
        "size": 300.0}
    a = tessella.panelize(Part.Face(periodic), method=method, **kw)
    b = tessella.panelize(Part.Face(closed), method=method, **kw)
    assert not close_node_pairs(b.vertices[b.nodes], 1e-6 * 3000)
    if method == "boundary_driven":
        # setUNotPeriodic moves the surface by up to 2e-5 mm, and
        # boundary_driven's smoothing carries such differences into its
        # interior nodes: the same layout, compared by its counts.
        assert len(b.panels) == len(a.panels)
        assert sorted(map(len, b.panels)) == sorted(map(len, a.panels))
        return
    assert [list(p) for p in a.panels] == [list(p) for p in b.panels]
    assert np.abs(a.vertices - b.vertices).max() < 1e-5


@pytest.mark.parametrize("nurbs", [False, True])
@pytest.mark.parametrize("radius, height, size", [(400.0, 1200.0, 63.0), (400.0, 1200.0, 126.0),
                                                  (400.0, 1200.0, 251.0), (300.0, 3000.0, 94.0),
                                                  (300.0, 3000.0, 188.0)])
def test_a_cone_with_its_apex(radius, height, size, nurbs):
    # A cone up to its apex (1:3, and a 1:10 spire): the curves from the
    # rim converged and joined each other until one or two went on, so the
    # cells near the top went round it as rings ("a panel goes half way
    # round", every size refused; 4.3% uncovered when the check was off).
    # Now lines keep an eighth of the girth apart where that is less than
    # their stop distance, at least three curves leave the apex (a fan of
    # panels round it), and no short edge's collapse widens a cell round
    # the spire past 0.3 of a turn (the spire's last lines are closer than
    # the collapse length).
    face = [f for f in Part.makeCone(radius, 0, height).Faces
            if f.Surface.__class__.__name__ == "Cone"][0]
    if nurbs:
        face = face.toNurbs().Faces[0]
    r = tessella.panelize(face, method="boundary_driven", size=size)
    assert r.summary["gap_fraction"] < 1e-3 and r.summary["overlap_fraction"] < 1e-3
    assert widest_turn_round_z(r) < 0.99 * math.pi
    worst = max(face.distToShape(Part.Vertex(FreeCAD.Vector(*p)))[0] for p in r.vertices)
    assert worst < 1e-6 * face.BoundBox.DiagonalLength
    apex = [int(v) for v in r.nodes
            if np.linalg.norm(r.vertices[v] - np.array([0, 0, height])) < 1e-6 * height]
    assert len(apex) == 1
    assert sum(apex[0] in set(map(int, p)) for p in r.panels) >= 3
    assert 0.75 < r.metrics["panel_area"].sum() / face.Area < 1.0


def test_too_coarse_a_size_is_a_clear_error_not_a_wrong_mesh():
    face = _load("vault_openings")
    with pytest.raises(RuntimeError, match="too coarse") as err:
        tessella.panelize(face, method="boundary_driven", size=math.sqrt(face.Area / 30))
    # The message names a size that works, and it does.
    import re
    works = re.search(r"size ([0-9.e+-]+) mm works", str(err.value))
    assert works, str(err.value)
    size = float(works.group(1))
    assert size < math.sqrt(face.Area / 30)
    r = tessella.panelize(face, method="boundary_driven", size=size)
    assert len(r.panels) > 0


def test_panelization_document_object_with_boundary_driven(freeform):
    from freecad_workbench.features import panelization as feat

    doc = FreeCAD.newDocument("TessellaBdTest")
    try:
        src = doc.addObject("Part::Feature", "Src")
        src.Shape = freeform
        doc.recompute()
        obj = tessella.make_panelization((src, "Face1"), method="boundary_driven", size=SIZE,
                                         smoothing_iterations=12)
        assert obj.SmoothingIterations == 12
        for name in feat.BD_PROPERTIES:
            assert name in obj.PropertiesList
        assert obj.getEditorMode("Rho") == [] and obj.getEditorMode("UCount") == ["Hidden"]
        doc.recompute()
        assert obj.PanelCount > 50
        assert obj.QuadShare == pytest.approx(1.0)  # four nodes each (trim outline points aside)
        first = obj.PanelCount
        obj.SourceLoops = [0]
        # (Rho 3 with the outer loop alone leaves 2.5% of this face uncovered:
        # refused by the coverage check since issue 18, see the xfail cases.)
        obj.Rho = 2.5
        doc.recompute()
        res = obj.Proxy.result(obj).result
        assert res.params["source_loops"] == [0] and res.params["rho"] == 2.5
        assert obj.PanelCount > 0
        assert first > 0
        panels = feat.children_of(obj)[0]
        # one shape per panel (a bent boundary panel is a shell of its pieces)
        assert len(panels.Shape.childShapes()) == obj.PanelCount
    finally:
        FreeCAD.closeDocument(doc.Name)


def test_curve_network_object_shows_the_traced_curves(freeform):
    doc = FreeCAD.newDocument("TessellaBdCurves")
    try:
        src = doc.addObject("Part::Feature", "Src")
        src.Shape = freeform
        doc.recompute()
        par = tessella.make_panelization((src, "Face1"), method="boundary_driven", size=SIZE)
        net = tessella.make_curve_network(par)
        stages = tessella.boundary_driven_stages(freeform, size=SIZE)
        assert net.CurveCount == len(stages["curves_xyz"]) > 10
        assert len(net.Shape.Edges) > 0
        # every curve vertex lies on the face (FreeCAD's own distance)
        for v in net.Shape.Vertexes[:: max(1, len(net.Shape.Vertexes) // 50)]:
            assert freeform.distToShape(v)[0] < 1e-6 * freeform.BoundBox.DiagonalLength
        net.Show = "Network"
        doc.recompute()
        assert len(net.Shape.Edges) == len(stages["network_edges"])
        iso = tessella.make_panelization((src, "Face1"), method="iso_grid", size=SIZE)
        with pytest.raises(ValueError, match="not boundary_driven"):
            tessella.make_curve_network(iso)
    finally:
        FreeCAD.closeDocument(doc.Name)


def _coverage_holds(r, face):
    """No gap and no overlap: re-measured independently (FreeCAD's trim test,
    random points, conftest.independent_coverage), within the sampling's
    resolution. The flat panels' area is the face's less what their chords
    cut off: at least 2 panels span the 90 deg arc, sin(pi/8) / (pi/8) =
    0.974 of it."""
    gap, extra = independent_coverage(face, r)
    assert gap <= 2e-3 and extra <= 2e-3, (gap, extra)
    assert 0.97 * face.Area <= r.metrics["panel_area"].sum() <= face.Area * (1 + 1e-9)


@pytest.mark.parametrize("scale", [1.0, 1000.0])
def test_strip_narrower_than_a_panel(scale):
    """A quarter-cylinder fillet 63 x 6,270 (x scale) wide, at a size 1.7 x
    its width: the curves across the strip are shorter than the shortest
    edge kept, and their two trim ends, on one loop but 6 km apart along it,
    used to be merged, pinching the strip to 6 panels (0.45 of its area)."""
    face = Part.makeCylinder(0.04 * scale, 6.27 * scale, FreeCAD.Vector(), FreeCAD.Vector(0, 0, 1),
                             90).Faces[0]
    size = math.sqrt(face.Area) / 6
    assert size > 0.0628 * scale
    r = tessella.panelize(face, method="boundary_driven", size=size)
    _coverage_holds(r, face)
    assert len(r.panels) >= 6.27 / (2 * size / scale)


def test_node_one_ulp_short_of_a_trim_vertex_keeps_its_trim_edge():
    """A 0.015 mm fillet (an SMD part from FreeCAD's test files): a curve end's
    arc length one ulp short of the trim polyline's vertex it stands on gave
    its trim edge a zero direction; the edge was dropped and with it a panel
    (0.7% of the face uncovered)."""
    face = Part.makeCylinder(0.015, 0.8, FreeCAD.Vector(0, 0, -1.2), FreeCAD.Vector(0, 0, 1),
                             90).Faces[0]
    for d in (12, 24):
        r = tessella.panelize(face, method="boundary_driven", size=math.sqrt(face.Area) / d)
        _coverage_holds(r, face)


@pytest.mark.parametrize("solid, size", [
    (lambda: Part.makeCylinder(3000.0, 5000.0), 391.0),
    (lambda: Part.makeCylinder(800.0, 2600.0), 150.0),
    (lambda: Part.makeCone(2000.0, 800.0, 3000.0), 300.0),
    (lambda: Part.makeCone(500.0, 1500.0, 2000.0), 180.0)])
def test_closed_periodic_face_has_one_node_per_seam_position(solid, size):
    """A full cylinder or cone side (built here; its seam inside the face) is
    traced from both sides of the seam: each seam node once and shared by the
    panels of both sides, as the grids have it (the cylinder had three twins
    at 0, 1/2 and 1 of the height, and T-junctions between them; on a cone a
    panel was cut along the seam, a rounding beside its points, and lost
    them)."""
    side = max(solid().Faces, key=lambda f: f.Area)
    r = tessella.panelize(side, method="boundary_driven", size=size)
    assert not close_node_pairs(r.vertices[r.nodes], 1e-6 * side.BoundBox.DiagonalLength)
    # The seam's nodes are shared by the panels on both sides of it.
    seam = [v for v in r.nodes if abs(r.vertices[v][1]) < 1e-6 and r.vertices[v][0] > 0]
    assert len(seam) >= 3
    for v in seam:
        around = [p for p in r.panels if v in p]
        xs = [x for p in around for x in r.vertices[list(p)][:, 1]]
        assert min(xs) < -1.0 and max(xs) > 1.0  # panels on both sides
    assert abs(r.metrics["panel_area"].sum() / side.Area - 1) < 1e-2


def _dome_faces():
    hemisphere = Part.makeSphere(10000.0, FreeCAD.Vector(), FreeCAD.Vector(0, 0, 1), 0, 90, 360)
    cap = Part.makeSphere(10000.0, FreeCAD.Vector(), FreeCAD.Vector(0, 0, 1), 40, 90, 360)
    profile = Part.BSplineCurve()
    profile.interpolate([FreeCAD.Vector(10000, 0, 0), FreeCAD.Vector(8000, 0, 5000),
                         FreeCAD.Vector(0, 0, 7000)])
    revolved = profile.toShape().revolve(FreeCAD.Vector(), FreeCAD.Vector(0, 0, 1), 360)
    return {"hemisphere": hemisphere.Faces[0], "cap": cap.Faces[0], "revolved": revolved.Faces[0]}


@pytest.mark.parametrize("name", ["hemisphere", "cap", "revolved"])
@pytest.mark.parametrize("size", [1000.0, 2000.0])
def test_dome_with_an_apex_is_panelized_with_one_apex_node(name, size):
    """A dome whose surface closes at an apex (a pole: a trim edge collapsed to
    one point) failed at every size ("the panels cover 0.92-0.96 of the
    face's (u,v) region"): every curve reaching the apex was joined to one
    (u,v) of it, so the network crossed the whole parameter range. Now each
    curve ends at the apex straight across the collapsed edge and the apex is
    one node, shared by the panels around it, none a sliver."""
    face = _dome_faces()[name]
    apex = [e.Vertexes[0].Point for e in face.Edges if e.Degenerated]
    assert len(apex) == 1
    r = tessella.panelize(face, method="boundary_driven", size=size)
    v = np.asarray(r.vertices)
    at_apex = np.flatnonzero(np.linalg.norm(v - np.array(apex[0]), axis=1) < 1e-6 * size)
    assert len(at_apex) == 1
    around = [p for p in r.panels if at_apex[0] in p]
    assert 3 <= len(around) <= 20
    for p in around:
        assert len(set(p)) == len(p) >= 3
    # Every vertex on the surface (FreeCAD's own projection).
    surf = face.Surface
    for x in v[:: max(1, len(v) // 300)]:
        u, w = surf.parameter(FreeCAD.Vector(*x))
        assert (surf.value(u, w) - FreeCAD.Vector(*x)).Length < 1e-6 * size
    # No rod collapsed at the apex (the old fan of slivers had 24 mm rods).
    rods = np.asarray(r.rods)
    lengths = np.linalg.norm(v[rods[:, 0]] - v[rods[:, 1]], axis=1)
    assert lengths.min() > 0.1 * size
    # The flat panels add up to the dome's area less their sag.
    assert 0.97 < r.metrics["panel_area"].sum() / face.Area < 1.005


def _corner_angles(r):
    """Every corner angle of every panel (deg), from the vertices in 3D."""
    v = np.asarray(r.vertices)
    out = []
    for p in r.panels:
        q = v[list(p)]
        for k in range(len(q)):
            a, b = q[k - 1] - q[k], q[(k + 1) % len(q)] - q[k]
            c = np.dot(a, b) / (np.linalg.norm(a) * np.linalg.norm(b))
            out.append(math.degrees(math.acos(max(-1.0, min(1.0, c)))))
    return np.array(out)


@pytest.mark.parametrize("name, size, longest, sharpest", [
    ("cylinder", 700.0, 1.1, 80.0),
    ("cylinder", 1500.0, 1.1, 80.0),
    ("hemisphere", 700.0, 2.0, 15.0),
    ("hemisphere", 1500.0, 2.0, 15.0),
    ("revolved", 1500.0, 2.0, 15.0)])
def test_no_long_thin_panels_beside_the_seam(name, size, longest, sharpest):
    """On a face closed round its period the seam is no edge of the surface.
    It was a source of the direction field (the rows beside it bent along it)
    and curves stopped half a spacing short of it, near their own start
    across it in 3D: the strip beside the seam had rods up to 15 x the size
    (a 10.5 m rod on a hemisphere at 700 mm) and corners of 2-5 deg. Now a
    cylinder is a regular grid and a dome has rings and meridians."""
    faces = dict(_dome_faces())
    faces["cylinder"] = Part.makeCylinder(5000.0, 12000.0).Faces[0]
    face = faces[name]
    r = tessella.panelize(face, method="boundary_driven", size=size)
    v = np.asarray(r.vertices)
    rods = np.asarray(r.rods)
    lengths = np.linalg.norm(v[rods[:, 0]] - v[rods[:, 1]], axis=1)
    assert lengths.max() <= longest * size
    assert _corner_angles(r).min() >= sharpest


def _square_with_hole(hole_from_second_arc, outer_from):
    """A 12 x 9 m plate with a round opening, its wires listed from another
    edge each time (the same edges and vertices)."""
    V = FreeCAD.Vector
    corners = [V(0, 0, 0), V(12000, 0, 0), V(12000, 9000, 0), V(0, 9000, 0)]
    sides = [Part.LineSegment(corners[i], corners[(i + 1) % 4]).toShape() for i in range(4)]
    sides = sides[outer_from:] + sides[:outer_from]
    circle = Part.Circle(V(5000, 4000, 0), V(0, 0, 1), 1800)
    arcs = [Part.ArcOfCircle(circle, 0.3, 0.3 + math.pi).toShape(),
            Part.ArcOfCircle(circle, 0.3 + math.pi, 0.3 + 2 * math.pi).toShape()]
    if hole_from_second_arc:
        arcs = arcs[::-1]
    return Part.Face([Part.Wire(sides), Part.Wire(arcs)])


def test_layout_does_not_depend_on_how_the_wires_are_listed():
    """The curves are seeded along each loop from its start: a start taken
    from the B-rep's wire order gave the British Museum roof as read and as
    united from its four sub-surfaces 2,650 and 2,679 panels. Each loop now
    starts at its vertex of least (u, v)."""
    a = _square_with_hole(False, 0)
    b = _square_with_hole(True, 2)
    assert abs(a.Area - b.Area) < 1e-6 * a.Area
    assert [e.Vertexes[0].Point for e in a.Wires[1].Edges] != \
        [e.Vertexes[0].Point for e in b.Wires[1].Edges]  # listed differently indeed
    ra = tessella.panelize(a, method="boundary_driven", size=1000.0)
    rb = tessella.panelize(b, method="boundary_driven", size=1000.0)
    assert ra.panels == rb.panels
    assert np.allclose(ra.vertices, rb.vertices, atol=1e-6)
    # The roof as read and the roof united again from its four sub-surfaces.
    roof = _load("british_museum_roof")
    split = Part.Shape()
    split.read(os.path.join(REPO, "examples", "face_sets", "british_museum_roof_split.brep"))
    united = Part.Shell(split.Faces).removeSplitter().Faces[0]
    r1 = tessella.panelize(roof, method="boundary_driven", size=4000.0)
    r2 = tessella.panelize(united, method="boundary_driven", size=4000.0)
    assert len(r1.panels) == len(r2.panels)
    assert np.allclose(np.sort(r1.metrics["rod_length"]), np.sort(r2.metrics["rod_length"]),
                       rtol=1e-6)
