"""Panel families (issue 17): closed-form cases, known templates, the tolerance
checked independently (numpy Kabsch written here), determinism, bad parameters,
and the Panels properties in a document (recompute, save and reopen)."""

import os
import sys

import pytest

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
for _p in ("/usr/lib/freecad-python3/lib", REPO):
    if _p not in sys.path:
        sys.path.append(_p)

import FreeCAD  # noqa: E402  (before Part, or Part segfaults)
import Part  # noqa: E402
import numpy as np  # noqa: E402

import freecad_workbench as tessella  # noqa: E402
from freecad_workbench import families  # noqa: E402

V = FreeCAD.Vector


# ------------------------------------------------------------ independent check
def kabsch_max(a, b, reflect):
    """Largest corner distance after the least-squares alignment of b onto a
    (rotation, or any orthogonal map with `reflect`), corners in given order."""
    a0, b0 = a - a.mean(axis=0), b - b.mean(axis=0)
    u, _s, vt = np.linalg.svd(b0.T @ a0)
    r = vt.T @ u.T
    if not reflect and np.linalg.det(r) < 0:
        vt[2] *= -1
        r = vt.T @ u.T
    return float(np.linalg.norm(b0 @ r.T - a0, axis=1).max())


def best_alignment(a, b, mirror):
    """Least kabsch_max over the corner correspondences: cyclic shifts of b, and
    with `mirror` the shifts of its reversed order (reflections allowed)."""
    if len(a) != len(b):
        return np.inf
    orders = [b] + ([b[::-1]] if mirror else [])
    return min(kabsch_max(a, np.roll(o, -s, axis=0), mirror) for o in orders for s in range(len(b)))


def check_tolerance(corners, fam, tol):
    """Every panel within tol of its family's template, measured here."""
    for k, c in enumerate(corners):
        t = fam.templates[fam.labels[k]]
        d = best_alignment(corners[t], c, fam.mirror)
        assert d <= tol + 1e-9, f"panel {k}: {d} mm from its template {t}"
        assert d >= fam.error[k] - 1e-9  # the core reports the best it found
    for f in range(fam.count):
        assert fam.labels[fam.templates[f]] == f
        assert fam.max_error[f] == pytest.approx(fam.error[fam.labels == f].max(), abs=1e-12)


def same_partition(labels, groups):
    """Whether two labellings split the items the same way."""
    pairs = set(zip(np.asarray(labels).tolist(), np.asarray(groups).tolist()))
    return len(pairs) == len(set(labels)) == len(set(groups))


def rows_by_height(result):
    """The row (parallel) of each panel of a surface of revolution about z:
    panels whose corners' mean height agrees are one row."""
    z = np.array([result.vertices[list(p)][:, 2].mean() for p in result.panels])
    return np.unique(np.round(z, 3), return_inverse=True)[1]


def sphere_zone(angle=360):
    """Zone of a 10 m sphere between 10 and 70 degrees of latitude (doubly curved)."""
    return Part.makeSphere(10000, V(0, 0, 0), V(0, 0, 1), 10, 70, angle).Faces[0]


def cone_band():
    """A 2.5 rad band of a cone, as a B-spline line revolved about z."""
    line = Part.LineSegment(V(12000, 0, 0), V(5000, 0, 7000)).toBSpline()
    surf = Part.SurfaceOfRevolution(line, V(0, 0, 0), V(0, 0, 1))
    return surf.toShape(0, 2.5, line.FirstParameter, line.LastParameter)


def bspline_face():
    """A doubly curved 9000 x 7500 mm cubic B-spline patch."""
    heights = [[0, 700, 700, 0], [500, 1800, 1600, 400], [400, 1500, 1900, 600], [0, 600, 800, 100]]
    poles = [[V(3000.0 * i, 2500.0 * j, heights[i][j]) for j in range(4)] for i in range(4)]
    surf = Part.BSplineSurface()
    surf.buildFromPolesMultsKnots(poles, [4, 4], [4, 4], [0.0, 1.0], [0.0, 1.0], False, False, 3, 3)
    return surf.toShape()


# ------------------------------------------------------------------ closed form
@pytest.mark.parametrize("face_of, counts", [
    (lambda: sphere_zone(360), (24, 8)), (lambda: sphere_zone(150), (30, 10)),
    (cone_band, (20, 7))])
