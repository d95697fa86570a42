"""One normalizer for what callers hand Tessella as "a face" or "edges".

Every caller (the console API, the make_* factories, the document features,
the GUI commands and the task panel's picking) goes through these functions,
so a form accepted in one place is accepted everywhere, with the same message
when it is wrong.

Accepted forms:

    Part.Face, a shape holding exactly one face (shell, compound, ...)
    Part.Edge, Part.Wire, a shape holding exactly one wire or one edge
    document object                      (its Shape; one face / one curve)
    (object, "FaceN") / (object, "EdgeN")
    (object, ["Sub1", ...])              (several sub-elements; [] = the whole object)
    FreeCAD selection objects            (Gui.Selection.getSelectionEx() items)
    a LinkSub / LinkSubList property value, and lists of all of the above

Results:

    one_face(x)     -> Part.Face                 faces_of(x)  -> [Part.Face]
    face_link(x)    -> (object, "FaceN")         (to store in a PropertyLinkSub)
    face_set_links(x) -> [(object, ["FaceN", ...])] (faces of one or more objects)
    one_edge(x)     -> Part.Edge or Part.Wire    edges_of(x)  -> [Part.Edge / Part.Wire]
    edge_links(x)   -> [(object, "EdgeN" or "")] (to store in a PropertyLinkSubList)
    links_of(x)     -> [(object, "SubName" or "")]

Wrong input raises ValueError (not a face, several faces where one is needed,
an empty shape, an object without a shape, a missing sub-element) or TypeError
(something that is no shape, object or selection at all; the edge functions
raise ValueError there too: the `guides` parameter's contract). `context`
prefixes the message ("guides: ...", "Panelization: Source: ...").

A wire (or an object whose shape is one wire) is one curve: edges_of keeps it
whole, as the guide-line methods take it.
"""

import FreeCAD

FACE, EDGE = "Face", "Edge"


def _part():
    import Part  # FreeCAD's; imported late so `import FreeCAD` comes first

    return Part


def _prefix(context, text):
    return f"{context}: {text}" if context else text


def _label(obj):
    return getattr(obj, "Label", obj)


def is_element(sub, kind):
    """Whether a sub-element name like 'Face3' is of the kind 'Face' / 'Edge' / 'Vertex'."""
    return isinstance(sub, str) and sub.startswith(kind)


def _is_shape(x):
    return isinstance(x, _part().Shape)


def _is_selection_object(x):
    """A FreeCAD SelectionObject (Gui.Selection.getSelectionEx())."""
    return hasattr(x, "SubElementNames") and hasattr(x, "Object") and not _is_shape(x)


def _is_object_like(x):
    """What can be the first member of an (object, 'Sub') pair."""
    return not isinstance(x, (str, bytes, list, tuple)) and not _is_shape(x) \
        and not _is_selection_object(x)


def _is_pair(x):
    """(object, 'Sub') or (object, ['Sub', ...]): not a list of two inputs."""
    if not isinstance(x, (tuple, list)) or len(x) != 2 or not _is_object_like(x[0]):
        return False
    second = x[1]
    if isinstance(second, FreeCAD.DocumentObject) or _is_shape(second) \
            or _is_selection_object(second):
        return False
    return not _is_pair(second)


def _items(x, kind):
    """Flatten any accepted input into ("link", obj, sub), ("shape", shape) or
    ("other", value) items (sub '' = the whole object)."""
    if _is_selection_object(x):
        names = [n for n in x.SubElementNames if n]
        if not names:
            yield ("link", x.Object, "")
        for name in names:
            yield ("link", x.Object, name)
    elif _is_pair(x):
        obj, sub = x
        if isinstance(sub, str):
            subs = [sub]
        elif isinstance(sub, (list, tuple)) and all(isinstance(s, str) for s in sub):
            subs = list(sub)
        else:
            raise TypeError(f"the sub-element must be a name like '{kind}1', not {sub!r}")
        subs = [s for s in subs if s]
        if not subs:
            yield ("link", obj, "")
        for s in subs:
            yield ("link", obj, s)
    elif isinstance(x, (list, tuple)):
        for item in x:
            yield from _items(item, kind)
    elif _is_shape(x):
        yield ("shape", x)
    elif isinstance(x, FreeCAD.DocumentObject):
        yield ("link", x, "")
    else:
        yield ("other", x)


def _shape_of(obj, context):
    shape = getattr(obj, "Shape", None)
    if shape is None or not _is_shape(shape) or shape.isNull():
        raise ValueError(_prefix(context, f"{_label(obj)!r} has no shape"))
    return shape


def _element(obj, shape, sub, context):
    try:
        return shape.getElement(sub)
    except Exception as exc:
        raise ValueError(_prefix(context, f"{_label(obj)} has no {sub}")) from exc


