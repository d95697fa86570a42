"""Fabrication console API: unfolded panels and their nesting on stock sheets.

    import freecad_workbench as tessella
    r = tessella.panelize(face, method="iso_grid", size=1500.0)
    flat = tessella.unfold(r)                  # one FlatPanel per panel, same order
    flat[i].outline                            # (k,2) mm, the panel's corner order, CCW from the front
    flat[i].fold, flat[i].fold_angle           # None / (a, b) corner indices; degrees (0 = flat)
    layout = tessella.nest(flat, sheet_width=2500.0, sheet_height=1250.0,
                           margin=10.0, spacing=6.0, rotations=4)
    layout = tessella.nest(flat, stock_sizes=[(2500, 1250), (3000, 1500)])
    layout.sheet_count, layout.sheet_sizes, layout.utilization, layout.placed_outline(i)
    layout.ids                                 # matched to panels by ID (unique)
    tessella.smallest_sheet(flat, margin=10.0, rotations=4)   # (width, height) every panel fits

No FreeCAD document is needed. Lengths in mm, angles in degrees.
"""

import math
from dataclasses import dataclass, field

import numpy as np

from . import core


@dataclass
class FlatPanel:
    """One panel drawn flat with its true edge lengths (see docs/fabrication.md)."""

    id: str
    outline: np.ndarray  # (k,2) float64, corner i = the panel's corner i
    fold: object = None  # None or (a, b): the fold diagonal's corner indices (largest fold)
    fold_angle: float = 0.0  # |angle| of that fold, degrees; 0 for a flat panel
    fold_valley: bool = False  # True: a valley seen from the panel's front
    folds: list = field(default_factory=list)  # every fold: (a, b, signed degrees, + = valley)
    max_fold: float = 0.0  # largest |dihedral| over all diagonals, also under the tolerance
    u_direction: tuple = (1.0, 0.0)  # the surface's u direction on the flat panel (orientation mark)
    triangles: list = field(default_factory=list)  # corner triples the panel was unfolded by
    self_intersecting: bool = False  # outline crosses itself: flatten as a curved patch instead

    @property
    def area(self):
        x, y = self.outline[:, 0], self.outline[:, 1]
        return 0.5 * float(np.dot(x, np.roll(y, -1)) - np.dot(np.roll(x, -1), y))

    @property
    def edge_lengths(self):
        return np.linalg.norm(np.roll(self.outline, -1, axis=0) - self.outline, axis=1)


def _check_number(name, value, lo, hi):
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be a number, got {value!r}") from None
    if not (math.isfinite(v) and lo <= v <= hi):
        raise ValueError(f"{name} must be in [{lo:g}, {hi:g}], got {value!r}")
    return v


#: Folds under this angle (degrees) count as flat: the core's default (see
#: docs/fabrication.md, "Fold tolerance").
DEFAULT_FOLD_TOLERANCE = core.UnfoldParams().fold_tolerance_deg


def unfold(result, fold_tolerance=DEFAULT_FOLD_TOLERANCE):
    """Unfold every panel of a PanelizeResult; returns a list of FlatPanel (panel order).

    Planar panels unfold exactly (no fold). A bent quad unfolds as two triangles
    about the diagonal with the smaller fold; the fold is kept if its angle
    exceeds `fold_tolerance` degrees. An n-gon unfolds through the triangulation
    of its (u,v) outline, edge by edge (exact edge lengths; a non-planar n-gon
    gets one fold per bent diagonal).
    """
    p = core.UnfoldParams()
    p.fold_tolerance_deg = _check_number("fold_tolerance (deg)", fold_tolerance, 0.0, 180.0)
    flats = core.unfold_panels(result._mesh, p)
    out = []
    for pid, f in zip(result.panel_ids, flats):
        folds = [(int(x.a), int(x.b), float(x.angle_deg)) for x in f.folds]
        panel = FlatPanel(
            id=pid,
            outline=np.asarray(f.outline),
            folds=folds,
            max_fold=float(f.max_fold_deg),
            u_direction=tuple(f.u_direction),
            triangles=[tuple(t) for t in f.triangles],
            self_intersecting=bool(f.self_intersecting),
        )
        if folds:
            a, b, angle = max(folds, key=lambda t: (abs(t[2]), -t[0], -t[1]))
            panel.fold, panel.fold_angle, panel.fold_valley = (a, b), abs(angle), angle > 0
        out.append(panel)
    return out


