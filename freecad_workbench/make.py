"""make_* factories: create parametric Tessella objects from the console or a command.

    import freecad_workbench as tessella
    p = tessella.make_panelization((doc.Surface, "Face1"), method="iso_grid", size=1500)
    p.PanelCount        # summary on the parent
    p.Size = 1000       # parametric: change, then doc.recompute()

The children (Panels, Rods, Nodes) are listed by
freecad_workbench.features.panelization.children_of(p).
"""

import FreeCAD

from . import selection


def _param_to_property():
    """make_panelization keyword -> Panelization property (from the declarations)."""
    from .methods import METHODS
    from .planarization import OPTIONS

    out = {p.name: p.property for m in METHODS.values() for p in m}
    out.update({name: spec[0] for name, spec in OPTIONS.items()})
    return out


_VIEW_STYLE = {
    "Panels": {"ShapeColor": (0.80, 0.68, 0.42), "LineColor": (0.35, 0.30, 0.20), "LineWidth": 1.0},
    "Rods": {"LineColor": (0.15, 0.20, 0.35), "LineWidth": 3.0, "PointSize": 1.0},
    "Nodes": {"PointColor": (0.80, 0.10, 0.10), "PointSize": 6.0},
}


def make_panelization(source, method="iso_grid", doc=None, progress=None, **params):
    """Create a Panelization (parent) and its Panels, Rods and Nodes children.

    source: (document object, "FaceN") or a document object with one face; or
        several faces of one object, (obj, ["Face1", "Face3"]) or the object
        itself (all its faces): one envelope, joined along the shared edges; or
        faces of several objects, [(a, ["Face1"]), (b, ["Face2"])] (where they
        touch along edges they do not share, they are sewn).
    method: one of freecad_workbench.api.METHODS.
    params: the keyword parameters of freecad_workbench.panelize (size, u_count,
        v_count, sliver_fraction, min_angle, max_panels, trim_deflection, samples).

    The parameters are checked by running the panelization once before anything is
    created: a bad parameter or an unusable face raises ValueError and leaves the
    document untouched. The four objects are created in one transaction ("Panelize",
    one undo step) and the document is recomputed. Returns the parent object.
    """
    from . import api
    from .features import panelization as feat

    sources = selection.face_set_links(source)
    obj, subs = sources[0]
    several = len(selection.faces_of(sources)) > 1
    sub = None if several else (subs[0] if subs else "Face1")
    if doc is None:
        doc = obj.Document
    for owner, _subs in sources:
        if owner.Document is not doc:
            raise ValueError(
                f"the source {owner.Label!r} is in document {owner.Document.Name!r}, "
                f"not in {doc.Name!r}"
            )
    from .methods import METHODS

    if method not in METHODS:
        raise ValueError(f"method must be one of {sorted(METHODS)}, got {method!r}")
    to_property = _param_to_property()
    # Curve parameters (guides, extra curves) are stored as links to document
    # edges (a loose Part.Edge could not recompute).
    links = {p.property: selection.edge_links(params[p.name], context=p.name)
             for p in METHODS[method] if p.type in ("curves", "uv_curves") and p.name in params}
    # Validate everything (method, parameter names and ranges, the face) by
    # computing the result once; the new object starts from it (no second run).
    try:
        if several:
            result = api.panelize_faces(sources, method=method, progress=progress, **params)
        else:
            result = api.panelize((obj, sub), method=method, progress=progress, **params)
    finally:
        close = getattr(progress, "close", None)
        if close is not None:
            close()

    created = []
    doc.openTransaction("Panelize")
    try:
        parent = doc.addObject("App::FeaturePython", "Panelization")
        created.append(parent.Name)
        feat.Panelization(parent)
        parent.Source = (obj, subs if several else [sub])
        if len(sources) > 1:
            # A whole object as (object, ['']): FreeCAD drops (object, []).
            parent.MoreSources = [(o, names or [""]) for o, names in sources[1:]]
        parent.Method = method
        for key, value in params.items():
            if to_property[key] not in links:
                setattr(parent, to_property[key], value)
        for prop, pairs in links.items():
            setattr(parent, prop, selection.link_sub_list(pairs))
        if FreeCAD.GuiUp:
            from .gui import preferences

            parent.PanelIdFormat = preferences.defaults()["panel_id_format"]
        parent.Proxy.seed(parent, result)
        children = []
        for role in feat.ROLES:
            child = doc.addObject("Part::FeaturePython", role)
            created.append(child.Name)
            feat.PanelizationPart(child, parent, role)
            children.append(child)
        # The panels take the face's place in the view, as PartDesign hides a
        # feature's base (in the transaction: undo shows it again); headless
        # too, so a saved document opens the same way.
        if FreeCAD.GuiUp:
            _attach_gui(parent, children)
        for owner, _subs in sources:
            if FreeCAD.GuiUp and getattr(owner, "ViewObject", None) is not None:
                owner.ViewObject.Visibility = False
            elif not FreeCAD.GuiUp and "Visibility" in owner.PropertiesList:
                owner.Visibility = False
        doc.recompute()
        broken = [o for o in [parent] + children if not o.isValid() or "Touched" in o.State]
        if broken:
            raise RuntimeError(
                "the panelization did not recompute: "
                + ", ".join(f"{o.Label} ({', '.join(o.State)})" for o in broken)
            )
    except BaseException:
        doc.abortTransaction()
        # Without undo (UndoMode 0) the abort leaves the objects: remove them.
        for name in reversed(created):
            if doc.getObject(name) is not None:
                doc.removeObject(name)
        raise
    doc.commitTransaction()
    return parent


def _attach_gui(parent, children):
    from .gui import view_providers as vp

    vp.ViewProviderPanelization(parent.ViewObject)
    for child in children:
        vp.ViewProviderPanelizationPart(child.ViewObject)
        for name, value in _VIEW_STYLE.get(child.Role, {}).items():
            if hasattr(child.ViewObject, name):
                setattr(child.ViewObject, name, value)


def make_curve_network(panelization, show="Curves"):
    """Create a CurveNetwork object showing the traced BDCurves ("Curves") or the
    preliminary network ("Network") of a boundary_driven Panelization. One undo
    step; raises ValueError (and creates nothing) for another method."""
    from .features import curve_network as cn
    from .features import panelization as feat

    if not feat.is_panelization(panelization):
        raise ValueError("make_curve_network needs a Panelization object")
    if panelization.Method != "boundary_driven":
        raise ValueError(f"{panelization.Label} uses {panelization.Method}, not boundary_driven")
    if show not in cn.SHOW:
        raise ValueError(f"show must be one of {cn.SHOW}, got {show!r}")
    doc = panelization.Document
    doc.openTransaction("Curve network")
    try:
        obj = doc.addObject("Part::FeaturePython", "CurveNetwork")
        cn.CurveNetwork(obj, panelization)
        obj.Show = show
        doc.recompute()
    except BaseException:
        doc.abortTransaction()
        raise
    doc.commitTransaction()
    return obj