@pytest.mark.parametrize("mirror", [True, False])
def test_rows_of_a_surface_of_revolution_are_the_families(face_of, counts, mirror):
    u, v = counts
    r = tessella.panelize(face_of(), method="iso_grid", u_count=u, v_count=v)
    assert len(r.panels) == u * v
    rows = rows_by_height(r)
    assert rows.max() + 1 == v
    fam = tessella.panel_families(r, family_tolerance=2.0, mirror=mirror)
    assert fam.count == v
    assert same_partition(fam.labels, rows)
    assert list(fam.counts) == [u] * v
    s = fam.summary()
    assert (s["families"], s["largest_family"], s["mean_panels_per_family"]) == (v, u, u)
    check_tolerance(families.panel_corners(r), fam, 2.0)
    assert fam.error.max() < 1e-6  # turned copies: congruent


# ------------------------------------------------------------ known templates
def _random_rotation(rng):
    q, r = np.linalg.qr(rng.normal(size=(3, 3)))
    q = q * np.sign(np.diag(r))
    return q if np.linalg.det(q) > 0 else -q


def _templates():
    return [
        np.array([[0, 0, 0], [1000, 0, 0], [1100, 800, 120], [-50, 900, -60]], float),
        np.array([[0, 0, 0], [1500, 0, 0], [1500, 1500, 0], [0, 1500, 0]], float),
        np.array([[0, 0, 0], [1400, 0, 0], [1300, 1200, 50], [100, 1250, 0]], float),
        np.array([[0, 0, 0], [1500, 0, 0], [700, 1300, 0]], float),
        np.array([[0, 0, 0], [900, -100, 0], [1300, 500, 80], [800, 1100, 0], [-100, 700, 40]], float),
    ]


def _moved_copies(rng, copies, push):
    """Copies of each template, turned, moved, listed from another corner and
    with every corner coordinate pushed by up to `push` mm."""
    corners, group = [], []
    for c in range(copies):
        for t, tpl in enumerate(_templates()):
            p = tpl + rng.uniform(-push, push, size=tpl.shape)
            p = np.roll(p, -(c % len(p)), axis=0) @ _random_rotation(rng).T + rng.uniform(-3e4, 3e4, 3)
            corners.append(p)
            group.append(t)
    return corners, np.array(group)


@pytest.mark.parametrize("mirror", [True, False])
def test_moved_copies_cluster_into_exactly_their_templates(mirror):
    rng = np.random.default_rng(17)
    corners, group = _moved_copies(rng, copies=30, push=0.25)
    tol = 2.0
    fam = families.families_of_corners(corners, tol, mirror)
    assert fam.count == len(_templates())
    assert list(fam.labels) == list(group)  # numbered by lowest panel: copy 0 is 0..4
    check_tolerance(corners, fam, tol)
    # Pushed by up to 0.25 mm per coordinate: two copies differ by at most
    # 2 x 0.25 x sqrt(3) at a corner under the known alignment.
    assert fam.error.max() <= 2 * 0.25 * np.sqrt(3) + 1e-9


def test_mirror_images_join_only_with_mirror():
    tpl = _templates()[0]
    mirrored = tpl * np.array([-1.0, 1.0, 1.0])
    turned = np.roll(mirrored, 1, axis=0) @ _random_rotation(np.random.default_rng(1)).T + 100.0
    corners = [tpl, mirrored, turned]
    assert list(families.families_of_corners(corners, 1.0, True).labels) == [0, 0, 0]
    assert list(families.families_of_corners(corners, 1.0, False).labels) == [0, 1, 1]
    assert best_alignment(tpl, mirrored, False) > 50.0
    # The same corners listed the other way round: the panel turned over
    # (front and back swapped), a match only with mirror.
    assert list(families.families_of_corners([tpl, tpl[::-1]], 1.0, True).labels) == [0, 0]
    assert list(families.families_of_corners([tpl, tpl[::-1]], 1.0, False).labels) == [0, 1]


# ---------------------------------------------------- a doubly curved surface
@pytest.mark.parametrize("tol", [0.5, 2.0, 10.0, 50.0])
def test_tolerance_holds_for_every_panel_of_a_doubly_curved_face(tol):
    r = tessella.panelize(bspline_face(), method="iso_grid", size=1000.0)
    fam = tessella.panel_families(r, family_tolerance=tol)
    corners = families.panel_corners(r)
    check_tolerance(corners, fam, tol)
    assert fam.count <= len(r.panels)
    # A template is a member of its own family, with no error.
    assert all(fam.error[t] == 0.0 for t in fam.templates)