@dataclass
class Placement:
    sheet: int  # 0-based sheet index
    angle: float  # degrees, counter-clockwise about the outline's origin
    offset: tuple  # (x, y) mm on the sheet, after the rotation


@dataclass
class NestLayout:
    """Where every flat panel lies: sheet point = R(angle) outline point + offset.

    Matched to panels by ID (`ids`, unique): the writers look each panel up by
    its ID, so the panel list may come in any order."""

    ids: list
    placements: list  # Placement per panel, input order
    sheet_count: int
    sheet_utilization: list  # per sheet: panel area / that sheet's area
    utilization: float  # all panel area / all sheets' area
    sheet_width: float  # the sheet size asked for (with stock sizes: the largest stock width)
    sheet_height: float
    margin: float
    spacing: float
    rotations: int
    kerf: float
    outlines: list = field(default_factory=list, repr=False)  # the nested (cut) outlines
    sheet_sizes: list = field(default_factory=list)  # per sheet: (width, height) mm
    stock_sizes: list = field(default_factory=list)  # the stock sizes offered (empty: one size)
    panel_outlines: list = field(default_factory=list, repr=False)  # nominal outlines nested

    def placed_outline(self, i, outline=None):
        """Outline i (or the given (k,2) points of that panel) in its sheet's coordinates."""
        pl = self.placements[i]
        pts = np.asarray(self.outlines[i] if outline is None else outline, dtype=float)
        a = math.radians(pl.angle)
        rot = np.array([[math.cos(a), -math.sin(a)], [math.sin(a), math.cos(a)]])
        return pts @ rot.T + np.asarray(pl.offset)

    def on_sheet(self, s):
        """Indices of the panels on sheet s."""
        return [i for i, p in enumerate(self.placements) if p.sheet == s]

    def sheet_size(self, s):
        """(width, height) mm of sheet s."""
        if self.sheet_sizes:
            return self.sheet_sizes[s]
        return (self.sheet_width, self.sheet_height)

    def index(self, panel_id):
        """Layout index of the panel with this ID (ValueError if it is not in the layout)."""
        try:
            return self.ids.index(panel_id)
        except ValueError:
            raise ValueError(f"panel {panel_id!r} is not in the layout") from None


def cut_outline(panel, kerf):
    """The cutter path of a flat panel: its outline grown by kerf/2 (kerf = cut width, mm)."""
    kerf = _check_number("kerf (mm)", kerf, 0.0, 1000.0)
    outline = np.asarray(getattr(panel, "outline", panel), dtype=float)
    if kerf == 0.0:
        return np.array(outline, dtype=float)
    p = core.OutlineOffsetParams()
    p.distance = 0.5 * kerf
    return np.asarray(core.offset_outline(outline, p))


def unique_ids(items, what="panel"):
    """The IDs of flat panels (attribute `id`); ValueError naming the first ID given twice
    (a layout is matched to its panels by ID)."""
    ids, seen = [], {}
    for i, f in enumerate(items):
        pid = getattr(f, "id", None)
        if not isinstance(pid, str) or not pid:
            raise ValueError(f"{what} {i} has no ID (got {pid!r})")
        if pid in seen:
            raise ValueError(f"{what} ID {pid!r} is given twice ({what}s {seen[pid]} and {i}): "
                             "IDs must be unique")
        seen[pid] = i
        ids.append(pid)
    return ids


