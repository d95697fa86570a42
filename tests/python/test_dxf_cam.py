"""CAM-ready DXF (freecad_workbench/export/dxf.py, export/cut_path.py): written with
ezdxf, read back, and checked against the flat panels with geometry computed here
(arc sampling from the bulges, distances, turning angles), on a trimmed doubly
curved B-spline face built here (not a bundled example) and synthetic outlines."""

import dataclasses
import glob
import math
import os
import re
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
from freecad_workbench.export import _arrange  # noqa: E402
from freecad_workbench.export import cut_path as cp  # noqa: E402
from freecad_workbench.export import dxf as dxf_mod  # noqa: E402
from freecad_workbench.fabrication import cut_outline  # noqa: E402

ezdxf = pytest.importorskip("ezdxf")

CHORD = 0.05
SIMPLIFY = 1e-3
SHEET = dict(sheet_width=3000.0, sheet_height=1500.0, margin=10.0, spacing=6.0, rotations=4)
FOLD_TEXT = re.compile(r"^[VM] \d+\.\d{4}°$")


# ---------------------------------------------------------------- independent geometry

def arc_points(p0, p1, bulge, step=0.1):
    """Sample the DXF bulge segment p0 -> p1 (own implementation: centre from the
    included angle 4 atan(bulge), counter-clockwise for bulge > 0), p0 included."""
    p0, p1 = np.asarray(p0, float), np.asarray(p1, float)
    chord = np.linalg.norm(p1 - p0)
    if bulge == 0:
        n = max(2, int(chord / step) + 1)
        return p0 + np.linspace(0, 1, n, endpoint=False)[:, None] * (p1 - p0)
    theta = 4 * math.atan(bulge)
    radius = chord / (2 * math.sin(abs(theta) / 2))
    mid = (p0 + p1) / 2
    normal = np.array([-(p1 - p0)[1], (p1 - p0)[0]]) / chord  # left of p0 -> p1
    centre = mid + normal * radius * math.cos(theta / 2) * np.sign(theta)
    a0 = math.atan2(*(p0 - centre)[::-1])
    n = max(4, int(abs(theta) * radius / step) + 1)
    t = a0 + theta * np.arange(n) / n
    pts = centre + radius * np.c_[np.cos(t), np.sin(t)]
    assert np.linalg.norm(pts[0] - p0) < 1e-6 and np.linalg.norm(
        centre + radius * np.array([math.cos(a0 + theta), math.sin(a0 + theta)]) - p1) < 1e-6
    return pts


def sample_lwpolyline(e, step=0.1):
    v = [(x, y, b) for x, y, _s, _e, b in e.get_points("xyseb")]
    return np.vstack([arc_points(v[k][:2], v[(k + 1) % len(v)][:2], v[k][2], step)
                      for k in range(len(v))])