def test_families_shrink_as_the_tolerance_grows():
    r = tessella.panelize(bspline_face(), method="iso_grid", size=1000.0)
    counts = [tessella.panel_families(r, tol).count for tol in (1e-3, 1.0, 5.0, 20.0, 100.0)]
    assert counts == sorted(counts, reverse=True)
    assert counts[-1] < counts[0]


def test_deterministic():
    r = tessella.panelize(bspline_face(), method="iso_grid", size=700.0)
    a = tessella.panel_families(r, 5.0)
    b = tessella.panel_families(r, 5.0)
    assert np.array_equal(a.labels, b.labels) and np.array_equal(a.templates, b.templates)
    assert a.error.tobytes() == b.error.tobytes()  # bit for bit
    assert a.max_error.tobytes() == b.max_error.tobytes()


@pytest.mark.parametrize("bad", [0, -1.0, float("nan"), float("inf"), "two"])
def test_bad_tolerance_is_a_clear_error(bad):
    r = tessella.panelize(cone_band(), method="iso_grid", u_count=4, v_count=2)
    with pytest.raises(ValueError, match="family_tolerance"):
        tessella.panel_families(r, family_tolerance=bad)


def test_bad_panels_are_clear_errors():
    ok = np.eye(3)
    with pytest.raises(ValueError, match="panel 1 has 2 corners"):
        families.families_of_corners([ok, ok[:2]], 1.0)
    with pytest.raises(ValueError, match="non-finite"):
        families.families_of_corners([ok, np.array([[0, 0, 0], [1, 0, 0], [np.nan, 1, 0]])], 1.0)
    with pytest.raises(ValueError, match=r"\(N, 3\)"):
        families.families_of_corners([np.zeros((4, 2))], 1.0)


# ------------------------------------------------------------------ document
@pytest.fixture
def doc():
    d = FreeCAD.newDocument("TessellaFamilies")
    name = d.Name
    yield d
    if name in FreeCAD.listDocuments():
        FreeCAD.closeDocument(name)


def _panels_of(parent):
    from freecad_workbench.features import panelization as feat

    return [k for k in feat.children_of(parent) if k.Role == "Panels"][0]


def test_panels_family_properties_recompute_save_and_reopen(doc, tmp_path):
    from freecad_workbench import analysis_colors

    src = doc.addObject("Part::Feature", "Zone")
    src.Shape = sphere_zone(150)
    doc.recompute()
    p = tessella.make_panelization((src, "Face1"), method="iso_grid", u_count=18, v_count=6)
    doc.recompute()
    panels = _panels_of(p)
    # Off by default: nothing computed.
    assert panels.FamilyTolerance.Value == 0.0 and panels.Mirror is True
    assert list(panels.PanelFamily) == [] and panels.FamilyCount == 0
    panels.FamilyTolerance = 2.0
    doc.recompute()
    res = p.Proxy.result(p).result
    rows = rows_by_height(res)
    assert panels.FamilyCount == 6
    assert same_partition(panels.PanelFamily, rows)
    assert (panels.LargestFamily, panels.PanelsPerFamily) == (18, pytest.approx(18.0))
    assert panels.FamilyMaxError.Value < 1e-6
    fam = panels.Proxy.families(panels)
    assert list(fam.labels) == list(panels.PanelFamily)
    assert list(fam.templates) == list(panels.FamilyTemplates)
    check_tolerance(families.panel_corners(res), fam, 2.0)
    # ColorBy = Family colours by the family index.
    values, unit = analysis_colors.values_for(panels, "Family")
    assert list(values) == list(panels.PanelFamily) and unit == "family"
    # A tolerance that merges rows: fewer families, each panel still within it.
    panels.FamilyTolerance = 200.0
    panels.Mirror = False
    doc.recompute()
    assert 0 < panels.FamilyCount < 6
    fam = panels.Proxy.families(panels)
    assert not fam.mirror and list(fam.labels) == list(panels.PanelFamily)
    check_tolerance(families.panel_corners(res), fam, 200.0)
    saved = (list(panels.PanelFamily), list(panels.FamilyTemplates), panels.FamilyCount)

    path = str(tmp_path / "families.FCStd")
    doc.saveAs(path)
    names = (p.Name, panels.Name)
    FreeCAD.closeDocument(doc.Name)
    d2 = FreeCAD.openDocument(path)
    try:
        p2, panels2 = d2.getObject(names[0]), d2.getObject(names[1])
        assert panels2.FamilyTolerance.Value == pytest.approx(200.0)
        assert panels2.Mirror is False
        assert (list(panels2.PanelFamily), list(panels2.FamilyTemplates),
                panels2.FamilyCount) == saved
        p2.touch()
        d2.recompute()
        assert (list(panels2.PanelFamily), list(panels2.FamilyTemplates),
                panels2.FamilyCount) == saved
        panels2.FamilyTolerance = 0.0  # off again
        d2.recompute()
        assert list(panels2.PanelFamily) == [] and panels2.FamilyCount == 0
        assert panels2.Proxy.families(panels2) is None
    finally:
        FreeCAD.closeDocument(d2.Name)