def _boxes(outlines, rotations):
    """(n, rotations, 2): width and height of each outline's bounding box at each
    allowed rotation (multiples of 360/rotations degrees, as the nesting core)."""
    out = np.zeros((len(outlines), rotations, 2))
    for k in range(rotations):
        a = math.radians(360.0 * k / rotations)
        rot = np.array([[math.cos(a), -math.sin(a)], [math.sin(a), math.cos(a)]])
        for i, o in enumerate(outlines):
            q = np.asarray(o, dtype=float) @ rot.T
            out[i, k] = q.max(axis=0) - q.min(axis=0)
    return out


# Slack on the fit test and on a suggested sheet (mm): the core places parts on
# a 1e-3 mm grid, so a part exactly as large as the free area may not fit.
_FIT_SLACK = 2e-3


def _fits(boxes, width, height, margin):
    """(n,) bool: part i fits a width x height sheet (margin all round) in some rotation."""
    ok = (boxes[:, :, 0] + 2 * margin + _FIT_SLACK <= width) & \
         (boxes[:, :, 1] + 2 * margin + _FIT_SLACK <= height)
    return ok.any(axis=1)


def smallest_sheet(flat, margin=10.0, rotations=4, kerf=0.0):
    """The smallest sheet (by area; whole mm, landscape on a tie) on which every
    flat panel fits by itself, with `margin` all round and one of the allowed
    rotations. Returns (width, height) mm."""
    margin = _check_number("margin (mm)", margin, 0.0, 1e7)
    r = _check_rotations(rotations)
    outlines = [cut_outline(f, kerf) for f in flat]
    if not outlines:
        return (0.0, 0.0)
    boxes = _boxes(outlines, r) + 2 * margin + _FIT_SLACK
    return _smallest_box(boxes)


def _smallest_box(boxes):
    """Minimum-area (W, H), whole mm, with every part i fitting in some rotation k:
    boxes[i, k] <= (W, H). A sweep over the widths: H(W) = max_i min over the
    rotations with w_ik <= W of h_ik (a heap of the parts' current heights)."""
    import heapq

    n, r, _ = boxes.shape
    boxes = np.ceil(boxes)  # whole mm
    entries = sorted((float(boxes[i, k, 0]), float(boxes[i, k, 1]), i)
                     for i in range(n) for k in range(r))
    height = [math.inf] * n
    placed = 0
    heap = []  # (-height, part): the largest current height on top (lazy deletion)
    best = None
    j = 0
    while j < len(entries):
        w = entries[j][0]
        while j < len(entries) and entries[j][0] == w:
            _, h, i = entries[j]
            if h < height[i]:
                if height[i] == math.inf:
                    placed += 1
                height[i] = h
                heapq.heappush(heap, (-h, i))
            j += 1
        if placed < n:
            continue
        while -heap[0][0] != height[heap[0][1]]:
            heapq.heappop(heap)
        h = -heap[0][0]
        key = (w * h, 0 if w >= h else 1, w)  # least area, then landscape
        if best is None or key < best[0]:
            best = (key, (w, h))
    return best[1]


def _check_rotations(rotations):
    r = _check_number("rotations", rotations, 1, 360)
    if r != int(r):
        raise ValueError(f"rotations must be a whole number in [1, 360], got {rotations!r}")
    return int(r)


def _check_stock(stock_sizes, margin):
    """Stock sizes as a list of (width, height) floats, smallest area first (ties:
    narrower first, then input order); duplicates dropped."""
    try:
        items = list(stock_sizes)
    except TypeError:
        raise ValueError(f"stock_sizes must be a list of (width, height), got {stock_sizes!r}") \
            from None
    if not items:
        raise ValueError("stock_sizes is empty: give at least one (width, height) or None")
    sizes = []
    for k, item in enumerate(items):
        try:
            w, h = item
        except (TypeError, ValueError):
            raise ValueError(f"stock_sizes[{k}] must be (width, height), got {item!r}") from None
        w = _check_number(f"stock_sizes[{k}] width (mm)", w, 1e-3, 1e7)
        h = _check_number(f"stock_sizes[{k}] height (mm)", h, 1e-3, 1e7)
        if 2 * margin >= min(w, h):
            raise ValueError(f"margin ({margin:g} mm) must be less than half the smaller side "
                             f"of stock size {w:g} x {h:g} mm")
        if (w, h) not in sizes:
            sizes.append((w, h))
    return sorted(sizes, key=lambda s: (s[0] * s[1], s[0], sizes.index(s)))