def _describe(items):
    subs = [it[2] for it in items if it[0] == "link"]
    objs = {id(it[1]) for it in items if it[0] == "link"}
    if len(subs) == len(items) and len(objs) == 1 and all(subs):
        return f"sub-elements {subs}"
    return f"{len(items)} selections"


# ------------------------------------------------------------------- links
def links_of(x, context=None):
    """[(document object, 'SubName' or '')] of a link-like input (objects,
    pairs, selection objects, property values, lists). TypeError for a loose
    shape or anything else that cannot be linked."""
    out = []
    for item in _items(x, "Sub"):
        if item[0] != "link" or not isinstance(item[1], FreeCAD.DocumentObject):
            value = item[1]
            raise TypeError(_prefix(
                context, "a link needs a document object or (object, 'SubName'), "
                f"not {type(value).__name__}"))
        out.append((item[1], item[2]))
    return out


def link_sub_list(links):
    """A PropertyLinkSubList value from [(object, 'Sub' or '')]. A whole object is
    stored as (object, ['']): FreeCAD drops an (object, []) entry altogether."""
    return [(o, [s or ""]) for o, s in links]


# ------------------------------------------------------------------- faces
def _one_face_of_shape(shape, context):
    if shape.isNull():
        raise ValueError(_prefix(context, "the shape is empty"))
    if shape.ShapeType == "Face":
        return shape
    faces = shape.Faces
    if len(faces) != 1:
        raise ValueError(_prefix(
            context, f"the shape has {len(faces)} faces: pass exactly one face "
            "(e.g. shape.Faces[0])"))
    return faces[0]


def _face_sub(obj, sub, context):
    """Check one face link; returns (shape, 'FaceN')."""
    shape = _shape_of(obj, context)
    if not sub:
        n = len(shape.Faces)
        if n != 1:
            raise ValueError(_prefix(
                context, f"{_label(obj)!r} has {n} faces: pass (object, 'FaceN') to choose one"))
        sub = "Face1"
    elif not is_element(sub, FACE):
        raise ValueError(_prefix(
            context, f"{sub!r} is not a face: select a face, not an edge or a vertex"))
    return shape, sub


def _exactly_one(items, context, what):
    if not items:
        raise ValueError(_prefix(context, f"nothing given: select exactly one {what}"))
    if len(items) > 1:
        raise ValueError(_prefix(context, f"select exactly one {what}, got {_describe(items)}"))
    return items[0]


def face_link(x, context=None):
    """(document object, 'FaceN') naming exactly one face: from (obj, 'FaceN'),
    (obj, ['FaceN']), a one-face object, one selected face, a LinkSub value."""
    items = list(_items(x, FACE))
    for item in items:
        if item[0] != "link" or not isinstance(item[1], FreeCAD.DocumentObject):
            raise TypeError(_prefix(
                context, "source must be a document object or (object, 'FaceN'), "
                f"not {type(item[1]).__name__}"))
    _kind, obj, sub = _exactly_one(items, context, "face")
    shape, sub = _face_sub(obj, sub, context)
    _element(obj, shape, sub, context)
    return obj, sub


def one_face(x, context=None):
    """The one Part.Face named by x (see the module docstring for the forms)."""
    items = list(_items(x, FACE))
    for item in items:
        if item[0] == "other":
            raise TypeError(_prefix(
                context, "face must be a Part.Face, a shape with one face, a document "
                f"object or (object, 'FaceN'), not {type(item[1]).__name__}"))
    item = _exactly_one(items, context, "face")
    if item[0] == "shape":
        return _one_face_of_shape(item[1], context)
    _kind, obj, sub = item
    shape, sub = _face_sub(obj, sub, context)
    return _one_face_of_shape(_element(obj, shape, sub, context), context)


def face_set_links(x, context=None):
    """[(document object, ['FaceN', ...]), ...] naming one or more faces: one
    entry per object, in the order first met ([] = all the object's faces);
    from (obj, 'FaceN'), (obj, ['Face1', 'Face3']), objects, the selected faces
    (of one object or several), a Source / MoreSources value, lists of these.
    Faces of several objects make one envelope: where they touch along edges
    they do not share, the face set sews them (core.FaceSet)."""
    items = list(_items(x, FACE))
    for item in items:
        if item[0] != "link" or not isinstance(item[1], FreeCAD.DocumentObject):
            raise TypeError(_prefix(
                context, "source must be a document object or (object, ['FaceN', ...]), "
                f"not {type(item[1]).__name__}"))
    if not items:
        raise ValueError(_prefix(context, "nothing given: select one or more faces"))
    owners, subs_of = [], {}
    for _kind, obj, sub in items:
        if obj not in owners:
            owners.append(obj)
            subs_of[obj.Name] = []
        shape = _shape_of(obj, context)
        subs = subs_of[obj.Name]
        if not sub:
            if not shape.Faces:
                raise ValueError(_prefix(context, f"{_label(obj)!r} has no faces"))
            subs_of[obj.Name] = None  # the whole object
            continue
        if not is_element(sub, FACE):
            raise ValueError(_prefix(
                context, f"{sub!r} is not a face: select a face, not an edge or a vertex"))
        _element(obj, shape, sub, context)
        if subs is not None and sub not in subs:
            subs.append(sub)
    return [(obj, subs_of[obj.Name] or []) for obj in owners]