def dist_to_ring(q, ring):
    """Distance of points q to the closed polyline ring (brute force, per segment)."""
    q = np.asarray(q, float)
    a = np.asarray(ring, float)
    d = np.roll(a, -1, axis=0) - a
    dd = np.maximum((d * d).sum(1), 1e-300)
    out = []
    for chunk in np.array_split(q, max(1, len(q) * len(a) // 2_000_000 + 1)):
        rel = chunk[:, None, :] - a[None]
        s = np.clip((rel * d[None]).sum(2) / dd[None], 0, 1)
        out.append(np.linalg.norm(rel - s[..., None] * d[None], axis=2).min(axis=1))
    return np.concatenate(out)


def turning(ring):
    a = ring - np.roll(ring, 1, axis=0)
    b = np.roll(ring, -1, axis=0) - ring
    return np.degrees(np.abs(np.arctan2(a[:, 0] * b[:, 1] - a[:, 1] * b[:, 0], (a * b).sum(1))))


# ---------------------------------------------------------------- the face

def make_face():
    """Doubly curved B-spline (5x5 poles, uneven knots), trimmed by a circle and with
    a circular hole."""
    surf = Part.BSplineSurface()
    poles = [[FreeCAD.Vector(2000.0 * i, 1600.0 * j,
                             900.0 * math.sin(1.1 * i) + 500.0 * math.cos(1.3 * j) + 80.0 * i * j)
              for j in range(5)] for i in range(5)]
    surf.buildFromPolesMultsKnots(poles, [4, 1, 4], [3, 1, 1, 3], [0.0, 0.4, 1.0],
                                  [0.0, 0.3, 0.6, 1.0], False, False, 3, 2)
    outer = Part.makeCylinder(4300.0, 20000, FreeCAD.Vector(4000, 3200, -10000))
    hole = Part.makeCylinder(1300.0, 20000, FreeCAD.Vector(4200, 3300, -10000))
    faces = surf.toShape().common(outer).cut(hole).Faces
    assert len(faces) == 1 and len(faces[0].Wires) == 2
    return faces[0]


@pytest.fixture(scope="module")
def panels():
    r = tessella.panelize(make_face(), method="equal_size_grid", size=1200.0)
    flat = tessella.unfold(r)
    assert max(len(f.outline) for f in flat) > 50  # long runs of points along the trim
    return r, flat


@pytest.fixture(scope="module")
def layout(panels):
    return tessella.nest(panels[1], kerf=0.3, **SHEET)


def entities(doc):
    return list(doc.modelspace())


def cut_entities(doc):
    return [e for e in entities(doc) if e.dxf.layer == "CUT"]


def part_of(e):
    return dxf_mod.id_from_xdata(e.get_xdata("TESSELLA"))


def entity_points(e):
    t = e.dxftype()
    if t == "LWPOLYLINE":
        return sample_lwpolyline(e, step=5.0)
    if t == "LINE":
        return np.array([tuple(e.dxf.start)[:2], tuple(e.dxf.end)[:2]])
    if t == "TEXT":
        return np.array([tuple(e.dxf.insert)[:2], tuple(e.dxf.align_point)[:2]])
    raise AssertionError(f"unexpected entity {t} on {e.dxf.layer}")


def without_jogs(ring, tol=SIMPLIFY):
    """The ring without the points closer than tol to the previous point kept."""
    kept = [ring[0]]
    for p in ring[1:]:
        if np.linalg.norm(p - kept[-1]) > tol:
            kept.append(p)
    while len(kept) > 3 and np.linalg.norm(kept[-1] - kept[0]) <= tol:
        kept.pop()
    return np.array(kept)


def check_cut_against_outline(e, placed, chord=CHORD, corner_tol=1e-9):
    """The arc-fitted path follows the true outline within the chord tolerance (both
    ways), its corners (turning > 30 degrees, jogs left out) are vertices of the path
    (exactly; within a jog's size for a path with jogs), and it has no sub-micron jog."""
    assert e.closed
    pts = np.array([(x, y) for x, y, *_ in e.get_points("xy")])
    samples = sample_lwpolyline(e, step=1.0)
    assert dist_to_ring(samples, placed).max() <= chord + 1e-6
    assert dist_to_ring(placed, samples).max() <= chord + 1e-3  # + the sampling error of 1 mm steps
    clean = without_jogs(placed)
    for c in clean[turning(clean) > 30.0]:
        assert np.min(np.linalg.norm(pts - c, axis=1)) <= corner_tol
    seg = np.linalg.norm(np.roll(pts, -1, axis=0) - pts, axis=1)
    assert seg.min() > SIMPLIFY
    return len(pts), sum(1 for *_, b in e.get_points("xyseb") if b != 0)


# ---------------------------------------------------------------- cut_path unit tests

def test_simplify_removes_collinear_points_and_jogs_keeps_corners():
    sq = [(0, 0), (400, 0), (400.0000001, 0.00000005), (1000, 0), (1000, 300),
          (1000.0000002, 300.0000001), (1000, 600), (0, 600), (0, 0.0000001)]
    kept = cp.simplify(sq, 1e-3)
    assert [sq[i] for i in kept] == [(0, 0), (1000, 0), (1000, 600), (0, 600)]
    # points 0.3 um beside a corner, on either edge: the corner itself stays
    for jog in ([(999.9999997, 0.0)], [(1000.0, 0.0000003)], [(999.9999997, 0.0), (1000.0, 0.0000003)]):
        ring = [(0, 0)] + jog[:1] * (jog[0][1] == 0) + [(1000, 0)] + [p for p in jog if p[1] > 0] \
            + [(1000, 600), (0, 600)]
        assert [ring[i] for i in cp.simplify(ring, 1e-3)] == [(0, 0), (1000, 0), (1000, 600), (0, 600)]
    # kept indices stay; tolerance 0 keeps everything; a real bend stays
    assert 1 in cp.simplify(sq, 1e-3, keep=[1])
    assert list(cp.simplify(sq, 0.0)) == list(range(len(sq)))
    bend = [(0, 0), (500, 0.01), (1000, 0), (1000, 600), (0, 600)]
    assert list(cp.simplify(bend, 1e-3)) == [0, 1, 2, 3, 4]
    # slivers under the tolerance are left as they are (never fewer than 3 points)
    tiny = [(0, 0), (1e-4, 0), (1e-4, 1e-4), (0, 1e-4)]
    assert len(cp.simplify(tiny, 1e-3)) >= 3 and cp.make_cut_path(tiny).segment_count >= 3
    needle = [(0, 0), (1000, 0), (1000, 0.0002), (0, 0.0001)]
    assert len(cp.simplify(needle, 1e-3)) >= 3
    for bad in ([(0, 0), (1, 1)], [(0, 0), (1, 0), (math.nan, 1)]):
        with pytest.raises(ValueError):
            cp.simplify(bad)
    with pytest.raises(ValueError, match="tolerance"):
        cp.simplify(sq, -1.0)


def synthetic_trim_panel(radius=900.0, sweep_deg=70.0, n=120, noise=0.0, seed=1):
    """A panel with straight grid edges and a curved trim edge (a circle of `radius`
    over `sweep_deg`, sampled in n chords, optionally with sub-tolerance noise), CCW."""
    rng = np.random.default_rng(seed)
    a = np.radians(np.linspace(0, sweep_deg, n + 1))
    arc = np.c_[radius * np.cos(a), radius * np.sin(a)]
    arc[1:-1] += noise * rng.standard_normal(arc[1:-1].shape)
    far = 1.8 * radius
    outer = [(far * math.cos(t), far * math.sin(t)) for t in (a[-1], 0.5 * a[-1], 0.0)]
    ring = np.vstack([arc, outer])  # clockwise: the arc is the inner edge
    return ring[::-1].copy()


@pytest.mark.parametrize("radius,sweep,n,noise", [(900.0, 70.0, 120, 0.0), (300.0, 170.0, 200, 0.0),
                                                  (5000.0, 20.0, 60, 0.004)])
def test_arc_fitting_within_chord_tolerance(radius, sweep, n, noise):
    ring = synthetic_trim_panel(radius, sweep, n, noise)
    path = cp.make_cut_path(ring, SIMPLIFY, CHORD)
    bulges = path.bulges
    # straight edges stay straight (lines), the trim becomes a few arcs, corners stay
    assert path.arc_count >= 1 and path.segment_count <= 4 + 3
    corners = ring[turning(ring) > 30]
    assert len(corners) >= 3
    for c in corners:
        assert np.min(np.linalg.norm(path.points - c, axis=1)) == 0.0
    # the input's straight edges (one long chord each) are lines of the path
    m = len(path.points)
    straight = [k for k in range(len(ring)) if np.linalg.norm(ring[(k + 1) % len(ring)] - ring[k]) > 10 * math.radians(sweep) * radius / n]
    assert len(straight) >= 3
    for k in straight:
        j = list(path.source).index(k)
        assert path.source[(j + 1) % m] == (k + 1) % len(ring) and bulges[j] == 0
    samples = np.vstack([arc_points(path.points[k], path.points[(k + 1) % len(path.points)], bulges[k], 0.5)
                         for k in range(len(path.points))])
    assert dist_to_ring(samples, ring).max() <= CHORD + 1e-9
    assert dist_to_ring(ring, samples).max() <= CHORD + 1e-3
    assert np.all(np.abs(bulges) <= 1.0 + 1e-12)
    # every vertex is an input point, unmoved, in input order
    assert np.array_equal(path.points, ring[path.source]) and np.all(np.diff(path.source) > 0)
    assert path.arc_count + (len(ring) - len(path.points)) > 0
    # deterministic
    again = cp.make_cut_path(ring, SIMPLIFY, CHORD)
    assert np.array_equal(again.points, path.points) and np.array_equal(again.bulges, path.bulges)


def test_arc_fitting_s_curve_and_polyline_option():
    """An S-shaped trim (an inflection) is still followed within the tolerance; arcs=False
    and chord tolerance 0 give polylines."""
    x = np.linspace(0, 2000, 301)
    s = np.c_[x, 150 * np.sin(x / 2000 * 2 * math.pi)]
    ring = np.vstack([s, [(2000, 800), (0, 800)]])
    path = cp.make_cut_path(ring, SIMPLIFY, CHORD)
    samples = path.sample(0.5)
    assert dist_to_ring(samples, ring).max() <= CHORD + 1e-6
    assert path.arc_count >= 2 and path.segment_count < 40
    flat = cp.make_cut_path(ring, SIMPLIFY, CHORD, arcs=False)
    # a polyline; only points within the simplify tolerance of it (at the inflection) left out
    assert flat.arc_count == 0 and len(ring) - 10 < flat.segment_count < len(ring)
    assert dist_to_ring(ring, flat.points).max() <= SIMPLIFY
    assert cp.make_cut_path(ring, SIMPLIFY, 0.0).arc_count == 0
    with pytest.raises(ValueError, match="chord tolerance"):
        cp.make_cut_path(ring, SIMPLIFY, -0.1)


# ---------------------------------------------------------------- DXF for CAM

def test_defaults_one_file_per_sheet_exploded_nominal(tmp_path, panels, layout):
    r, flat = panels
    base = str(tmp_path / "panels.dxf")
    s = tessella.export_dxf(flat, base, layout=layout)
    n = layout.sheet_count
    assert s["per_sheet"] and not s["blocks"] and s["cut_path"] == "nominal"
    assert s["paths"] == [str(tmp_path / f"panels_sheet{k + 1:02d}.dxf") for k in range(n)]
    assert sorted(glob.glob(str(tmp_path / "*.dxf"))) == s["paths"]  # nothing else written
    seen, counts, arcs = {}, [], 0
    W, H = layout.sheet_width, layout.sheet_height
    for sheet, path in enumerate(s["paths"]):
        doc = ezdxf.readfile(path)
        assert doc.header["$INSUNITS"] == 4
        ents = entities(doc)
        types = {(e.dxftype(), e.dxf.layer) for e in ents}
        assert not any(t == "INSERT" for t, _ in types)  # exploded
        assert not doc.layers.has_entry("OUTLINE") and not doc.layers.has_entry("REFERENCE")
        assert {t for t, layer in types if layer == "CUT"} == {"LWPOLYLINE"}
        assert {t for t, layer in types if layer == "FOLD"} <= {"LINE"}  # no text on FOLD
        assert {layer for t, layer in types if t == "TEXT"} <= {"LABEL", "ENGRAVE"}
        # the sheet frame: the sheet rectangle, on a non-plotting layer that is not CUT
        frames = [e for e in ents if e.dxf.layer == "SHEET_REF"]
        assert len(frames) == 1 and doc.layers.get("SHEET_REF").dxf.plot == 0
        assert np.allclose([p[:2] for p in frames[0].get_points("xy")], [(0, 0), (W, 0), (W, H), (0, H)])
        for e in ents:  # everything on the sheet, origin at its corner
            p = entity_points(e)
            assert p[:, 0].min() >= -1e-6 and p[:, 0].max() <= W + 1e-6, e.dxf.layer
            assert p[:, 1].min() >= -1e-6 and p[:, 1].max() <= H + 1e-6, e.dxf.layer
        for e in cut_entities(doc):
            i, pid = part_of(e)
            assert pid == flat[i].id and pid not in seen
            seen[pid] = sheet
            assert layout.placements[i].sheet == sheet
            placed = layout.placed_outline(i, flat[i].outline)
            k, a = check_cut_against_outline(e, placed)
            counts.append(k)
            arcs += a
            inside = sample_lwpolyline(e, step=5.0)  # within the margin
            assert inside.min() >= layout.margin - 1e-6
        # fold lines: exact, with their XDATA; labels show the IDs of the sheet's parts
        for e in ents:
            if e.dxf.layer == "FOLD":
                tags = e.get_xdata("TESSELLA")
                assert tags[0] == (1000, "fold") and len(tags) == 4
        labels = [e.dxf.text for e in ents if e.dxftype() == "TEXT" and e.dxf.layer == "LABEL"
                  and not FOLD_TEXT.match(e.dxf.text) and not e.dxf.text.startswith("Sheet")]
        assert sorted(labels) == sorted(pid for pid, sh in seen.items() if sh == sheet)
    assert sorted(seen) == sorted(f.id for f in flat)  # exactly one cut path per part
    assert s["segments"] and s["segments_per_part"]["max"] == max(counts)
    assert s["segments_per_part"]["mean"] == pytest.approx(np.mean(counts))
    assert s["arcs"] == arcs and arcs > 0
    assert s["segments_per_part"]["max"] < s["raw_segments_per_part"]["max"] / 5


def test_compensated_cut_and_reference(tmp_path, panels, layout):
    """cut_path="compensated": CUT is the outline grown by kerf/2; the nominal outline
    only with reference=True, on the non-plotting REFERENCE layer. The raw compensated
    path has sub-micron jogs; the written one has none."""
    r, flat = panels
    raw = [cut_outline(f, layout.kerf) for f in flat]
    jogs = [int((np.linalg.norm(np.roll(c, -1, 0) - c, axis=1) < SIMPLIFY).sum()) for c in raw]
    assert max(jogs) > 0  # the test is meaningful
    s = tessella.export_dxf(flat, str(tmp_path / "c.dxf"), layout=layout, cut_path="compensated",
                            reference=True)
    found = 0
    for path in s["paths"]:
        doc = ezdxf.readfile(path)
        assert doc.layers.get("REFERENCE").dxf.plot == 0
        refs = [e for e in entities(doc) if e.dxf.layer == "REFERENCE"]
        cuts = cut_entities(doc)
        assert len(refs) == len(cuts)
        for e, ref in zip(cuts, refs):
            i, pid = part_of(e)
            placed = layout.placed_outline(i, raw[i])
            check_cut_against_outline(e, placed, corner_tol=SIMPLIFY)
            check_cut_against_outline(ref, layout.placed_outline(i, flat[i].outline))
            # the cut runs kerf/2 outside the nominal outline
            d = dist_to_ring(sample_lwpolyline(e, 20.0), sample_lwpolyline(ref, 1.0))
            assert np.median(d) == pytest.approx(layout.kerf / 2, abs=2e-3)
            found += 1
    assert found == len(flat)
    no_ref = tessella.export_dxf(flat, str(tmp_path / "d.dxf"), layout=layout, cut_path="compensated")
    assert not ezdxf.readfile(no_ref["paths"][0]).layers.has_entry("REFERENCE")


def test_one_drawing_with_blocks(tmp_path, panels, layout):
    r, flat = panels
    path = str(tmp_path / "all.dxf")
    s = tessella.export_dxf(flat, path, layout=layout, per_sheet=False, blocks=True, arcs=False)
    assert s["paths"] == [path] and os.listdir(tmp_path) == ["all.dxf"]
    doc = ezdxf.readfile(path)
    ins = doc.modelspace().query("INSERT")
    assert sorted(i.dxf.name for i in ins) == sorted(s["block_names"]) and len(ins) == len(flat)
    frames = [e for e in entities(doc) if e.dxf.layer == "SHEET_REF"]
    assert len(frames) == layout.sheet_count and all(f.dxftype() == "LWPOLYLINE" for f in frames)
    assert not [e for e in entities(doc) if e.dxf.layer == "CUT"]  # cuts are in the blocks
    for i, f in enumerate(flat):
        block = doc.blocks[s["block_names"][i]]
        cuts = [e for e in block if e.dxf.layer == "CUT"]
        assert len(cuts) == 1 and part_of(cuts[0]) == (i, f.id)
        assert all(b == 0 for *_, b in cuts[0].get_points("xyseb"))  # arcs=False: polyline
        check_cut_against_outline(cuts[0], np.asarray(f.outline), chord=SIMPLIFY)
        assert not [e for e in block if e.dxftype() == "TEXT" and e.dxf.layer in ("FOLD", "CUT")]
    # no layout: one drawing in rows, no sheet frame; per_sheet=True needs a layout
    s2 = tessella.export_dxf(flat, str(tmp_path / "rows.dxf"))
    assert s2["paths"] == [str(tmp_path / "rows.dxf")] and s2["sheets"] == 0
    assert not ezdxf.readfile(s2["paths"][0]).layers.has_entry("SHEET_REF")
    with pytest.raises(ValueError, match="per_sheet"):
        tessella.export_dxf(flat, str(tmp_path / "x.dxf"), per_sheet=True)


WEIRD = ["ROOF/A:01", "ROOF:A/01", "ROOF_A_01", "roof_a_01", "a*b<c>d?e\"f|g\\h", "with spaces  here",
         "Dach-Süd-Ä1", "屋根-北-07", "x" * 300, "%%c50 100%", "semi;colon=eq`tick", "*Model_Space",
         "_", "."]


def test_ids_a_user_can_type(tmp_path, panels):
    r, flat = panels
    weird = [dataclasses.replace(f, id=WEIRD[k] if k < len(WEIRD) else f.id) for k, f in enumerate(flat)]
    lay = tessella.nest(weird, **SHEET)
    names = dxf_mod.block_names([f.id for f in weird])
    assert names == dxf_mod.block_names([f.id for f in weird])  # deterministic
    assert len({n.lower() for n in names}) == len(names)  # unique, also without case
    from ezdxf.lldxf.validator import is_valid_block_name
    used = set()
    for pid, name in zip([f.id for f in weird], names):
        assert is_valid_block_name(name) and len(name) <= 64 and name.isascii() and " " not in name
        assert name[0] != "*"
        if re.fullmatch(r"[A-Za-z0-9_.-]{1,64}", pid) and pid.lower() not in used:
            assert name == pid  # a safe ID keeps its name unless taken (without case)
        used.add(name.lower())
    assert names[3] == "roof_a_01_2"  # "ROOF_A_01" took the name (DXF names ignore case)
    assert names[0].startswith("ROOF_A_01_") and names[1].startswith("ROOF_A_01_")
    for blocks in (True, False):
        s = tessella.export_dxf(weird, str(tmp_path / f"w{blocks}.dxf"), layout=lay, blocks=blocks)
        labels, cut_ids = [], []
        for path in s["paths"]:
            doc = ezdxf.readfile(path)
            spaces = [doc.blocks[i.dxf.name] for i in doc.modelspace().query("INSERT")] if blocks \
                else [doc.modelspace()]
            for space in spaces:
                for e in space:
                    if e.dxftype() == "TEXT" and e.dxf.layer == "LABEL" and not FOLD_TEXT.match(e.dxf.text):
                        labels.append(e.dxf.text)
                    if e.dxf.layer == "CUT":
                        cut_ids.append(part_of(e)[1])
        # the IDs as typed (AutoCAD's %%% = one '%' where an ID holds '%%')
        assert sorted(labels) == sorted(_arrange.dxf_text(f.id) for f in weird)
        assert sorted(cut_ids) == sorted(f.id for f in weird)
    for bad in ("", "a\nb", "tab\there"):
        broken = [dataclasses.replace(weird[0], id=bad)] + weird[1:]
        with pytest.raises(ValueError, match="ID"):
            tessella.export_dxf(broken, str(tmp_path / "bad.dxf"))


def test_engrave_layer_and_bad_options(tmp_path, panels, layout):
    r, flat = panels
    s = tessella.export_dxf(flat, str(tmp_path / "e.dxf"), layout=layout, id_layer="ENGRAVE")
    doc = ezdxf.readfile(s["paths"][0])
    ids = {flat[part_of(e)[0]].id for e in cut_entities(doc)}
    engraved = [e.dxf.text for e in entities(doc) if e.dxftype() == "TEXT" and e.dxf.layer == "ENGRAVE"]
    assert sorted(engraved) == sorted(ids)
    assert all(FOLD_TEXT.match(e.dxf.text) for e in entities(doc)
               if e.dxftype() == "TEXT" and e.dxf.layer == "LABEL")
    for bad in (dict(cut_path="outline"), dict(id_layer="CUT"), dict(chord_tolerance=-1),
                dict(simplify_tolerance="x"), dict(kerf=-0.1)):
        with pytest.raises(ValueError):
            tessella.export_dxf(flat, str(tmp_path / "b.dxf"), **bad)