def _size_text(sizes):
    return ", ".join(f"{w:g} x {h:g}" for w, h in sizes)


def _not_fitting(ids, boxes, fit, sizes, margin, rotations):
    """ValueError naming the first part that fits no sheet and the smallest sheet
    that fits every part."""
    bad = [i for i in range(len(ids)) if not fit[i]]
    i = bad[0]
    w, h = boxes[i, 0]
    where = (f"the sheet {sizes[0][0]:g} x {sizes[0][1]:g} mm" if len(sizes) == 1
             else f"any stock size ({_size_text(sizes)} mm)")
    more = f" (and {len(bad) - 1} more part{'s' if len(bad) > 2 else ''})" if len(bad) > 1 else ""
    sw, sh = _smallest_box(boxes + 2 * margin + _FIT_SLACK)
    turns = (f"in any of the {rotations} allowed rotations" if rotations > 1
             else "in its own orientation (rotations=1)")
    return ValueError(
        f"{ids[i]} ({w:.1f} x {h:.1f} mm) does not fit on {where} with margin {margin:g} mm "
        f"{turns}{more}; the smallest sheet that fits "
        f"every part is {sw:g} x {sh:g} mm (sheet_width={sw:g}, sheet_height={sh:g})")


def _core_nest(outlines, ids, width, height, params):
    """One core call on a width x height sheet: (placements, sheet count)."""
    p = core.NestParams()
    p.sheet_width, p.sheet_height = width, height
    p.margin, p.spacing, p.rotations = params.margin, params.spacing, params.rotations
    lay = core.nest_parts(outlines, p, ids)
    return ([Placement(int(q.sheet), float(q.angle_deg), tuple(q.offset)) for q in lay.placements],
            int(lay.sheet_count))


def _stock_nest(outlines, ids, fits_by_size, sizes, params):
    """Sheets from stock sizes: the parts are nested on the size that holds most of
    them (the larger on a tie), those that fit only elsewhere on their own sizes;
    then each sheet is re-nested on the smallest stock size (by area) that holds
    all its parts on one sheet. Returns (placements in part order, size per sheet)."""
    n = len(outlines)
    remaining = list(range(n))
    sheets = []  # [size index, [part indices], [Placement (sheet index local 0)]]
    while remaining:
        s = max(range(len(sizes)), key=lambda t: (sum(fits_by_size[t][i] for i in remaining),
                                                  sizes[t][0] * sizes[t][1], -t))
        group = [i for i in remaining if fits_by_size[s][i]]
        pls, count = _core_nest([outlines[i] for i in group], [ids[i] for i in group],
                                *sizes[s], params)
        for k in range(count):
            members = [g for g, pl in zip(group, pls) if pl.sheet == k]
            sheets.append([s, members, [Placement(0, pl.angle, pl.offset)
                                        for pl in pls if pl.sheet == k]])
        remaining = [i for i in remaining if not fits_by_size[s][i]]
    for sheet in sheets:
        s, members, _ = sheet
        for t in range(s):  # smaller (by area) first
            if not all(fits_by_size[t][i] for i in members):
                continue
            pls, count = _core_nest([outlines[i] for i in members], [ids[i] for i in members],
                                    *sizes[t], params)
            if count == 1:
                sheet[0], sheet[2] = t, pls
                break
    placements = [None] * n
    for k, (s, members, pls) in enumerate(sheets):
        for i, pl in zip(members, pls):
            placements[i] = Placement(k, pl.angle, pl.offset)
    return placements, [sizes[s] for s, _, _ in sheets]