# ------------------------------------------------- schedules, drawings, nesting
@pytest.fixture(scope="module")
def zone():
    """A sphere zone in 12 x 4 panels: 4 families (the rows) of 12."""
    r = tessella.panelize(sphere_zone(150), method="iso_grid", u_count=12, v_count=4)
    fam = tessella.panel_families(r, 2.0)
    assert fam.count == 4
    from freecad_workbench import fabrication

    return r, fam, fabrication.unfold(r)


def _read_csv(path):
    import csv

    with open(path, newline="", encoding="utf-8") as f:
        return list(csv.reader(f))


def test_panel_and_family_schedules(zone, tmp_path):
    from freecad_workbench.export import members, schedule_csv

    r, fam, flat = zone
    ids = r.panel_ids
    assert schedule_csv.write_panel_schedule(r, tmp_path / "p.csv", fam) == len(r.panels)
    rows = _read_csv(tmp_path / "p.csv")
    assert rows[0][-1] == "family" and len(rows) == len(r.panels) + 1
    by_row = rows_by_height(r)
    assert same_partition([row[-1] for row in rows[1:]], by_row)
    # Without families the schedule is as before (no family column).
    schedule_csv.write_panel_schedule(r, tmp_path / "q.csv")
    assert "family" not in _read_csv(tmp_path / "q.csv")[0]

    assert schedule_csv.write_family_schedule(r, fam, tmp_path / "f.csv") == 4
    frows = _read_csv(tmp_path / "f.csv")
    assert tuple(frows[0]) == schedule_csv.FAMILY_COLUMNS
    seen = []
    for name, template, count, err, mem in frows[1:]:
        mem = mem.split()
        assert int(count) == len(mem) == 12 and template in mem and float(err) < 1e-6
        assert len({by_row[ids.index(m)] for m in mem}) == 1  # one row
        seen += mem
    assert sorted(seen) == sorted(ids)

    members.write_panel_fabrication_schedule(r, flat, tmp_path / "pf.csv", families=fam)
    prow = _read_csv(tmp_path / "pf.csv")
    assert prow[0][-1] == "family"
    assert [row[-1] for row in prow[1:]] == [rows[k + 1][-1] for k in range(len(ids))]
    with pytest.raises(ValueError, match="families"):
        schedule_csv.write_family_schedule(r, families.families_of_corners(
            families.panel_corners(r)[:5], 2.0), tmp_path / "bad.csv")


def test_dxf_and_svg_draw_one_template_per_family_with_its_members(zone, tmp_path):
    import xml.etree.ElementTree as ET

    import ezdxf

    from freecad_workbench.export import dxf, svg

    r, fam, flat = zone
    s = dxf.export_family_dxf(flat, r, fam, str(tmp_path / "t.dxf"))
    assert s["families"] == 4
    doc = ezdxf.readfile(str(tmp_path / "t.dxf"))
    cuts = doc.modelspace().query('LWPOLYLINE[layer=="CUT"]')
    assert len(cuts) == 4
    assert sorted(dxf.id_from_xdata(c.get_xdata(dxf.APPID))[1] for c in cuts) == \
        [families.family_name(f) for f in range(4)]
    texts = " ".join(t.dxf.text for t in doc.modelspace().query("TEXT"))
    for pid in r.panel_ids:
        assert pid in texts
    for f, t in enumerate(fam.templates):
        assert f"{families.family_name(f)}: template {r.panel_ids[t]}, 12 panels" in texts
    # The template outline is the template panel's unfolded outline.
    by_id = {f.id: f for f in flat}
    cut0 = [c for c in cuts if dxf.id_from_xdata(c.get_xdata(dxf.APPID))[1] == "PF-001"][0]
    assert len(cut0) == len(by_id[r.panel_ids[fam.templates[0]]].outline)

    svg.export_family_svg(flat, r, fam, str(tmp_path / "t.svg"))
    root = ET.parse(tmp_path / "t.svg").getroot()
    ns = "{http://www.w3.org/2000/svg}"
    groups = [g for g in root.iter(ns + "g") if g.get("data-id")]
    assert sorted(g.get("data-id") for g in groups) == ["PF-001", "PF-002", "PF-003", "PF-004"]
    text = " ".join(t.text or "" for t in root.iter(ns + "text"))
    assert all(pid in text for pid in r.panel_ids)
    h = float(root.get("viewBox").split()[3])
    assert all(float(t.get("y")) <= h for t in root.iter(ns + "text"))