def faces_of(x, context=None):
    """Every face x names, in order: all faces of a shape or of an object given
    without a sub-element, the named face of (obj, 'FaceN')."""
    faces = []
    for item in _items(x, FACE):
        if item[0] == "other":
            raise TypeError(_prefix(
                context, "expected faces (Part shapes, document objects or "
                f"(object, 'FaceN')), not {type(item[1]).__name__}"))
        if item[0] == "shape":
            shape = item[1]
            if shape.isNull():
                raise ValueError(_prefix(context, "the shape is empty"))
            found = [shape] if shape.ShapeType == "Face" else list(shape.Faces)
            if not found:
                raise ValueError(_prefix(context, "the shape has no faces"))
            faces.extend(found)
            continue
        _kind, obj, sub = item
        shape = _shape_of(obj, context)
        if not sub:
            if not shape.Faces:
                raise ValueError(_prefix(context, f"{_label(obj)!r} has no faces"))
            faces.extend(shape.Faces)
        elif not is_element(sub, FACE):
            raise ValueError(_prefix(
                context, f"{sub!r} is not a face: select a face, not an edge or a vertex"))
        else:
            faces.append(_element(obj, shape, sub, context))
    return faces


# ------------------------------------------------------------------- edges
def _one_curve_of_shape(shape, context):
    """An edge, a wire, or the one wire / one edge of a shape."""
    if shape.isNull():
        raise ValueError(_prefix(context, "the shape is empty"))
    if shape.ShapeType == "Edge":
        return shape
    wires = shape.Wires if shape.ShapeType != "Wire" else [shape]
    if len(wires) == 1:
        return wires[0]
    if len(shape.Edges) == 1:
        return shape.Edges[0]
    raise ValueError(_prefix(context, "each guide must be one edge or one wire"))


def _curve_of_link(obj, sub, context):
    shape = _shape_of(obj, context)
    if not sub:
        return _one_curve_of_shape(shape, context)
    if not is_element(sub, EDGE):
        raise ValueError(_prefix(context, f"{_label(obj)}.{sub} is not an edge"))
    return _element(obj, shape, sub, context)


def _curves(x, context):
    curves = []
    for item in _items(x, EDGE):
        if item[0] == "other":
            raise ValueError(_prefix(
                context, f"expected Part.Edge objects, got {type(item[1]).__name__}"))
        if item[0] == "shape":
            curves.append(_one_curve_of_shape(item[1], context))
        else:
            curves.append(_curve_of_link(item[1], item[2], context))
    return curves


def edges_of(x, context="guides"):
    """The curves x names, in order: Part.Edge / Part.Wire shapes (a wire stays
    one curve). Accepts edges, wires, one-curve shapes, (obj, 'EdgeN'),
    (obj, ['EdgeN', ...]), document objects, selection objects, LinkSubList
    values and lists of these."""
    return _curves(x, context)


def one_edge(x, context="guides"):
    """The one curve (Part.Edge or Part.Wire) x names."""
    curves = _curves(x, context)
    if len(curves) != 1:
        raise ValueError(_prefix(context, f"expected one edge, got {len(curves)}"))
    return curves[0]


def edge_links(x, context="guides"):
    """[(document object, 'EdgeN' or '')] to store as links (checked: each names
    an edge, or an object whose shape is one curve). A loose shape cannot be
    linked (it could not recompute): ValueError."""
    links = []
    for item in _items(x, EDGE):
        if item[0] != "link" or not isinstance(item[1], FreeCAD.DocumentObject):
            raise ValueError(_prefix(
                context, "links need (object, 'EdgeN') pairs or document objects "
                f"(a loose {type(item[1]).__name__} cannot be linked, so it could not "
                "recompute)"))
        _curve_of_link(item[1], item[2], context)
        links.append((item[1], item[2]))
    return links


# ------------------------------------------------------------ document objects
def panelization_of(objects):
    """The one Panelization among `objects` (a child, an Unfold or anything else
    whose Base is a Panelization counts as that Panelization); None when there
    is none or more than one."""
    from .features.panelization import is_panelization

    found = {}
    for obj in objects or []:
        if is_panelization(obj):
            found.setdefault(obj.Name, obj)
            continue
        base = getattr(obj, "Base", None)
        if base is not None and is_panelization(base):
            found.setdefault(base.Name, base)
    return next(iter(found.values())) if len(found) == 1 else None


def unfold_of(objects):
    """The one Unfold object among `objects`, else None."""
    from .features.unfold import Unfold

    picks = [o for o in objects or [] if isinstance(getattr(o, "Proxy", None), Unfold)]
    return picks[0] if len(picks) == 1 else None
