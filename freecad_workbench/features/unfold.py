"""App proxy of the Unfold feature: the flat panels of a Panelization in the XY plane.

    Unfold (Part::FeaturePython, proxy `Unfold`)
        Base -> Panelization
        FoldTolerance (deg); CurvedPanels, Subdivisions; Nest, SheetWidth, SheetHeight,
        StockSizes ("2500 x 1250", ...), Margin, Spacing, Rotations, Kerf (mm)
        read-only: PanelIds, FoldAngles, FoldedPanels, MaxFoldAngle, MaxStrain, SheetCount,
        SheetSizes, Utilization, Status

Shape: a compound with one sub-compound per panel (panel order, PanelIds: the
Panelization's PanelIdFormat) holding the closed outline wire (the cutter path
when Kerf > 0) and its fold lines; laid out on sheets (in a grid, each sheet of
its own size, see export/_arrange.py) when Nest is true, else in rows.

Status: "OK" or what went wrong with the settings (e.g. a part that fits no
sheet, with the smallest sheet that fits every part). Such an error is reported
in one line, without a traceback: the object stays valid, its panels are drawn
in rows (not nested) and SheetCount is 0. Errors of the code itself raise.

FROZEN: the module path `freecad_workbench.features.unfold` and the class name
`Unfold` are stored in every saved .FCStd.
"""

import re

import FreeCAD

from .base import (  # noqa: F401
    _READONLY_OUTPUT,
    SCHEMA_VERSION,
    _attach_view_provider,
    _StateMixin,
    add_property,
    value_of,
)
from ..fabrication import DEFAULT_FOLD_TOLERANCE
from .panelization import is_panelization
from .user_errors import reports_user_errors


_SIZE = re.compile(r"\s*([0-9]*\.?[0-9]+(?:[eE][-+]?[0-9]+)?)\s*(?:mm)?\s*[xX×*]\s*"
                   r"([0-9]*\.?[0-9]+(?:[eE][-+]?[0-9]+)?)\s*(?:mm)?\s*\Z")


def parse_stock_sizes(entries):
    """[(width, height)] mm from entries like '2500 x 1250' (also '2500x1250 mm',
    '2500 × 1250') or (width, height) pairs; ValueError naming a bad entry."""
    out = []
    for k, entry in enumerate(entries or []):
        if isinstance(entry, str):
            m = _SIZE.match(entry)
            if not m:
                raise ValueError(f"StockSizes[{k}] {entry!r} is not a size like '2500 x 1250'")
            out.append((float(m.group(1)), float(m.group(2))))
        else:
            try:
                w, h = entry
                out.append((float(w), float(h)))
            except (TypeError, ValueError):
                raise ValueError(f"StockSizes[{k}] {entry!r} is not (width, height)") from None
    return out


def format_stock_sizes(sizes):
    """The StockSizes entries ('2500 x 1250') of (width, height) pairs or entries."""
    return [f"{w:g} x {h:g}" for w, h in parse_stock_sizes(sizes)]


def flat_panels(panelization, result, curved, subdivisions, fold_tolerance, by_class=False):
    """The flat panels of `result` (the Panelization's): flattened curved
    patches (`curved`), each panel as its class says (`by_class`: the Panels
    object's classes; curved ones flattened, the others unfolded) or unfolded
    flat panels."""
    from .. import fabrication
    from ..spreadsheets import panel_classes_of

    # A face set's result keeps its faces; one face is named for a result
    # made elsewhere.
    def face_arg():
        return (None if result.face_count > 1
                else panelization.Proxy.source_face(panelization)[0])

    if curved:
        return fabrication.flatten(result, face_arg(), subdivisions=subdivisions)
    if by_class:
        classes = panel_classes_of(panelization)
        if classes is not None and bool((classes.labels == 2).any()):
            return fabrication.by_class(result, classes, face_arg(), subdivisions=subdivisions,
                                        fold_tolerance=fold_tolerance)
    return fabrication.unfold(result, fold_tolerance=fold_tolerance)