def _polygon_area(outline):
    x, y = np.asarray(outline, dtype=float).T
    return 0.5 * abs(float(np.dot(x, np.roll(y, -1)) - np.dot(np.roll(x, -1), y)))


def nest(flat, sheet_width=2500.0, sheet_height=1250.0, margin=10.0, spacing=6.0, rotations=4,
         kerf=0.0, stock_sizes=None):
    """Nest flat panels on stock sheets (deterministic bottom-left fill, no overlaps).

    `spacing` is the least gap between two cut outlines, `margin` the free border
    of the sheet, `rotations` the number of allowed rotations (multiples of
    360/rotations degrees; 1 = keep the orientation mark), `kerf` the cut width
    (outlines are nested grown by kerf/2). `stock_sizes` (optional, a list of
    (width, height) mm) replaces the one sheet size: each sheet takes the
    smallest stock size (by area) its parts need (layout.sheet_sizes).

    Raises ValueError for a negative or non-numeric setting, for two panels with
    the same ID, and for a panel that fits no sheet in any allowed rotation (the
    message names it and the smallest sheet that fits every panel).
    """
    params = core.NestParams()
    params.sheet_width = _check_number("sheet_width (mm)", sheet_width, 1e-3, 1e7)
    params.sheet_height = _check_number("sheet_height (mm)", sheet_height, 1e-3, 1e7)
    params.margin = _check_number("margin (mm)", margin, 0.0, 1e7)
    params.spacing = _check_number("spacing (mm)", spacing, 0.0, 1e7)
    params.rotations = _check_rotations(rotations)
    kerf = _check_number("kerf (mm)", kerf, 0.0, 1000.0)
    flat = list(flat)
    ids = unique_ids(flat)
    if stock_sizes is None:
        sizes = [(params.sheet_width, params.sheet_height)]
        if 2 * params.margin >= min(sizes[0]):
            raise ValueError("margin (mm) must be less than half the sheet's smaller side")
    else:
        sizes = _check_stock(stock_sizes, params.margin)
    outlines = [cut_outline(f, kerf) for f in flat]
    for pid, o in zip(ids, outlines):
        if len(o) < 3 or not np.all(np.isfinite(o)):
            raise ValueError(f"{pid}: an outline needs at least 3 finite points")
    boxes = _boxes(outlines, params.rotations)
    fits_by_size = [_fits(boxes, w, h, params.margin) for w, h in sizes]
    fit = np.logical_or.reduce(fits_by_size) if flat else np.zeros(0, dtype=bool)
    if not fit.all():
        raise _not_fitting(ids, boxes, fit, sizes, params.margin, params.rotations)
    if stock_sizes is None:
        placements, count = _core_nest(outlines, ids, *sizes[0], params)
        sheet_sizes = [sizes[0]] * count
    else:
        placements, sheet_sizes = _stock_nest(outlines, ids, fits_by_size, sizes, params)
    area = [_polygon_area(o) for o in outlines]
    per_sheet = [0.0] * len(sheet_sizes)
    for a, pl in zip(area, placements):
        per_sheet[pl.sheet] += a
    sheet_area = [w * h for w, h in sheet_sizes]
    widest = max(sizes, key=lambda s: (s[0] * s[1], s))
    return NestLayout(
        ids=ids,
        placements=placements,
        sheet_count=len(sheet_sizes),
        sheet_utilization=[a / b for a, b in zip(per_sheet, sheet_area)],
        utilization=sum(area) / sum(sheet_area) if sheet_area else 0.0,
        sheet_width=params.sheet_width if stock_sizes is None else widest[0],
        sheet_height=params.sheet_height if stock_sizes is None else widest[1],
        margin=params.margin,
        spacing=params.spacing,
        rotations=params.rotations,
        kerf=kerf,
        outlines=outlines,
        sheet_sizes=list(sheet_sizes),
        stock_sizes=[] if stock_sizes is None else list(sizes),
        panel_outlines=[np.array(f.outline, dtype=float) for f in flat],
    )



