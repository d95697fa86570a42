"""Fabrication console API: unfolded panels and their nesting on stock sheets.

    import freecad_workbench as tessella
    r = tessella.panelize(face, method="iso_grid", size=1500.0)
    flat = tessella.unfold(r)                  # one FlatPanel per panel, same order
    flat[i].outline                            # (k,2) mm, the panel's corner order, CCW from the front
    flat[i].fold, flat[i].fold_angle           # None / (a, b) corner indices; degrees (0 = flat)
    layout = tessella.nest(flat, sheet_width=2500.0, sheet_height=1250.0,
                           margin=10.0, spacing=6.0, rotations=4)
    layout.sheet_count, layout.utilization, layout.placed_outline(i)

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


def unfold(result, fold_tolerance=0.01):
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
    """Where every flat panel lies: sheet point = R(angle) outline point + offset."""

    ids: list
    placements: list  # Placement per panel, input order
    sheet_count: int
    sheet_utilization: list  # per sheet: panel area / sheet area
    utilization: float  # all panel area / all sheets' area
    sheet_width: float
    sheet_height: float
    margin: float
    spacing: float
    rotations: int
    kerf: float
    outlines: list = field(default_factory=list, repr=False)  # the nested outlines

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


def cut_outline(panel, kerf):
    """The cutter path of a flat panel: its outline grown by kerf/2 (kerf = cut width, mm)."""
    kerf = _check_number("kerf (mm)", kerf, 0.0, 1000.0)
    outline = np.asarray(getattr(panel, "outline", panel), dtype=float)
    if kerf == 0.0:
        return np.array(outline, dtype=float)
    p = core.OutlineOffsetParams()
    p.distance = 0.5 * kerf
    return np.asarray(core.offset_outline(outline, p))


def nest(flat, sheet_width=2500.0, sheet_height=1250.0, margin=10.0, spacing=6.0, rotations=4,
         kerf=0.0):
    """Nest flat panels on stock sheets (deterministic bottom-left fill, no overlaps).

    `spacing` is the least gap between two cut outlines, `margin` the free border
    of the sheet, `rotations` the number of allowed rotations (multiples of
    360/rotations degrees; 1 = keep the orientation mark), `kerf` the cut width
    (outlines are nested grown by kerf/2). Raises ValueError for a negative or
    non-numeric setting and for a panel that fits the sheet in no rotation.
    """
    params = core.NestParams()
    params.sheet_width = _check_number("sheet_width (mm)", sheet_width, 1e-3, 1e7)
    params.sheet_height = _check_number("sheet_height (mm)", sheet_height, 1e-3, 1e7)
    params.margin = _check_number("margin (mm)", margin, 0.0, 1e7)
    params.spacing = _check_number("spacing (mm)", spacing, 0.0, 1e7)
    r = _check_number("rotations", rotations, 1, 360)
    if r != int(r):
        raise ValueError(f"rotations must be a whole number in [1, 360], got {rotations!r}")
    params.rotations = int(r)
    kerf = _check_number("kerf (mm)", kerf, 0.0, 1000.0)
    flat = list(flat)
    ids = [getattr(f, "id", f"part {i}") for i, f in enumerate(flat)]
    outlines = [cut_outline(f, kerf) for f in flat]
    lay = core.nest_parts(outlines, params, ids)
    placements = [Placement(int(p.sheet), float(p.angle_deg), tuple(p.offset)) for p in lay.placements]
    return NestLayout(
        ids=ids,
        placements=placements,
        sheet_count=int(lay.sheet_count),
        sheet_utilization=[float(u) for u in lay.sheet_utilization],
        utilization=float(lay.utilization),
        sheet_width=params.sheet_width,
        sheet_height=params.sheet_height,
        margin=params.margin,
        spacing=params.spacing,
        rotations=params.rotations,
        kerf=kerf,
        outlines=outlines,
    )


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
    result was panelized from; optional: the result keeps it). Each patch is meshed with subdivisions^2 pieces per
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
    if surface is None:
        surface = core.SurfaceFace.from_brep_string(face_to_brep(face))
    patches = core.flatten_panels(surface, result._mesh, p)
    return [FlatPatch(pid, np.asarray(f.outline), list(f.corner_index), float(f.strain_max),
                      float(f.strain_mean), float(f.area_3d), tuple(f.u_direction))
            for pid, f in zip(result.panel_ids, patches)]