class Unfold(_StateMixin):
    def __init__(self, obj, base=None):
        self._restore(None)
        self.setup_properties(obj)
        if base is not None:
            obj.Base = base
        obj.Proxy = self

    def setup_properties(self, obj):
        add_property(obj, "App::PropertyLink", "Base", "Unfold", "The Panelization to unfold")
        add_property(obj, "App::PropertyAngle", "FoldTolerance", "Unfold",
                     "Folds under this angle count as flat (a sheet takes a smaller kink when fixed)",
                     default=DEFAULT_FOLD_TOLERANCE)
        add_property(obj, "App::PropertyBool", "CurvedPanels", "Unfold",
                     "Keep panels as curved patches of the surface and flatten them (LSCM)",
                     default=False)
        add_property(obj, "App::PropertyBool", "ByPanelClass", "Unfold",
                     "Curved panels (the Panels' classes) flattened as surface patches with "
                     "their strain, flat and cold-bent ones unfolded exactly", default=False)
        add_property(obj, "App::PropertyInteger", "Subdivisions", "Unfold",
                     "Curved panels: mesh pieces per triangle edge", default=8)
        add_property(obj, "App::PropertyBool", "Nest", "Nesting",
                     "Lay the panels out on stock sheets", default=False)
        add_property(obj, "App::PropertyLength", "SheetWidth", "Nesting", "Sheet width",
                     default=2500.0)
        add_property(obj, "App::PropertyLength", "SheetHeight", "Nesting", "Sheet height",
                     default=1250.0)
        add_property(obj, "App::PropertyStringList", "StockSizes", "Nesting",
                     "Stock sheet sizes 'width x height' (mm), e.g. 2500 x 1250: each sheet "
                     "takes the smallest (by area) that holds its parts. Empty: SheetWidth x "
                     "SheetHeight")
        add_property(obj, "App::PropertyLength", "Margin", "Nesting",
                     "Free border on every side of a sheet", default=10.0)
        add_property(obj, "App::PropertyLength", "Spacing", "Nesting",
                     "Least gap between two parts", default=6.0)
        add_property(obj, "App::PropertyInteger", "Rotations", "Nesting",
                     "Allowed rotations: multiples of 360/Rotations degrees", default=4)
        add_property(obj, "App::PropertyLength", "Kerf", "Nesting",
                     "Cut width: outlines are grown by Kerf/2 for the cutter", default=0.0)
        ro = _READONLY_OUTPUT
        add_property(obj, "App::PropertyStringList", "PanelIds", "Result",
                     "Panel IDs, one per sub-shape", attr=ro)
        add_property(obj, "App::PropertyFloatList", "FoldAngles", "Result",
                     "Fold angle per panel (deg, 0 = flat)", attr=ro)
        add_property(obj, "App::PropertyInteger", "FoldedPanels", "Result",
                     "Panels with at least one fold", attr=ro)
        add_property(obj, "App::PropertyFloat", "MaxFoldAngle", "Result",
                     "Largest fold angle (deg)", attr=ro)
        add_property(obj, "App::PropertyFloat", "MaxStrain", "Result",
                     "Curved panels: largest flattening strain |flat/3D length - 1|", attr=ro)
        add_property(obj, "App::PropertyInteger", "SheetCount", "Result",
                     "Sheets used (0 without nesting)", attr=ro)
        add_property(obj, "App::PropertyFloat", "Utilization", "Result",
                     "Panel area / sheet area over all sheets", attr=ro)
        add_property(obj, "App::PropertyStringList", "SheetSizes", "Result",
                     "Size of every sheet, 'width x height' (mm)", attr=ro)
        add_property(obj, "App::PropertyString", "Status", "Result",
                     "OK, or why the panels could not be unfolded or nested", attr=ro)

    def onDocumentRestored(self, obj):
        self._ensure_runtime()
        self.setup_properties(obj)
        _attach_view_provider(obj, "ViewProviderUnfold")

    def options(self, obj):
        return {
            "fold_tolerance": value_of(obj.FoldTolerance),
            "curved": bool(obj.CurvedPanels),
            "by_class": bool(getattr(obj, "ByPanelClass", False)),
            "subdivisions": int(obj.Subdivisions),
            "nest": bool(obj.Nest),
            "sheet_width": value_of(obj.SheetWidth),
            "sheet_height": value_of(obj.SheetHeight),
            "margin": value_of(obj.Margin),
            "spacing": value_of(obj.Spacing),
            "rotations": int(obj.Rotations),
            "kerf": value_of(obj.Kerf),
            "stock_sizes": list(getattr(obj, "StockSizes", [])),
        }

    def _unfold(self, obj):
        base = obj.Base
        if base is None or not is_panelization(base):
            raise ValueError("Base must link to a Panelization object")
        res = base.Proxy.result(base).result  # carries the Panelization's ID formats
        o = self.options(obj)
        flat = flat_panels(base, res, o["curved"], o["subdivisions"], o["fold_tolerance"],
                           o["by_class"])
        return res, flat

    def compute_flat(self, obj):
        """The flat panels (FlatPanel or FlatPatch, panel order) for the current options."""
        return self._unfold(obj)[1]

    def compute(self, obj):
        """(result, flat, layout or None) for the current Base and options."""
        res, flat = self._unfold(obj)
        return res, flat, self.nest(obj, flat)

    def nest(self, obj, flat):
        """The nesting layout of `flat` for the current options (None without Nest)."""
        from .. import fabrication

        o = self.options(obj)
        if o["nest"]:
            return fabrication.nest(flat, sheet_width=o["sheet_width"],
                                    sheet_height=o["sheet_height"], margin=o["margin"],
                                    spacing=o["spacing"], rotations=o["rotations"],
                                    kerf=o["kerf"],
                                    stock_sizes=parse_stock_sizes(o["stock_sizes"]) or None)
        fabrication.cut_outline(flat[0] if flat else [[0, 0], [1, 0], [0, 1]], o["kerf"])
        return None

    @reports_user_errors
    def execute(self, obj):
        import Part

        from .. import fabrication
        from ..export import _arrange

        # A setting the user can fix (ValueError: a part that fits no sheet, a bad
        # stock size, an ID format) becomes the Status, reported in one line; the
        # panels are still drawn (in rows) when only the nesting failed.
        flat, layout, status = [], None, "OK"
        try:
            flat = self.compute_flat(obj)
            layout = self.nest(obj, flat)
        except ValueError as exc:
            status = f"{'Not nested: ' if flat else ''}{exc}"
            FreeCAD.Console.PrintError(f"Tessella: {obj.Label}: {status}\n")
            layout = None
        obj.Status = status
        kerf = layout.kerf if layout is not None else value_of(obj.Kerf)
        if not 0.0 <= kerf <= 1000.0:  # reported in Status: draw the nominal outlines
            kerf = 0.0
        placements, _ = _arrange.arrange(flat, layout)
        parts = []
        for f, pl in zip(flat, placements):
            cut = _arrange.transform(fabrication.cut_outline(f, kerf), *pl)
            pts = [FreeCAD.Vector(float(x), float(y), 0.0) for x, y in cut]
            edges = [Part.makePolygon(pts + [pts[0]])]
            for a, b, _angle in f.folds:
                pa, pb = _arrange.transform([f.outline[a], f.outline[b]], *pl)
                edges.append(Part.LineSegment(FreeCAD.Vector(*pa, 0), FreeCAD.Vector(*pb, 0)).toShape())
            parts.append(Part.makeCompound(edges))
        obj.Shape = Part.makeCompound(parts)
        obj.PanelIds = [f.id for f in flat]
        obj.FoldAngles = [float(getattr(f, "fold_angle", 0.0)) for f in flat]
        obj.MaxStrain = float(max((getattr(f, "strain_max", 0.0) for f in flat), default=0.0))
        obj.FoldedPanels = sum(1 for f in flat if f.folds)
        obj.MaxFoldAngle = float(max(obj.FoldAngles, default=0.0))
        obj.SheetCount = layout.sheet_count if layout else 0
        obj.Utilization = float(layout.utilization) if layout else 0.0
        obj.SheetSizes = [f"{w:g} x {h:g}" for w, h in layout.sheet_sizes] if layout else []