def test_nesting_by_family_cuts_every_panel_to_its_template(zone):
    from freecad_workbench import fabrication

    r, fam, flat = zone
    parts = families.family_parts(flat, r, fam)
    assert [p.id for p in parts] == r.panel_ids
    by_id = {f.id: f for f in flat}
    for k, p in enumerate(parts):
        tpl = by_id[r.panel_ids[fam.templates[fam.labels[k]]]]
        assert np.array_equal(p.outline, tpl.outline)
    layout = fabrication.nest_families(flat, r, fam, sheet_width=6000, sheet_height=3000)
    assert layout.sheet_count >= 1
    assert list(layout.ids) == r.panel_ids and len(layout.placements) == len(r.panels)
    # What is nested is the template outline of each panel's family.
    for k, outline in enumerate(layout.panel_outlines or []):
        assert np.allclose(outline, parts[k].outline)


def test_spreadsheets_and_document_exports_with_families(doc, tmp_path):
    from freecad_workbench import make_fabrication

    src = doc.addObject("Part::Feature", "Zone")
    src.Shape = sphere_zone(150)
    doc.recompute()
    p = tessella.make_panelization((src, "Face1"), method="iso_grid", u_count=12, v_count=4)
    doc.recompute()
    panels = _panels_of(p)
    sheets = tessella.make_schedules(p)
    assert [s.Name for s in sheets] == ["PanelSchedule", "RodSchedule", "NodeSchedule"]
    with pytest.raises(ValueError, match="FamilyTolerance"):
        make_fabrication.export_families(p, str(tmp_path / "t.dxf"))
    panels.FamilyTolerance = 2.0
    doc.recompute()
    sheets = tessella.make_schedules(p)
    fs = [s for s in sheets if s.Name.startswith("FamilySchedule")]
    assert len(fs) == 1
    assert fs[0].get("A1") == "Family" and fs[0].get("C1") == "Panels"
    assert [fs[0].get(f"C{i}") for i in range(2, 6)] == [12, 12, 12, 12]
    ps = [s for s in sheets if s.Name.startswith("PanelSchedule")][-1]
    assert ps.get("O1") == "Warp" and ps.get("P1") == "Class"
    assert {ps.get(f"P{i}") for i in range(2, 50)} <= {"flat", "cold-bent", "curved"}
    last = "Q"  # the column after the 16 fabrication columns (warp and class the last two)
    assert ps.get(f"{last}1") == "Family"
    assert {ps.get(f"{last}{i}") for i in range(2, 50)} == {"PF-001", "PF-002", "PF-003", "PF-004"}
    s = make_fabrication.export_families(p, str(tmp_path / "t.svg"))
    assert s["families"] == 4


def test_buildability_summary_has_the_family_figures(zone):
    r, fam, _flat = zone
    s = tessella.buildability(r, family_tolerance=2.0)
    assert (s["panel_families"], s["largest_family"], s["panels_per_family"]) == (4, 12, 12.0)
    assert s["family_max_error"] < 1e-6
    assert "panel_families" not in tessella.buildability(r)


def test_coarse_grouping_keeps_the_tolerance():
    r = tessella.panelize(bspline_face(), method="iso_grid", size=700.0)
    full = tessella.panel_families(r, 20.0)
    coarse = tessella.panel_families(r, 20.0, max_pairs=5)
    assert not full.summary()["coarse"] and coarse.summary()["coarse"]
    assert coarse.count >= full.count
    check_tolerance(families.panel_corners(r), coarse, 20.0)