def nest_families(flat, result, families, **options):
    """Nest every panel cut to its family's template (freecad_workbench.families):
    each template's outline as many times as its family has panels, each copy
    with the ID of the panel it becomes. `flat`: fabrication.unfold(result);
    `families`: tessella.panel_families(result, ...); options as nest()."""
    from .families import family_parts

    return nest(family_parts(flat, result, families), **options)

@dataclass
class FlatPatch:
    """A panel kept as its curved surface patch, flattened (LSCM, scaled to the 3D area)."""

    id: str
    outline: np.ndarray  # (n*subdivisions, 2): points along the panel's edges, CCW from the front
    corner_index: list  # outline index of panel corner i
    strain_max: float  # max |flat / 3D length - 1| over the edges of the fine mesh
    strain_mean: float
    area_3d: float  # area of the fine 3D mesh of the patch
    u_direction: tuple = (1.0, 0.0)  # the surface's u direction on the flat patch
    folds: list = field(default_factory=list)  # none: a curved panel is not folded

    @property
    def area(self):
        x, y = self.outline[:, 0], self.outline[:, 1]
        return 0.5 * float(np.dot(x, np.roll(y, -1)) - np.dot(np.roll(x, -1), y))


def flatten(result, face=None, subdivisions=8):
    """Flatten every panel as the curved patch of `face` it covers (the face the
    result was panelized from; optional: the result keeps it; a face-set result
    flattens each panel on its own face). Each patch is meshed with subdivisions^2 pieces per
    triangle of its (u,v) outline, flattened by least-squares conformal maps and
    scaled to its 3D area. Returns one FlatPatch per panel, with the strain."""
    from .api import face_to_brep

    n = _check_number("subdivisions", subdivisions, 1, 64)
    if n != int(n):
        raise ValueError(f"subdivisions must be a whole number in [1, 64], got {subdivisions!r}")
    p = core.FlattenParams()
    p.subdivisions = int(n)
    # The face the result was built on (no second parse); a face passed with a
    # result made elsewhere is parsed.
    surface = result.surface
    if getattr(result, "face_count", 1) > 1:
        # Each panel on its own face (its corners' (u,v) are on that face).
        face_set = getattr(result, "_face_set", None)
        if face_set is None:
            raise ValueError(f"flatten: this result covers {result.face_count} faces but does "
                             "not keep them: flatten a result of tessella.panelize_faces")
        patches = core.flatten_face_set_panels(face_set, result._mesh,
                                               result.panel_face.tolist(), p)
        return _flat_patches(result, patches)
    if surface is None:
        surface = core.SurfaceFace.from_brep_string(face_to_brep(face))
    patches = core.flatten_panels(surface, result._mesh, p)
    return _flat_patches(result, patches)


def by_class(result, classes=None, face=None, subdivisions=8,
             fold_tolerance=DEFAULT_FOLD_TOLERANCE):
    """Each panel made flat as its class says (issue 16): flat and cold-bent
    panels unfolded exactly (a cold-bent panel is cut flat and bent on site:
    its cut shape is its unfolded one, edge lengths kept), curved panels
    flattened as their surface patches with the strain reported (FlatPatch).
    `classes`: a panel_classes.PanelClasses of the result (default: the
    result's own at the defaults). Panel order."""
    from .panel_classes import panel_classes

    if classes is None:
        classes = panel_classes(result)
    if len(classes.labels) != len(result.panels):
        raise ValueError("the panel classes are not of this result's panels")
    flat = unfold(result, fold_tolerance=fold_tolerance)
    if not np.any(classes.labels == 2):
        return flat
    patches = flatten(result, face, subdivisions=subdivisions)
    return [patches[k] if classes.labels[k] == 2 else flat[k] for k in range(len(flat))]


def _flat_patches(result, patches):
    return [FlatPatch(pid, np.asarray(f.outline), list(f.corner_index), float(f.strain_max),
                      float(f.strain_mean), float(f.area_3d), tuple(f.u_direction))
            for pid, f in zip(result.panel_ids, patches)]
