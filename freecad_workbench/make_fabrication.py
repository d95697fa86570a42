"""make_unfold: the parametric Unfold object of a Panelization (console and command).

    u = tessella.make_unfold(panelization, fold_tolerance=0.5, nest=True,
                             sheet_width=2500, sheet_height=1250, margin=10, spacing=6,
                             rotations=4, kerf=0.0,
                             stock_sizes=[(2500, 1250), (3000, 1500)])   # optional
    # curved panels (the Panels' classes) flattened with their strain, the rest unfolded:
    u = tessella.make_unfold(panelization, by_panel_class=True)
"""

import FreeCAD

_OPTIONS = {
    "fold_tolerance": "FoldTolerance",
    "curved_panels": "CurvedPanels",
    "by_panel_class": "ByPanelClass",
    "subdivisions": "Subdivisions",
    "nest": "Nest",
    "sheet_width": "SheetWidth",
    "sheet_height": "SheetHeight",
    "margin": "Margin",
    "spacing": "Spacing",
    "rotations": "Rotations",
    "kerf": "Kerf",
    "stock_sizes": "StockSizes",
}


def make_unfold(panelization, doc=None, **options):
    """Create an Unfold object for `panelization` in one transaction ("Unfold").

    Options are checked by unfolding (and nesting) once before anything is
    created: a bad value raises ValueError and leaves the document untouched.
    """
    from . import fabrication
    from .features import panelization as pfeat
    from .features import unfold as feat

    if not pfeat.is_panelization(panelization):
        raise ValueError("make_unfold needs a Panelization object (select one, or pass it)")
    unknown = sorted(set(options) - set(_OPTIONS))
    if unknown:
        raise ValueError(f"unknown option(s) {unknown}; accepted: {sorted(_OPTIONS)}")
    doc = doc or panelization.Document
    res = panelization.Proxy.result(panelization).result
    flat = feat.flat_panels(panelization, res, options.get("curved_panels", False),
                            options.get("subdivisions", 8),
                            options.get("fold_tolerance", fabrication.DEFAULT_FOLD_TOLERANCE),
                            options.get("by_panel_class", False))
    kerf = options.get("kerf", 0.0)
    if "stock_sizes" in options:  # entries like "2500 x 1250" or (width, height) pairs
        options["stock_sizes"] = feat.format_stock_sizes(options["stock_sizes"])
    if options.get("nest"):
        nest_opts = {k: options[k] for k in ("sheet_width", "sheet_height", "margin", "spacing",
                                             "rotations") if k in options}
        stock = feat.parse_stock_sizes(options.get("stock_sizes")) or None
        fabrication.nest(flat, kerf=kerf, stock_sizes=stock, **nest_opts)
    else:
        fabrication.cut_outline([[0, 0], [1, 0], [0, 1]], kerf)

    doc.openTransaction("Unfold")
    name = None
    try:
        obj = doc.addObject("Part::FeaturePython", "Unfold")
        name = obj.Name
        feat.Unfold(obj, panelization)
        for key, value in options.items():
            setattr(obj, _OPTIONS[key], value)
        if FreeCAD.GuiUp:
            from .gui.unfold_view import ViewProviderUnfold

            ViewProviderUnfold(obj.ViewObject)
            obj.ViewObject.LineColor = (0.8, 0.1, 0.1)
        doc.recompute()
        if not obj.isValid() or "Touched" in obj.State:
            raise RuntimeError(f"the Unfold did not recompute: {', '.join(obj.State)}")
        placement = beside(panelization, obj)
        if placement is not None:
            obj.Placement = placement  # moves the shape at once: nothing to recompute
            obj.purgeTouched()
        if obj.Status != "OK":
            raise ValueError(obj.Status)
    except BaseException:
        doc.abortTransaction()
        if name and doc.getObject(name) is not None:
            doc.removeObject(name)
        raise
    doc.commitTransaction()
    return obj


def export_unfold(unfold_obj, path, **options):
    """Write an Unfold object's flat panels (as laid out: nested or in rows) to a
    DXF or SVG file, chosen by the extension. Returns the writer's summary. A DXF is
    written for CAM as `export_dxf` does by default (one file per sheet when nested:
    <stem>_sheet01.dxf, ...; the summary's "paths"); `options` go to `export_dxf`
    (per_sheet, blocks, cut_path, reference, arcs, chord_tolerance, ...)."""
    from .export.dxf import export_dxf
    from .export.svg import export_svg
    from .features.unfold import Unfold

    if not isinstance(getattr(unfold_obj, "Proxy", None), Unfold):
        raise ValueError("export_unfold needs an Unfold object (select one, or pass it)")
    ext = str(path).lower().rsplit(".", 1)[-1]
    if ext not in ("dxf", "svg"):
        raise ValueError(f"the file must end in .dxf or .svg, got {path!r}")
    _res, flat, layout = unfold_obj.Proxy.compute(unfold_obj)
    kerf = layout.kerf if layout else float(getattr(unfold_obj.Kerf, "Value", unfold_obj.Kerf))
    if ext == "svg":
        if options:
            raise ValueError(f"options {sorted(options)} apply to DXF only")
        return export_svg(flat, path, layout=layout, kerf=kerf)
    return export_dxf(flat, path, layout=layout, kerf=kerf, **options)


def export_families(panelization, path, fold_tolerance=0.01, **options):
    """Write one template per panel family of a Panelization (its Panels object's
    FamilyTolerance / Mirror) with the list of members, to DXF or SVG by the
    extension (export.dxf.export_family_dxf / export.svg.export_family_svg;
    `options` go to the DXF writer). ValueError while families are off."""
    from . import fabrication
    from .export.dxf import export_family_dxf
    from .export.svg import export_family_svg
    from .spreadsheets import panel_families_of

    fam = panel_families_of(panelization)
    if fam is None:
        raise ValueError(f"{panelization.Label}: panel families are off: set the Panels "
                         "object's FamilyTolerance (mm) above 0")
    ext = str(path).lower().rsplit(".", 1)[-1]
    if ext not in ("dxf", "svg"):
        raise ValueError(f"the file must end in .dxf or .svg, got {path!r}")
    res = panelization.Proxy.result(panelization).result
    flat = fabrication.unfold(res, fold_tolerance=fold_tolerance)
    if ext == "svg":
        if options:
            raise ValueError(f"options {sorted(options)} apply to DXF only")
        return export_family_svg(flat, res, fam, path)
    return export_family_dxf(flat, res, fam, path, **options)

def beside(panelization, unfold):
    """A Placement that lays the flat parts of a new Unfold (still at the
    identity) next to the model: to the right of the Panels' bounding box with
    a gap of a tenth of its size, fronts aligned, still in the XY plane (the
    workshop floor), so the Unfold never covers the model in the 3D view.
    None when either shape is empty."""
    from .features.panelization import children_of

    panels = [c for c in children_of(panelization) if c.Role == "Panels"]
    if not panels or panels[0].Shape.isNull() or unfold.Shape.isNull():
        return None
    model, flat = panels[0].Shape.BoundBox, unfold.Shape.BoundBox
    gap = 0.1 * max(model.XLength, model.YLength, 1.0)
    offset = FreeCAD.Vector(model.XMax + gap - flat.XMin, model.YMin - flat.YMin, 0.0)
    return FreeCAD.Placement(offset, FreeCAD.Rotation())
